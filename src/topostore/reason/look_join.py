"""A rule of several body atoms with simple conditions, evaluated by a nested-loop join of index
look-ups, for the compiled step (:mod:`.program`) where few facts are in play.

Why this exists
---------------
:mod:`.direct` answers the join-free operations of the step by look-ups; a rule with two or three
atoms and a FILTER (a robot's reachability, the clock's comparison) still cost a SPARQL text of
1–2 KB whose parse and plan is 40–120 µs, while its facts are a handful.  Here such a rule's
recheck (does a candidate head still have a derivation in the new state?) and additions (the heads a
changed atom's new facts derive) are answered by binding the atoms one by one in the rule's compiled
join order (:func:`~..compile.rule.join_order`), each atom's matches read from the store's indexes,
and the conditions decided by :mod:`.look_filters`.

It never guesses: an atom with more than :data:`.direct.FEW` matches, a condition the evaluator
answers UNKNOWN, or a head that would be written with a literal makes the operation answer False,
and its SPARQL text runs instead (before anything was written).
"""

from __future__ import annotations

from collections.abc import Callable, Collection, Iterator, Mapping

from pyoxigraph import Literal, NamedNode, Triple

from ..compile.condition import BIND, TEST
from ..compile.rule import Atom, ReadKey, Rule, join_order
from ..rdf.vocab import ASSERTED, AUX, INFERRED, TYPE
from . import direct
from .atom_shape import Shape
from .delta_texts import KEEP, NEW_STATE
from .direct import _instance, _named_only, _terms, _write_new, triple_of
from .join_code import Join, JoinDecision, compile_join, interpreted
from .look_code import compile_conditions, compile_exact_over, compile_holds_over
from .look_filters import Unsupported, closure, parse_expression
from .look_values import UNKNOWN, all_of
from .scratch import CANDIDATES, NEW_FACTS, OVERDELETED
from .triggers import Present, matches

#: False: joins are interpreted atom by atom (:func:`.join_code.interpreted`), the reference the tests
#: compare the compiled joins against
COMPILED_JOINS = True
_TYPE_KEY = ("p", str(TYPE))


class StateGraphs:
    """The graphs of the new state that may hold facts of an atom: the helper graph alone for a helper
    atom, else the asserted graph, and the inferred and helper graphs only where some rule's head may
    write the atom's key there (a rule writing any predicate, or ``rdf:type`` with a variable class,
    writes every key it may match).  Only rules write those two graphs, so an atom on a predicate
    no rule derives (a robot's clock, its visit times) is read from the asserted graph alone."""

    def __init__(self, rules: list[Rule]) -> None:
        self._by_key: dict[ReadKey, set[NamedNode]] = {}
        self._rules = rules
        #: per key, the named keys of the body of each rule writing it (made at the first :meth:`derived`)
        self._bodies: dict[ReadKey, list[tuple[ReadKey, ...]]] | None = None
        #: the same per key, each with the graph the rule writes (:meth:`firing`)
        self._heads: dict[ReadKey, list[tuple[NamedNode, tuple[ReadKey, ...]]]] = {}
        #: :meth:`derived` per key, with the sizes of the ``present`` sets it was answered for
        self._present: Present | None = None
        self._seen: dict[ReadKey, tuple[tuple[int, int], bool]] = {}
        for rule in rules:
            if rule.head is not None:
                self._by_key.setdefault(rule.writes(), set()).add(AUX if rule.head_aux() else INFERRED)

    def of(self, atom: Atom) -> tuple[NamedNode, ...]:
        """The graphs to read ``atom``'s facts from, in :data:`.delta_texts.NEW_STATE`'s order."""
        if atom.aux:
            return (AUX,)
        return self.of_key(atom.read_key())

    def derived(self, census: tuple[Mapping[str, int], Mapping[str, int]], present: Present) -> bool:
        """Whether a fact of a key of ``census`` (:func:`~..stores.base.key_census`: predicates, and the
        classes of type facts) may be in the inferred or the helper graph: some rule writes the key there
        and every key its body names had facts (``present``, the keys with facts since the last full run,
        a superset).  Else no such fact is there to discard when it is asserted: a rule one of whose
        premises never had a fact (owl:sameAs replacement, on a map without equalities) never fired.

        Answered once per key while ``present`` keeps its sizes: its sets only grow until a full run
        makes new ones, so the same sets of the same sizes hold the same keys."""
        if present is not self._present:
            self._present, self._seen = present, {}
        sizes = (len(present[0]), len(present[1]))
        seen = self._seen
        preds, classes = census
        for kind, names in (("t", classes), ("p", preds)):
            for name in names:
                found = seen.get((kind, name))
                if found is None or found[0] != sizes:
                    found = seen[(kind, name)] = (sizes, self._written(kind, name, present))
                if found[1]:
                    return True
        return False

    def _written(self, kind: str, name: str, present: Present) -> bool:
        """:meth:`derived` of one key (rdf:type itself is no key: its facts' classes are)."""
        if kind == "p" and name == _TYPE_KEY[1]:
            return False
        if self._bodies is None:
            self._index_bodies()
        key = (kind, name)
        writers = (key, ("*",), _TYPE_KEY) if kind == "t" else (key, ("*",))
        return any(all(matches(k, *present) for k in body) for writer in writers
                   for body in self._bodies.get(writer, ()))

    def firing(self, atom: Atom, present: Present, affected: Collection[ReadKey], absent: set) -> tuple[NamedNode, ...]:
        """:meth:`of` narrowed to the graphs of the rules that can have written ``atom``'s key: a rule some
        named premise of which has had no fact since the last full run (``present``, a superset) and gets
        none from the change (``affected``) never fired, and wrote nothing there (owl:sameAs replacement,
        which writes any predicate, on a map without equalities: every atom was read from the inferred
        graph too).  Each premise that left a graph out joins ``absent`` (the program's ``needs_absent``:
        it is compiled again once one has facts)."""
        graphs = self.of(atom)
        key = atom.read_key()
        if len(graphs) == 1 or key[0] == "*" or key == _TYPE_KEY:
            return graphs
        if self._bodies is None:
            self._index_bodies()
        found = set()
        for writer in ((key, ("*",), _TYPE_KEY) if key[0] == "t" else (key, ("*",))):
            for graph, body in self._heads.get(writer, ()):
                missing = [k for k in body if k not in affected and not matches(k, *present)]
                if missing:
                    absent.update(missing)
                else:
                    found.add(graph)
        return (ASSERTED, *(g for g in (INFERRED, AUX) if g in found))

    def _index_bodies(self) -> None:
        """The named premises of each rule writing a key (:meth:`derived`), and with its graph (:meth:`firing`)."""
        self._bodies, self._heads = {}, {}
        for rule in self._rules:
            if rule.head is not None:
                named = tuple(dict.fromkeys(a.read_key() for a in rule.body if a.p[0] == "<"))
                self._bodies.setdefault(rule.writes(), []).append(named)
                self._heads.setdefault(rule.writes(), []).append((AUX if rule.head_aux() else INFERRED, named))

    def of_key(self, key: ReadKey) -> tuple[NamedNode, ...]:
        """The graphs of the new state that may hold facts of ``key`` (not a helper atom's)."""
        if key[0] == "*":
            return NEW_STATE
        found = set(self._by_key.get(("*",), ())) | self._by_key.get(key, set())
        if key[0] == "t":
            found |= self._by_key.get(_TYPE_KEY, set())
        elif key == _TYPE_KEY:
            found.update(*(g for k, g in self._by_key.items() if k[0] == "t"))
        return (ASSERTED, *(g for g in (INFERRED, AUX) if g in found))


def every_graph(atom: Atom) -> tuple[NamedNode, ...]:
    """The graphs of the new state an atom is read from when nothing is known of the rules' heads."""
    return (AUX,) if atom.aux else NEW_STATE


def _read(store, pattern: tuple, graphs: tuple[NamedNode, ...], graph_set: frozenset) -> list[Triple]:
    """The distinct facts of ``pattern`` in ``graphs`` (at most FEW, else :class:`_Fallback`): one read
    over every graph where the store offers it (``match_in``: a bound subject or object), else one per
    graph (``graph_set``: ``graphs`` as a set).  One graph is read alone: the read over every graph
    would go through the other graphs' quads of the pattern to find the same facts."""
    if len(graphs) == 1:  # its facts as the index gives them (the join reads their terms)
        found = store.matches(*pattern, graphs[0], direct.FEW)
    else:
        match_in = getattr(store, "match_in", None)
        found = match_in(*pattern, graph_set, direct.FEW) if match_in is not None else None
        if found is None:
            found = store.few_facts(*pattern, graphs, direct.FEW)
    if found is None or len(found) > direct.FEW:
        raise _Fallback
    return found


class _Fallback(Exception):
    """More matches than :data:`.direct.FEW`: the SPARQL text decides."""


class Conditions:
    """A rule's BINDs and FILTERs, compiled once (:class:`~.look_filters.Unsupported` outside the subset).

    A group's BINDs extend the solution in order, after its atoms (every rule text writes them there),
    and its FILTERs apply to the whole group, so they are decided after every BIND."""

    def __init__(self, rule: Rule) -> None:
        self.binds = []
        #: the tests' expressions, for a caller that needs their value rather than its truth
        self.raw = []
        trees: tuple[list, list] = ([], [])
        for c in rule.conditions:
            if not c.plain or c.kind not in (BIND, TEST):
                raise Unsupported(f"condition {c.text!r} reads the graph")
            tree = parse_expression(c.expression)
            if c.kind == BIND:
                self.binds.append((c.binds, closure(tree)))
                trees[0].append((c.binds, tree))
            else:
                self.raw.append(closure(tree))
                trees[1].append(tree)
        #: the tests together, in SPARQL's three-valued logic
        self.test = all_of(self.raw)
        #: the expression trees, generated into functions that take :meth:`holds` and :meth:`exact`'s
        #: place at the first call (:mod:`.look_code`; :func:`joinable` only asks whether they parse)
        self._trees = trees if COMPILED_JOINS else None
        self._parsed = trees

    def bound(self, solution: dict) -> dict | object:
        """``solution`` extended by the BINDs in order; UNKNOWN where one is not exact."""
        if not self.binds:
            return solution
        solution = dict(solution)
        for var, expr in self.binds:
            found = expr(solution)
            if found is UNKNOWN:
                return UNKNOWN
            solution[var] = found
        return solution

    def holds(self, solution: dict) -> object:
        """True / False for a solution of the atoms, UNKNOWN where the evaluator is not exact."""
        if self._trees is not None:
            return self._generate().holds(solution)
        solution = self.bound(solution)
        return UNKNOWN if solution is UNKNOWN else self.test(solution)

    def _generate(self) -> Conditions:
        """The generated :meth:`holds` and :meth:`exact` in the methods' place, for this instance."""
        self.holds, self.exact = compile_conditions(*self._trees)  # type: ignore[method-assign]
        self._trees = None
        return self

    def exact_over(self, names: list[str]) -> Callable:
        """:meth:`exact` generated as a function of the values of ``names``, in that order
        (:func:`.look_code.compile_exact_over`), for a generated flip branch to call with its locals."""
        return compile_exact_over(*self._parsed, names)

    def holds_over(self, names: list[str]) -> Callable:
        """:meth:`holds` as a function of the values of ``names`` (:func:`.look_code.compile_holds_over`),
        for a generated join deciding its solutions to call with its locals."""
        return compile_holds_over(*self._parsed, names)

    def exact(self, solution: dict) -> bool | None:
        """True / False where every BIND is exact and every test's value a boolean (as the flip text's
        ``COALESCE(test, false)`` then is), else None."""
        if self._trees is not None:
            return self._generate().exact(solution)
        s = self.bound(solution)
        if s is UNKNOWN:
            return None
        answer = True
        for test in self.raw:
            found = test(s)
            if type(found) is not bool:
                return None
            answer = answer and found
        return answer


def joinable(rule: Rule) -> bool:
    """Whether :class:`Joined` can evaluate ``rule``: a head, every atom's term a variable or an IRI,
    the head's variables bound by atoms (not by a BIND), every condition inside the evaluated subset."""
    if rule.head is None or not rule.body or not _named_only(*rule.body, rule.head):
        return False
    if not rule.head.variables() <= set().union(*(a.variables() for a in rule.body)):
        return False
    if rule.binds & set().union(*(a.variables() for a in rule.body)):
        return False
    try:
        Conditions(rule)
    except Unsupported:
        return False
    return True


#: a join runs interpreted this many times before its code is generated: a step program of a TBox-heavy
#: ontology makes thousands of joins that run once or never, and generating their code cost more than
#: it saved (a tutorial-style TBox's steps spent a third of their time in it)
COMPILE_AFTER = 2


class _Compiling:
    """A join made on its first run (interpreted) and compiled on its :data:`COMPILE_AFTER`-th, which puts the
    compiled join (or the interpreted one, where it cannot be compiled) in its owner's attribute: later
    runs call that directly.  Until its first run it holds no closure: a step program of a TBox-heavy
    ontology makes thousands of joins that never run, and every object they hold is walked by each full
    collection of the cycle collector."""

    __slots__ = ("_owner", "_name", "_order", "_given", "_slow", "_left")

    def __init__(self, owner: Joined, name: str, order: list[int], given: set[str]) -> None:
        self._owner, self._name, self._order, self._given = owner, name, order, given
        self._slow: Join | None = None
        self._left = COMPILE_AFTER

    def __call__(self, store, bound: dict) -> Iterator[dict]:
        owner = self._owner
        if self._slow is None:
            self._slow = interpreted(owner._body, self._order, owner._graphs, _read)
        self._left -= 1
        if self._left > 0:
            return self._slow(store, bound)
        terms = [shape.terms for shape in owner._body]
        join = compile_join(terms, self._order, self._given, owner._graphs, _read) or self._slow
        setattr(owner, self._name, join)
        # the same join deciding its solutions where it finds them (its owner calls that one from now on)
        setattr(owner, f"{self._name}_decided",
                compile_join(terms, self._order, self._given, owner._graphs, _read, owner._decision(self._name)))
        return join(store, bound)


class Joined:
    """Rule ``rule`` (see :func:`joinable`), whose heads live in ``graph``: its recheck of candidates
    (as KEEP marks, or as the one-prover deletion) and its additions from an atom's new facts."""

    def __init__(self, rule: Rule, graph: NamedNode, delta: int | None = None,
                 graphs_of: Callable[[Atom], tuple[NamedNode, ...]] = every_graph) -> None:
        """``delta``: the atom whose new facts the additions start from.  The recheck reads the new
        state (a rule that only restates a premise is rechecked from asserted facts by its text);
        ``graphs_of``: the graphs an atom's facts may be in (:meth:`StateGraphs.of`)."""
        self.rule = rule
        self.graph = graph
        self.delta = delta
        self.conditions = Conditions(rule)
        self._body = [Shape(_terms(a)) for a in rule.body]
        self._head = Shape(_terms(rule.head))
        #: whether its recheck reads every candidate of its key, each bound (:func:`.direct.whole_key`)
        self._whole = direct.whole_key(self._head, rule.head.read_key())
        self._graphs = [(g, frozenset(g)) for g in map(graphs_of, rule.body)]
        self._proof_order = join_order(rule.body, None, rule.head.variables())
        self._delta_order = join_order(rule.body, delta)[1:] if delta is not None else []
        #: the keys whose facts it reads: its atoms' and its head's
        self.reads = frozenset({a.read_key() for a in rule.body} | {rule.head.read_key()})
        #: per operation, keys of the new state without whose facts it finds nothing: the atoms the
        #: additions join to a delta fact (premises: the keys with facts are kept for them)
        self.needs = {"additions": frozenset(rule.body[m].read_key() for m in self._delta_order)}
        #: the recheck's join from a candidate's head values, and the additions' from a delta fact's
        #: bindings, each compiled once into a flat function (:mod:`.join_code`)
        self._prove = self._join(self._proof_order, self._head, "_prove")
        self._derive = self._join(self._delta_order, self._body[delta], "_derive") if delta is not None else None
        #: the compiled joins deciding their solutions where they find them (:class:`.join_code.JoinDecision`):
        #: made with the compiled joins, None until then (or where a join is too long to compile)
        self._prove_decided: Callable | None = None
        self._derive_decided: Callable | None = None

    def _decision(self, name: str) -> JoinDecision:
        """What the compiled join ``name`` ("_prove" or "_derive") decides its solutions with."""
        names = tuple(sorted({x for shape in self._body for x in shape.terms if isinstance(x, str)}))
        holds = self.conditions.holds_over(list(names))
        if name == "_prove":
            return JoinDecision(holds, names)
        return JoinDecision(holds, names, self._head.terms, triple_of, direct.FEW)

    def _join(self, order: list[int], start: Shape, name: str) -> Join:
        """The join of the atoms ``order`` from the solutions ``start``'s facts bind, interpreted until
        it has run :data:`COMPILE_AFTER` times, then compiled into attribute ``name``."""
        if not COMPILED_JOINS:
            return interpreted(self._body, order, self._graphs, _read)
        return _Compiling(self, name, order, {x for x in start.terms if isinstance(x, str)})

    def _proven(self, store, bound: dict) -> object:
        """Whether some derivation with the head's values ``bound`` holds (UNKNOWN: not decided)."""
        if self._prove_decided is not None:
            return self._prove_decided(store, bound)
        answer: object = False
        for solution in self._prove(store, bound):
            b = self.conditions.holds(solution)
            if b is True:
                return True
            if b is UNKNOWN:
                answer = UNKNOWN
        return answer

    def _decide(self, store) -> list[tuple[Triple, bool]] | None:
        """Each candidate of the head's pattern and whether the rule still derives it (None: the
        SPARQL text decides)."""
        candidates = direct._facts(store, self._head.free, CANDIDATES)
        if candidates is None:
            return None
        out = []
        try:
            for c in candidates:
                bound = self._head.bind(c)
                if bound is None:
                    continue
                proven = self._proven(store, bound)
                if proven is UNKNOWN:
                    return None
                out.append((c, proven))
        except _Fallback:
            return None
        return out

    def keep(self, store) -> bool:
        """:func:`.delta_texts.keep`: the candidates the rule derives from the new state go to KEEP
        (:data:`.direct.ALL_KEPT` where that is every candidate of its key)."""
        decided = self._decide(store)
        if decided is None:
            return False
        kept = [c for c, proven in decided if proven]
        store.add_scratch(kept, KEEP)
        return direct.ALL_KEPT if self._whole and len(kept) == len(decided) else True

    def delete(self, store) -> bool:
        """:func:`.delta_texts.recheck_one`: the candidates the rule no longer derives and not asserted
        leave the graph and join OVERDELETED."""
        decided = self._decide(store)
        if decided is None:
            return False
        return self.remove([c for c, proven in decided if not proven], store)

    def remove(self, dead: list[Triple], store) -> bool:
        """The heads ``dead`` (no longer derived) not asserted leave the graph and join OVERDELETED; False
        where the SPARQL text moves them (a literal among them: it may be stored in another spelling)."""
        if any(isinstance(c.object, Literal) for c in dead):
            return False
        dead = [c for c, asserted in zip(dead, store.contains_each(dead, ASSERTED)) if not asserted] if dead else []
        if dead:
            store.discard(dead, (self.graph,))
            store.add_scratch(dead, OVERDELETED)
        return True

    def additions(self, store, facts: list[Triple] | None = None) -> bool:
        """:func:`.delta_texts.additions`: heads the rule derives with an added fact of the delta atom,
        not known yet, into the graph and NEW_FACTS; ``facts``: the delta atom's added facts where the run
        has them (:data:`.direct.GIVEN`), else read."""
        heads = self.derived(store, facts)
        if heads is None:
            return False
        _write_new(store, heads, self.graph)
        return True

    def derived(self, store, facts: list[Triple] | None = None) -> list[Triple] | None:
        """The heads the rule derives in the new state with ``facts`` of the delta atom (None: its added
        facts, read from NEW_FACTS), known or not; None where the SPARQL text decides (more than
        :data:`.direct.FEW`, a condition not decided, a head holding a literal)."""
        delta = self._body[self.delta]
        if facts is None:
            facts = direct._facts(store, delta.free, NEW_FACTS)
        if facts is None:
            return None
        heads: list[Triple] = []
        try:
            for t in facts:
                start = delta.bind(t)
                if start is None:
                    continue
                if self._derive_decided is not None:
                    if not self._derive_decided(store, start, heads):
                        return None
                    continue
                for solution in self._derive(store, start):
                    b = self.conditions.holds(solution)
                    if b is UNKNOWN:
                        return None
                    if b:
                        head = _instance(self._head.terms, solution)
                        if head is False:
                            return None
                        if head is not None:
                            heads.append(head)
                    if len(heads) > direct.FEW:
                        return None
        except _Fallback:
            return None
        return heads


__all__ = ["Conditions", "Joined", "StateGraphs", "every_graph", "joinable"]
