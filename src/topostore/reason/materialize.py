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
"""

from __future__ import annotations

import time
from collections.abc import Collection, Mapping, Sequence
from dataclasses import dataclass, field, replace
from itertools import islice

from pyoxigraph import NamedNode

from ..compile.generic import PREFIXES
from ..compile.rule import ReadKey, Rule, RuleSet, key_pattern
from ..compile.schema import schema_dataset
from ..rdf.vocab import ASSERTED, AUX, DELTA, INFERRED, INTERNAL, NEW_AUX, NEW_INFERRED
from ..stores.base import Store
from . import limits
from .class_unions import class_unions, lead_first, union_where
from .key_pairs import grouped_form
from .negation import Idle, evaluated_last, unless_known_text
from .order import (
    TYPE_KEY,
    asserted_paths,
    evaluation_order,
    implied_atoms,
    implied_first_passes,
    is_path,
    reachable,
    single_graphs,
)
from .plan import KeyCounts, is_small, plan_where
from .triggers import Present, Triggers

DATASET = f"USING {ASSERTED} USING {INFERRED} USING {AUX} USING NAMED {AUX} USING NAMED {DELTA}"
#: the other delta graph of a full run: each round reads one and fills the other
DELTA_NEXT = NamedNode(INTERNAL + "graph:delta-next")
#: at most this many solutions make a one-atom evaluation :meth:`Materializer._few` (a look-up each, ≈ 9 µs)
FEW = 200
#: ... against a head extent of more than this many facts per solution (reading one costs ≈ 1–1.6 µs)
EXTENT_PER_SOLUTION = 8


@dataclass
class ReasonStats:
    """What one REASON did: rounds, rule evaluations, facts derived, time."""

    rounds: int = 0
    evaluations: int = 0
    derived: int = 0
    seconds: float = 0.0
    mode: str = "full"
    #: why this mode was chosen (e.g. "schema changed", "change of 5000 triples > 10% of ...")
    reason: str = ""
    #: incremental maintenance only: facts over-deleted and put back by rederivation
    overdeleted: int = 0
    rederived: int = 0
    #: incremental only: rule evaluations replaced by one flip query (replaced values only compared)
    flipped: int = 0
    #: incremental only: "compiled" when the compiled step ran (see :mod:`.program`), with what it handed
    #: to the general phases; else why the general phases ran instead
    program: str = ""
    per_rule: dict[str, float] = field(default_factory=dict)


def insert_text(rule: Rule, delta_index: int | None = None, planned: bool = False, lateral: bool = True,
                direct: tuple[NamedNode, NamedNode | None] | None = None,
                graphs: Mapping[ReadKey, NamedNode] | None = None, derived: bool = False,
                union: Sequence[Rule] = (), few: bool = False) -> str:
    """The INSERT evaluating ``rule`` (atom ``delta_index`` on the delta) into NEW_*.

    ``planned`` uses :func:`.plan.plan_where` for delta evaluations (delta atom
    first, rest per delta fact), whose cost follows the delta rather than the data.
    ``direct`` = (delta read, next delta) writes the head into its final graph and into the
    next delta (None: no delta) instead of NEW_* (the full run's rounds, see :meth:`Materializer.run`).
    ``graphs``: the one graph holding each of some read keys (:func:`.order.single_graphs`), read
    there instead of in the whole default dataset (unplanned evaluations only).  ``derived``: the
    head's key already has derived facts, which a rule without delta keeps out too.  ``union``: rules
    concluding the same class, evaluated with ``rule`` as one (:mod:`.class_unions`; no delta).
    ``few``: the evaluation has few solutions against a large head extent (:meth:`Materializer._few`),
    so the heads known are kept out by a look-up per solution instead of reading the extent.
    """
    final = AUX if rule.head_aux() else INFERRED
    target = NEW_AUX if rule.head_aux() else NEW_INFERRED
    head = rule.head.text()
    delta = DELTA if direct is None else direct[0]
    small = planned and delta_index is not None and lateral
    if planned and delta_index is not None:
        where = plan_where(rule, delta_index, delta, lateral=lateral)
    else:
        where = rule.where(delta_index, str(delta), graphs)
    pair = grouped_form(rule) if direct is not None and delta_index is None else None
    if union:
        where = union_where((rule, *union), graphs)
    elif pair is not None:
        where = pair.where(graphs)
    elif direct is not None and delta_index is None and distinct_pays(rule):
        where = f"{{ SELECT DISTINCT {' '.join(sorted(rule.head.variables()))} WHERE {{\n  {where}\n  }} }}"
    into = f"GRAPH {target} {{ {head} }}" if direct is None else f"GRAPH {final} {{ {head} }}"
    if direct is not None and direct[1] is not None:
        into += f" GRAPH {direct[1]} {{ {head} }}"
    dataset = (DATASET if direct is None else DATASET.replace(str(DELTA), str(delta))) + schema_dataset(rule)
    named = {graphs[a.read_key()] for r in (rule, *union) for a in r.body
             if not a.aux and a.read_key() in graphs} if graphs else set()
    named -= {AUX, delta}
    known = new_only(rule, small or few)
    if direct is not None and direct[1] is None and not derived:
        # no delta and no derived fact of the head's key yet: only the asserted facts are kept out
        # (an inferred fact is never an asserted one); once another rule derived facts of the key,
        # writing them again costs more than the anti-join (a write looks up six indexes)
        known = new_only(rule, small or few, ASSERTED)
        named.add(ASSERTED)
    dataset += "".join(f" USING NAMED {g}" for g in sorted(named, key=str))
    return f"INSERT {{ {into} }}\n{dataset}\nWHERE {{\n  {where}\n  {known}\n}}"


def distinct_pays(rule: Rule) -> bool:
    """Whether a full run's evaluation of ``rule`` without delta projects its matches on the head first.

    A class head on one variable from a body with more (a domain ``p(x, y) ⟹ C(x)``, a restriction
    ``p(x, y1) ∧ p(x, y2) ∧ … ⟹ R(x)``) matches once per value: writing a membership again looks
    up six indexes, hashing it away costs less (10,000 locations: ≥2 hasDoor 205 → 185 ms, ∃hasDoor
    65 → 47 ms).  Where each match is a new head (two-variable heads such as a difference by
    values) the hashing only costs (158 → 183 ms), so they keep the plain form.
    """
    head = rule.head
    return (head is not None and head.p == TYPE_KEY and not head.o.startswith("?")
            and len(head.variables()) == 1 and len({v for a in rule.body for v in a.variables()} | set(rule.binds)) > 1)


def new_only(rule: Rule, small: bool, graph: NamedNode | None = None) -> str:
    """The line that keeps the heads already known out of an evaluation.

    ``FILTER NOT EXISTS`` is a look-up per solution (≈ 9 µs each in Oxigraph), right for a small
    delta; ``MINUS`` reads the head's facts once and anti-joins them (a rule over 10,000 facts:
    9 ms instead of 92 ms).  Both mean the same when the head has a variable, which every solution
    binds (a rule's head variables come from its body); a ground head keeps ``NOT EXISTS``, as
    ``MINUS`` with no shared variable removes nothing.  ``graph`` looks in that graph only.
    """
    head = rule.head.text() if graph is None else f"GRAPH {graph} {{ {rule.head.text()} }}"
    if small or not rule.head.variables():
        return f"FILTER NOT EXISTS {{ {head} }}"
    return f"MINUS {{ {head} }}"


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
        #: pass whose first evaluation reads those alone (:func:`.order.implied_first_passes`)
        self._asserted: Present = (set(), set())
        self._implied: set[int] = set()
        #: keys put in :attr:`present` by a first pass before the evaluation writing them ran
        self._claimed: set[ReadKey] = set()
        #: while :meth:`run` reaches its fixpoint: the candidate rules it evaluates last (:mod:`.negation`)
        self._deferring: set[int] = set()
        #: of those, the ones asking nothing a twin could be published for on derived facts of a key
        #: (:func:`.negation.idle_asks`): by rule, that key, whose asserted facts alone they read
        self._idle: dict[int, Idle] = {}
        #: rules of :meth:`run`'s ordered pass whose first evaluation leaves out class atoms another
        #: atom implies (:func:`.order.implied_atoms`), as the rule that first evaluation runs
        self._lean: dict[int, Rule] = {}
        #: rules of :meth:`run`'s ordered pass evaluated as one per class (:mod:`.class_unions`): by the
        #: first of each group the others, and every other
        self._unions: dict[int, tuple[int, ...]] = {}
        self._joined: set[int] = set()
        #: rules of :meth:`run`'s ordered pass whose property paths read asserted facts alone
        self._paths: set[int] = set()

    def _run(self, index: int, delta_index: int | None, stats: ReasonStats, asserted_only: bool = False,
             first: bool = False, union: tuple[int, ...] = ()) -> None:
        """Evaluate rule ``index`` (its atom ``delta_index`` on the delta); ``asserted_only``: its one
        atom reads the asserted graph alone (see :func:`.order.implied_first_passes`); ``first``: the
        first pass of the ordered stratum, which leaves out the atoms :attr:`_lean` says are implied;
        ``union``: rules evaluated with it as one (:mod:`.class_unions`)."""
        if index in self._deferring:
            return
        derived = self._direct is not None and self.rules[index].writes() in self._derived
        lean = first and index in self._lean
        few = self._direct is not None and delta_index is None and not union and self._few(
            self._lean[index] if lean else self.rules[index])
        key = (index, delta_index, self._lateral, self._direct, self._graphs is not None, derived, asserted_only,
               lean, union, few)
        text = self._texts.get(key)
        if text is None:
            graphs = self._graphs
            if asserted_only:
                graphs = {**(graphs or {}), self.rules[index].body[0].read_key(): ASSERTED}
            if graphs is not None and index in self._paths:
                graphs = {**graphs, **{a.read_key(): ASSERTED for a in self.rules[index].body if is_path(a)}}
            rule = self._lean[index] if lean else self.rules[index]
            text = self._texts[key] = insert_text(rule, delta_index, self.planned, self._lateral,
                                                  self._direct, graphs, derived, [self.rules[j] for j in union], few)
        stats.evaluations += 1
        self._queued.add(self.rules[index].writes())
        self._timed(text, self.rules[index].name, stats)

    def _few(self, rule: Rule) -> bool:
        """Whether a full run's evaluation of ``rule`` without delta keeps its known heads out by a
        look-up per solution (``FILTER NOT EXISTS``) rather than by reading the head's whole extent
        (``MINUS``): a body of one atom whose key has at most :data:`FEW` facts (so at most as many
        solutions) against a head key with more than :data:`EXTENT_PER_SOLUTION` times as many.

        A range over a handful of derived links (``canReach(r, y) ⟹ LOCATION(y)``, two links) anti-joined
        with every LOCATION read 100,000 memberships: 11 ms at 10,000 locations, 167 ms at 100,000 (see
        docs/benchmarks.md, "Full REASON from 10,000 to 100,000 locations").  Both forms mean the same
        (:func:`new_only`); only stores read without a round trip are asked (bounded index reads, in
        the graphs of the default dataset).  A body key an evaluation waiting in the queue may write
        (:attr:`_queued`) is not counted: the store does not hold those facts yet.
        """
        if self.store.round_trips or len(rule.body) != 1 or rule.head is None or not rule.head.variables():
            return False
        body, head = rule.body[0].read_key(), rule.writes()
        if any(k[0] not in ("p", "t") or not k[1].startswith("<") or k == ("p", TYPE_KEY) for k in (body, head)):
            return False  # a key of any predicate or class, or a path: counted by no index read
        queued = self._queued
        if body in queued or ("*",) in queued or (body[0] == "t" and ("p", TYPE_KEY) in queued):
            return False
        solutions = self._facts(body, FEW)
        return solutions <= FEW and self._facts(head, EXTENT_PER_SOLUTION * solutions) > EXTENT_PER_SOLUTION * solutions

    def _facts(self, key: ReadKey, limit: int) -> int:
        """The facts of ``key`` in the asserted, inferred and helper graphs, counted up to ``limit + 1``."""
        pattern = key_pattern(key)
        found = 0
        for graph in (ASSERTED, INFERRED, AUX):
            found += sum(1 for _ in islice(self.store.triples(*pattern, graph), limit + 1 - found))
            if found > limit:
                break
        return found

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

    def _asserted_keys(self) -> Present:
        """The predicates and classes rule bodies need that have an asserted fact (one look-up each)."""
        preds: set[str] = set()
        classes: set[str] = set()
        for kind, key in self.triggers.needed_keys():
            if next(iter(self.store.triples(*key_pattern((kind, key)), ASSERTED)), None) is not None:
                (classes if kind == "t" else preds).add(key)
        return preds, classes

    def clear(self) -> None:
        self.store.update(
            " ; ".join(f"DROP SILENT GRAPH {g}" for g in (INFERRED, AUX, DELTA, DELTA_NEXT, NEW_INFERRED, NEW_AUX))
        )

    def run(self) -> ReasonStats:
        """Recompute the inferred graphs from the asserted graph alone.

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
        self.clear()
        self._derived = set()
        self._direct = (DELTA, DELTA_NEXT)
        later, self._idle = evaluated_last(self.rules)
        self._deferring = later | set(self._idle)
        try:
            self._materialize(stats)
        finally:
            self._direct = None
            self._deferring = set()
            self.store.update(f"DROP SILENT GRAPH {DELTA} ; DROP SILENT GRAPH {DELTA_NEXT}")
        stats.derived = self.store.count(INFERRED)
        stats.seconds = time.perf_counter() - start
        return stats

    def _ask_unknown(self, stats: ReasonStats, active: list[int]) -> None:
        """After the first stratum's fixpoint: the deferred candidate rules without the pairs whose
        conclusion is known (:mod:`.negation`), then the rounds their facts trigger among ``active``."""
        rules, self._deferring = sorted(self._deferring), set()
        # written by the asks queued before a later one reads them
        asking = {w for i in rules if (w := self.rules[i].writes()) is not None}
        for i in rules:
            if not self.triggers.feasible(i, self.present):
                continue
            idle = self._idle.get(i)
            if idle is not None and any(self.triggers.feasible(w, self.present) for w in idle.others):
                idle = None  # a rule of a variable predicate may have written the key
            key = idle.key if idle is not None else None
            if key is None:
                text = insert_text(self.rules[i], None, self.planned, self._lateral, self._direct,
                                   self._only_asserted(self.rules[i], asking))
                if self.rules[i].unless_known is not None:
                    text = unless_known_text(text, self.rules[i])
            elif next(iter(self.store.triples(*key_pattern(key), ASSERTED)), None) is not None:
                # its asks on derived facts of the key are idle: the asserted ones alone
                text = insert_text(self.rules[i], None, self.planned, self._lateral, self._direct, {key: ASSERTED})
            else:
                continue
            stats.evaluations += 1
            self._queued.add(self.rules[i].writes())
            self._timed(text, self.rules[i].name, stats)
        if rules:
            self._flush()
            stats.rounds += 1
            self.propagate(active, stats)

    def _only_asserted(self, rule: Rule, asking: Collection[ReadKey] = ()) -> dict[ReadKey, NamedNode]:
        """The read keys of ``rule``'s body whose facts are all asserted so far in :meth:`run`: read
        there alone (one index look-up per pattern instead of one per graph of the default dataset).

        A key had asserted facts at the start and no rule of this run wrote it (:attr:`_derived`
        holds every key written: the first passes add theirs, every round its delta's).  A rule of a
        variable predicate may have written any key, one of a variable class any class: then the
        keys they may cover stay on the default dataset.  The deferred ask of Connectability's
        candidate reads its 20,000 door facts so: 65 → 54 ms at 10,000 locations.  ``asking``: the
        keys the deferred asks write, which a later one of them may read before they reach a delta.
        """
        written = self._derived | set(asking)
        if any(k[0] == "*" for k in written):
            return {}
        any_class = ("p", TYPE_KEY) in written or any(k[0] == "t" for k in asking)
        out: dict[ReadKey, NamedNode] = {}
        for atom in rule.body:
            key = atom.read_key()
            if atom.aux or key[0] not in ("p", "t") or key == ("p", TYPE_KEY) or key in written:
                continue
            if (key[0] == "t" and any_class) or not self._has_asserted(key):
                continue
            out[key] = ASSERTED
        return out

    def _timed(self, text: str, name: str, stats: ReasonStats) -> None:
        """Queue ``text`` (sent by :meth:`_flush`, one request per round), or send it and time it under
        ``name`` when profiling."""
        if not self.profile:
            self._queue.append(text)
            return
        start = time.perf_counter()
        self.store.update(text, prefixes=PREFIXES)
        stats.per_rule[name] = stats.per_rule.get(name, 0.0) + time.perf_counter() - start

    def _first_pass(self, component: list[int], back: set[int], stats: ReasonStats) -> None:
        """Evaluate a component's rules once each, in order, in one request.

        Operations of one request see what the earlier ones wrote, so a rule's facts are already
        read by every later rule of the pass: they go to the next delta only for a rule in
        ``back`` (a rule of the pass at or before it reads them) or with a head of any class or
        predicate.  The key a rule without delta writes joins :attr:`present` at once (a
        superset, as it must be), so later rules of the pass are not skipped for want of it.
        """
        read = self._direct
        for i in component:
            if i in self._joined:
                continue  # evaluated with the first rule of its class union
            members = [m for m in (i, *self._unions.get(i, ()))
                       if self.triggers.feasible(m, self.present) and self._claims_hold(m)]
            if not members:
                continue
            i, *union = lead_first(self.rules, members)
            union = tuple(union)
            asserted_only = i in self._implied
            if asserted_only and not self._has_asserted(self.rules[i].body[0].read_key()):
                continue  # every fact it reads is derived, and what it concludes of them holds already
            key = self.rules[i].writes()
            if i in back or key[0] == "*" or key == ("p", TYPE_KEY):
                self._run(i, None, stats, asserted_only, first=True)
                self._derived.add(key)
                continue
            self._direct = (read[0], None)
            try:
                self._run(i, None, stats, asserted_only, first=True, union=union)
            finally:
                self._direct = read
            self._derived.add(key)
            if key[1] not in self.present[1 if key[0] == "t" else 0]:
                self._claimed.add(key)
            self.present[1 if key[0] == "t" else 0].add(key[1])
            if key[0] == "t":
                self.present[0].add(TYPE_KEY)
        self._flush()
        stats.rounds += 1

    def _claims_hold(self, i: int) -> bool:
        """Whether rule ``i`` can still match once the keys it reads that earlier rules of the pass only
        claimed (:attr:`_claimed`: put in :attr:`present` before their evaluation ran) are looked up.

        A claim is a superset, as :attr:`present` must be; but a rule that wrote nothing leaves its
        readers to scan for nothing (the six disjoint-classes rules over 10,000 doors and locations,
        asking about pairs no rule asked about).  The queued evaluations are sent first, so that the
        look-up sees what they wrote: one request more per pass that needs it.
        """
        keys = {a.read_key() for a in self.rules[i].body} & self._claimed
        if not keys:
            return True
        self._flush()
        for key in keys:
            self._claimed.discard(key)
            pattern = key_pattern(key)
            if not any(next(iter(self.store.triples(*pattern, g)), None) is not None for g in (INFERRED, AUX, ASSERTED)):
                self.present[1 if key[0] == "t" else 0].discard(key[1])
        return self.triggers.feasible(i, self.present)

    def _has_asserted(self, key: ReadKey) -> bool:
        """Whether read key ``key`` had an asserted fact when :meth:`run` started."""
        return key[1] in self._asserted[1 if key[0] == "t" else 0]

    def _materialize(self, stats: ReasonStats) -> None:
        """The passes of :meth:`run`: components in order, then the rest and the upper strata."""
        # keys with facts so far; each round's delta adds its keys (_delta_round), so a rule
        # skipped here for an empty key runs as soon as that key gets a fact, with it as the delta
        self.present = self._asserted_keys()
        strata = sorted({r.stratum for r in self.rules}) or [0]
        first = [i for i, r in enumerate(self.rules) if r.stratum == strata[0]]
        # rules that cannot fire in the first stratum stay out of its order: left in, one such rule
        # (eq-rep-s without any owl:sameAs) ties every class reader and writer into one component
        # whose rules are then evaluated round after round; a key they need that an upper stratum
        # derives triggers them on its delta, which finds all they derive
        possible = reachable(self.triggers, first, self.present)
        first = [i for i in first if self.triggers.feasible(i, possible)]
        ordered, rest, back = evaluation_order(self.rules, first)
        # until the rules of a variable predicate and the upper strata run, only the ordered rules
        # write, so a key's facts lie where its asserted facts and its writers put them
        asserted = self._asserted = (set(self.present[0]), set(self.present[1]))
        self._claimed = set()
        self._implied = implied_first_passes(self.rules, [i for c in ordered for i in c])
        self._lean = {i: _without(self.rules[i], atoms)
                      for i, atoms in implied_atoms(self.rules, [i for c in ordered for i in c], asserted).items()}
        self._graphs = single_graphs(self.rules, [i for c in ordered for i in c], self.triggers.needed_keys(),
                                     asserted, lambda r: AUX if r.head_aux() else INFERRED, ASSERTED)
        self._unions = class_unions(self.rules, ordered, back, self._graphs, ASSERTED, distinct_pays,
                                    self._implied | set(self._lean) | self._deferring)
        self._joined = {j for others in self._unions.values() for j in others}
        self._paths = asserted_paths(self.rules, [i for c in ordered for i in c])
        # a text reading a key in one graph holds only for this run's asserted keys: none is kept from before
        self._texts = {k: t for k, t in self._texts.items() if not k[4]}
        try:
            for component in ordered:
                self._first_pass(component, back, stats)
                self.propagate(component, stats)
        finally:
            self._graphs = None
            self._unions, self._joined, self._paths = {}, set(), set()
        for level in strata:
            active = [i for i, r in enumerate(self.rules) if r.stratum <= level]
            fresh = rest if level == strata[0] else [i for i in active if self.rules[i].stratum == level]
            for i in fresh:
                if self.triggers.feasible(i, self.present):
                    self._run(i, None, stats)
            self._flush()
            stats.rounds += 1
            if level > strata[0] and not self.store.is_empty(self._direct[1]):
                self.upper_derived = True
            self.propagate(active, stats)
            if level == strata[0]:  # before the upper strata, which may read what the asks derive
                self._ask_unknown(stats, active)


def _without(rule: Rule, atoms: tuple[int, ...]) -> Rule:
    """``rule`` with the body atoms ``atoms`` left out (the body as written kept for explanations)."""
    return replace(rule, body=tuple(a for n, a in enumerate(rule.body) if n not in atoms), written=rule.premises)


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
