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
from collections.abc import Collection
from dataclasses import dataclass, field

from pyoxigraph import NamedNode

from ..compile.generic import PREFIXES
from ..compile.rule import Rule, RuleSet
from ..rdf.vocab import ASSERTED, AUX, DELTA, INFERRED, INTERNAL, NEW_AUX, NEW_INFERRED, TYPE
from ..stores.base import Store
from . import limits
from .plan import KeyCounts, is_small, plan_where
from .triggers import Present, Triggers

DATASET = f"USING {ASSERTED} USING {INFERRED} USING {AUX} USING NAMED {AUX} USING NAMED {DELTA}"
#: the other delta graph of a full run: each round reads one and fills the other
DELTA_NEXT = NamedNode(INTERNAL + "graph:delta-next")


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
    per_rule: dict[str, float] = field(default_factory=dict)


def insert_text(rule: Rule, delta_index: int | None = None, planned: bool = False, lateral: bool = True,
                direct: tuple[NamedNode, NamedNode | None] | None = None) -> str:
    """The INSERT evaluating ``rule`` (atom ``delta_index`` on the delta) into NEW_*.

    ``planned`` uses :func:`.plan.plan_where` for delta evaluations (delta atom
    first, rest per delta fact), whose cost follows the delta rather than the data.
    ``direct`` = (delta read, next delta) writes the head into its final graph and into the
    next delta (None: no delta) instead of NEW_* (the full run's rounds, see :meth:`Materializer.run`).
    """
    final = AUX if rule.head_aux() else INFERRED
    target = NEW_AUX if rule.head_aux() else NEW_INFERRED
    head = rule.head.text()
    delta = DELTA if direct is None else direct[0]
    small = planned and delta_index is not None and lateral
    if planned and delta_index is not None:
        where = plan_where(rule, delta_index, delta, lateral=lateral)
    else:
        where = rule.where(delta_index, str(delta))
    into = f"GRAPH {target} {{ {head} }}" if direct is None else f"GRAPH {final} {{ {head} }}"
    if direct is not None and direct[1] is not None:
        into += f" GRAPH {direct[1]} {{ {head} }}"
    dataset = DATASET if direct is None else DATASET.replace(str(DELTA), str(delta))
    known = new_only(rule, small)
    if direct is not None and direct[1] is None:
        # no delta: a head already inferred is written again, which changes nothing, so only the
        # asserted facts are kept out (an inferred fact is never an asserted one)
        known = new_only(rule, small, ASSERTED)
        dataset += f" USING NAMED {ASSERTED}"
    return f"INSERT {{ {into} }}\n{dataset}\nWHERE {{\n  {where}\n  {known}\n}}"


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
        self._lateral = store.supports_lateral
        #: (delta read, next delta) while :meth:`run` writes derived facts straight to their graphs
        self._direct: tuple[NamedNode, NamedNode] | None = None

    def _run(self, index: int, delta_index: int | None, stats: ReasonStats) -> None:
        key = (index, delta_index, self._lateral, self._direct)
        text = self._texts.get(key)
        if text is None:
            text = self._texts[key] = insert_text(self.rules[index], delta_index, self.planned, self._lateral,
                                                  self._direct)
        stats.evaluations += 1
        if not self.profile:
            self._queue.append(text)  # sent by _flush, one request per round
            return
        start = time.perf_counter()
        self.store.update(text, prefixes=PREFIXES)
        name = self.rules[index].name
        stats.per_rule[name] = stats.per_rule.get(name, 0.0) + time.perf_counter() - start

    def _flush(self) -> None:
        """Send the queued evaluations of a round as one update request.

        They all insert into NEW_* graphs, which none of them reads, so one
        request gives the same result and saves the per-request cost.
        """
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
            term = NamedNode(key[1:-1])
            pattern = (None, TYPE, term) if kind == "t" else (None, term, None)
            if next(iter(self.store.triples(*pattern, ASSERTED)), None) is not None:
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
        self._direct = (DELTA, DELTA_NEXT)
        try:
            self._materialize(stats)
        finally:
            self._direct = None
            self.store.update(f"DROP SILENT GRAPH {DELTA} ; DROP SILENT GRAPH {DELTA_NEXT}")
        stats.derived = self.store.count(INFERRED)
        stats.seconds = time.perf_counter() - start
        return stats

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
            if not self.triggers.feasible(i, self.present):
                continue
            key = self.rules[i].writes()
            if i in back or key[0] == "*" or key == ("p", _TYPE_KEY):
                self._run(i, None, stats)
                continue
            self._direct = (read[0], None)
            try:
                self._run(i, None, stats)
            finally:
                self._direct = read
            self.present[1 if key[0] == "t" else 0].add(key[1])
            if key[0] == "t":
                self.present[0].add(_TYPE_KEY)
        self._flush()
        stats.rounds += 1

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
        for component in ordered:
            self._first_pass(component, back, stats)
            self.propagate(component, stats)
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


def reachable(triggers: Triggers, indexes: list[int], present: Present) -> Present:
    """The predicates and classes that may get facts when the rules ``indexes`` run from ``present``.

    A rule that can match (every key its body needs may have facts) adds the key it writes; a
    head of any class (``?x rdf:type ?c``) or any predicate may write every key, and the result
    says so by holding every key the rules need.  A rule not feasible in the result can never
    match in those rules' fixpoint.
    """
    preds, classes = set(present[0]), set(present[1])
    needed = triggers.needed_keys()
    waiting = list(indexes)
    grew = True
    while grew:
        grew = False
        for i in [i for i in waiting if triggers.feasible(i, (preds, classes))]:
            waiting.remove(i)
            grew = True
            key = triggers.rules[i].writes()
            if key is None:
                continue
            if key[0] == "t":
                classes.add(key[1])
                preds.add(_TYPE_KEY)
            else:
                preds.add(key[1] if key[0] == "p" else _TYPE_KEY)
                if key[0] == "*":
                    preds.update(k[1] for k in needed if k[0] == "p")
                if key[0] == "*" or key[1] == _TYPE_KEY:
                    classes.update(k[1] for k in needed if k[0] == "t")
    return preds, classes


_TYPE_KEY = str(TYPE)


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


def evaluation_order(rules: list[Rule], indexes: list[int]) -> tuple[list[list[int]], list[int], set[int]]:
    """Strongly connected components of the rules' dependency graph, writers first, each in an
    order where most readers come after the writers they read (:func:`within`).

    Rules that read or write a variable predicate (``*``) depend on everything
    and are returned apart (second value), to run after the ordered pass; the
    third value holds the rules whose facts a rule at or before them in their
    component reads (the edges that make the component recursive).
    """
    wild = [i for i in indexes if rules[i].writes() == ("*",) or ("*",) in rules[i].reads()]
    skipped = set(wild)
    nodes = [i for i in indexes if i not in skipped]
    # readers per key, so that the edges cost their number, not rules² (a TBox of 100 classes
    # compiles to thousands of rules).  A written key reaches the readers of the same key; a class
    # membership also reaches patterns ``?x rdf:type ?c``, and those reach every class reader.
    readers: dict[tuple, list[int]] = {}
    for b in nodes:
        for key in rules[b].reads():
            readers.setdefault(key, []).append(b)
    type_key = ("p", str(TYPE))
    class_readers = [b for key, bs in readers.items() if key[0] == "t" for b in bs]
    position = {b: n for n, b in enumerate(nodes)}
    succ: dict[int, list[int]] = {}
    for a in nodes:
        w = rules[a].writes()
        found = set(readers.get(w, ()))
        if w[0] == "t":
            found.update(readers.get(type_key, ()))
        elif w == type_key:
            found.update(class_readers)
        succ[a] = sorted(found, key=position.__getitem__)
    components = [within(c, succ) for c in strongly_connected(nodes, succ)]
    at = {a: n for c in components for n, a in enumerate(c)}
    comp = {a: k for k, c in enumerate(components) for a in c}
    back = {a for a in nodes if any(comp[b] == comp[a] and at[b] <= at[a] for b in succ[a])}
    return components, wild, back


def within(component: list[int], succ: dict[int, list[int]]) -> list[int]:
    """The rules of a component in reverse post-order of a depth-first walk inside it: a
    topological order where the component has no cycle, and few readers before their writers
    where it has (each such edge makes a rule's facts go through a delta)."""
    if len(component) == 1:
        return component
    members = set(component)
    seen: set[int] = set()
    post: list[int] = []
    for root in component:
        if root in seen:
            continue
        seen.add(root)
        work = [(root, iter(succ[root]))]
        while work:
            node, children = work[-1]
            child = next((c for c in children if c in members and c not in seen), None)
            if child is None:
                work.pop()
                post.append(node)
                continue
            seen.add(child)
            work.append((child, iter(succ[child])))
    post.reverse()
    return post


def strongly_connected(nodes: list[int], succ: dict[int, list[int]]) -> list[list[int]]:
    """The strongly connected components of a graph (each sorted), in topological order: a
    component comes before every component it has an edge to.

    Tarjan's algorithm, iterative (rule sets are deep enough to exhaust Python's recursion).
    Written here rather than taken from networkx, which is not a dependency of topostore: the
    core install is kept to what the service needs (pyproject.toml), and networkx would be
    imported by every CLI start for these thirty lines.  tests/test_rule_structure.py checks
    the result against the definition (mutual reachability) and the order on random graphs.
    """
    # components come out of Tarjan's algorithm in reverse topological order
    index: dict[int, int] = {}
    low: dict[int, int] = {}
    on_stack: set[int] = set()
    stack: list[int] = []
    components: list[list[int]] = []
    counter = 0
    for root in nodes:
        if root in index:
            continue
        work = [(root, 0)]
        while work:
            v, k = work.pop()
            if k == 0:
                index[v] = low[v] = counter
                counter += 1
                stack.append(v)
                on_stack.add(v)
            if k < len(succ[v]):
                work.append((v, k + 1))
                w = succ[v][k]
                if w not in index:
                    work.append((w, 0))
                elif w in on_stack:
                    low[v] = min(low[v], index[w])
                continue
            for w in succ[v]:
                if w in on_stack:
                    low[v] = min(low[v], low[w])
            if low[v] == index[v]:
                component = []
                while True:
                    w = stack.pop()
                    on_stack.discard(w)
                    component.append(w)
                    if w == v:
                        break
                components.append(sorted(component))
    components.reverse()
    return components
