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

Exact or nothing: an atom with more than :data:`.direct.FEW` matches, a condition the evaluator does
not decide to a boolean (the text's ``COALESCE(test, false)`` would need to know an error from an
unmodelled value), or a head holding a literal makes it answer False before writing anything, and
the text runs.  Only rules whose head names no compared value are taken (the text then writes the
head as it stands, :func:`.flip.compact_possible`).
"""

from __future__ import annotations

from collections.abc import Callable

from pyoxigraph import NamedNode, Triple

from ..compile.rule import Atom, Rule, join_order
from . import direct, look_join
from .atom_shape import Shape
from .delta_texts import FLIP_LOST
from .direct import _instance, _terms
from .flip import CHANGE_OLD, compact_possible
from .join_code import compile_flip
from .look_join import Conditions, every_graph, joinable
from .scratch import FLIP_GAINED


class _Fallback(Exception):
    """Too many matches, or a condition not decided: the SPARQL text runs."""


def flippable(rule: Rule, order: tuple[int, ...]) -> bool:
    """Whether :class:`Flipped` evaluates the flip of ``rule`` over the changed atoms ``order``."""
    return joinable(rule) and compact_possible(rule, order)


class Flipped:
    """The flip of ``rule`` over its changed atoms ``order`` (see :func:`.delta_texts.flips`)."""

    def __init__(self, rule: Rule, order: tuple[int, ...],
                 graphs_of: Callable[[Atom], tuple[NamedNode, ...]] = every_graph) -> None:
        """``graphs_of``: the graphs an atom's facts may be in (:meth:`.look_join.StateGraphs.of`)."""
        self.order = order
        self.conditions = Conditions(rule)
        self._body = [Shape(_terms(a)) for a in rule.body]
        #: per changed atom, its pattern with the object left free (its subject and predicate bound by
        #: the replaced fact: only the value is new)
        self._valued = [Shape(_terms(a)[:2] + ("?",)) for a in rule.body]
        self._head = _terms(rule.head)
        self._graphs = [graphs_of(a) for a in rule.body]
        self._plans = [[m for m in join_order(rule.body, k) if m != k] for k in order]
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
        branches = [compile_flip(terms, k, self._plans[position], self.order[position + 1:],
                                 [(g,) for g in self._graphs], ((CHANGE_OLD,),), self._facts)
                    for position, k in enumerate(self.order)]
        return None if None in branches else branches

    def run(self, store) -> bool:
        """Write the flipped heads to FLIP_GAINED / FLIP_LOST; False (nothing written) where the text must run."""
        gained: dict[Triple, None] = {}
        lost: dict[Triple, None] = {}
        if self._runs_left > 0:
            self._runs_left -= 1
            if not self._runs_left:
                self._branches = self._compile()
        try:
            if self._branches is not None:
                for branch in self._branches:
                    for solution, olds in branch(store):
                        self._decide(solution, olds, gained, lost)
            else:
                for position, k in enumerate(self.order):
                    for bound, old in self._seeds(store, k):
                        for solution, olds in self._extend(store, position, bound, old, 0):
                            self._decide(solution, olds, gained, lost)
        except _Fallback:
            return False
        store.add_scratch(list(gained), FLIP_GAINED)
        store.add_scratch(list(lost), FLIP_LOST)
        return True

    def _facts(self, store, pattern: tuple, graphs) -> list[Triple]:
        """The distinct facts of ``pattern`` in ``graphs``; :class:`_Fallback` (the text runs) past FEW."""
        found = store.few_facts(*pattern, graphs, direct.FEW)
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

    def _extend(self, store, position: int, bound: dict, old: dict, at: int):
        """The solutions extending ``bound`` by the branch's other atoms, with the old values so far."""
        plan = self._plans[position]
        if at == len(plan):
            yield bound, old
            return
        m = plan[at]
        shape = self._body[m]
        for t in self._facts(store, shape.read(bound), self._graphs[m]):
            extended = shape.extend(bound, t)  # the read pattern holds every bound value: a fact read agrees
            if extended is None:
                continue
            if m in self.order[position + 1:]:  # paired: its old value where one was replaced
                olds = [o.object for o in self._facts(store, (t.subject, t.predicate, None), (CHANGE_OLD,))] \
                    or [t.object]
                for value in olds:
                    yield from self._extend(store, position, extended, {**old, shape.terms[2]: value}, at + 1)
            else:  # settled or not changed: the old value is the new one
                yield from self._extend(store, position, extended, old, at + 1)

    def _ok(self, solution: dict) -> bool:
        """Whether every condition holds (each test's value must be a boolean, as the text's
        ``COALESCE(test, false)`` then is)."""
        answer = self.conditions.exact(solution)
        if answer is None:
            raise _Fallback
        return answer

    def _decide(self, solution: dict, olds: dict, gained: dict, lost: dict) -> None:
        before = {**solution, **olds}  # settled and unchanged atoms: the old value is the new one
        now, then = self._ok(solution), self._ok(before)
        if now == then:
            return
        head = _instance(self._head, solution)
        if head is False:
            raise _Fallback  # a literal head: its spelling is left to the store
        if head is not None:
            (gained if now else lost)[head] = None


__all__ = ["Flipped", "flippable"]
