"""Semi-naive materialisation of a rule set into the inferred graphs.

Round 0 evaluates every rule on the whole data.  Each later round evaluates
only the rules that read a predicate or class that changed in the previous
round, and for each such body atom once with that atom restricted to the
*delta* graph (the facts derived in the previous round).  A rule whose filters
read something that changed is evaluated in full.  The loop stops when a
round derives nothing new.

Derived facts go to ``NEW_INFERRED`` / ``NEW_AUX`` first (never re-deriving a
fact already present), then become the next delta.  Rules with negated premises
(``stratum`` 1: "y1 and y2 are not known to be different, so they are the same")
join only after the positive rules reached their fixpoint.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field

from ..compile.generic import PREFIXES
from ..compile.rule import Rule, RuleSet
from ..store import Store
from ..vocab import ASSERTED, AUX, DELTA, INFERRED, NEW_AUX, NEW_INFERRED, TYPE

DATASET = f"USING {ASSERTED} USING {INFERRED} USING {AUX} USING NAMED {AUX} USING NAMED {DELTA}"


@dataclass
class ReasonStats:
    """What one REASON did: rounds, rule evaluations, facts derived, time."""

    rounds: int = 0
    evaluations: int = 0
    derived: int = 0
    seconds: float = 0.0
    mode: str = "full"
    per_rule: dict[str, float] = field(default_factory=dict)


def insert_text(rule: Rule, delta_index: int | None = None) -> str:
    target = NEW_AUX if rule.head_aux() else NEW_INFERRED
    head = rule.head.text()
    where = rule.where(delta_index, str(DELTA))
    return f"INSERT {{ GRAPH {target} {{ {head} }} }}\n{DATASET}\nWHERE {{\n  {where}\n  FILTER NOT EXISTS {{ {head} }}\n}}"


def matches(key: tuple, changed_preds: set[str], changed_classes: set[str]) -> bool:
    if key[0] == "*":
        return bool(changed_preds)
    if key[0] == "t":
        return key[1] in changed_classes
    return key[1] in changed_preds


class Materializer:
    """Runs a :class:`RuleSet` to its fixpoint over one store's graphs."""

    def __init__(self, store: Store, rules: RuleSet, profile: bool = False) -> None:
        self.store = store
        self.rules = rules.inference_rules
        self.profile = profile
        self._texts: dict[tuple[int, int | None], str] = {}

    def _run(self, index: int, delta_index: int | None, stats: ReasonStats) -> None:
        key = (index, delta_index)
        text = self._texts.get(key)
        if text is None:
            text = self._texts[key] = insert_text(self.rules[index], delta_index)
        start = time.perf_counter() if self.profile else 0.0
        self.store.update(text, prefixes=PREFIXES)
        stats.evaluations += 1
        if self.profile:
            name = self.rules[index].name
            stats.per_rule[name] = stats.per_rule.get(name, 0.0) + time.perf_counter() - start

    def _changed(self) -> tuple[set[str], set[str]]:
        preds = {str(r["p"]) for r in self.store.query(f"SELECT DISTINCT ?p WHERE {{ GRAPH {DELTA} {{ ?s ?p ?o }} }}")}
        classes: set[str] = set()
        if str(TYPE) in preds:
            classes = {str(r["c"]) for r in self.store.query(f"SELECT DISTINCT ?c WHERE {{ GRAPH {DELTA} {{ ?s {TYPE} ?c }} }}")}
        return preds, classes

    def _promote(self) -> bool:
        """Move the facts of this round into the inferred graphs and make them the delta."""
        if self.store.is_empty(NEW_INFERRED) and self.store.is_empty(NEW_AUX):
            return False
        self.store.update(
            f"DROP SILENT GRAPH {DELTA} ; "
            f"ADD SILENT {NEW_INFERRED} TO {DELTA} ; ADD SILENT {NEW_AUX} TO {DELTA} ; "
            f"ADD SILENT {NEW_INFERRED} TO {INFERRED} ; ADD SILENT {NEW_AUX} TO {AUX} ; "
            f"DROP SILENT GRAPH {NEW_INFERRED} ; DROP SILENT GRAPH {NEW_AUX}"
        )
        return True

    def _delta_round(self, active: list[int], stats: ReasonStats) -> None:
        preds, classes = self._changed()
        for i in active:
            rule = self.rules[i]
            if any(matches(k, preds, classes) for k in rule.filter_reads):
                self._run(i, None, stats)
                continue
            for j, atom in enumerate(rule.body):
                if matches(atom.read_key(), preds, classes):
                    self._run(i, j, stats)

    def clear(self) -> None:
        self.store.update(
            " ; ".join(f"DROP SILENT GRAPH {g}" for g in (INFERRED, AUX, DELTA, NEW_INFERRED, NEW_AUX))
        )

    def run(self) -> ReasonStats:
        """Recompute the inferred graphs from the asserted graph alone."""
        start = time.perf_counter()
        stats = ReasonStats()
        self.clear()
        strata = sorted({r.stratum for r in self.rules}) or [0]
        for level in strata:
            active = [i for i, r in enumerate(self.rules) if r.stratum <= level]
            fresh = [i for i in active if self.rules[i].stratum == level]
            for i in fresh:
                self._run(i, None, stats)
            stats.rounds += 1
            while self._promote():
                stats.rounds += 1
                self._delta_round(active, stats)
        self.store.update(f"DROP SILENT GRAPH {DELTA}")
        stats.derived = self.store.count(INFERRED)
        stats.seconds = time.perf_counter() - start
        return stats
