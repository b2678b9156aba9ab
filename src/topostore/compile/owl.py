"""OWL axioms → rules.

Implements the OWL 2 RL/RDF rules (W3C OWL 2 Profiles §4.3) for the axioms an
ontology actually contains, each rule instantiated for one axiom, plus what a
tableau reasoner such as Pellet concludes beyond OWL 2 RL on this kind of
ontology:

* membership by qualified minimum cardinality (≥ n fillers that are pairwise
  different) and by exact cardinality (when a maximum is also known);
* subsumption between restrictions (≥ n by ≥ m for m ≤ n, and by someValuesFrom),
  so that e.g. every ``≥2 hasDoor.DOOR`` is also ``∃hasDoor.DOOR``;
* domain/range typing, functional properties merging individuals (owl:sameAs)
  unless they are known to be different, in which case the ontology is inconsistent.

Rule names are the W3C names (``prp-dom``, ``cls-int1``, ...) or ``ext-*`` for
the extensions; the origin says which axiom the rule was made from.

The rules of the kinds of axiom that fit a row of fixed width (class and property hierarchies,
equivalent classes, domain, range, inverse, symmetric, transitive, chains of two, disjointness,
restrictions by kind, restriction subsumption, a functional or inverse-functional property's sameAs rule,
check and candidate rule, the rules finding two individuals different by two values of a data property
allowing one) are not written here: they are the generic rules
of ``rules/owl/`` instantiated with the axiom's row of its schema table (:mod:`.schema`); a full
REASON reads those rows back from the rules and may run the generic rule over them instead
(:mod:`.schema_program`).  An axiom without a row (an inverse property, a longer chain) keeps the
rule written here.  The pairs of disjoint classes are not even instantiated: they are rows
(:mod:`.disjointness`), instantiated only for what maintains them rule by rule.
"""

from __future__ import annotations

from collections.abc import Sequence

from pyoxigraph import Literal, NamedNode

from ..rdf.terms import sparql
from ..rdf.vocab import NOTHING, SAME_AS, THING, TYPE
from . import condition as cond
from .condition import Condition
from .datatypes import implied_ranges
from .disjointness import Disjointness
from .fillers import FillerIndex, Subsumption, told_superclasses
from .model import Expr, Prop, TBox
from .negation import NegativeMembership
from .notices import Notice
from .owl_restrictions import RestrictionRules, nm
from .property_hierarchy import single_valued
from .rule import Atom, Rule
from .schema import Row, schema_rule, schema_rules
from .schema_rows import chain_row, class_row, disjoint_row, member_row, subproperty_row, typing_row, value_row
from .snippets import (
    candidate_atom,
    different_atom,
    distinct_values,
    in_datatype,
    same_value,
    surely_in_datatype,
)

T = str(TYPE)


def _walk(found: dict[NamedNode, Expr], e: Expr | None) -> None:
    """``e`` and its sub-expressions into ``found`` by node, each once, in the order met (as :func:`_link`,
    a function of the module)."""
    if e is None or e.node in found:
        return
    found[e.node] = e
    for m in e.members:
        _walk(found, m)
    _walk(found, e.filler)


class OwlCompiler:
    """TBox → rules.  The rules of restrictions with fillers are a named part (:attr:`restrictions`)
    that emits through this compiler's :meth:`emit` and reads its TBox helpers."""

    def __init__(self, tbox: TBox) -> None:
        self.tb = tbox
        #: the rules of restrictions with fillers (cardinalities, some/all values), a named part
        self.restrictions = RestrictionRules(self)
        self.rules: list[Rule] = []
        self.notices: list[Notice] = []
        #: the pairs of disjoint classes, as rows: no rule is emitted per pair (see :mod:`.disjointness`)
        self.disjointness = Disjointness()
        #: the told disjoint pairs of named classes (read by the parts of the compiler)
        self.disjoint_pairs = [
            (a.node, b.node) for a, b in tbox.disjoint if a.is_named and b.is_named
        ]
        self.told = told_superclasses(tbox)
        #: told subsumption between class expressions and fillers, each pair decided once
        self.subsumption = Subsumption(self.told)
        #: :meth:`all_expressions`, once walked
        self._expressions: list[Expr] | None = None
        #: :meth:`disjoint_classes`, once found
        self._disjoint: list[tuple[Expr, Expr]] | None = None
        #: the rules of non-membership the complements need, a named part
        self.negation = NegativeMembership(self)
        #: the property expressions with at most one value (a functional one's sub-properties too)
        self.single_valued = single_valued(tbox)

    # ------------------------------------------------------------------ helpers
    @staticmethod
    def member(var: str, e: Expr | None) -> list[Atom]:
        """Atoms saying ``var`` is an instance of ``e`` (none for owl:Thing)."""
        if e is None or e.node == THING:
            return []
        return [Atom(var, T, sparql(e.node))]

    @staticmethod
    def prop_atom(s: str, p: Prop, o: str) -> Atom:
        return Atom(o, sparql(p.iri), s) if p.inverse else Atom(s, sparql(p.iri), o)

    def is_data(self, p: Prop, e: Expr | None = None) -> bool:
        return (e is not None and e.is_data) or p.iri in self.tb.data_properties

    def emit(self, name: str, origin: str, body: list[Atom], head: Atom | None = None,
             filters: Sequence[Condition] = (), reads: frozenset = frozenset(), violation: tuple[str, ...] = (),
             message: str = "", stratum: int = 0, value_range: tuple[str, str] | None = None) -> None:
        self.rules.append(Rule(name, origin, tuple(body), head, tuple(filters), reads, violation, message,
                               stratum=stratum, value_range=value_range))

    def instantiate(self, row: Row | None, origin: str, *names: str, labels: Sequence[str] | None = None) -> bool:
        """Emit the generic rules ``names`` instantiated with the axiom's ``row`` (``labels``: how a
        check's message names its terms); False (nothing emitted) when the axiom has no row (e.g. a
        domain of an inverse property expression)."""
        if row is None:
            return False
        for name in names:
            self.rules.append(schema_rule(name).instantiate(row, origin, labels))
        return True

    def type_head(self, var: str, e: Expr) -> Atom | None:
        return None if e.node == THING else Atom(var, T, sparql(e.node))

    def disjoint_classes(self) -> list[tuple[Expr, Expr]]:
        """Every pair of disjoint class expressions: disjointWith, AllDisjointClasses, the parts of a
        disjoint union, and an expression with its complement (owl:Thing left out: it says nothing
        of a pair).  Found once per compiler (the TBox is read whole before): the difference rows and
        the negation part both ask, and a TBox of siblings made disjoint has tens of thousands."""
        if self._disjoint is None:
            pairs = {(a.node, b.node): (a, b) for a, b in self.tb.disjoint}
            for e in self.all_expressions():
                if e.kind == "not":
                    pairs.setdefault((e.node, e.members[0].node), (e, e.members[0]))
            self._disjoint = [(a, b) for a, b in pairs.values() if a.node != b.node and THING not in (a.node, b.node)]
        return list(self._disjoint)

    def difference_rules(self) -> None:
        """When asked about a pair, conclude it is different if equality would be
        inconsistent: disjoint classes, or two distinct values of a data property
        that allows at most one (functional, or a maximum of one for a class of
        either individual).

        Members of disjoint classes are different as plainly as declared individuals are:
        a tableau reasoner sees both classes in the individuals' labels, and Pellet fires
        SWRL rules on that difference and on what those rules conclude.  Two values of a
        property allowing one are a difference found by refutation (e.g. two locations with
        different ``visitedAt`` times): entailed, but it fires no further rules."""
        a, b, v1, v2 = "?a", "?b", "?v1", "?v2"
        for c1, c2 in self.disjoint_classes():
            for x, y in ((c1, c2), (c2, c1)):
                self.disjointness.add_different(disjoint_row(x, y), x, y)
        for p in sorted(self.tb.characteristics.get("FunctionalProperty", ()), key=lambda t: t.value):
            if p in self.tb.data_properties:  # a row of rules/owl/different-values-3.rq
                self.instantiate((sparql(p),), f"{nm(p)} is functional", "different-values-3")
        for e in self.all_expressions():
            if e.kind not in ("max", "exact") or e.n != 1 or e.prop.inverse or not self.is_data(e.prop, e):
                continue
            origin = f"class expression {e} allows one value"
            if e.datatype is None or self._range_within(e.prop.iri, e.datatype):  # rows of different-values-4-*
                self.instantiate((e.term, sparql(e.prop.iri)), origin, "different-values-4-a", "different-values-4-b")
                continue
            tests = [cond.test(distinct_values(v1, v2)),
                     cond.test(f"{surely_in_datatype(v1, e.datatype)} && {surely_in_datatype(v2, e.datatype)}")]
            for member in (a, b):  # a filter naming the datatype: no row (the files' filters read no schema term)
                self.emit("different-values", origin,
                          [candidate_atom(a, b), Atom(member, T, sparql(e.node)),
                           Atom(a, sparql(e.prop.iri), v1), Atom(b, sparql(e.prop.iri), v2)],
                          different_atom(a, b), tests)

    def _range_within(self, p: NamedNode, datatype: NamedNode) -> bool:
        """Whether every value of ``p`` outside ``datatype`` is already a range violation: each told
        range of ``p`` is checked (``dt-range``) and together they imply ``datatype``.  A test that a
        value is in ``datatype`` then holds in every consistent store, and leaving it out keeps the
        rule short (a robot step parses its text: the SWRL rules that join this difference too)."""
        told = [dt for q, dt in self.tb.data_range if q == p]
        return bool(told) and all(in_datatype("?v", dt) for dt in told) and datatype in implied_ranges(told)

    def filler_subsumed(self, a: Expr, b: Expr) -> bool:
        """Told: every instance of filler ``a`` is an instance of filler ``b`` (:class:`.fillers.Subsumption`)."""
        return self.subsumption.fillers(a, b)

    # ------------------------------------------------------------------ expressions
    def all_expressions(self) -> list[Expr]:
        """Every class expression of the axioms and the typed expressions, each once (by node).

        Walked once per compiler (its TBox is read whole before the compiler is made): the parts of the
        compilation ask for it again and again."""
        if self._expressions is None:
            self._expressions = self._walk_expressions()
        return list(self._expressions)

    def _walk_expressions(self) -> list[Expr]:
        found: dict[NamedNode, Expr] = {}
        tb = self.tb
        for a, b in tb.subclass + tb.equivalent + tb.disjoint:
            _walk(found, a)
            _walk(found, b)
        for _, e in tb.domain + tb.range:
            _walk(found, e)
        for e in tb.typed_expressions:
            _walk(found, e)
        return list(found.values())

    def expression_rules(self, e: Expr) -> None:
        x, y = "?x", "?y"
        node = sparql(e.node)
        origin = f"class expression {e}"
        if e.kind == "and":
            body = [a for m in e.members for a in self.member(x, m)]
            width = f"cls-int1-{len(body)}"  # a file of rules/owl/ per number of members, up to the widest
            if body and (width not in schema_rules() or not self.instantiate((node, *(a.o for a in body)), origin,
                                                                               width)):
                self.emit("cls-int1", origin, body, Atom(x, T, node))
            for m in e.members:
                self.instantiate(member_row(e, m), origin, "cls-int2")
        elif e.kind == "or":
            for m in e.members:
                self.instantiate(member_row(e, m), origin, "cls-uni")
            if len(e.members) == 1:  # a union of one member (owl:Nothing ones dropped) is that member
                self.instantiate(member_row(e, e.members[0]), origin, "cls-int2")
        elif e.kind == "oneof":
            for ind in e.individuals:
                self.instantiate((node, sparql(ind)), origin, "cls-oo")
            if len(set(e.individuals)) == 1:  # x ∈ {b} is x sameAs b: Horn (not in OWL 2 RL), no choice to make
                one = sparql(e.individuals[0])
                self.emit("cls-oo1", origin, [Atom(x, T, node)], Atom(x, sparql(SAME_AS), one),
                          [cond.test(f"!sameTerm({x}, {one})")])
        elif e.kind == "not":
            self.emit("cls-com", origin, [Atom(x, T, node)] + self.member(x, e.members[0]),
                      violation=(x,), message=f"an individual is in {e.members[0]} and in its complement")
        elif e.kind == "value" and isinstance(e.value, Literal) and same_value(y, e.value) is not None:
            # a value with other spellings (3.0 is 3): members by value; the value itself as usual
            if not self.instantiate(value_row(e), origin, "cls-hv1"):
                self.emit("cls-hv1", origin, [Atom(x, T, node)], self.prop_atom(x, e.prop, sparql(e.value)))
            self.emit("cls-hv2", origin, [self.prop_atom(x, e.prop, y)], Atom(x, T, node),
                      [cond.test(same_value(y, e.value))])
        elif e.kind == "value":
            if not self.instantiate(value_row(e), origin, "cls-hv1", "cls-hv2"):
                self.emit("cls-hv1", origin, [Atom(x, T, node)], self.prop_atom(x, e.prop, sparql(e.value)))
                self.emit("cls-hv2", origin, [self.prop_atom(x, e.prop, sparql(e.value))], Atom(x, T, node))
        elif e.kind == "self":
            self.emit("cls-self1", origin, [Atom(x, T, node)], self.prop_atom(x, e.prop, x))
            self.emit("cls-self2", origin, [self.prop_atom(x, e.prop, x)], Atom(x, T, node))
        elif e.kind == "all":
            self.restrictions.all_rules(e, node, origin)
        elif e.kind in ("some", "min", "exact"):
            self.restrictions.lower_bound_rules(e, node, origin)
        if e.kind in ("max", "exact"):
            self.restrictions.upper_bound_rules(e, node, origin)

    def restriction_subsumption(self, exprs: list[Expr]) -> None:
        """≥n p.C ⊑ ≥m p.D (n ≥ m ≥ 1, C ⊑ D), with ∃ as ≥1 and = n as ≥ n; and = n p.C ⊑ = n p.D when
        C ≡ D (two restrictions written alike are one class).

        Only restrictions on one property are compared, those whose filler may subsume ``a``'s found
        through an index (:class:`.fillers.FillerIndex`): a tutorial-style TBox has hundreds of
        existentials on one property over a few hundred fillers."""
        lower = [e for e in exprs if e.kind in ("some", "min", "exact")]
        on: dict[Prop | None, list[Expr]] = {}
        for e in lower:
            on.setdefault(e.prop, []).append(e)
        index = {p: FillerIndex(self.subsumption, group) for p, group in on.items()}
        for a in lower:
            na = 1 if a.kind == "some" else a.n
            for b in index[a.prop].subsuming(a):
                if a.node == b.node:
                    continue
                if b.kind == "exact" and not (a.kind == "exact" and a.n == b.n and self.filler_subsumed(b, a)):
                    continue
                nb = 1 if b.kind == "some" else b.n
                if na >= nb >= 1:
                    self.instantiate(class_row(a, b), f"{a} is subsumed by {b}", "ext-card-sub")

    # ------------------------------------------------------------------ axioms
    def class_axioms(self) -> None:
        for a, b in self.tb.subclass:
            self.instantiate(class_row(a, b), f"{a} SubClassOf {b}", "cax-sco")
        for a, b in self.tb.equivalent:
            self.instantiate(class_row(a, b), f"{a} EquivalentTo {b}", "cax-eqc1", "cax-eqc2")
        for a, b in self.tb.disjoint:
            if self.disjointness.add_told(disjoint_row(a, b), a, b):
                continue
            body = self.member("?x", a) + self.member("?x", b)
            if body:  # with owl:Thing: a check of one class
                self.emit("cax-dw", f"{a} DisjointWith {b}", body, violation=("?x",),
                          message=f"{{x}} is in the disjoint classes {a} and {b}")
        self.emit("cls-nothing2", "owl:Nothing has no instances", [Atom("?x", T, sparql(NOTHING))], violation=("?x",),
                  message="{x} is an instance of owl:Nothing")

    def property_axioms(self) -> None:
        tb = self.tb
        x, y = "?x", "?y"
        for p, c in tb.domain:
            origin = f"{nm(p.iri)} domain {c}"
            if not self.instantiate(typing_row(p, c), origin, "prp-dom") and c.node != THING:
                self.emit("prp-dom", origin, [self.prop_atom(x, p, y)], Atom(x, T, sparql(c.node)))
        for p, c in tb.range:
            origin = f"{nm(p.iri)} range {c}"
            if not self.instantiate(typing_row(p, c), origin, "prp-rng") and c.node != THING:
                self.emit("prp-rng", origin, [self.prop_atom(x, p, y)], Atom(y, T, sparql(c.node)))
        for p, dt in tb.data_range:
            test = in_datatype(y, dt)
            if test:
                self.emit("dt-range", f"{nm(p)} range {nm(dt)}", [Atom(x, sparql(p), y)],
                          filters=[cond.test(f"isLITERAL({y}) && !({test})")],  # an IRI: a punned use, not a value
                          violation=(x, y), message=f"{{x}} has the value {{y}} of {nm(p)}, outside its range {nm(dt)}",
                          value_range=(p.value, dt.value))
        for p, q in tb.subproperty:
            origin = f"{nm(p.iri)} SubPropertyOf {nm(q.iri)}"
            if not self.instantiate(subproperty_row(p, q), origin, "prp-spo1") and p != q:
                self.emit("prp-spo1", origin, [self.prop_atom(x, p, y)], self.prop_atom(x, q, y))
        for p, q in tb.inverse:
            self.instantiate((sparql(p), sparql(q)), f"{nm(p)} InverseOf {nm(q)}", "prp-inv1", "prp-inv2")
        for q, chain in tb.chains:
            origin = f"{nm(q)} chain of {' o '.join(nm(p.iri) for p in chain)}"
            if self.instantiate(chain_row(q, chain), origin, "prp-spo2"):
                continue
            vars_ = [f"?u{i}" for i in range(len(chain) + 1)]
            body = [self.prop_atom(vars_[i], p, vars_[i + 1]) for i, p in enumerate(chain)]
            self.emit("prp-spo2", origin, body, Atom(vars_[0], sparql(q), vars_[-1]))
        for p, q in tb.disjoint_props:
            self.emit("prp-pdw", f"{nm(p)} DisjointWith {nm(q)}", [Atom(x, sparql(p), y), Atom(x, sparql(q), y)],
                      violation=(x, y),
                      message=f"{{x}} is linked to {{y}} by the disjoint properties {nm(p)} and {nm(q)}")
        ch = tb.characteristics
        for p in ch.get("SymmetricProperty", ()):
            self.instantiate((sparql(p),), f"{nm(p)} is symmetric", "prp-symp")
        for p in ch.get("TransitiveProperty", ()):
            self.instantiate((sparql(p),), f"{nm(p)} is transitive", "prp-trp")
        for p in ch.get("AsymmetricProperty", ()):
            self.emit("prp-asyp", f"{nm(p)} is asymmetric", [Atom(x, sparql(p), y), Atom(y, sparql(p), x)],
                      violation=(x, y), message=f"{{x}} and {{y}} are linked both ways by the asymmetric {nm(p)}")
        for p in ch.get("IrreflexiveProperty", ()):
            self.emit("prp-irp", f"{nm(p)} is irreflexive", [Atom(x, sparql(p), x)], violation=(x,),
                      message=f"{{x}} is linked to itself by the irreflexive {nm(p)}")
        for p in ch.get("FunctionalProperty", ()):
            self._functional(p, inverse=False)
        for p in ch.get("InverseFunctionalProperty", ()):
            self._functional(p, inverse=True)

    def _functional(self, p: NamedNode, inverse: bool) -> None:
        """Rows of the property's files: its check (two values, or two subjects, known different; two
        distinct values of a data property), and for an object property the candidate rule asking whether
        the two differ and the sameAs rule (rules/owl/prp-fp*.rq, prp-ifp*.rq, different-candidate-2-*.rq)."""
        name = "prp-ifp" if inverse else "prp-fp"
        origin = f"{nm(p)} is {'inverse functional' if inverse else 'functional'}"
        row, labels = (sparql(p),), [nm(p)]
        if not inverse and p in self.tb.data_properties:
            self.instantiate(row, origin, "prp-fp-2-data", labels=labels)
            return
        self.instantiate(row, origin, f"different-candidate-2-{name[4:]}")
        self.instantiate(row, origin, f"{name}-3", labels=labels)
        self.instantiate(row, origin, name)

    def compile(self) -> list[Rule]:
        exprs = self.all_expressions()
        for e in exprs:
            if not e.is_named:
                self.expression_rules(e)
        self.restriction_subsumption(exprs)
        self.class_axioms()
        self.property_axioms()
        self.difference_rules()
        self.negation.compile()
        return self.rules


__all__ = ["OwlCompiler"]
