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
union / one-of, positively          non-Horn: which member is not known
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
in part (:attr:`TBox.partial`: a disjoint union's covering), statements about the
RDF list vocabulary (``rdf:nil`` with a first element or a rest: inconsistent under
the RDF-Based semantics, not reasoned), imports of ontologies not loaded, the
universal and empty properties (``owl:topObjectProperty`` …), and, informatively, the reflexivity of
``owl:sameAs`` (:data:`~.notices.NOT_STORED`) when a file uses it.
"""

from __future__ import annotations

from collections.abc import Iterator
from functools import cached_property
from itertools import islice

from pyoxigraph import Literal, NamedNode

from ..rdf.vocab import FIRST, NIL, RDFS, REST, SAME_AS, THING, TYPE, is_skolem, owl
from ..stores.base import Store
from . import data_ranges
from .model import Expr, Prop, TBox, describe, is_datatype
from .notices import INCOMPLETE, NOT_STORED, Notice
from .owl import OwlCompiler
from .property_hierarchy import inverse, subject_classes, super_expressions
from .snippets import in_datatype
from .unnamed_values import UnnamedValues

#: Axiom kinds of the report (the groups of the LOAD warning).
UNION = "union or one-of as a superclass"
COMPLEMENT = "complement on the left"
UNIVERSAL = "universal restriction on the left"
MAX_LEFT = "maximum cardinality on the left"
MAX_CASES = "maximum cardinality needing case analysis"
EXISTENTIAL = "existential with consequences for an unnamed value"
DIFFERENCE = "difference entailed by a property characteristic"
UNSUPPORTED = "not supported"
UNCHECKED_DATATYPE = "values of a datatype not checked"

#: The universal and the empty properties, with what they mean.
_TOP_AND_BOTTOM = {
    "topObjectProperty": "the universal property (every two individuals are linked by it)",
    "topDataProperty": "the universal data property (every individual has every literal as its value)",
    "bottomObjectProperty": "the empty property (a link by it, or an existential on it, is inconsistent)",
    "bottomDataProperty": "the empty data property (a value of it, or an existential on it, is inconsistent)",
}

#: Why ``x owl:sameAs x`` is not stored, said whenever a file uses owl:sameAs.
REFLEXIVE_SAME_AS = ("owl:sameAs is reflexive: x sameAs x holds for every individual, but is not stored (it "
                     "would add a triple per term and list each individual as its own alias); every fact of an "
                     "individual is copied to each of its names, so only the triple x sameAs x itself is not "
                     "answered")

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
        out += list(_uses(c, True, f"{_name(p.iri)} domain {describe(c)}", None))
    for p, c in tb.range:
        out += list(_uses(c, True, f"{_name(p.iri)} range {describe(c)}", None))
    for e in tb.typed_expressions:
        out += list(_uses(e, True, f"an individual typed {describe(e)}", None))
    for c, props in tb.keys:
        out += list(_uses(c, False, f"{describe(c)} HasKey ({' '.join(_name(p.iri) for p in props)})", None))
    for e, head in rule_uses:
        out += list(_uses(e, head, f"a SWRL rule {'head' if head else 'body'} atom {describe(e)}", None))
    return out


def _name(t: NamedNode) -> str:
    if not isinstance(t, NamedNode) or is_skolem(t):
        return "[]" if not isinstance(t, Literal) else str(t)
    v = t.value
    return v.rsplit("#", 1)[-1] if "#" in v else v.rsplit("/", 1)[-1]


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
            self.note(UNSUPPORTED, f"{_name(a)} sameAs {_name(b)}", "properties made the same are not "
                      "substituted for each other (owl:equivalentProperty is)")
        for axiom, reason in self.tb.unsupported:
            self.note(UNSUPPORTED, axiom, f"set aside: {reason}")
        for axiom, kind, reason in self.tb.partial:
            self.note(kind, axiom, reason)
        self.unchecked_datatypes(store, graph)
        self.list_vocabulary(store, graph)
        self.imports(store, graph)
        self.top_and_bottom(store, graph)
        self.reflexive_equality(store, graph)
        return list(self.notices.values())

    # ---------------------------------------------------------------- datatypes
    def unchecked_datatypes(self, store: Store, graph: NamedNode) -> None:
        """A range or a universal restriction into a datatype whose values topostore does not test: a value
        outside it is not found.  For a datatype of the ontology's own (not in the OWL 2 datatype map, not
        defined) that is the OWL 2 Direct Semantics (its value space is any set of values, so no value is
        known to be outside it), but Pellet takes such a datatype as disjoint from the built-in ones and finds
        ``:d 3`` with ``:d rdfs:range :MyType`` inconsistent: the difference is said, never silent."""
        for p, dt in self.tb.data_range:
            self.unchecked(dt, f"{_name(p)} range {_name(dt)}", store, graph)
        for e, positive, axiom, _ in self.uses:
            if positive and e.kind == "all" and e.datatype is not None:
                self.unchecked(e.datatype, axiom, store, graph)

    def unchecked(self, dt: NamedNode, axiom: str, store: Store, graph: NamedNode) -> None:
        if in_datatype("?v", dt) is not None or is_skolem(dt) or dt.value.startswith(data_ranges.PREFIX):
            return
        if is_datatype(dt):
            self.note(UNCHECKED_DATATYPE, axiom, f"{_name(dt)} is a datatype whose values topostore does not "
                      "test: a value outside it is not found inconsistent")
            return
        declared = NamedNode(RDFS + "Datatype") in store.objects(dt, TYPE, graph)
        self.note(UNCHECKED_DATATYPE, axiom, f"{_name(dt)} is not a datatype of the OWL 2 datatype map"
                  + ("" if declared else " and is not declared rdfs:Datatype (as OWL 2 DL requires)")
                  + ", nor defined: its value space may be any set of values (OWL 2 Direct Semantics), so no "
                  "value is checked against it; a reasoner that takes it as disjoint from the built-in datatypes "
                  "(Pellet) finds a value of another datatype inconsistent")

    # ---------------------------------------------------------------- RDF vocabulary
    def list_vocabulary(self, store: Store, graph: NamedNode) -> None:
        """``rdf:nil`` is the empty list: a first element or a rest of it is a contradiction under the
        RDF-Based semantics, which topostore does not find (it reads lists, it does not reason about them)."""
        for p in (FIRST, REST):
            for t in islice(store.triples(NIL, p, None, graph), 1):
                self.note(UNSUPPORTED, f"nil {_name(p)} {_name(t.object)}", "rdf:nil is the empty list, which has "
                          "no first element and no rest: inconsistent under the RDF-Based semantics; the RDF "
                          "list vocabulary is not reasoned, the statement is kept as a plain triple")

    def imports(self, store: Store, graph: NamedNode) -> None:
        """An ``owl:imports`` of an ontology not loaded: its axioms are missing (topostore fetches no URL)."""
        imported = [t.object for t in store.triples(None, owl("imports"), None, graph)]
        if not imported:
            return
        loaded = {t.subject for t in store.triples(None, TYPE, owl("Ontology"), graph)}
        loaded |= {t.object for t in store.triples(None, owl("versionIRI"), None, graph)}
        for target in imported:
            if target not in loaded:
                self.note(UNSUPPORTED, f"imports {target.value}", "the imported ontology is not loaded and "
                          "not fetched (topostore reads no URL): its axioms are not reasoned; load its file too")

    def top_and_bottom(self, store: Store, graph: NamedNode) -> None:
        """The universal and the empty properties have no rules: named wherever a file uses them."""
        for name, meaning in _TOP_AND_BOTTOM.items():
            p = owl(name)
            if any(next(iter(store.triples(*pattern, graph)), None) is not None
                   for pattern in ((p, None, None), (None, p, None), (None, None, p))):
                self.note(UNSUPPORTED, f"owl:{name}", f"{meaning}: not reasoned, used as any other property")

    def reflexive_equality(self, store: Store, graph: NamedNode) -> None:
        """Said once when the file states an equality: see :data:`REFLEXIVE_SAME_AS` for why."""
        first = next(iter(store.triples(None, SAME_AS, None, graph)), None)
        if first is not None:
            subject = f"owl:sameAs (as in {_name(first.subject)} sameAs {_name(first.object)})"
            self.notices.setdefault((NOT_STORED, "owl:sameAs"), Notice(NOT_STORED, subject, REFLEXIVE_SAME_AS))

    # ---------------------------------------------------------------- expressions
    def expression(self, e: Expr, positive: bool, axiom: str, subject: NamedNode | None = None) -> None:
        k = e.kind
        if positive and k == "or" and all(m.node != THING for m in e.members):
            self.note(UNION, axiom, f"an instance of {describe(e)} is in one of its members, which one is not "
                      "known: conclusions by case analysis are not drawn")
        elif positive and k == "oneof":
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
        if self.tb.has("InverseFunctionalProperty" if p.inverse else "FunctionalProperty", p.iri):
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
                      f"of {_name(p.iri)} only through a told value")
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
                          f"({describe(filler)} and the range of {_name(p.iri)}): the inconsistency is not found")

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
        name, filler = _name(e.prop.iri), describe(e.filler) if e.filler is not None else "owl:Thing"
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
                self.note(DIFFERENCE, f"{_name(p)} is {kind[:-len('Property')].lower()}",
                          f"x {_name(p)} y makes x and y different: not used where difference matters")

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
