"""The scratch graphs of incremental maintenance, and the dataset clauses that name them.

Shared by the phases of :mod:`.incremental` (additions, flips) and :mod:`.dred` (deletions).
"""

from __future__ import annotations

from collections.abc import Iterable

from pyoxigraph import NamedNode

from ..compile.rule import Rule
from ..rdf.vocab import AUX, INFERRED, INTERNAL
from . import flip

#: Scratch graphs of incremental maintenance (never visible to queries).
ADDED = NamedNode(INTERNAL + "graph:inc-added")          # asserted triples added since the last REASON
REMOVED = NamedNode(INTERNAL + "graph:inc-removed")      # asserted triples removed since the last REASON
OVERDELETED = NamedNode(INTERNAL + "graph:inc-overdeleted")
DEL_DELTA = NamedNode(INTERNAL + "graph:inc-del-delta")  # over-deleted in the previous round
CANDIDATES = NamedNode(INTERNAL + "graph:inc-candidates")
PROVEN = NamedNode(INTERNAL + "graph:inc-proven")        # proven to hold in the new state
NEW_PROVEN = NamedNode(INTERNAL + "graph:inc-new-proven")
SUBGOALS = NamedNode(INTERNAL + "graph:inc-subgoals")    # premises a candidate's proof needs
NEW_FACTS = NamedNode(INTERNAL + "graph:inc-new-facts")  # facts that may be new in the closure
FLIP_GAINED = NamedNode(INTERNAL + "graph:inc-flip-gained")  # heads a replaced value may have made true
SCRATCH = (ADDED, REMOVED, OVERDELETED, DEL_DELTA, CANDIDATES, PROVEN, NEW_PROVEN, SUBGOALS, NEW_FACTS,
           FLIP_GAINED, flip.CHANGE_OLD)


def dataset(default: Iterable[NamedNode], named: Iterable[NamedNode] = ()) -> str:
    """USING / USING NAMED clauses of an update."""
    return " ".join([f"USING {g}" for g in default] + [f"USING NAMED {g}" for g in named])


def rule_start(rule: Rule, j: int | None, kind: str) -> tuple:
    """Read key of the pattern an evaluation starts from: the delta atom, or the head."""
    if kind == "cand" and j is not None:
        return rule.body[j].read_key()
    return rule.head.read_key() if rule.head is not None else ("*",)


def target(rule: Rule) -> NamedNode:
    return AUX if rule.head_aux() else INFERRED


__all__ = ["ADDED", "CANDIDATES", "DEL_DELTA", "FLIP_GAINED", "NEW_FACTS", "NEW_PROVEN", "OVERDELETED", "PROVEN",
           "REMOVED", "SCRATCH", "SUBGOALS", "dataset", "rule_start", "target"]
