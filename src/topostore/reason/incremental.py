"""Incremental maintenance of the inferred graphs after asserted triples change.

Why this algorithm
------------------
A robot changes a handful of asserted facts per step (where it is, the time,
when it visited a place); recomputing the closure of the whole map each time
costs time proportional to the map.  Maintenance must give exactly the graphs
a from-scratch run gives, so it has to handle deletions soundly too.

* **Additions** are semi-naive evaluation (the same loop as
  :class:`~.materialize.Materializer`), with the added asserted triples as the
  first delta: only rules reading a changed predicate or class run, each with
  one body atom restricted to the delta.
* **Deletions** use DRed, "delete and rederive" (Gupta, Mumick & Subrahmanian,
  SIGMOD 1993): propagate the removed facts through the rule bodies to
  *over-delete* every inferred fact that may have lost a derivation, delete
  them, then *rederive* those of them that still follow from what is left, and
  propagate the rederived facts semi-naively.  DRed works set-at-a-time, so
  every step is one SPARQL update per rule and body atom, like the forward
  loop; counting-based maintenance would need derivation counts, which a
  SPARQL INSERT cannot keep, and is incomplete for recursive rules.
* Plain DRed over-deletes too much on this ontology: the class axioms are
  cyclic (``LOCATION ≡ visitedAt exactly 1``, ``URGENT ⊑ LOCATION``, the
  Urgency rule reads ``LOCATION``), so a new ``now`` would over-delete URGENT,
  then LOCATION of those places, then everything built on LOCATION.  Before a
  candidate is over-deleted it is therefore checked for a derivation from
  facts that are *proven* to hold in the new state: asserted triples and
  candidates already proven this way (a restricted form of the backward check
  of the Backward/Forward algorithm, Motik et al., AAAI 2015).  Proofs are
  grounded in asserted facts, so cyclic derivations cannot justify
  themselves; a candidate that is not proven is over-deleted as in DRed and
  may still come back in the rederive step.  Only rules whose bodies read no
  helper-graph atoms and whose filters contain no EXISTS are used for such
  proofs, since those read graphs that are still being over-deleted.

Correctness conditions and fallbacks
------------------------------------
DRed is sound for monotone rules.  The rule set has two non-monotone parts:

* rules with negated premises (``stratum`` 1: "``?y1`` and ``?y2`` are the
  same unless known to be different").  A full run evaluates them after
  stratum 0 reached its fixpoint.  Maintenance keeps stratum 0 only; it is
  exact when no stratum-1 rule matched in the previous state (then that state
  was the stratum-0 fixpoint) and none matches in the new one (then the new
  stratum-0 fixpoint is the answer).  Otherwise — an owl:sameAs merge appears,
  persists or is undone — it falls back to a full rematerialisation.
* built-in comparisons (the Urgency rule's ``now - visitedAt > threshold``)
  only compare values bound by body atoms, so they are monotone in the facts:
  a new ``now`` is a deleted and an added ``now`` fact.

Consistency: the checks are monotone queries too, so a consistent state stays
consistent unless a check matches with at least one body atom on a fact that
is new in the closure; only then (or when the previous state was
inconsistent, or a check negates a premise) are all checks run.

A change to schema triples recompiles the rules and forces a full run; so does
a change touching more than :attr:`IncrementalReasoner.max_change_share` of
the asserted graph, where recomputation is as cheap as maintenance.  The mode
and the reason are reported in :class:`~.stats.ReasonStats`.

Where the parts live: this module chooses the mode and runs the phases;
:mod:`.maintenance` holds the state kept between REASONs and the parts made for
maintenance; :mod:`.kinds` what a repeated kind of change keeps (its decisions,
the pairs known to hold one value); :mod:`.compiled_step` compiles each kind of
change once and runs its program; :mod:`.outcome` reads consistency and the
entailed-only graph after maintenance, :mod:`.change_checks` whether a check or
a negated premise may match; :mod:`.dred` holds the deletion phases (over-delete with proofs,
rederive), :mod:`.requests` the batching of evaluations into update
requests, :mod:`.scratch` the scratch graphs they share.
"""

from __future__ import annotations

import time
from collections.abc import Collection

from pyoxigraph import NamedNode, Triple

from ..compile.generic import PREFIXES
from ..compile.rule import RuleSet
from ..compile.schema_program import full_program
from ..rdf.collector import collector_paused
from ..rdf.lexer import negates_exists  # noqa: F401 - public here since the first release
from ..rdf.terms import Term
from ..rdf.vocab import ASSERTED, AUX, DELTA, ENTAILED, INFERRED, NEW_AUX, NEW_INFERRED
from ..stores.base import Store
from .closing import close_full, counting_asserted
from .compiled_step import MAX_PROGRAMS
from .component import WHOLE_ROUNDS
from .consistency import Violation, check_consistency
from .dred import can_prove
from .kinds import KeptKinds, read_change
from .maintenance import MaintenanceParts, MaintenanceState, Part, early_checks, is_monotone, needed_keys
from .materialize import Materializer
from .negation import ASKED, completion_text
from .present import key_graphs, with_facts
from .program import PROGRAM_SCRATCH
from .requests import LaterCopies
from .scratch import ADDED, FLIP_GAINED, NEW_FACTS, OVERDELETED, REMOVED, SCRATCH
from .stats import ReasonStats, incremental_reason

#: Default share of the asserted graph above which a change is recomputed from scratch.
DEFAULT_MAX_CHANGE_SHARE = 0.10

#: The reasoning modes: incremental when sound and the change is small, incremental whenever sound, full.
MODES = ("auto", "incremental", "full")


def check_mode(mode: str) -> None:
    """Refuse an unknown reasoning mode (a wrong argument, not a failed REASON: nothing is undone)."""
    if mode not in MODES:
        raise ValueError(f"unknown reasoning mode {mode!r}; use auto, incremental or full")


#: the scratch graphs every REASON drops at its end
DROPPED = (*SCRATCH, *PROGRAM_SCRATCH, DELTA, NEW_INFERRED, NEW_AUX)


class IncrementalReasoner:
    """Keeps the inferred graphs of one store equal to the closure of its asserted graph.

    Holds the rules and the state of the previous REASON; :meth:`reason` gets
    the net asserted additions and removals since then (already applied to
    the asserted graph) and chooses incremental maintenance or a full run.
    Its parts: the request queue the phases share (:mod:`.requests`), the
    flips of replaced values (:mod:`.flips`) and the deletion phases
    (:mod:`.dred`); additions are the materializer's semi-naive rounds.
    """

    def __init__(self, store: Store, rules: RuleSet, max_change_share: float = DEFAULT_MAX_CHANGE_SHARE) -> None:
        self.store = store
        self.ruleset = rules
        self.max_change_share = max_change_share
        self.state = MaintenanceState()
        #: set by a compiled step that may have lost such a key: the REASON is then run in full
        self._incomplete = False
        #: the keys some rule or check body reads: the only ones :attr:`MaintenanceState.present` is asked
        #: about (found without the rule per pair of disjoint classes: :func:`needed_keys`)
        self._needed = needed_keys(rules)
        store.hold_scratch(DROPPED)  # only this reasoner reads them, and it drops them after every REASON
        #: what the kind of a change decides and the pairs known to hold one value (:mod:`.kinds`); the
        #: decisions are shared with the reads after maintenance (:mod:`.change_checks`)
        self.kinds = KeptKinds(MAX_PROGRAMS)
        #: the parts of maintenance, made by the first REASON that maintains (:attr:`parts`)
        self._parts: MaintenanceParts | None = None
        #: (individual, class) pairs whose type fact the last REASON may have changed; None after a full run
        self.touched_types: list[tuple[Term, NamedNode]] | None = None

    rules = Part()
    monotone = Part()
    _monotone_set = Part()
    deferred = Part()
    _completion = Part()
    triggers = Part()
    checks = Part()
    check_triggers = Part()
    negated = Part()
    _unmaintainable = Part()
    provers = Part()
    checks_monotone = Part()
    requests = Part()
    flips = Part()
    deletion = Part()
    changed = Part()
    change_checks = Part()
    step = Part()
    outcome = Part()

    @property
    def parts(self) -> MaintenanceParts:
        """The maintenance parts, made on first use."""
        if self._parts is None:
            with collector_paused():  # a rule per pair of disjoint classes indexed: see ..rdf.collector
                self._parts = MaintenanceParts(self)
            # read as plain attributes from now on (a :class:`.maintenance.Part` gives way to the instance's own)
            self.__dict__.update(vars(self._parts))
        return self._parts

    # ------------------------------------------------------------------ entry point
    def reason(self, added: Collection[Triple] = (), removed: Collection[Triple] = (), mode: str = "auto",
               profile: bool = False, forced_reason: str = "") -> tuple[ReasonStats, list[Violation]]:
        """Bring the inferred graphs up to date; returns the stats and the violations.

        ``mode`` is "auto" (incremental when sound and the change is small),
        "incremental" (incremental whenever sound, whatever the size) or "full".
        ``forced_reason`` makes the run full and says why (e.g. the schema changed).
        """
        check_mode(mode)
        why = forced_reason or self._full_reason(len(added) + len(removed), mode)
        if why:
            return self.full(why, profile)
        start = time.perf_counter()
        self.change_checks.begin(added)
        stats = ReasonStats(mode="incremental", reason=incremental_reason(len(added), len(removed)))
        self.requests.profile = profile
        self._incomplete = False
        try:
            self._maintain(added, removed, stats, profile)
            if self._incomplete:
                self._clear_scratch()
                return self.full("the compiled step may have lost a declaration of difference a full REASON "
                                 "left pairs unasked for (see topostore.reason.negation)", profile)
            changed = bool(added or removed)
            if changed and self.store.round_trips and stats.program == "compiled":
                after = self.step.read_after()
                if after.unsettled:
                    self.step.unsettled.add(self.step.last_sig)  # once is enough: the general phases from now on
                    self._clear_scratch()
                    return self.full(f"the compiled step's {WHOLE_ROUNDS} rounds of a recursive component were "
                                     "not enough", profile)
                if after.negated:
                    return self.full("the change makes a rule with a negated premise (stratum 1) match", profile)
                violations = check_consistency(self.store, self.ruleset) \
                    if self.state.violations or not self.checks_monotone or after.violation_possible else []
                self.requests.scratch(after.entailed_add, ENTAILED)
                self.requests.discard(after.entailed_drop, (ENTAILED,))
                self.touched_types = after.touched_types
            else:
                if changed and self.change_checks.negated_match():
                    return self.full("the change makes a rule with a negated premise (stratum 1) match", profile)
                violations = self.outcome.violations(self.state, stats, changed)
                self.outcome.publish_entailed(changed, stats.program == "compiled")
                self.touched_types = self.changed.touched_types() if changed else []
            if profile:
                stats.derived = self.store.count(NEW_FACTS)
        except Exception:
            self.state.ready = False  # half-maintained graphs: the next REASON recomputes them
            self.touched_types = None
            self.outcome.twinless = None
            self.kinds.failed()
            self.flips.forget()
            self.requests.clear()
            raise
        finally:
            self._clear_scratch()
        self.state.asserted_size += len(added) - len(removed)
        self.state.violations = violations
        stats.seconds = time.perf_counter() - start
        return stats, violations

    def full(self, why: str, profile: bool = False) -> tuple[ReasonStats, list[Violation]]:
        """Recompute everything from the asserted graph; records the state maintenance starts from."""
        self.state.ready = False
        self.touched_types = None
        self.kinds.clear()
        if self._parts is not None:
            self.outcome.twinless = None
            self.flips.forget()
            self.step.programs.clear()  # compiled against the keys with facts, which a full run recounts
            self.step.forget_runs()
            self._completion.forget()
            self._clear_scratch()
        program = full_program(self.ruleset)  # large schema tables as one generic rule each
        failed = True
        with counting_asserted(self.store) as asserted:  # beside the rules where the store overlaps
            try:
                program.write(self.store)
                materializer = Materializer(self.store, program.rules, profile=profile)
                materializer.checks = early_checks(self.ruleset)  # those final early run beside the fixpoint
                stats = materializer.run(count=False)  # counted after the fixpoint (close_full)
                failed = False
            finally:
                try:
                    program.drop(self.store)
                except Exception:
                    if not failed:
                        raise
                    # the run's own error is the one to report; the next full REASON drops these graphs first
        start = time.perf_counter()
        # where the keys the rules and checks read have facts: the checks read a key of one graph
        # there, and maintenance starts from the keys with facts (one query for both); the checks
        # beside the publication where the store overlaps (:mod:`.closing`)
        closed = close_full(self.store, self.ruleset, self.key_graphs, asserted.result(), materializer.checked)
        keys, violations = closed.keys, closed.violations
        stats.derived = closed.inferred
        stats.mode, stats.reason = "full", why
        # "quiet": the closure is the stratum-0 fixpoint, which maintenance keeps up to date
        # (a negated premise may have fired and stopped matching since, so ask the run)
        self.state = MaintenanceState(True, not materializer.upper_derived, closed.asserted, violations,
                                      with_facts(keys), with_facts(keys, ASSERTED))
        if self._parts is not None:
            self.change_checks.state = self.state
        stats.seconds += time.perf_counter() - start
        return stats, violations

    def _full_reason(self, change: int, mode: str) -> str:
        """Why the next REASON must recompute everything ("" when maintenance is sound)."""
        if mode == "full":
            return "full rematerialisation requested"
        if not self.state.ready:
            return "no previous materialisation with the current rules (first REASON or schema changed)"
        if self._unmaintainable:
            return f"rules with negated premises in stratum 0 cannot be maintained: {', '.join(self._unmaintainable)}"
        if not self.state.quiet:
            return "a rule with a negated premise (stratum 1, e.g. owl:sameAs by 'not known different') matched before"
        limit = self.max_change_share * max(self.state.asserted_size, 1)
        if mode == "auto" and change > limit:
            return (f"change of {change} asserted triples exceeds {self.max_change_share:.0%} "
                    f"of {self.state.asserted_size}")
        return ""

    # ------------------------------------------------------------------ maintenance
    def _maintain(self, added: Collection[Triple], removed: Collection[Triple], stats: ReasonStats,
                  profile: bool) -> None:
        if not added and not removed:
            return
        self.flips.note(added, removed)
        requests = self.requests
        copy_changes = LaterCopies(requests, ((added, ADDED), (removed, REMOVED)))
        if self.store.round_trips:
            copy_changes()  # queued with the program's request
        change = read_change(added, removed)  # each triple read once, for the kind and the replacements
        preds, classes = change.census
        lost = change.lost  # read by the completion's decision and the program's signature alike
        state = self.state
        for keys in (state.present, state.asserted):
            keys[0].update(preds)
            keys[1].update(classes)
        replaced = self.kinds.replaced(self.store, change, ASSERTED)
        sig, discard, ask_again = self.kinds.maintained((preds, classes), lost, replaced, state, self.step,
                                                        self._completion if self.deferred else None)
        if discard:
            requests.discard(added, (INFERRED, AUX))
        if not ask_again and self.step.run(added, removed, replaced, stats, state, (preds, classes),
                                           copy_changes, lost, sig):
            self._incomplete = bool(self.deferred and removed) and self._completion.needed(
                self.state.present, self.step.lost_keys)
            return
        copy_changes()
        self.step.forget_runs()  # the general phases may change the keys with facts either way
        try:
            self._general(added, removed, stats, profile, (preds, classes), replaced)
        finally:
            self._completion.forget()

    def _general(self, added: Collection[Triple], removed: Collection[Triple], stats: ReasonStats, profile: bool,
                 census: tuple, replaced: dict) -> None:
        """The general phases (flips, over-deletion and rederivation, semi-naive additions) of a change
        no compiled step maintains."""
        requests = self.requests
        preds, classes = census
        requests.flush()  # the scratch copies are read from here on
        skip, lost, gained_rules = self.flips.find(self.state, added, removed, (preds, classes), stats, replaced)
        if removed:
            self.deletion.overdelete(self.state, stats, skip, lost)
            self.deletion.rederive(self.state, stats)
        if gained_rules:
            requests.start(FLIP_GAINED)
        for i in sorted(gained_rules):
            requests.run(("flip-gained", i), self.deletion.rederive_text, i, FLIP_GAINED, stats)
        requests.defer(f"ADD SILENT {ADDED} TO {NEW_FACTS}")
        requests.flush()
        m = Materializer(self.store, self.ruleset, profile=profile, triggers=self.triggers)  # the general path only
        m.present = self.state.present
        m.planned = True
        m.propagate(self.monotone, stats, seed=ADDED, record=NEW_FACTS, skip_first=skip)
        if self.deferred and removed:
            self._ask_again(m, stats)

    def _ask_again(self, m: Materializer, stats: ReasonStats) -> None:
        """Ask the value rules again about the pairs a full REASON left out because their conclusion was
        known, when this maintenance lost a fact that may have held such a conclusion (:mod:`.negation`);
        what the asks derive is propagated as new facts."""
        lost = self.store.census_many([OVERDELETED])[OVERDELETED]
        self._completion.forget()  # the propagation changed the keys with facts
        if not self._completion.needed(self.state.present, lost, asserted=True):
            return
        try:
            self.store.update(" ;\n".join(completion_text(self.rules[i], ASKED) for i in self.deferred),
                              prefixes=PREFIXES)
            stats.evaluations += len(self.deferred)
            m.propagate(self.monotone, stats, seed=ASKED, record=NEW_FACTS)
        finally:
            self.store.update(f"DROP SILENT GRAPH {ASKED}")

    def key_graphs(self) -> dict:
        """Which of the asserted, inferred and helper graphs hold facts of each key a rule or check
        body reads (after a full run): maintenance only ever asks about those keys
        (:meth:`.Triggers.feasible`), and the checks read a key of one graph there."""
        return key_graphs(self.store, self._needed, [ASSERTED, INFERRED, AUX])

    def _clear_scratch(self) -> None:
        """Drop the scratch graphs (with what the queue holds: one request)."""
        self.changed.forget()
        self.requests.drop(DROPPED)
        self.requests.flush()


__all__ = ["IncrementalReasoner", "MaintenanceState", "DEFAULT_MAX_CHANGE_SHARE", "MODES", "can_prove", "check_mode",
           "negates_exists", "is_monotone"]
