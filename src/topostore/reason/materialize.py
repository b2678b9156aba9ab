"""Semi-naive materialisation of a rule set into the inferred graphs.

Round 0 evaluates every rule on the whole data.  Each later round evaluates
only the rules that read a predicate or class that changed in the previous
round, and for each such body atom once with that atom restricted to the
*delta* graph (the facts derived in the previous round).  A rule whose filters
read something that changed is evaluated in full.  The loop stops when a
round derives nothing new.

Derived facts go to ``NEW_INFERRED`` / ``NEW_AUX`` first (never re-deriving a
fact already present), then become the next delta.  A full run (:meth:`Materializer.run`)
writes each derived fact straight into its final graph *and* into the next delta, two
graphs that take turns (:data:`DELTA` and :data:`DELTA_NEXT`): promoting a round is then
dropping the old delta, instead of copying every fact twice more (into the delta and the
inferred graph), which was a third of a full REASON.  Rules with negated premises
(``stratum`` 1: "y1 and y2 are not known to be different, so they are the same")
join only after the positive rules reached their fixpoint.

This module is the run's rounds (the core loop); its parts live beside it: :mod:`.full_passes`
sets up a full run's passes and runs them in order, :mod:`.insert_text` writes the text of one
evaluation and its forms, :mod:`.few_solutions` decides which evaluations keep their known heads
out by a look-up per solution, :mod:`.first_pass` evaluates each ordered component once with its
shortcuts, :mod:`.deferred_asks` runs the candidate rules after the first stratum's fixpoint, and
:mod:`.stats` holds what a REASON reports.
"""

from __future__ import annotations

import time
from collections.abc import Collection

from pyoxigraph import NamedNode

from ..compile.generic import PREFIXES
from ..compile.rule import ReadKey, Rule, RuleSet, key_pattern
from ..rdf.vocab import ASSERTED, AUX, DELTA, INFERRED, INTERNAL, NEW_AUX, NEW_INFERRED
from ..stores.base import Store
from . import limits
from .early_reads import EarlyReads
from .few_solutions import few_solutions
from .full_passes import full_passes
from .insert_text import insert_text
from .keyed_asks import key_censuses
from .keyed_first_pass import keyed_passes
from .negation import Idle, evaluated_last
from .one_group import keys_kept_by_group, one_group, without_group_tests
from .order import TYPE_KEY, is_path
from .plan import KeyCounts, is_small
from .stats import ReasonStats
from .triggers import Present, Triggers, may_hold

#: the other delta graph of a full run: each round reads one and fills the other
DELTA_NEXT = NamedNode(INTERNAL + "graph:delta-next")


class Materializer:
    """Runs a :class:`RuleSet` to its fixpoint over one store's graphs."""

    def __init__(self, store: Store, rules: RuleSet, profile: bool = False, triggers: Triggers | None = None) -> None:
        self.store = store
        self.rules = rules.inference_rules
        self.triggers = triggers or Triggers(self.rules)
        self.profile = profile
        self._texts: dict[tuple, str] = {}
        #: when set, evaluations that cannot match are skipped (see :meth:`.Triggers.feasible`);
        #: the keys of every delta are added to it, so it stays a superset
        self.present: Present | None = None
        #: evaluate delta rounds with :func:`.plan.plan_where` (set by incremental runs)
        self.planned = False
        #: set by :meth:`run` when a rule above the first stratum derived something,
        #: i.e. the closure is not the fixpoint of the first stratum alone
        self.upper_derived = False
        self._queue: list[str] = []
        #: the keys the evaluations in :attr:`_queue` may write (not in the store until :meth:`_flush`)
        self._queued: set[ReadKey | None] = set()
        self._lateral = store.supports_lateral
        #: (delta read, next delta) while :meth:`run` writes derived facts straight to their graphs
        self._direct: tuple[NamedNode, NamedNode] | None = None
        #: while :meth:`run` evaluates the ordered first stratum: the one graph of some read keys
        self._graphs: dict[ReadKey, NamedNode] | None = None
        #: the keys rules of :meth:`run` have written so far
        self._derived: set[ReadKey] = set()
        #: the needed keys with asserted facts at the start of :meth:`run`, and the rules of its ordered
        #: pass whose first evaluation reads those alone (:func:`.implied_passes.implied_first_passes`)
        self._asserted: Present = (set(), set())
        #: while :meth:`run` runs: whether the asserted graph holds a fact of a head's key, by key
        self._asserted_heads: dict[ReadKey, bool] = {}
        self._implied: set[int] = set()
        #: keys put in :attr:`present` by a first pass before the evaluation writing them ran
        self._claimed: set[ReadKey] = set()
        #: while :meth:`run` reaches its fixpoint: the candidate rules it evaluates last (:mod:`.negation`)
        self._deferring: set[int] = set()
        #: of those, the ones asking nothing a twin could be published for on derived facts of a key
        #: (:func:`.negation.idle_asks`): by rule, that key, whose asserted facts alone they read
        self._idle: dict[int, Idle] = {}
        #: rules of :meth:`run`'s ordered pass whose first evaluation leaves out class atoms another
        #: atom implies (:func:`.implied_passes.implied_atoms`), as the rule that first evaluation runs
        self._lean: dict[int, Rule] = {}
        #: rules of :meth:`run`'s ordered pass evaluated as one per class (:mod:`.class_unions`): by the
        #: first of each group the others, and every other
        self._unions: dict[int, tuple[int, ...]] = {}
        self._joined: set[int] = set()
        #: rules of :meth:`run`'s ordered pass whose property paths read asserted facts alone
        self._paths: set[int] = set()
        #: while :meth:`run` reaches its fixpoint: the deferred asks and checks started early (:mod:`.early_reads`)
        self._early: EarlyReads | None = None
        #: the consistency checks a caller will run after :meth:`run`: those whose keys are final early are
        #: run beside the fixpoint, their matches left in :attr:`checked` by their index here
        self.checks: list[Rule] = []
        self.checked: dict[int, list[dict]] = {}
        #: rules with a "two keys of one group" test, left out of their evaluations without delta of a
        #: full run while the store holds one AllDifferent group (:mod:`.one_group`)
        self._grouped: set[int] = ({i for i, r in enumerate(self.rules) if without_group_tests(r) is not None}
                                   if keys_kept_by_group(self.rules) else set())
        #: deferred asks a census of the AllDifferent keys may show empty (:mod:`.keyed_asks`), by rule
        self.censuses = key_censuses(self.rules)
        #: their keyed conclusions, whose first pass may leave the keys out (:mod:`.keyed_first_pass`)
        self.keyed = keyed_passes(self.rules, self.censuses)

    def _run(self, index: int, delta_index: int | None, stats: ReasonStats, asserted_only: bool = False,
             first: bool = False, union: tuple[int, ...] = ()) -> None:
        """Evaluate rule ``index`` (its atom ``delta_index`` on the delta); ``asserted_only``: its one
        atom reads the asserted graph alone (see :func:`.implied_passes.implied_first_passes`); ``first``: the
        first pass of the ordered stratum, which leaves out the atoms :attr:`_lean` says are implied;
        ``union``: rules evaluated with it as one (:mod:`.class_unions`).  An evaluation whose solutions
        the worker found and wrote already (:mod:`.early_rules`) has nothing left to write; a keyed
        conclusion's first pass the census covers leaves its keys out (:mod:`.keyed_first_pass`)."""
        if index in self._deferring:
            return
        keyless = (first and delta_index is None and not union and self._early is not None
                   and self._early.keyless(index))
        text = self.evaluation_text(index, delta_index, asserted_only, first, union, keyless)
        stats.evaluations += 1
        written = self.rules[index].writes()
        found = self._early.evaluated(index, text) if self._early is not None else None
        if found is not None:
            return  # its facts were written by the worker before any read started after its own
        self._queued.add(written)
        if self._early is not None:
            self._early.wrote(written)
        self._timed(text, self.rules[index].name, stats)

    def evaluation_text(self, index: int, delta_index: int | None, asserted_only: bool = False,
                        first: bool = False, union: tuple[int, ...] = (), keyless: bool = False) -> str:
        """The text :meth:`_run` sends for these arguments in the run's present state (kept by its form);
        ``keyless``: a keyed conclusion without its key atoms (:mod:`.keyed_first_pass`)."""
        derived = self._direct is not None and self.rules[index].writes() in self._derived
        bare = self.bare(index)
        lean = first and index in self._lean
        rule = self._lean[index] if lean else self.rules[index]
        if keyless:
            rule = self.keyed[index].lean(rule)
        few = self._direct is not None and delta_index is None and not union and few_solutions(
            self.store, rule, self._queued)
        one = (self._direct is not None and delta_index is None and index in self._grouped and not keyless
               and one_group(self.store, self._queued))
        key = (index, delta_index, self._lateral, self._direct, self._graphs is not None, derived, asserted_only,
               lean, union, few, one, bare, keyless)
        text = self._texts.get(key)
        if text is None:
            graphs = self._graphs
            if asserted_only:
                graphs = {**(graphs or {}), self.rules[index].body[0].read_key(): ASSERTED}
            if graphs is not None and index in self._paths:
                graphs = {**graphs, **{a.read_key(): ASSERTED for a in self.rules[index].body if is_path(a)}}
            text = self._texts[key] = insert_text(rule, delta_index, self.planned, self._lateral,
                                                  self._direct, graphs, derived, [self.rules[j] for j in union], few, one,
                                                  bare)
        return text

    @property
    def delta_read(self) -> NamedNode | None:
        """The delta graph evaluations read while :meth:`run` writes straight to the graphs (None outside)."""
        return self._direct[0] if self._direct is not None else None

    def first_pass_evaluates(self, index: int, present: Present | None = None) -> bool:
        """Whether the ordered first pass of :meth:`run` evaluates rule ``index``, as far as the run's start
        tells: not deferred to the end, not evaluated as part of another rule's class union, its keys able
        to hold facts (in ``present``: by default the keys with facts now)."""
        return (index not in self._deferring and index not in self._joined
                and self.triggers.feasible(index, self.present if present is None else present))

    def first_pass_alone(self, index: int, present: Present | None = None) -> bool:
        """Whether that evaluation is rule ``index``'s alone (no class union led by it)."""
        return index not in self._unions and self.first_pass_evaluates(index, present)

    def first_pass_text(self, index: int) -> str:
        """The text the ordered first pass sends for rule ``index``, evaluated without a delta, in the run's
        present state (its shortcuts and the heads it keeps out as they stand now)."""
        read = self._direct
        if read is not None:
            self._direct = (read[0], None)  # as the first pass evaluates it: no next delta written
        try:
            return self.evaluation_text(index, None, index in self._implied, first=True)
        finally:
            self._direct = read

    def _flush(self) -> None:
        """Send the queued evaluations of a round as one update request.

        They all insert into NEW_* graphs, which none of them reads, so one
        request gives the same result and saves the per-request cost.
        """
        self._queued.clear()
        if self._queue:
            text = " ;\n".join(self._queue)
            self._queue.clear()
            self.store.update(text, prefixes=PREFIXES)

    def _promote(self, seed: NamedNode | None = None, record: NamedNode | None = None) -> KeyCounts | None:
        """Queue moving the facts of this round into the inferred graphs, as the next delta.

        ``seed`` (a graph of facts already stored, e.g. newly asserted triples)
        joins the delta; ``record`` accumulates every promoted fact, so that an
        incremental run knows what is new since the previous state.  Returns the
        read keys of the next delta (None when it is empty); the moves go with
        the round's evaluations in one request.
        """
        if self._direct is not None:
            return self._turn()
        census = self.store.census_many([g for g in (NEW_INFERRED, NEW_AUX, seed) if g is not None])
        parts = [g for g, (preds, _) in census.items() if preds]
        if not parts:
            return None
        counts = _merge(census[g] for g in parts)
        seeded = seed in parts
        ops = [f"DROP SILENT GRAPH {DELTA}", f"ADD SILENT {NEW_INFERRED} TO {DELTA}", f"ADD SILENT {NEW_AUX} TO {DELTA}"]
        if seeded:
            ops.append(f"ADD SILENT {seed} TO {DELTA}")
        ops += [f"ADD SILENT {NEW_INFERRED} TO {INFERRED}", f"ADD SILENT {NEW_AUX} TO {AUX}"]
        if record is not None:
            ops += [f"ADD SILENT {NEW_INFERRED} TO {record}", f"ADD SILENT {NEW_AUX} TO {record}"]
        ops += [f"DROP SILENT GRAPH {NEW_INFERRED}", f"DROP SILENT GRAPH {NEW_AUX}"]
        self._queue.insert(0, " ; ".join(ops))
        return counts

    def _turn(self) -> KeyCounts | None:
        """Promote a round of the full run: the filled next delta becomes the delta read.

        Its facts are already in their final graphs; the old delta is dropped (queued first in
        the round's request) and becomes the graph the round fills.
        """
        read, filled = self._direct
        (preds, classes), = self.store.census_many([filled]).values()
        if not preds:
            return None
        self._direct = (filled, read)
        self._queue.insert(0, f"DROP SILENT GRAPH {read}")
        return preds, classes

    def propagate(self, active: list[int], stats: ReasonStats, seed: NamedNode | None = None,
                  record: NamedNode | None = None, skip_first: Collection[tuple[int, int]] = ()) -> None:
        """Semi-naive rounds until nothing new: the facts in NEW_* (and ``seed``) are the first delta.

        Shared by the full run and by incremental maintenance, which seeds it
        with the added asserted triples and the rederived facts.  The first
        round leaves out the (rule, delta atom) evaluations in ``skip_first``
        (their effect of the seed was found otherwise, see :mod:`.flip`).
        """
        skip = skip_first
        while (counts := self._promote(seed, record)) is not None:
            seed = None
            stats.rounds += 1
            self._delta_round(active, stats, counts, skip)
            skip = ()

    def _delta_round(self, active: list[int], stats: ReasonStats, counts: KeyCounts,
                     skip: Collection[tuple[int, int]] = ()) -> None:
        preds, classes = counts
        limits.tick(sum(preds.values()), lambda: limits.writers(self.rules, preds, classes))
        if self.profile:
            self._flush()  # the promotion first: profiled evaluations do not wait in the queue
        if self.planned:
            self._lateral = is_small((preds, classes)) and self.store.supports_lateral
        if self.present is not None:
            self.present[0].update(preds)
            self.present[1].update(classes)
        if self._direct is not None:
            self._derived.update([("p", p) for p in preds] + [("t", c) for c in classes])
        for i, j in self.triggers.evaluations(preds, classes, self._active(active), self.present, skip):
            self._run(i, j, stats)
        self._flush()

    def _active(self, active: list[int]) -> set[int] | range:
        if len(active) == len(self.rules):
            return range(len(self.rules))
        return set(active)

    def clear(self) -> None:
        self.store.update(
            " ; ".join(f"DROP SILENT GRAPH {g}" for g in (INFERRED, AUX, DELTA, DELTA_NEXT, NEW_INFERRED, NEW_AUX))
        )

    def run(self, count: bool = True) -> ReasonStats:
        """Recompute the inferred graphs from the asserted graph alone (``count``: the inferred graph's
        size into the stats; a caller counting it beside other reads, :mod:`.closing`, says no).

        The first stratum is evaluated component by component of the rule
        dependency graph, in topological order (:func:`evaluation_order`): a rule
        runs once everything it reads is complete, so a non-recursive rule such
        as a SWRL rule is evaluated exactly once instead of once per round that
        touched one of its inputs.  Rules that read or write any predicate
        (owl:sameAs replacement) and the upper strata then run, followed by
        ordinary semi-naive rounds over every rule, which changes nothing unless
        they derived something.  Derived facts go straight to their graphs and to
        the next delta (:meth:`_turn`): no round copies them.
        """
        start = time.perf_counter()
        stats = ReasonStats()
        self.checked = {}
        self.clear()
        self._derived = set()
        self._direct = (DELTA, DELTA_NEXT)
        later, self._idle = evaluated_last(self.rules)
        self._deferring = later | set(self._idle)
        try:
            full_passes(self, stats)
        finally:
            self._direct = None
            self._deferring = set()
            self.store.update(f"DROP SILENT GRAPH {DELTA} ; DROP SILENT GRAPH {DELTA_NEXT}")
        if count:
            stats.derived = self.store.count(INFERRED)
        stats.seconds = time.perf_counter() - start
        return stats

    def _timed(self, text: str, name: str, stats: ReasonStats) -> None:
        """Queue ``text`` (sent by :meth:`_flush`, one request per round), or send it and time it under
        ``name`` when profiling."""
        if not self.profile:
            self._queue.append(text)
            return
        start = time.perf_counter()
        self.store.update(text, prefixes=PREFIXES)
        stats.per_rule[name] = stats.per_rule.get(name, 0.0) + time.perf_counter() - start

    def bare(self, index: int) -> bool:
        """Whether an evaluation of rule ``index`` in a full run finds no fact of its head's key in any
        graph: none derived so far nor queued, none asserted (:func:`.insert_text.insert_text`'s ``bare``).
        A remote store keeps its anti-joins: a look-up there is a request of its own."""
        key = self.rules[index].writes()
        if self._direct is None or self.store.round_trips or key is None or key[0] == "*" or key == ("p", TYPE_KEY):
            return False  # not a full run, a remote store, or a head of any predicate or class
        return (not may_hold(self._derived, key) and None not in self._queued and not may_hold(self._queued, key)
                and not self._head_asserted(key))

    def _head_asserted(self, key: ReadKey) -> bool:
        """Whether the asserted graph holds a fact of head key ``key``, a predicate or a class (one look-up
        per key and run)."""
        found = self._asserted_heads.get(key)
        if found is None:
            found = self._asserted_heads[key] = next(
                iter(self.store.triples(*key_pattern(key), ASSERTED)), None) is not None
        return found

    def _has_asserted(self, key: ReadKey) -> bool:
        """Whether read key ``key`` had an asserted fact when :meth:`run` started."""
        return key[1] in self._asserted[1 if key[0] == "t" else 0]


def _merge(parts) -> KeyCounts:
    """The read-key counts of several graphs together."""
    preds: dict[str, int] = {}
    classes: dict[str, int] = {}
    for p, c in parts:
        for k, n in p.items():
            preds[k] = preds.get(k, 0) + n
        for k, n in c.items():
            classes[k] = classes.get(k, 0) + n
    return preds, classes
