"""The store operations of a REASON counted by kind (benchmarks.step_ops), and the store as it was after."""

from __future__ import annotations

from benchmarks import step_ops
from topostore.stores.held import HeldGraphs
from topostore.stores.oxigraph import OxigraphStore


def test_a_reason_of_the_step_is_counted_by_kind_and_the_store_methods_are_put_back() -> None:
    before = {name: OxigraphStore.__dict__.get(name) for name in step_ops.STORE_METHODS}
    held_before = {name: HeldGraphs.__dict__.get(name) for name in step_ops.HELD_METHODS}
    calls = step_ops.count("example", 4, warm=4)
    kinds = {kind for kind, _ in calls}
    # a step's REASON reads its joins' facts, tests a scratch graph's facts, writes scratch facts and reads the index
    assert {"matches", "add_scratch", "index read", "held.add"} <= kinds
    assert all(n > 0 for n in calls.values())
    assert {name: OxigraphStore.__dict__.get(name) for name in step_ops.STORE_METHODS} == before
    assert {name: HeldGraphs.__dict__.get(name) for name in step_ops.HELD_METHODS} == held_before
