"""The declarations an ontology file needs for what it uses, added only where the file is written.

A manipulation (``ADD OBJECTPROP IND [hasDoor, C9, D9]``) stores the fact alone, as RDF needs
nothing more; but an OWL 2 document must declare its entities, and readers built on that rule
(Owlready2, so the Pellet runs made through it) do not see an undeclared individual at all.  The
OWL API, through which aRMOR saves, adds the missing declarations when it writes; so does every
export here, from how each IRI is used, without touching the stored graph:

* the subject of a fact, and the IRI object of an object property's fact: an ``owl:NamedIndividual``;
* the class of an ``rdf:type`` fact: an ``owl:Class``;
* a predicate with an IRI value: an ``owl:ObjectProperty``; with a literal: an ``owl:DatatypeProperty``.

An IRI used several ways is declared each way (punning, as the OWL API writes it).  A fact is a
triple whose predicate is no built-in vocabulary term and no declared annotation property, and
not an undeclared predicate describing the ontology, a class or a property (an annotation there);
IRIs of the built-in vocabularies and blank nodes are never declared.
"""

from __future__ import annotations

from collections.abc import Iterable

from pyoxigraph import Literal, NamedNode, Triple

from .vocab import NAMED_INDIVIDUAL, OWL, RDF, RDFS, STANFORD_SWRL, SWRL, SWRLB, TYPE, XSD, is_skolem, owl

_BUILT_IN = (RDF, RDFS, OWL, XSD, SWRL, SWRLB, STANFORD_SWRL)
CLASS = owl("Class")
OBJECT_PROPERTY = owl("ObjectProperty")
DATATYPE_PROPERTY = owl("DatatypeProperty")
_ANNOTATION_PROPERTY = owl("AnnotationProperty")
_ONTOLOGY = owl("Ontology")
#: what a subject declared so is, when an undeclared predicate describes it: annotated, not an individual
_NOT_INDIVIDUALS = {_ONTOLOGY, CLASS, OBJECT_PROPERTY, DATATYPE_PROPERTY, _ANNOTATION_PROPERTY,
                    owl("Restriction"), owl("TransitiveProperty"), owl("FunctionalProperty"),
                    owl("SymmetricProperty"), owl("AsymmetricProperty"), owl("ReflexiveProperty"),
                    owl("IrreflexiveProperty"), owl("InverseFunctionalProperty"), owl("AllDifferent"),
                    owl("AllDisjointClasses"), owl("AllDisjointProperties"), owl("Axiom"),
                    owl("NegativePropertyAssertion"), NamedNode(RDFS + "Datatype"), NamedNode(RDFS + "Class"),
                    NamedNode(RDF + "Property"), NamedNode(SWRL + "Imp"), NamedNode(SWRL + "Variable")}
_FACT_PROPERTIES = {OBJECT_PROPERTY, DATATYPE_PROPERTY}


def _own(term: object) -> bool:
    """An IRI of the document's own (not of a built-in vocabulary, not a skolemised blank node)."""
    return isinstance(term, NamedNode) and not term.value.startswith(_BUILT_IN) and not is_skolem(term)


def _uses(triples: list[Triple], present: set[tuple[object, object]]) -> Iterable[tuple[NamedNode, NamedNode]]:
    """(entity, declaration type) for each use of an own IRI in a fact.

    An undeclared predicate on the ontology, a class or a property is an annotation there (as the
    OWL API reads it), no fact; a declared object or data property makes it a fact (punning)."""
    kinds: dict[object, set[object]] = {}
    for s, o in present:
        kinds.setdefault(s, set()).add(o)
    for s, p, o in ((t.subject, t.predicate, t.object) for t in triples):
        if p == TYPE:
            if _own(o):
                yield o, CLASS
                if _own(s):
                    yield s, NAMED_INDIVIDUAL
            continue
        if not _own(p) or _ANNOTATION_PROPERTY in kinds.get(p, ()):
            continue
        if kinds.get(s, set()) & _NOT_INDIVIDUALS and not kinds.get(p, set()) & _FACT_PROPERTIES:
            continue
        if _own(s):
            yield s, NAMED_INDIVIDUAL
        if isinstance(o, Literal):
            yield p, DATATYPE_PROPERTY
        elif isinstance(o, NamedNode):
            yield p, OBJECT_PROPERTY
            if _own(o):
                yield o, NAMED_INDIVIDUAL


def missing_declarations(triples: Iterable[Triple]) -> list[Triple]:
    """The declarations (``x rdf:type owl:NamedIndividual`` ...) the facts of ``triples`` need and
    ``triples`` do not hold, in a stable order, so a saved file reads back with every entity it uses."""
    triples = list(triples)
    present = {(t.subject, t.object) for t in triples if t.predicate == TYPE}
    wanted = {use for use in _uses(triples, present) if use not in present}
    return [Triple(s, TYPE, o) for s, o in sorted(wanted, key=lambda u: (u[0].value, u[1].value))]


def declared(triples: Iterable[Triple]) -> list[Triple]:
    """``triples`` followed by the declarations they lack (see :func:`missing_declarations`)."""
    triples = list(triples)
    return [*triples, *missing_declarations(triples)]


__all__ = ["declared", "missing_declarations"]
