"""The few-solutions check of a full run: which evaluations keep their known heads out by look-ups.

An evaluation without delta whose one body atom has few facts, against a head key with many, keeps
the heads already known out by a look-up per solution (``FILTER NOT EXISTS``) rather than by
reading the head's whole extent (``MINUS``); :func:`.insert_text.new_only` writes either form.
"""

from __future__ import annotations

from collections.abc import Collection
from itertools import islice

from ..compile.rule import ReadKey, Rule, key_pattern
from ..rdf.vocab import ASSERTED, AUX, INFERRED
from ..stores.base import Store
from .order import TYPE_KEY

#: at most this many solutions make a one-atom evaluation few (:func:`few_solutions`; a look-up each, ≈ 9 µs)
FEW = 200
#: ... against a head extent of more than this many facts per solution (reading one costs ≈ 1–1.6 µs)
EXTENT_PER_SOLUTION = 8


def few_solutions(store: Store, rule: Rule, queued: Collection[ReadKey | None]) -> bool:
    """Whether a full run's evaluation of ``rule`` without delta keeps its known heads out by a
    look-up per solution (``FILTER NOT EXISTS``) rather than by reading the head's whole extent
    (``MINUS``): a body of one atom whose key has at most :data:`FEW` facts (so at most as many
    solutions) against a head key with more than :data:`EXTENT_PER_SOLUTION` times as many.

    A range over a handful of derived links (``canReach(r, y) ⟹ LOCATION(y)``, two links) anti-joined
    with every LOCATION read 100,000 memberships: 11 ms at 10,000 locations, 167 ms at 100,000 (see
    docs/benchmarks-history.md, "Full REASON from 10,000 to 100,000 locations").  Both forms mean the same
    (:func:`.insert_text.new_only`); only stores read without a round trip are asked (bounded index
    reads, in the graphs of the default dataset).  A body key an evaluation waiting in the queue may
    write (``queued``) is not counted: the store does not hold those facts yet.
    """
    if store.round_trips or len(rule.body) != 1 or rule.head is None or not rule.head.variables():
        return False
    body, head = rule.body[0].read_key(), rule.writes()
    if any(k[0] not in ("p", "t") or not k[1].startswith("<") or k == ("p", TYPE_KEY) for k in (body, head)):
        return False  # a key of any predicate or class, or a path: counted by no index read
    if body in queued or ("*",) in queued or (body[0] == "t" and ("p", TYPE_KEY) in queued):
        return False
    solutions = _facts(store, body, FEW)
    return solutions <= FEW and _facts(store, head, EXTENT_PER_SOLUTION * solutions) > EXTENT_PER_SOLUTION * solutions


def _facts(store: Store, key: ReadKey, limit: int) -> int:
    """The facts of ``key`` in the asserted, inferred and helper graphs, counted up to ``limit + 1``."""
    pattern = key_pattern(key)
    found = 0
    for graph in (ASSERTED, INFERRED, AUX):
        found += sum(1 for _ in islice(store.triples(*pattern, graph), limit + 1 - found))
        if found > limit:
            break
    return found
