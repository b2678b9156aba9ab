"""The profile report: every axiom topostore does not reason completely, with the reason.

topostore compiles OWL to Horn rules (OWL 2 RL plus the cardinality reasoning of
:mod:`.owl_restrictions`).  What needs case analysis (a union as a superclass, a
maximum cardinality of two or more) or unnamed individuals (an existential whose
value would carry consequences) is not derived: a tableau reasoner such as Pellet
answers more there.  This module finds those axioms from where each class
expression is used, so that such a difference is never silent:

* an expression used *positively* (a superclass, a range, a type, a rule head) is
  one whose membership is told; its consequences must be drawn;
* one used *negatively* (a subclass, a rule body, a disjointness) is one whose
  membership must be derived.

=================================  =====================================================
union / one-of, positively          non-Horn: which member is not known (a one-of of one
                                    individual is Horn: x ∈ {b} ⇒ x sameAs b, .owl)
complement, negatively              non-membership by case analysis (:mod:`.negation`)
universal restriction, negatively   membership needs every value known
max cardinality, negatively         idem, when a maximum can be told elsewhere
max cardinality ≥ 2, positively     which of the values are equal is not known
existential, positively             the unnamed value's consequences (a single value,
                                    disjoint classes, nested restrictions, chains through
                                    it; the subject's domains are derived: .owl_extras)
difference by irreflexivity         x p y ⇒ x ≠ y is not used where difference matters
range or universal into a datatype  a value outside a datatype topostore does not test (a
not tested                          user's own, undefined) is not found
=================================  =====================================================

plus the axioms the reader set aside (:attr:`TBox.unsupported`), those read
in part (:attr:`TBox.partial`: a disjoint union's covering), and what is read off the graph itself
(:mod:`.graph_notices`): statements about the RDF list vocabulary (``rdf:nil`` with a first element or
a rest: inconsistent under the RDF-Based semantics, not reasoned), imports of ontologies not loaded, the
universal and empty properties (``owl:topObjectProperty`` …), and, informatively, the reflexivity of
``owl:sameAs`` (:data:`~.notices.NOT_STORED`) when a file uses it.
"""

from __future__ import annotations

from collections.abc import Iterator
from functools import cached_property

from pyoxigraph import NamedNode

from ..rdf.vocab import THING
from ..stores.base import Store
from . import graph_notices
from .model import Expr, Prop, TBox, describe, short_name
from .notices import (
    ANNOTATION,
    COMPLEMENT,
    DIFFERENCE,
    EXISTENTIAL,
    INCOMPLETE,
    MAX_CASES,
    MAX_LEFT,
    NOT_STORED,
    UNCHECKED_DATATYPE,
    UNION,
    UNIVERSAL,
    UNSUPPORTED,
    Notice,
)
from .owl import OwlCompiler
from .property_hierarchy import inverse, subject_classes, super_expressions
from .unnamed_values import UnnamedValues

#: (expression, positive?, the axiom it occurs in, the axiom's named subject or None)
Use = tuple[Expr, bool, str, NamedNode | None]


def _uses(e: Expr, positive: bool, axiom: str, subject: NamedNode | None) -> Iterator[Use]:
    """Every sub-expression of ``e`` with its polarity (complement and maximum flip it)."""
    yield e, positive, axiom, subject
    if e.kind in ("and", "or"):
        for m in e.members:
            yield from _uses(m, positive, axiom, subject if e.kind == "and" else None)
    elif e.kind == "not":
        yield from _uses(e.members[0], not positive, axiom, None)
    elif e.filler is not None:
        if e.kind == "exact":
            yield from _uses(e.filler, True, axiom, None)
            yield from _uses(e.filler, False, axiom, None)
        else:
            yield from _uses(e.filler, positive if e.kind != "max" else not positive, axiom, None)


def all_uses(tb: TBox, rule_uses: list[tuple[Expr, bool]]) -> list[Use]:
    """Where each class expression of the ontology occurs, and how."""
    out: list[Use] = []
    for a, b in tb.subclass:
        axiom = f"{describe(a)} SubClassOf {describe(b)}"
        out += [*_uses(a, False, axiom, None), *_uses(b, True, axiom, a.node if a.is_named else None)]
    for a, b in tb.equivalent:
        axiom = f"{describe(a)} EquivalentTo {describe(b)}"
        for x, y in ((a, b), (b, a)):
            out += [*_uses(x, False, axiom, None), *_uses(y, True, axiom, x.node if x.is_named else None)]
    for a, b in tb.disjoint:
        axiom = f"{describe(a)} DisjointWith {describe(b)}"
        out += [*_uses(a, False, axiom, None), *_uses(b, False, axiom, None)]
    for p, c in tb.domain:
        out += list(_uses(c, True, f"{short_name(p.iri)} domain {describe(c)}", None))
    for p, c in tb.range:
        out += list(_uses(c, True, f"{short_name(p.iri)} range {describe(c)}", None))
    for e in tb.typed_expressions:
        out += list(_uses(e, True, f"an individual typed {describe(e)}", None))
    for c, props in tb.keys:
        out += list(_uses(c, False, f"{describe(c)} HasKey ({' '.join(short_name(p.iri) for p in props)})", None))
    for e, head in rule_uses:
        out += list(_uses(e, head, f"a SWRL rule {'head' if head else 'body'} atom {describe(e)}", None))
    return out


class ProfileReport:
    """Finds the axioms not reasoned completely (see the module)."""

    def __init__(self, tb: TBox, owl_compiler: OwlCompiler, rule_uses: list[tuple[Expr, bool]],
                 uses_difference: bool) -> None:
        self.tb, self.owl = tb, owl_compiler
        self.uses = all_uses(tb, rule_uses)
        #: restriction uses by property: (expression, positive), so lookups stay linear in the TBox
        self.on: dict[Prop, list[tuple[Expr, bool]]] = {}
        for e, positive, _, _ in self.uses:
            if e.prop is not None:
                self.on.setdefault(e.prop, []).append((e, positive))
        self.uses_difference = uses_difference
        self.notices: dict[tuple[str, str], Notice] = {}
        #: :meth:`single_valued`'s answers by property
        self._single: dict[Prop, Expr | str | None] = {}
        #: what an existential's unnamed value implies beyond its own restriction (:mod:`.unnamed_values`)
        self.unnamed = UnnamedValues(self)

    def note(self, kind: str, axiom: str, reason: str) -> None:
        self.notices.setdefault((kind, axiom), Notice(INCOMPLETE, axiom, reason, kind))

    def note_existential(self, axiom: str, reason: str) -> None:
        self.note(EXISTENTIAL, axiom, reason)

    def told(self, c: NamedNode) -> set[NamedNode]:
        """``c`` and its told named superclasses."""
        return {c, *self.owl.told.get(c, set())}

    def run(self, store: Store, graph: NamedNode) -> list[Notice]:
        for e, positive, axiom, subject in self.uses:
            self.expression(e, positive, axiom, subject)
        self.difference()
        for a, b in self.tb.same_properties:
            self.note(UNSUPPORTED, f"{short_name(a)} sameAs {short_name(b)}", "properties made the same are not "
                      "substituted for each other (owl:equivalentProperty is)")
        for axiom, reason in self.tb.unsupported:
            self.note(UNSUPPORTED, axiom, f"set aside: {reason}")
        for axiom, kind, reason in self.tb.partial:
            self.note(kind, axiom, reason)
        self.annotation_notices()
        graph_notices.unchecked_datatypes(self.note, self.tb.data_range, self.uses, store, graph)
        graph_notices.list_vocabulary(self.note, store, graph)
        graph_notices.malformed_lists(self.note, store, graph)
        graph_notices.imports(self.note, store, graph)
        graph_notices.top_and_bottom(self.note, store, graph)
        same_as = graph_notices.reflexive_equality(store, graph)
        if same_as is not None:
            self.notices.setdefault((NOT_STORED, "owl:sameAs"), same_as)
        return list(self.notices.values())

    def annotation_notices(self) -> None:
        """One notice per annotation property whose axioms were set aside, and per IRI declared both an
        annotation and an object or data property (OWL 2 DL forbids it; the object or data reading is kept)."""
        for p, axioms in self.tb.annotation_axioms.items():
            self.notices.setdefault((ANNOTATION, p.value), Notice(
                ANNOTATION, short_name(p), f"an annotation property: {'; '.join(axioms)} set aside, as Pellet does"))
        for p in sorted(self.tb.annotation_punned, key=lambda n: n.value):
            self.notices.setdefault((ANNOTATION, p.value), Notice(
                ANNOTATION, short_name(p), "declared both an annotation property and an object or data property "
                "(or told an axiom only those have: a characteristic of object properties, an inverse, a chain), which "
                "OWL 2 DL forbids: read as the object or data property"))

    # ---------------------------------------------------------------- expressions
    def expression(self, e: Expr, positive: bool, axiom: str, subject: NamedNode | None = None) -> None:
        k = e.kind
        if positive and k == "or" and len(e.members) > 1 and all(m.node != THING for m in e.members):
            self.note(UNION, axiom, f"an instance of {describe(e)} is in one of its members, which one is not "
                      "known: conclusions by case analysis are not drawn")
        elif positive and k == "oneof" and len(set(e.individuals)) > 1:  # {b}: x sameAs b is derived
            self.note(UNION, axiom, f"an instance of {describe(e)} is one of those individuals: which one "
                      "(owl:sameAs) is not derived")
        elif not positive and k == "not":
            self.note(COMPLEMENT, axiom, self.complement_gap(e))
        elif not positive and k == "all":
            self.note(UNIVERSAL, axiom, f"membership of {describe(e)} needs every value known: never derived")
        elif not positive and k == "max" and self.max_told(e.prop):
            self.note(MAX_LEFT, axiom, f"membership of {describe(e)} is derived only from the same restriction "
                      "told, not from other maxima or functional properties")
        if positive and k in ("max", "exact") and e.n >= 2 and not self.owl.is_data(e.prop, e):
            self.note(MAX_CASES, axiom, f"more than {e.n} values not known to be different: which are equal "
                      "needs case analysis, not drawn")
        if positive and k in ("some", "min", "exact") and (k == "some" or e.n >= 1):
            self.existential(e, axiom, subject)

    def complement_gap(self, e: Expr) -> str:
        """What of a complement's membership is not derived: the rules of :mod:`.negation` derive that an
        individual is outside the complemented class from disjoint classes, through intersections, unions,
        subclasses and universal restrictions; never by case analysis, nor for the parts without rules."""
        inner = describe(e.members[0])
        said = (f"membership of {describe(e)} is derived only where not being in {inner} follows from disjoint "
                "classes through intersections, unions, subclasses and universal restrictions (over known values "
                "or an existential's value of a class told disjoint with the filler); where it needs case "
                "analysis it is not derived")
        gaps = self.owl.negation.gaps(e)
        if gaps:
            said += "; not being in " + ", ".join(describe(g) for g in gaps) + " is never derived"
        return said

    def max_told(self, p: Prop) -> bool:
        """Some axiom or characteristic tells a maximum on ``p`` (so a reasoner may derive membership)."""
        if p in self.owl.single_valued:  # functional, or under a functional property
            return True
        return any(pos and e.kind in ("max", "exact") for e, pos in self.on.get(p, ()))

    def existential(self, e: Expr, axiom: str, subject: NamedNode | None = None) -> None:
        """Consequences of the unnamed value of an existential that are not drawn (``subject``: the named
        class it is told of, None where it is nested, a rule atom or an individual's type)."""
        p, what = e.prop, describe(e)
        supers = self.supers.get(p, frozenset())
        if any(not pos and m.kind in ("some", "min", "exact") and not self.reaches(e, m)
               for q in supers for m, pos in self.on.get(q, ())):
            self.note(EXISTENTIAL, axiom, f"an instance of {what} is in the restrictions on the super-properties "
                      f"of {short_name(p.iri)} only through a told value")
        self.unnamed.chain_links(e, axiom, {p, *supers}, subject)
        bound = self.single_valued(p, e)
        if isinstance(bound, Expr) and e.kind in ("min", "exact") and e.n >= 2 and (
                e.filler is None or e.filler.node == THING or self.owl.is_data(p, e)):
            # a qualified minimum on an object property is said below, with its filler
            self.note(EXISTENTIAL, axiom, self._single_valued_gap(e, bound) or "")
        if self.owl.is_data(p, e):
            return
        value_classes = self.value_classes(p)
        classes = self.unnamed.value_classes(e, {p, *supers}, subject)
        self.unnamed.links_back(e, classes, axiom)
        self.unnamed.gives_back(e, classes, axiom)
        self.unnamed.defined_filler(e, classes, axiom, {p, *supers})
        filler = e.filler
        if filler is not None and filler.is_named:
            self.unnamed.wider_filler(e, filler.node, axiom, {p, *supers})
        if filler is not None and not filler.is_named:
            self.note(EXISTENTIAL, axiom, f"the unnamed value of {what} is in {describe(filler)}: its own "
                      "restrictions are not reasoned")
        elif filler is not None and filler.node not in value_classes:
            single = self.single_valued(p, e)
            said = None if single is None else self._single_valued_gap(e, single)
            if said:
                self.note(EXISTENTIAL, axiom, said)
            if any(self.disjoint(filler.node, c) for c in value_classes):
                self.note(EXISTENTIAL, axiom, f"the unnamed value of {what} would be in disjoint classes "
                          f"({describe(filler)} and the range of {short_name(p.iri)}): the inconsistency is not found")

    def reaches(self, e: Expr, m: Expr) -> bool:
        """Whether membership of ``e`` gives membership of ``m`` on a super-property (ext-restriction-sub)."""
        ne, nm_ = (1 if e.kind == "some" else e.n), (1 if m.kind == "some" else m.n)
        return m.kind != "exact" and ne >= nm_ >= 1 and self.owl.filler_subsumed(e, m)

    @cached_property
    def supers(self) -> dict[Prop, frozenset[Prop]]:
        """Each property expression's strict super-expressions (:mod:`.property_hierarchy`)."""
        return super_expressions(self.tb)

    def value_classes(self, p: Prop) -> set[NamedNode]:
        """Named classes every value of ``p`` is told to be in: the range of ``p`` and of its super-expressions
        (the domain of an inverse one), with their told superclasses."""
        out: set[NamedNode] = set()
        for _, c in subject_classes(self.tb, self.supers, inverse(p)):
            if c.is_named:
                out |= self.told(c.node)
        return out

    def single_valued(self, p: Prop, e: Expr) -> Expr | str | None:
        """Why ``p`` may have at most one value: "" where it is functional (every subject), the told
        unqualified maximum of one (or none) where only that restriction's instances are bounded, None where
        nothing bounds it (decided once per property: asked for every existential on it)."""
        if p not in self._single:
            self._single[p] = self._single_valued(p)
        return self._single[p]

    def _single_valued(self, p: Prop) -> Expr | str | None:
        if self.tb.has("InverseFunctionalProperty" if p.inverse else "FunctionalProperty", p.iri):
            return ""
        for m, pos in self.on.get(p, ()):
            if pos and m.kind in ("max", "exact") and m.n <= 1 and m.filler is None and m.datatype is None:
                return m
        return None

    @staticmethod
    def _single_valued_gap(e: Expr, single: Expr | str) -> str | None:
        """The notice for an existential on a property with at most one value (None: nothing is missed).

        A functional property's told value is the unnamed one (a minimum of two or more on it is found
        inconsistent); a maximum told in a restriction bounds that restriction's instances only, so the
        notice says where it applies. Where the two cannot hold together (a minimum of two or more, or a
        maximum of none), the clash is found for a class under both restrictions (it is unsatisfiable), not
        for an individual typed with two classes that carry one each: that is what the notice says."""
        name, filler = short_name(e.prop.iri), describe(e.filler) if e.filler is not None else "owl:Thing"
        many = e.kind in ("min", "exact") and e.n >= 2
        if isinstance(single, str):
            return None if many else \
                f"{name} has at most one value, so the told value is the one in {filler}: not derived"
        bound = describe(single)
        if many or single.n == 0:
            return (f"an individual in both {describe(e)} and {bound} is inconsistent: found where a class is "
                    "under both, not where the individual is in two classes that carry one each")
        return (f"on instances of {bound}, {name} has at most one value, so the told value is the one "
                f"in {filler}: not derived")

    def disjoint(self, a: NamedNode, b: NamedNode) -> bool:
        """Some told superclass of ``a`` (or ``a``) is told disjoint with one of ``b`` (or ``b``)."""
        tb_ = self.told(b)
        return any(not tb_.isdisjoint(self.disjoint_with.get(x, ())) for x in self.told(a))

    @cached_property
    def disjoint_with(self) -> dict[NamedNode, set[NamedNode]]:
        """Each named class's told disjoint named classes, both ways: :meth:`disjoint` looks a class's
        superclasses up here instead of scanning every disjoint pair (thousands in a TBox whose
        siblings are made pairwise disjoint)."""
        found: dict[NamedNode, set[NamedNode]] = {}
        for x, y in self.owl.disjoint_pairs:
            found.setdefault(x, set()).add(y)
            found.setdefault(y, set()).add(x)
        return found

    # ---------------------------------------------------------------- difference
    def difference(self) -> None:
        """Irreflexive and asymmetric properties entail difference; topostore's difference (used by
        SWRL DifferentIndividuals atoms, minimum cardinalities ≥ 2 and maxima) does not read them."""
        if not self.difference_matters():
            return
        for kind in ("IrreflexiveProperty", "AsymmetricProperty"):
            for p in sorted(self.tb.characteristics.get(kind, ()), key=lambda t: t.value):
                self.note(DIFFERENCE, f"{short_name(p)} is {kind[:-len('Property')].lower()}",
                          f"x {short_name(p)} y makes x and y different: not used where difference matters")

    def difference_matters(self) -> bool:
        if self.uses_difference or self.tb.characteristics.get("FunctionalProperty") or \
                self.tb.characteristics.get("InverseFunctionalProperty"):
            return True
        return any(e.kind in ("min", "exact", "max") and e.n >= 1 and not self.owl.is_data(e.prop, e)
                   for e, _, _, _ in self.uses)


def profile(store: Store, graph: NamedNode, tb: TBox, owl_compiler: OwlCompiler,
            rule_uses: list[tuple[Expr, bool]], uses_difference: bool) -> list[Notice]:
    """The incompleteness notices of an ontology (one per axiom and kind)."""
    return ProfileReport(tb, owl_compiler, rule_uses, uses_difference).run(store, graph)


__all__ = ["COMPLEMENT", "DIFFERENCE", "EXISTENTIAL", "MAX_CASES", "MAX_LEFT", "UNCHECKED_DATATYPE", "UNION",
           "UNIVERSAL", "UNSUPPORTED", "profile"]
