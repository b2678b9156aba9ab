"""The robot-like steps on the tutorial-style TBox: the row is produced, its steps do what they say, every
step's answers are held against a full REASON from scratch (a difference is a mismatch), and the suite's
full part runs it in a process of its own.  Tiny runs; no timing is asserted."""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Any

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # the benchmarks package lives beside src/

import benchmarks.__main__ as suite  # noqa: E402
from benchmarks import tables, tbox, tbox_steps  # noqa: E402

NS = tbox.NS
TYPE = "<http://www.w3.org/1999/02/22-rdf-syntax-ns#type>"


def test_the_row_has_the_first_step_apart_and_the_others_summed_up(tmp_path: Path) -> None:
    row = tbox_steps.run(50, 3, tmp_path)
    assert row["kind"] == "tbox_steps" and row["steps"] == 3 and row["mismatches"] == []
    assert row["first_ms"] > 0 and 0 < row["median_ms"] <= row["p95_ms"] <= row["max_ms"]
    assert sum(row["modes"].values()) == 3 and row["answers"] > 0 and "doing" not in row
    text = tables.extra_tables([row])
    assert "| tutorial-style TBox (50 classes) |" in text and "equal to full REASON" in text


def test_each_step_types_a_pizza_with_toppings_its_closure_allows() -> None:
    steps = tbox_steps.plan(50, 4)
    allowed = tbox.pizza_toppings(50)
    for i, step in enumerate(steps):
        pizza_cls, leaf = step.types[1][1], step.types[3][1]
        assert leaf in allowed[pizza_cls]
        assert (f"stepPizza{i}", "hasTopping", f"stepTopping{i}") in step.add
    assert steps[0].remove == [("pizzaA", "hasTopping", "salami1")]
    assert steps[2].remove == [("stepPizza1", "hasTopping", "stepTopping1")]


def test_the_steps_answers_follow_the_changes(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    seen: list[dict[str, Any]] = []
    answers = tbox_steps.answers
    monkeypatch.setattr(tbox_steps, "answers", lambda onto: seen.append(answers(onto)) or seen[-1])
    tbox_steps.run(50, 2, tmp_path)
    last = set(seen[1]["triples"])  # step 2's own answers, before the check
    # the pizza of step 2 is a Pizza (hasTopping's domain) and its topping a Topping (its range)
    assert f"<{NS}stepPizza1> {TYPE} <{NS}Pizza>" in last and f"<{NS}stepTopping1> {TYPE} <{NS}Topping>" in last
    # step 2 took step 1's topping away; step 1 took salami1 (a MeatTopping) off pizzaA
    assert f"<{NS}stepPizza0> <{NS}hasTopping> <{NS}stepTopping0>" not in last
    assert f"<{NS}pizzaA> {TYPE} <{NS}MeatyPizza>" not in last
    assert f"<{NS}pizzaA> {TYPE} <{NS}CheeseyPizza>" in last


def test_a_step_answering_otherwise_than_a_full_reason_is_a_mismatch(tmp_path: Path,
                                                                     monkeypatch: pytest.MonkeyPatch) -> None:
    scratch = tbox_steps.from_scratch

    def one_triple_short(asserted: bytes) -> dict[str, Any]:
        found = scratch(asserted)
        return {**found, "triples": found["triples"][1:]}

    monkeypatch.setattr(tbox_steps, "from_scratch", one_triple_short)
    row = tbox_steps.run(50, 2, tmp_path)
    assert len(row["mismatches"]) == 2 and all("1 extra, 0 missing" in m for m in row["mismatches"])
    assert "**MISMATCH** (2): step 1:" in tables.tbox_steps_table([row])
    with pytest.raises(SystemExit) as stop:
        tbox_steps.main(["tbox:50", "--steps", "2"])
    assert stop.value.code == 3


def test_too_few_steps_or_another_input_are_refused(tmp_path: Path) -> None:
    with pytest.raises(ValueError, match="at least 2 steps"):
        tbox_steps.run(50, 1, tmp_path)
    with pytest.raises(SystemExit):
        tbox_steps.main(["1000"])


def test_the_full_part_runs_the_steps_in_a_bounded_process_of_their_own(monkeypatch: pytest.MonkeyPatch) -> None:
    calls: list[tuple[list[str], float]] = []
    monkeypatch.setattr(suite, "run_size", lambda cmd, timeout, size, kind: calls.append((cmd, timeout)) or
                        {"kind": kind, "size": size, "label": size, "error": "not run", "mismatches": []})
    args = suite.parse_args(["--parts", "full", "--full-maps", "--tbox", "tbox:60", "--tbox-steps", "5"])
    rows = suite.full_rows(args)
    assert calls[-1] == (["benchmarks.tbox_steps", "tbox:60", "--steps", "5"], 300)
    assert rows[-1]["kind"] == "tbox_steps" and "failed: not run" in tables.extra_tables(rows[-1:])


@pytest.mark.parametrize("freeze", ["none", "first-step"])
def test_the_collector_measurement_runs_each_policy_and_leaves_nothing_frozen(freeze: str) -> None:
    """benchmarks.tbox_gc, tiny: the row says what it measured; a frozen run is thawed for the rest of the tests."""
    import gc

    from benchmarks import tbox_gc

    try:
        row = tbox_gc.run(50, 3, freeze)
        assert row["freeze"] == freeze and row["median_ms"] > 0 and row["full_collections"] >= 0
        assert (row["frozen"] > 0) == (freeze != "none")
    finally:
        gc.unfreeze()


@pytest.mark.parametrize(("argv", "compare", "scale"), [([], "200", "20"), (["--quick"], "50", "10"),
                                                        (["--compare-steps", "7", "--steps", "3"], "7", "3")])
def test_the_compared_maps_take_their_own_number_of_steps(monkeypatch: pytest.MonkeyPatch, argv: list[str],
                                                          compare: str, scale: str) -> None:
    calls: list[list[str]] = []
    monkeypatch.setattr(suite, "_timed", lambda cmd, timeout, size, kind: calls.append(cmd) or {})
    args = suite.parse_args([*argv, "--no-pellet", "--sizes", "example", "--scale-sizes", "1000"])
    suite.step_rows(args)
    assert calls[0][:4] == ["benchmarks.compare", "example", "--steps", compare]
    assert calls[1][:4] == ["benchmarks.scale", "1000", "--steps", scale]
