"""Classes no individual can be a member of, decided by simple sound tests of the TBox, and the clashes
among unnamed values that those tests do not decide (named in a notice, never silent).

Why
---
The rules of :mod:`.owl` reason about the values an individual is told to have.  A class can also demand
values nobody named, and those demands can clash: ``C ≡ ≥3 p`` with ``p`` functional, ``C ⊑ ∃p.A ⊓ ∀p.B``
with ``A`` and ``B`` disjoint, ``B ⊑ ∃p.A`` with ``A ⊑ owl:Nothing``.  Such a class has no member, so a
member of it is an inconsistency, which no rule over told values finds.

What is decided
---------------
Each class expression (and named class) is read with everything it is told to be under (superclasses,
equivalents, the members of an intersection, closed), and is unsatisfiable when that set holds:

* a lower bound (``some``, ``value``, ``min n``, ``exact n``, n ≥ 1) on a property whose filler is
  unsatisfiable;
* a lower bound of ``n`` values in ``F`` and an upper bound (``max m``, ``exact m``, a functional
  property: ``m = 1``) of ``m < n`` values in ``G`` with ``F`` under ``G``; or two lower bounds under
  the same upper bound whose fillers cannot meet (disjoint classes, or datatypes whose value spaces do not
  meet) and whose values together exceed it;
* a lower bound in ``F`` and a universal ``∀p.G`` on the same property where ``F ⊓ G`` is unsatisfiable
  by these same tests (disjoint classes, owl:Nothing, a complement, restrictions of both).

The tests are sound (each "no member" follows from the axioms) and run to a fixpoint, so an unsatisfiable
filler makes its existentials unsatisfiable in turn.  What existing rules already report (a member of
owl:Nothing, of two disjoint classes, of a class and its complement) is left to them: a check
(``cls-unsat``) is emitted only for the topmost class whose clash is found here, so a member of it is one
violation.  Besides: a functional data property with ``∃d.D`` makes a told value outside ``D`` an
inconsistency (``cls-svf-fp``).

What is said
------------
Where a lower bound meets a maximum on values whose fillers may or may not overlap, or meets a universal
whose filler together with its own holds unions, complements or one-ofs, whether the class is empty needs
case analysis: an :data:`UNNAMED_CLASH` notice names the pair once.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass

from pyoxigraph import NamedNode

from ..rdf.terms import sparql
from ..rdf.vocab import NOTHING, THING, TYPE
from . import condition as cond
from .model import Expr, Prop, describe
from .notices import INCOMPLETE, Notice
from .owl import OwlCompiler
from .range_values import disjoint
from .rule import Atom, Rule
from .snippets import in_datatype

#: The axiom kind of the notices: a clash among unnamed values that the tests do not decide.
UNNAMED_CLASH = "clash among unnamed values not decided"

#: Kinds a conjunction is not decided for (case analysis on which member, or on non-membership).
_BEYOND = frozenset({"or", "not", "oneof"})

_LOWER = frozenset({"some", "min", "exact", "value"})


@dataclass(frozen=True)
class Bound:
    """A number of values of a property in a filler: the lower or upper bound a restriction sets.

    ``filler``/``datatype`` None (both) is owl:Thing; ``expr`` is the restriction (None for a functional
    property's bound)."""

    prop: Prop
    n: int
    filler: Expr | None
    datatype: NamedNode | None
    expr: Expr | None

    @property
    def text(self) -> str:
        if self.expr is not None:
            return describe(self.expr)
        kind = "inverse functional" if self.prop.inverse else "functional"
        return f"the {kind} property {_short(self.prop.iri)}"


def _short(t: NamedNode) -> str:
    v = t.value
    return v.rsplit("#", 1)[-1] if "#" in v else v.rsplit("/", 1)[-1]


def _lower(e: Expr) -> Bound | None:
    if e.kind not in _LOWER or e.prop is None:
        return None
    n = 1 if e.kind in ("some", "value") else e.n
    filler = None if e.kind == "value" or (e.filler is not None and e.filler.node == THING) else e.filler
    return Bound(e.prop, n, filler, None if e.kind == "value" else e.datatype, e) if n >= 1 else None


def _upper(e: Expr) -> Bound | None:
    if e.kind not in ("max", "exact") or e.prop is None:
        return None
    filler = None if e.filler is not None and e.filler.node == THING else e.filler
    return Bound(e.prop, e.n, filler, e.datatype, e)


class Unsatisfiable:
    """Decides the unsatisfiable classes of a compiled TBox (see the module) and what is left undecided."""

    def __init__(self, owl: OwlCompiler) -> None:
        self.owl, self.tb = owl, owl.tb
        self.exprs: dict[NamedNode, Expr] = {e.node: e for e in owl.all_expressions()}
        for c in self.tb.named_classes:
            self.exprs.setdefault(c, Expr(c, "named"))
        self.above = self._closure()
        self.disjoint: dict[NamedNode, set[NamedNode]] = {}
        for a, b in self.tb.disjoint:
            self.disjoint.setdefault(a.node, set()).add(b.node)
            self.disjoint.setdefault(b.node, set()).add(a.node)
        for e in self.exprs.values():
            if e.kind == "not" and e.members:
                self.disjoint.setdefault(e.node, set()).add(e.members[0].node)
        #: node -> (why it has no member, whether existing rules already report its members)
        self.reason: dict[NamedNode, tuple[str, bool]] = {}
        self._open: set[frozenset[NamedNode]] = set()
        #: :meth:`clash`'s answers in this round of the fixpoint (a meeting of fillers is asked again and again)
        self._asked: dict[tuple[frozenset[NamedNode], bool], tuple[str, bool] | None] = {}
        self.notices: dict[tuple[NamedNode, NamedNode | str], Notice] = {}
        self._decide()

    # ---------------------------------------------------------------- the sets of classes
    def _closure(self) -> dict[NamedNode, frozenset[NamedNode]]:
        """Each expression's node with the nodes of everything it is told to be under (closed)."""
        edges: dict[NamedNode, set[NamedNode]] = {}
        for a, b in self.tb.subclass:
            edges.setdefault(a.node, set()).add(b.node)
        for a, b in self.tb.equivalent:
            edges.setdefault(a.node, set()).add(b.node)
            edges.setdefault(b.node, set()).add(a.node)
        for e in self.exprs.values():
            if e.kind == "and":
                edges.setdefault(e.node, set()).update(m.node for m in e.members)
        out: dict[NamedNode, frozenset[NamedNode]] = {}
        for start in self.exprs:
            seen, todo = {start}, [start]
            while todo:
                for nxt in edges.get(todo.pop(), ()):
                    if nxt not in seen:
                        seen.add(nxt)
                        todo.append(nxt)
            out[start] = frozenset(seen)
        return out

    def under(self, e: Expr | None) -> frozenset[NamedNode]:
        if e is None:
            return frozenset()
        return self.above.get(e.node, frozenset({e.node}))

    # ---------------------------------------------------------------- the tests
    def _decide(self) -> None:
        """Every expression's clash, to a fixpoint (an unsatisfiable filler makes more classes unsatisfiable)."""
        changed = True
        while changed:
            changed = False
            self._asked.clear()
            for node in self.exprs:
                if node not in self.reason:
                    found = self.clash(self.above[node])
                    if found is not None:
                        self.reason[node] = found
                        changed = True

    def clash(self, nodes: frozenset[NamedNode], note: bool = False) -> tuple[str, bool] | None:
        """Why a member of every class of ``nodes`` cannot exist, and whether existing rules report it;
        None when the tests find no clash (``note``: name the undecided pairs in a notice)."""
        if NOTHING in nodes:
            return "it is under owl:Nothing", True
        for x in nodes:
            met = self.disjoint.get(x, set()) & nodes
            if met:
                return f"it is under the disjoint {self._name(x)} and {self._name(min(met, key=str))}", True
        if nodes in self._open:
            return None  # met again inside its own test: asked again in the fixpoint's next round
        key = (nodes, note)
        if key not in self._asked:
            self._open.add(nodes)
            try:
                self._asked[key] = self._restrictions([self.exprs[n] for n in nodes if n in self.exprs], note)
            finally:
                self._open.discard(nodes)
        return self._asked[key]

    def _restrictions(self, members: list[Expr], note: bool) -> tuple[str, bool] | None:
        lowers: dict[Prop, list[Bound]] = {}
        uppers: dict[Prop, list[Bound]] = {}
        alls: dict[Prop, list[Expr]] = {}
        for e in members:
            low, up = _lower(e), _upper(e)
            if low is not None:
                lowers.setdefault(e.prop, []).append(low)
            if up is not None:
                uppers.setdefault(e.prop, []).append(up)
            if e.kind == "all" and e.prop is not None:
                alls.setdefault(e.prop, []).append(e)
        for p, lows in sorted(lowers.items(), key=lambda kv: (kv[0].iri.value, kv[0].inverse)):
            ups = uppers.get(p, []) + self._functional(p)
            for low in lows:
                found = self._filler_empty(low) or self._beyond_maximum(low, ups, note) \
                    or self._meets_universal(low, alls.get(p, []), note)
                if found:
                    return found
            found = self._two_lowers(lows, ups)
            if found:
                return found
        return None

    def _functional(self, p: Prop) -> list[Bound]:
        """At most one value of ``p``: it is functional, or its inverse is inverse-functional, also where
        the inverse is a property of its own (``owl:inverseOf``, either way round)."""
        if self._at_most_one(p.iri, p.inverse) or any(
                self._at_most_one(other, not p.inverse) for other in self._inverses(p.iri)):
            return [Bound(p, 1, None, None, None)]
        return []

    def _at_most_one(self, iri: NamedNode, inverse: bool) -> bool:
        return self.tb.has("InverseFunctionalProperty" if inverse else "FunctionalProperty", iri)

    def _inverses(self, iri: NamedNode) -> list[NamedNode]:
        """The named properties told inverse of ``iri`` (``owl:inverseOf`` read either way round)."""
        return [b if a == iri else a for a, b in self.tb.inverse
                if isinstance(b, NamedNode) and iri in (a, b)]

    def _filler_empty(self, low: Bound) -> tuple[str, bool] | None:
        if low.filler is None:
            return None
        if low.filler.node == NOTHING:
            return f"{low.text} needs a value in owl:Nothing", True
        found = self.reason.get(low.filler.node)
        if found is not None:
            return f"{low.text} needs a value in {describe(low.filler)}, which has no member ({found[0]})", False
        return None

    def covered(self, low: Bound, up: Bound) -> bool:
        """Every value ``low`` counts is one ``up`` counts: its filler is under the upper bound's."""
        if up.filler is None and up.datatype is None:
            return True
        if low.datatype is not None or up.datatype is not None:
            return low.expr is not None and up.expr is not None and self.owl.filler_subsumed(low.expr, up.expr)
        if low.filler is None:
            return False
        return up.filler.node in self.under(low.filler) or self.owl.subsumption.classes(low.filler, up.filler)

    def _beyond_maximum(self, low: Bound, ups: list[Bound], note: bool) -> tuple[str, bool] | None:
        for up in ups:
            if low.n <= up.n:
                continue
            if self.covered(low, up):
                return f"{low.text} needs more values than {up.text} allows", False
            if note and not self._apart(low, up):
                self._note(low, up, f"{low.text} meets {up.text}: how many of its values are in "
                           f"{self._filler_text(up)} needs case analysis, not decided")
        return None

    def _apart(self, a: Bound, b: Bound) -> bool:
        """The fillers of ``a`` and ``b`` cannot share a value (told disjoint, or their meeting is empty; two
        datatypes by their value spaces)."""
        if a.datatype is not None and b.datatype is not None:
            return disjoint(a.datatype, b.datatype)
        if a.datatype is not None or b.datatype is not None or a.filler is None or b.filler is None:
            return False
        found = self.clash(self.under(a.filler) | self.under(b.filler))
        return found is not None

    def _meets_universal(self, low: Bound, alls: list[Expr], note: bool) -> tuple[str, bool] | None:
        for u in alls:
            if low.datatype is not None or u.datatype is not None:
                if note and low.datatype is not None and u.datatype is not None and low.expr is not None \
                        and not self.owl.filler_subsumed(low.expr, u):
                    self._note(low, u, f"the value {low.text} needs lies in the data ranges of both and "
                               f"{describe(u)}: whether they meet is not decided")
                continue
            if u.filler is None or u.filler.node == THING:
                continue
            met = self.under(low.filler) | self.under(u.filler)
            found = self.clash(met)
            if found is not None:
                return (f"{low.text} needs a value that {describe(u)} puts in {describe(u.filler)}, and "
                        f"{self._filler_text(low)} and {describe(u.filler)} have no member in common "
                        f"({found[0]})", False)
            if note and not self._within(low.filler, u.filler) \
                    and any(self.exprs[n].kind in _BEYOND for n in met if n in self.exprs):
                self._note(low, u, f"the value {low.text} needs is in {describe(u.filler)} too: whether "
                           "both can hold needs case analysis (a union, complement or one-of), not decided")
        return None

    def _within(self, f: Expr | None, g: Expr) -> bool:
        """Filler ``f`` is told under ``g`` (a member of a union, say): their meeting is ``f``, decided as ``f``
        is (``None``, owl:Thing, meets ``g`` as ``g`` is: its own question, not the existential's)."""
        return f is None or g.node in self.under(f) or self.owl.subsumption.classes(f, g)

    def _two_lowers(self, lows: list[Bound], ups: list[Bound]) -> tuple[str, bool] | None:
        for up in ups:
            under = [low for low in lows if self.covered(low, up)]
            for i, a in enumerate(under):
                for b in under[i + 1:]:
                    if a.n + b.n > up.n and self._apart(a, b):
                        return (f"{a.text} and {b.text} need {a.n + b.n} different values, more than "
                                f"{up.text} allows", False)
        return None

    # ---------------------------------------------------------------- texts
    def _name(self, node: NamedNode) -> str:
        e = self.exprs.get(node)
        return describe(e) if e is not None else _short(node)

    @staticmethod
    def _filler_text(b: Bound) -> str:
        if b.datatype is not None:
            return _short(b.datatype)
        return describe(b.filler) if b.filler is not None else "Thing"

    def _note(self, low: Bound, other: Bound | Expr, reason: str) -> None:
        key = (low.expr.node if low.expr is not None else low.prop.iri,
               other.node if isinstance(other, Expr) else (other.expr.node if other.expr else f"{other.text}"))
        self.notices.setdefault(key, Notice(INCOMPLETE, low.text, reason, UNNAMED_CLASH))

    # ---------------------------------------------------------------- results
    def checks(self) -> list[Rule]:
        """A ``cls-unsat`` check per topmost class found empty here (see the module)."""
        rules = []
        for node in sorted(self.reason, key=lambda n: n.value):
            why, reported = self.reason[node]
            if reported or node == THING or not self._topmost(node):
                continue
            name = self._name(node)
            rules.append(Rule("cls-unsat", f"{name} has no member: {why}", (Atom("?x", str(TYPE), sparql(node)),),
                              None, violation=("?x",), message=f"{{x}} is a member of {name}, which has no member"))
        return rules

    def _topmost(self, node: NamedNode) -> bool:
        """No class ``node`` is under (other than its equivalents) has no member, and ``node`` is the first of
        its equivalents (named first): a member of it is reported once."""
        same = [s for s in self.above[node] if node in self.above.get(s, ())]
        if any(s in self.reason for s in self.above[node] if s not in same):
            return False
        return node == min(same, key=lambda s: (not self.exprs[s].is_named if s in self.exprs else True, s.value))

    def undecided(self) -> list[Notice]:
        """The :data:`UNNAMED_CLASH` notices: the pairs met while testing the satisfiable classes."""
        self._asked.clear()
        for node, nodes in self.above.items():
            if node not in self.reason:
                self.clash(nodes, note=True)
        return sorted(self.notices.values(), key=lambda n: (n.subject, n.reason))


def functional_data_rules(owl: OwlCompiler, exprs: Iterable[Expr]) -> list[Rule]:
    """``x ∈ ∃d.D``, ``d`` functional, ``x d v`` with ``v`` outside ``D``: inconsistent (the one value
    ``d`` has is the one the existential needs)."""
    rules = []
    for e in exprs:
        low = _lower(e)
        if low is None or e.datatype is None or e.prop.inverse or not owl.tb.has("FunctionalProperty", e.prop.iri):
            continue
        test = in_datatype("?v", e.datatype)
        if not test:
            continue
        d = _short(e.prop.iri)
        rules.append(Rule("cls-svf-fp", f"{describe(e)} and {d} is functional",
                          (Atom("?x", str(TYPE), sparql(e.node)), Atom("?x", sparql(e.prop.iri), "?v")), None,
                          (cond.test(f"!({test})"),), violation=("?x", "?v"),
                          message=f"{{x}} has the value {{v}} of the functional property {d}, outside "
                                  f"{_short(e.datatype)} that {describe(e)} needs"))
    return rules


def unsatisfiable(owl: OwlCompiler) -> tuple[list[Rule], list[Notice]]:
    """The checks of the classes found to have no member, and the notices of the clashes not decided."""
    found = Unsatisfiable(owl)
    return found.checks() + functional_data_rules(owl, owl.all_expressions()), found.undecided()


__all__ = ["UNNAMED_CLASH", "Unsatisfiable", "functional_data_rules", "unsatisfiable"]
