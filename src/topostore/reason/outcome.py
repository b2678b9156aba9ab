"""What a maintained REASON reads after maintenance: its consistency, and the entailed-only graph.

Why apart from :mod:`.incremental`: that module chooses the mode and runs the phases; this one reads
their outcome where the store is in memory or the general phases ran (a compiled step on a store
reached over HTTP reads both in its one after-step query, :mod:`.after`).  Both reads are
semi-naive: consistency asks only the checks a new fact may make match (:mod:`.change_checks`), and
the entailed-only graph is refreshed from the touched triples only (:mod:`.entailed`), or not at all
where no internal twin exists nor can have been written.
"""

from __future__ import annotations

import time
from typing import TYPE_CHECKING

from ..compile.rule import RuleSet
from ..stores.base import Store
from .change_checks import ChangeChecks
from .changed import ChangedGraphs
from .compiled_step import CompiledStep
from .consistency import Violation, check_consistency
from .entailed import any_twin, internal, refresh_entailed, refresh_touched
from .requests import RequestQueue
from .scratch import NEW_FACTS, OVERDELETED
from .stats import ReasonStats

if TYPE_CHECKING:
    from .maintenance import MaintenanceState


class Outcome:
    """The reads after maintenance of one reasoner (made with its maintenance parts)."""

    def __init__(self, store: Store, ruleset: RuleSet, requests: RequestQueue, changed: ChangedGraphs,
                 change_checks: ChangeChecks, step: CompiledStep, checks_monotone: bool) -> None:
        self.store = store
        self.ruleset = ruleset
        self.requests = requests
        self.changed = changed
        self.change_checks = change_checks
        self.step = step
        self.checks_monotone = checks_monotone
        #: the read keys of the internal forms of the entailed-only predicates (:func:`.entailed.internal`)
        self._twin_keys = frozenset(("p", f"<{internal(p).value}>") for p in ruleset.entailed_predicates)
        #: True once the helper graph was found to hold no internal fact (no entailed-only conclusion), until
        #: something may write one (see :meth:`publish_entailed`); None: not known
        self.twinless: bool | None = None

    def violations(self, state: MaintenanceState, stats: ReasonStats, changed: bool) -> list[Violation]:
        """Consistency of the new state, running all checks only when one may have changed."""
        start = time.perf_counter()
        try:
            if not changed:
                return list(state.violations)
            if state.violations or not self.checks_monotone or self.change_checks.violation_possible():
                return check_consistency(self.store, self.ruleset)
            return []
        finally:
            if self.requests.profile:
                stats.per_rule["consistency"] = stats.per_rule.get("consistency", 0.0) + time.perf_counter() - start

    def publish_entailed(self, changed: bool, compiled: bool) -> None:
        """Bring the ENTAILED graph up to date from what this maintenance touched (see :mod:`.entailed`).

        A triple is in ENTAILED only while its internal twin is in the helper graph.  Where the helper
        graph holds no twin and this REASON's compiled step writes none (its program's heads name no
        internal form), it held none before either: ENTAILED held none of the touched triples and holds
        none now, and the touched triples are not read (a robot's canReach on a map whose individuals
        are declared different)."""
        if not changed:
            return
        self.requests.flush()  # what follows reads the store (the touched types too)
        if not self.ruleset.entailed_predicates:
            return
        if compiled and self._no_twin_written():
            if self.twinless is None:  # nothing added or removed a twin in this REASON: the graph as it was
                self.twinless = not any_twin(self.store, self.ruleset.entailed_predicates)
            if self.twinless:
                return
        else:
            self.twinless = None  # the general phases may write any key
        found = self.changed.touched_watched((NEW_FACTS, OVERDELETED))
        if found is None:  # a graph too large to read into memory, or a store reached over HTTP
            refresh_entailed(self.store, self.ruleset, (NEW_FACTS, OVERDELETED), self.changed.quads)
        else:
            refresh_touched(self.store, *found)

    def _no_twin_written(self) -> bool:
        """Whether the compiled step of this REASON can have written no internal twin, neither added nor
        removed one (no key it may have changed is the key of one, nor a key standing for any predicate):
        then the helper graph's twins read after it are those before it."""
        heads = self.step.written
        if self._twin_keys.isdisjoint(heads) and all(len(key) == 2 for key in heads):
            return True
        self.twinless = None
        return False


__all__ = ["Outcome"]
