"""A comparison rule's flip (:mod:`.flip`) by index look-ups, for the compiled step where few facts are in play.

Why this exists
---------------
A clock tick's flip is one SPARQL update of about 1 KB (old and new values paired, the rule's
conditions evaluated twice) whose parse and plan costs 130–170 µs on the example map, while the
replaced facts are one or two and the facts they join a handful.  Here the same branches are
evaluated by look-ups: per changed atom (the *seed*), its old values from :data:`.flip.CHANGE_OLD`
paired with its new values, the changed atoms before it read with their new value only (settled),
the ones after it paired with their old value where one was replaced, the other atoms from the new
state; the conditions are decided by :mod:`.look_filters` for the old and for the new values, and a
head whose answer differs goes to FLIP_GAINED (true now) or FLIP_LOST.

The branch seeded by the last changed atom (the others read settled) enumerates every fact of a compared
atom not bound by the seed (every location's visit time, for a clock's move).  Where its tests are linear
(:mod:`.window`), only the facts whose value lies between the two thresholds can flip: that branch reads
the subjects in that window from the predicate's sorted value index (``values``, kept between REASONs) and
their facts by subject, instead of every fact; a bound that is not a number, a non-linear test or a wide
window keeps the full read.

Exact or nothing: an atom with more than :data:`.direct.FEW` matches, a condition the evaluator does
not decide to a boolean (the text's ``COALESCE(test, false)`` would need to know an error from an
unmodelled value), or a head holding a literal makes it answer False before writing anything, and
the text runs.  Only rules whose head names no compared value are taken (the text then writes the
head as it stands, :func:`.flip.compact_possible`).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from pyoxigraph import NamedNode, Triple

from ..compile.rule import Atom, Rule, join_order
from . import direct, look_join, window
from .atom_shape import Shape
from .delta_texts import FLIP_LOST
from .direct import _instance, _terms, triple_of
from .flip import CHANGE_OLD, compact_possible, compared_only
from .join_code import FlipDecision, compile_flip
from .look_join import Conditions, every_graph, joinable
from .look_values import value
from .scratch import FLIP_GAINED


class _Fallback(Exception):
    """Too many matches, or a condition not decided: the SPARQL text runs."""


@dataclass(frozen=True)
class _Window:
    """Where the last seed's branch may read a compared atom through a value window: its plan's ``at``-th
    atom, of predicate ``predicate``, whose value variable ``v`` the linear ``tests`` compare with the seed's
    ``t`` and the variables ``rest`` (names without ``?``), all bound before it."""

    at: int
    predicate: NamedNode
    t: str
    v: str
    rest: tuple[str, ...]
    tests: tuple
    #: the tests as :func:`.window.integer_forms` reads them (None: in fractions only)
    forms: tuple | None


def _window_of(rule: Rule, order: tuple[int, ...], plan: list[int]) -> _Window | None:
    """The window of the branch seeded by ``order[-1]`` (every other changed atom read settled, so only the
    seed's value differs between the old and the new state), or None.  The first atom of ``plan`` that
    enumerates a compared value (its subject and value unbound when it is read) and whose tests are
    linear in the seed's value, with every other variable of those tests bound before it."""
    seed = rule.body[order[-1]]
    t = seed.o[1:]
    tests = window.tests(rule)
    if not seed.o.startswith("?") or not window.possible(tests, t):
        return None
    known = set(seed.variables())
    for at, m in enumerate(plan):
        atom = rule.body[m]
        if compared_only(rule, m) and atom.s.startswith("?") and atom.s not in known and atom.o not in known:
            v = atom.o[1:]
            rest = sorted({n for test in tests if test.form for n in test.form[0]} - {t, v})
            if all(f"?{n}" in known for n in rest):
                return _Window(at, NamedNode(atom.p[1:-1]), t, v, tuple(rest), tuple(tests),
                               window.integer_forms(tests, v, t))
        known |= atom.variables()
    return None


def flippable(rule: Rule, order: tuple[int, ...]) -> bool:
    """Whether :class:`Flipped` evaluates the flip of ``rule`` over the changed atoms ``order``."""
    return joinable(rule) and compact_possible(rule, order)


class Flipped:
    """The flip of ``rule`` over its changed atoms ``order`` (see :func:`.delta_texts.flips`)."""

    def __init__(self, rule: Rule, order: tuple[int, ...],
                 graphs_of: Callable[[Atom], tuple[NamedNode, ...]] = every_graph,
                 values: Callable[[str], window.ValueIndex | None] | None = None) -> None:
        """``graphs_of``: the graphs an atom's facts may be in (:meth:`.look_join.StateGraphs.of`);
        ``values``: a predicate's (IRI text) sorted value index, None where it has none (see
        :meth:`.flips.Flips.sorted_values`); without it every branch reads every compared fact."""
        self.order = order
        self.conditions = Conditions(rule)
        self._body = [Shape(_terms(a)) for a in rule.body]
        #: per changed atom, its pattern with the object left free (its subject and predicate bound by
        #: the replaced fact: only the value is new)
        self._valued = [Shape(_terms(a)[:2] + ("?",)) for a in rule.body]
        self._head = _terms(rule.head)
        self._graphs = [graphs_of(a) for a in rule.body]
        self._plans = [[m for m in join_order(rule.body, k) if m != k] for k in order]
        self._values = values
        #: the last seed's branch read through a value window (see :func:`_window_of`), or None
        self._window = None if values is None else _window_of(rule, order, self._plans[-1])
        self._window_key = None if self._window is None else f"<{self._window.predicate.value}>"
        #: the keys whose facts it reads: its atoms' and its head's
        self.reads = frozenset({a.read_key() for a in rule.body} | {rule.head.read_key()})
        #: per changed atom, its branch compiled once into a flat function (:func:`.join_code.compile_flip`),
        #: where every changed atom's compared value is a variable; else the branches are interpreted.  Made
        #: at the :data:`.look_join.COMPILE_AFTER`-th run (a flip that runs once is cheaper interpreted)
        self._branches: list | None = None
        self._runs_left = look_join.COMPILE_AFTER if look_join.COMPILED_JOINS else -1

    def _compile(self) -> list | None:
        terms = [shape.terms for shape in self._body]
        if not all(isinstance(terms[k][2], str) for k in self.order):
            return None
        names = tuple(sorted({x for atom in terms for x in atom if isinstance(x, str)}))
        decision = FlipDecision(self.conditions.exact_over(list(names)), names, self._head, triple_of, _Fallback)
        branches = [compile_flip(terms, k, self._plans[position], self.order[position + 1:],
                                 [(g,) for g in self._graphs], ((CHANGE_OLD,),), self._facts, decision)
                    for position, k in enumerate(self.order)]
        return None if None in branches else branches

    def run(self, store) -> bool:
        """Write the flipped heads to FLIP_GAINED / FLIP_LOST; False (nothing written) where the text must run."""
        found = self.heads(store)
        if found is None:
            return False
        store.add_scratch(found[0], FLIP_GAINED)
        store.add_scratch(found[1], FLIP_LOST)
        return True

    def heads(self, store) -> tuple[list[Triple], list[Triple]] | None:
        """The flipped heads, true now and true before (each without duplicates), written nowhere: a
        staged run hands them to its part's lost and gained operations (:mod:`.staged`); None where
        the text must run."""
        gained: dict[Triple, None] = {}
        lost: dict[Triple, None] = {}
        if self._runs_left > 0:
            self._runs_left -= 1
            if not self._runs_left:
                self._branches = self._compile()
        index = None if self._window is None else self._values(self._window_key)
        last = len(self.order) - 1
        try:
            for position, k in enumerate(self.order):
                if index is None or position != last:
                    if self._branches is not None:  # each solution decided where the branch finds it
                        self._branches[position](store, gained, lost)
                        continue
                    index_here = None
                else:
                    index_here = index  # the windowed branch is interpreted: it reads few facts
                for bound, old in self._seeds(store, k):
                    for solution, olds in self._extend(store, position, bound, old, 0, index_here):
                        self._decide(solution, olds, gained, lost)
        except _Fallback:
            return None
        return list(gained), list(lost)

    def _facts(self, store, pattern: tuple, graphs) -> list[Triple]:
        """The distinct facts of ``pattern`` in ``graphs``; :class:`_Fallback` (the text runs) past FEW."""
        found = store.matches(*pattern, graphs[0], direct.FEW) if len(graphs) == 1 \
            else store.few_facts(*pattern, graphs, direct.FEW)
        if found is None:
            raise _Fallback
        return found

    def _seeds(self, store, k: int):
        """The seed atom's replaced facts: its bindings with the new value, and its old value."""
        shape = self._body[k]
        value = shape.terms[2]
        for f in self._facts(store, shape.free, (CHANGE_OLD,)):
            start = shape.bind(f)
            if start is None:
                continue
            for t in self._facts(store, self._valued[k].read(start), self._graphs[k]):
                bound = shape.bind(t)  # subject and predicate read as bound: only the value is new
                if bound is not None:
                    yield bound, {value: f.object}

    def _extend(self, store, position: int, bound: dict, old: dict, at: int, index=None):
        """The solutions extending ``bound`` by the branch's other atoms, with the old values so far;
        ``index``: the windowed atom's sorted values (the last seed's branch only)."""
        plan = self._plans[position]
        if at == len(plan):
            yield bound, old
            return
        m = plan[at]
        shape = self._body[m]
        facts = None
        if index is not None and at == self._window.at:
            facts = self._windowed(store, m, bound, old, index)
        if facts is None:
            facts = self._facts(store, shape.read(bound), self._graphs[m])
        for t in facts:
            extended = shape.extend(bound, t)  # the read pattern holds every bound value: a fact read agrees
            if extended is None:
                continue
            if m in self.order[position + 1:]:  # paired: its old value where one was replaced
                olds = [o.object for o in self._facts(store, (t.subject, t.predicate, None), (CHANGE_OLD,))] \
                    or [t.object]
                for value in olds:
                    yield from self._extend(store, position, extended, {**old, shape.terms[2]: value}, at + 1, index)
            else:  # settled or not changed: the old value is the new one
                yield from self._extend(store, position, extended, old, at + 1, index)

    def _windowed(self, store, m: int, bound: dict, old: dict, index: window.ValueIndex) -> list[Triple] | None:
        """Atom ``m``'s facts whose value may flip: those of the subjects whose value lies in the window
        of the seed's old and new value (:func:`.window.interval`), read by subject (the stored facts,
        whatever spelling the index kept); None where there is no window (every fact is read)."""
        w = self._window
        t = f"?{w.t}"
        terms = [old.get(t), bound.get(t), *(bound.get(f"?{n}") for n in w.rest)]
        if not index.exact_for(terms):
            return None
        values = [value(term) for term in terms]
        if w.forms is not None and all(type(x) is int for x in values):  # xsd:integer values: exact in ints
            span = window.integer_interval(w.forms, values[0], values[1], dict(zip(w.rest, values[2:])))
        else:
            values = [window.number(term) for term in terms]
            if any(x is None for x in values):
                return None
            span = window.interval(w.tests, w.v, w.t, values[0], values[1], dict(zip(w.rest, values[2:])),
                                   window.margin(terms, values))
        if span is None:
            return None
        if span is False:
            return []  # no test reads the seed's value in a way that changed
        inside = index.between(span[0], span[1], direct.FEW)
        if inside is None:
            return None
        facts: list[Triple] = []
        for subject in dict.fromkeys(f.subject for f in inside):
            facts += self._facts(store, (subject, w.predicate, None), self._graphs[m])
        return facts

    def _decide(self, solution: dict, olds: dict, gained: dict, lost: dict) -> None:
        before = {**solution, **olds}  # settled and unchanged atoms: the old value is the new one
        exact = self.conditions.exact  # each test's value a boolean (as the text's COALESCE(test, false))
        now, then = exact(solution), exact(before)
        if now is None or then is None:
            raise _Fallback
        if now == then:
            return
        head = _instance(self._head, solution)
        if head is False:
            raise _Fallback  # a literal head: its spelling is left to the store
        if head is not None:
            (gained if now else lost)[head] = None


__all__ = ["Flipped", "flippable"]
