"""Negative membership: rules deriving "x is not an instance of C", and membership of complements from it.

Why
---
A complement on the left (``NonVegetarianPizza ≡ Pizza ⊓ ¬VegetarianPizza``) is a class whose membership
needs what is *not* the case.  OWL 2 RL has no rule for it; a tableau reasoner answers it by refutation.
Much of it needs no case analysis at all: a pizza with a salami topping is not vegetarian because salami
is a meat topping and meat toppings are disjoint with every vegetarian kind.  This module derives such
non-memberships as helper facts ``x ts:notType C`` (helper graph, never shown) and uses them:

=========  ==========================================================================================
rule       derivation (every one sound: it only chains disjointness, nothing is assumed)
=========  ==========================================================================================
neg-dw     x ∈ D, D disjoint with C (disjointWith, AllDisjointClasses, disjoint union, D = ¬C) ⇒ x ∉ C
neg-uni    x ∉ every member of a union ⇒ x ∉ the union
neg-int    x ∉ one conjunct of an intersection ⇒ x ∉ the intersection
neg-avf    x p y, y ∉ U ⇒ x ∉ ∀p.U
neg-svf    x ∈ ∃q.X (≥ n q.X, = n q.X with n ≥ 1), q = p or a told sub-property of p, X disjoint with U
           as told ⇒ x ∉ ∀p.U: the value the existential promises, named or not, is outside U
neg-sco    x ∉ B, A ⊑ B ⇒ x ∉ A (both ways for A ≡ E)
neg-com    x ∉ C ⇒ x ∈ ¬C (then cls-int1 and the equivalences conclude the named class)
neg-empty  x an individual ⇒ x ∉ C, for C with no instance: owl:Nothing, ∃p.⊥ (≥ n p.⊥, = n p.⊥, n ≥ 1)
neg-clash  x ∈ C and x ∉ C: inconsistent (a check)
=========  ==========================================================================================

The rules of one premise, neg-uni of two to eight members (a file per number of members, its rows
joined before its premises: :func:`.condition.leading`) and the universal's neg-avf on a named property
are files of ``rules/owl/``, emitted as rows of their tables (:mod:`.schema`): more complemented classes
are more rows, not more rules.  neg-uni of nine members or more, neg-avf on an inverse property and the
neg-clash checks are written here.

Only the classes whose non-membership some complement needs get rules: the closure of the complemented
classes backwards through the rules above (a complement of C needs x ∉ C; x ∉ A ⊓ B needs x ∉ A or x ∉ B;
…).  An ontology without complements gets none, so its rule set (and a robot step) is unchanged.

What stays underived is named in the load's warning (:meth:`NegativeMembership.gaps`): non-membership of
expressions with no rule above (a value, a one-of, an existential, a cardinality, a data range), and
whatever needs case analysis (y ∈ A ⊔ B with A and B each disjoint with U: y ∉ U by cases).
"""

from __future__ import annotations

import weakref
from functools import cached_property
from typing import TYPE_CHECKING

from pyoxigraph import NamedNode

from ..rdf.terms import sparql
from ..rdf.vocab import INTERNAL, NOTHING, THING, TYPE
from .every_individual import for_every_individual
from .model import Expr, Prop, describe
from .reach import reachable
from .rule import Atom
from .schema import schema_rules

if TYPE_CHECKING:
    from .owl import OwlCompiler

#: helper predicate: ``x ts:notType C`` says x is not an instance of C (derived, helper graph)
NOT_TYPE = NamedNode(INTERNAL + "notType")
T = str(TYPE)
_NOT = str(NOT_TYPE)
#: kinds of expression whose non-membership has rules of its own (a named class has neg-dw and neg-sco)
_WITH_RULES = frozenset({"named", "and", "or", "all", "not"})


def not_type(var: str, e: Expr) -> Atom:
    """Atom: ``var`` is not an instance of ``e`` (a helper fact, read from the default dataset)."""
    return Atom(var, _NOT, sparql(e.node))


class NegativeMembership:
    """The rules of non-membership a TBox's complements need (see the module)."""

    def __init__(self, compiler: OwlCompiler) -> None:
        """The tables below are built when first read: an ontology without complements reads none of them
        (its :meth:`compile` stops at :attr:`complements`), so none of them is built for it.  The compiler
        is held weakly: it holds this part, and a cycle would outlive the compilation (see
        :class:`.owl_restrictions.RestrictionRules`)."""
        self.compiler = weakref.proxy(compiler)

    # ------------------------------------------------------------------ tables read from the TBox
    @cached_property
    def partners(self) -> dict[NamedNode, list[Expr]]:
        """The expressions told disjoint with each class (both ways)."""
        partners: dict[NamedNode, list[Expr]] = {}
        for a, b in self.compiler.disjoint_classes():
            partners.setdefault(a.node, []).append(b)
            partners.setdefault(b.node, []).append(a)
        return partners

    @cached_property
    def disjoint_nodes(self) -> set[tuple[NamedNode, NamedNode]]:
        """The told disjoint pairs as nodes, both ways."""
        return {(a, b) for a, bs in self.partners.items() for b in (x.node for x in bs)}

    @cached_property
    def supers(self) -> dict[NamedNode, list[Expr]]:
        """Told superclass expressions of each class (both sides of an equivalence)."""
        tb = self.compiler.tb
        supers: dict[NamedNode, list[Expr]] = {}
        for a, b in tb.subclass:
            supers.setdefault(a.node, []).append(b)
        for a, b in tb.equivalent:
            supers.setdefault(a.node, []).append(b)
            supers.setdefault(b.node, []).append(a)
        return supers

    @cached_property
    def expressions(self) -> list[Expr]:
        return self.compiler.all_expressions()

    @cached_property
    def complements(self) -> list[Expr]:
        return [e for e in self.expressions if e.kind == "not"]

    # ------------------------------------------------------------------ what is needed
    @cached_property
    def needed(self) -> dict[NamedNode, Expr]:
        """The classes whose non-membership a complement needs, closed backwards through the rules."""
        return self._closure([e.members[0] for e in self.complements])

    def _closure(self, starts: list[Expr]) -> dict[NamedNode, Expr]:
        """``starts`` and the classes whose non-membership their rules read, and so on (owl:Thing,
        which nothing is outside of, ends a walk), in the order the walk first meets them."""
        found: dict[NamedNode, Expr] = {}
        todo = list(starts)
        while todo:
            c = todo.pop()
            if c.node in found or c.node == THING:
                continue
            found[c.node] = c
            todo += self._premises(c)
        return found

    def _premises(self, c: Expr) -> list[Expr]:
        """The classes whose non-membership the rules concluding ``x ∉ c`` read."""
        out = list(self.supers.get(c.node, ()))
        if c.kind in ("and", "or"):
            out += c.members
        elif c.kind == "all" and self._class_filler(c) is not None:
            out.append(self._class_filler(c))
        return out

    def _class_filler(self, e: Expr) -> Expr | None:
        """The class filler of an object universal restriction (None for Thing or a data range)."""
        if e.filler is None or e.filler.node == THING or self.compiler.is_data(e.prop, e):
            return None
        return e.filler

    # ------------------------------------------------------------------ rules
    def compile(self) -> None:
        """Emit the rules and checks (nothing when the TBox has no complement)."""
        for e in self.complements:
            self.compiler.instantiate((e.term, e.members[0].term), f"class expression {e}", "neg-com")
        for c in self.needed.values():
            self._rules_for(c)

    def _rules_for(self, c: Expr) -> None:
        emit, x, origin = self.compiler.emit, "?x", f"not in {describe(c)}"
        head, row = not_type(x, c), self.compiler.instantiate
        if has_no_instance(c):
            self.compiler.rules += for_every_individual("neg-empty", f"{describe(c)} has no instance", head)
            return
        for d in self.partners.get(c.node, ()):
            row((d.term, c.term), f"{describe(d)} and {describe(c)} are disjoint", "neg-dw")
        for b in self.supers.get(c.node, ()):
            if b.node != THING:
                row((c.term, b.term), f"{describe(c)} is subsumed by {describe(b)}", "neg-sco")
        if c.kind == "or" and c.members and all(m.node != THING for m in c.members):
            # n members, n premises: a file of rules/owl/ per number of members, up to the widest
            width = f"neg-uni-{len(c.members)}"
            if width not in schema_rules() or not row((c.term, *(m.term for m in c.members)), origin, width):
                emit("neg-uni", origin, [not_type(x, m) for m in c.members], head)
        elif c.kind == "and":
            for m in c.members:
                if m.node != THING:
                    row((c.term, m.term), origin, "neg-int")
        elif c.kind == "all" and self._class_filler(c) is not None:
            self._universal(c, head)
        if c.node != NOTHING:
            emit("neg-clash", origin, [Atom(x, T, sparql(c.node)), head], violation=(x,),
                 message=f"{{x}} is in {describe(c)} and, by disjoint classes, not in it")

    def _universal(self, c: Expr, head: Atom) -> None:
        """neg-avf over known values; neg-svf over the existentials whose filler is disjoint with U."""
        u = self._class_filler(c)
        assert u is not None and c.prop is not None
        x, y = "?x", "?y"
        named = None if c.prop.inverse else (c.term, sparql(c.prop.iri), u.term)
        if not self.compiler.instantiate(named, f"not in {describe(c)}", "neg-avf"):  # an inverse: no row
            self.compiler.emit("neg-avf", f"not in {describe(c)}",
                               [self.compiler.prop_atom(x, c.prop, y), not_type(y, u)], head)
        below = self._sub_properties(c.prop)
        for e in self.expressions:
            if e.prop not in below or e.kind not in ("some", "min", "exact") or (e.kind != "some" and e.n < 1):
                continue
            if e.filler is not None and self.class_disjoint(e.filler, u):
                self.compiler.instantiate((e.term, c.term), f"the value of {describe(e)} is not in {describe(u)}",
                                          "neg-svf")

    def _sub_properties(self, p: Prop) -> set[Prop]:
        """``p`` and its told sub-properties (closure; q ⊑ p gives q⁻ ⊑ p⁻): a value by any of them is a
        value by ``p``, so an existential on one promises a value ∀p.U constrains."""
        down: dict[Prop, set[Prop]] = {}
        for q, r in self.compiler.tb.subproperty:
            down.setdefault(r, set()).add(q)
            down.setdefault(Prop(r.iri, not r.inverse), set()).add(Prop(q.iri, not q.inverse))
        return reachable(p, lambda q: down.get(q, ()))

    # ------------------------------------------------------------------ told disjointness of classes
    def class_disjoint(self, a: Expr, b: Expr) -> bool:
        """Told: no instance of ``a`` is an instance of ``b`` (through named superclasses, the members of
        a union — each — and of an intersection — one)."""
        if b.kind == "or":
            return bool(b.members) and all(self.class_disjoint(a, m) for m in b.members)
        if a.kind == "or":
            return bool(a.members) and all(self.class_disjoint(m, b) for m in a.members)
        if b.kind == "and" and any(self.class_disjoint(a, m) for m in b.members):
            return True
        if a.kind == "and" and any(self.class_disjoint(m, b) for m in a.members):
            return True
        return any((p, q) in self.disjoint_nodes for p in self._ancestors(a) for q in self._ancestors(b))

    def _ancestors(self, e: Expr) -> set[NamedNode]:
        return {e.node, *self.compiler.told.get(e.node, set())} if e.is_named else {e.node}

    # ------------------------------------------------------------------ what the warning says
    def gaps(self, complement: Expr) -> list[Expr]:
        """The expressions, in the closure a complement needs, whose non-membership no rule derives."""
        return [c for c in self._closure([complement.members[0]]).values() if not has_no_instance(c)
                and (c.kind not in _WITH_RULES or (c.kind == "all" and self._class_filler(c) is None))]


def has_no_instance(c: Expr) -> bool:
    """Whether ``c`` is empty whatever the facts: owl:Nothing, or an existential (a minimum or exact
    cardinality of at least one) into it.  Every individual is outside it, which the rules of a complement
    reading it need (``¬(A ⊔ ∃p.⊥)``): nothing else derives "x is not in owl:Nothing"."""
    if c.node == NOTHING:
        return True
    return (c.kind == "some" or (c.kind in ("min", "exact") and c.n >= 1)) and c.filler is not None \
        and c.filler.node == NOTHING


__all__ = ["NOT_TYPE", "NegativeMembership", "has_no_instance", "not_type"]
