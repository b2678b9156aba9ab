"""Deletions: DRed (delete and rederive) with a proof check before over-deleting.

See :mod:`.incremental` for why this algorithm and when it is sound.  In short:
removed facts are propagated through the rule bodies to find every inferred
fact that may have lost a derivation (candidates); a candidate with a
derivation from asserted or already proven facts is kept (proven), the others
are over-deleted; over-deleted facts that still follow from what is left are
rederived and join the additions' semi-naive rounds.
"""

from __future__ import annotations

from pyoxigraph import NamedNode, Triple

from ..compile.rule import Rule
from ..rdf.vocab import ASSERTED, AUX, INFERRED, NEW_AUX, NEW_INFERRED
from . import limits
from .plan import KeyCounts, plan_where
from .requests import RequestQueue
from .scratch import CANDIDATES, DEL_DELTA, NEW_PROVEN, OVERDELETED, PROVEN, REMOVED, SUBGOALS, dataset, target
from .stats import ReasonStats
from .triggers import Present, Triggers, matches


def can_prove(rule: Rule) -> bool:
    """Whether the rule may be used to prove a candidate from asserted + proven facts.

    Its body must read only the default graph and its filters only bound
    values: helper-graph atoms and EXISTS filters would read facts that may be
    over-deleted later in the same run.
    """
    return not rule.is_check and not any(a.aux for a in rule.body) and not rule.filter_reads \
        and not rule.conditions_read_graph


class Deletion:
    """DRed's phases of :class:`~.incremental.IncrementalReasoner`: over-delete (with proofs), rederive.

    Holds the rule indexes the phases choose from; the previous REASON's
    state (what has facts, what is asserted) is handed to each phase, and the
    evaluations go through the reasoner's :class:`~.requests.RequestQueue`.
    """

    def __init__(self, requests: RequestQueue, triggers: Triggers, monotone: list[int], provers: list[int]) -> None:
        self.requests = requests
        self.store = requests.store
        self.rules = requests.rules
        self.triggers = triggers
        #: indexes of the monotone rules (as a list, in rule order, and as a set)
        self.monotone = monotone
        self._monotone_set = set(monotone)
        #: indexes of the rules usable in proofs (:func:`can_prove`)
        self.provers = provers
        #: the previous REASON's state (a :class:`~.incremental.MaintenanceState`), set by each phase
        self.state = None

    def overdelete(self, state, stats: ReasonStats, skip: set[tuple[int, int]] = frozenset(),
                   lost: list[Triple] = ()) -> None:
        """DRed's first phase, with the proof check that keeps cyclic axioms from cascading.

        In the first round, the evaluations in ``skip`` are replaced by the
        heads in ``lost`` (found by :class:`~.flips.Flips`).
        """
        self.state = state
        with limits.doing("DRed's over-deletion"):
            self._overdelete(stats, skip, lost)

    def _overdelete(self, stats: ReasonStats, skip: set[tuple[int, int]], lost: list[Triple]) -> None:
        """Propagate the removed facts to candidates round by round, proving those that still hold."""
        self.requests.defer(f"ADD SILENT {REMOVED} TO {DEL_DELTA} ; ADD SILENT {REMOVED} TO {OVERDELETED}")
        preds, classes = self.requests.start(REMOVED)  # what DEL_DELTA holds once the queue is sent
        while True:
            limits.check()
            for i, j in self.triggers.evaluations(preds, classes, self._monotone_set, self.state.present, skip):
                self.requests.run(("cand", i, j), self._candidate_text, i, j, stats)
            self.requests.flush()
            if lost:
                self.store.add_scratch(lost, CANDIDATES)
            skip, lost = frozenset(), ()
            counts = self.requests.keys(CANDIDATES)
            if not counts[0]:
                break
            with limits.doing("DRed's proof of the over-deletion candidates"):
                self._prove(stats, counts)
            stats.overdeleted += self.store.count(CANDIDATES) if self.requests.profile else 0
            preds, classes = self.requests.start(CANDIDATES)  # the next DEL_DELTA
            self.requests.defer(f"DROP SILENT GRAPH {DEL_DELTA} ; ADD SILENT {CANDIDATES} TO {DEL_DELTA} ; "
                        f"ADD SILENT {CANDIDATES} TO {OVERDELETED} ; DROP SILENT GRAPH {CANDIDATES}")
        self.requests.defer(" ; ".join(f"DELETE {{ GRAPH {g} {{ ?s ?p ?o }} }} {dataset((), (OVERDELETED, g))} "
                               f"WHERE {{ GRAPH {OVERDELETED} {{ ?s ?p ?o }} GRAPH {g} {{ ?s ?p ?o }} }}"
                               for g in (INFERRED, AUX)))

    def _prove(self, stats: ReasonStats, counts: KeyCounts | None = None) -> None:
        """Move candidates that still hold to PROVEN: a derivation from asserted or proven facts.

        When that proves nothing more, the premises of the remaining
        candidates' derivations in the current graphs become subgoals, proven
        the same way (one level of backward chaining); then candidates are
        tried again.  PROVEN only ever receives facts with a derivation from
        asserted or earlier proven facts, so it stays inside the new closure.
        ``counts``: the candidates' read keys, when the caller has just counted them.
        """
        known = (set(self.state.asserted[0]), set(self.state.asserted[1]))
        tried_subgoals = False
        while True:
            limits.check()
            proved = self._prove_goals(CANDIDATES, known, stats, counts)
            counts = None
            if proved:
                continue
            if tried_subgoals or self.store.is_empty(CANDIDATES):
                return
            tried_subgoals = True
            self._make_subgoals(stats)
            progress = False
            while self._prove_goals(SUBGOALS, known, stats):
                progress = True
            self.requests.defer(f"DROP SILENT GRAPH {SUBGOALS}")
            if not progress:
                return

    def _prove_goals(self, goals: NamedNode, known: Present, stats: ReasonStats,
                     counts: KeyCounts | None = None) -> bool:
        """One pass of the provers over ``goals`` (``counts``: their read keys if known); True when something
        was proven."""
        if counts is None:
            counts = self.requests.start(goals)
        else:
            self.requests.counts = counts
        preds, classes = counts
        for i in self.provers:
            key = self.rules[i].writes()
            if key is not None and matches(key, preds, classes) and self.triggers.feasible(i, known):
                self.requests.run(("prove", i, goals.value), self._prove_text, i, goals, stats)
        self.requests.flush()
        new_preds, new_classes = self.requests.keys(NEW_PROVEN)
        if not new_preds:
            return False
        known[0].update(new_preds)
        known[1].update(new_classes)
        self.requests.defer(f"DROP SILENT GRAPH {NEW_PROVEN}")
        return True

    def _make_subgoals(self, stats: ReasonStats) -> None:
        """Premises (not of an asserted kind) of the candidates' derivations in the current graphs."""
        preds, classes = self.requests.start(CANDIDATES)
        for i in self.provers:
            key = self.rules[i].writes()
            if key is None or not matches(key, preds, classes) or not self.triggers.feasible(i, self.state.present):
                continue
            if self.triggers.unknown_atoms(i, self.state.asserted):
                self.requests.run(("subgoal", i), self._subgoal_text, i, None, stats)
        self.requests.flush()

    def rederive(self, state, stats: ReasonStats) -> None:
        """DRed's second phase: over-deleted facts that still follow from what is left go to NEW_*."""
        self.state = state
        with limits.doing("DRed's rederivation"):
            self._rederive(stats)

    def _rederive(self, stats: ReasonStats) -> None:
        preds, classes = self.requests.start(OVERDELETED)
        for i in self.monotone:
            key = self.rules[i].writes()
            if key is not None and matches(key, preds, classes) and self.triggers.feasible(i, self.state.present):
                self.requests.run(("rederive", i), self.rederive_text, i, None, stats)
        if self.requests.profile:
            self.requests.flush()
            stats.rederived = self.store.count(NEW_INFERRED) + self.store.count(NEW_AUX)

    # ------------------------------------------------------------------ SPARQL texts
    def _candidate_text(self, i: int, j: int | None) -> str:
        """Heads of matches over the *old* closure that use an over-deleted fact (atom ``j``),
        or every head of the rule when ``j`` is None (a filter read something deleted)."""
        rule = self.rules[i]
        head = rule.head.text()
        where = plan_where(rule, j, DEL_DELTA, lateral=self.requests.lateral)
        old_closure = (ASSERTED, INFERRED, AUX, REMOVED)
        named = (AUX, DEL_DELTA, target(rule), OVERDELETED, PROVEN)
        return (f"INSERT {{ GRAPH {CANDIDATES} {{ {head} }} }}\n{dataset(old_closure, named)}\nWHERE {{\n  {where}\n"
                f"  FILTER EXISTS {{ GRAPH {target(rule)} {{ {head} }} }}\n"
                f"  FILTER NOT EXISTS {{ GRAPH {OVERDELETED} {{ {head} }} }}\n"
                f"  FILTER NOT EXISTS {{ GRAPH {PROVEN} {{ {head} }} }}\n}}")

    def _prove_text(self, i: int, goals: NamedNode) -> str:
        """Move the goals the rule derives from asserted + proven facts to PROVEN (and NEW_PROVEN)."""
        rule = self.rules[i]
        head = rule.head.text()
        where = plan_where(rule, head_graph=goals, lateral=self.requests.lateral)
        return (f"DELETE {{ GRAPH {goals} {{ {head} }} }}\n"
                f"INSERT {{ GRAPH {PROVEN} {{ {head} }} GRAPH {NEW_PROVEN} {{ {head} }} }}\n"
                f"{dataset((ASSERTED, PROVEN), (goals, PROVEN))}\nWHERE {{\n  {where}\n}}")

    def _subgoal_text(self, i: int, _: None) -> str:
        rule = self.rules[i]
        # the premises that may need a proof: body atoms of a kind not known to be asserted
        atoms = " ".join(rule.body[j].text() for j in self.triggers.unknown_atoms(i, self.state.asserted))
        where = plan_where(rule, head_graph=CANDIDATES, lateral=self.requests.lateral)
        return (f"INSERT {{ GRAPH {SUBGOALS} {{ {atoms} }} }}\n"
                f"{dataset((ASSERTED, INFERRED, AUX), (AUX, CANDIDATES))}\nWHERE {{\n  {where}\n}}")

    def rederive_text(self, i: int, heads: NamedNode | None) -> str:
        """Insert into NEW_* the heads in ``heads`` (over-deleted ones by default) that the rule derives now."""
        heads = heads or OVERDELETED
        rule = self.rules[i]
        head = rule.head.text()
        new = NEW_AUX if rule.head_aux() else NEW_INFERRED
        where = plan_where(rule, head_graph=heads, lateral=self.requests.lateral)
        return (f"INSERT {{ GRAPH {new} {{ {head} }} }}\n{dataset((ASSERTED, INFERRED, AUX), (AUX, heads))}\n"
                f"WHERE {{\n  {where}\n  FILTER NOT EXISTS {{ {head} }}\n}}")


__all__ = ["Deletion", "can_prove"]
