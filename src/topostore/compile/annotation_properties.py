"""Which properties are annotation properties, whose axioms the TBox reader sets aside.

Why: OWL 2 gives an annotation property's domain, range and super-properties no logical meaning, and
Pellet ignores them; Protégé writes them all the same (``:source rdfs:range xsd:anyURI``), so reasoning
over them types individuals wrongly and makes ontologies inconsistent.  An IRI declared an annotation
property and also an object or data property (declared so, or told an axiom only those have: a
characteristic only an object property has, an inverse, a chain, an equivalent or disjoint property) is
illegal punning in OWL 2 DL; it keeps the object or data reading, as Pellet does, and is named.  Declared
functional or inverse functional, characteristics a data property may have too, an annotation property stays
one: Pellet's loader gives such a declaration no property type and reads the values as annotations (no merge,
no clash), so the characteristic is set aside with its other axioms.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable

from pyoxigraph import NamedNode, Triple

from ..rdf.vocab import BUILTIN_ANNOTATION_PROPERTIES, TYPE, owl
from ..stores.base import Store
from .model import TBox

#: the property characteristics OWL 2 gives object and data properties (their ``rdf:type``)
CHARACTERISTICS = (
    "FunctionalProperty", "InverseFunctionalProperty", "TransitiveProperty", "SymmetricProperty",
    "AsymmetricProperty", "IrreflexiveProperty", "ReflexiveProperty",
)
#: the characteristics that make an IRI an object property (told of an annotation property: illegal punning);
#: functional and inverse functional, which Pellet leaves untyped, do not
OBJECT_CHARACTERISTICS = CHARACTERISTICS[2:]


class AnnotationProperties:
    """The annotation properties of one TBox graph, and the IRIs punned as both kinds."""

    def __init__(self, store: Store, graph: NamedNode, logical: set[NamedNode]) -> None:
        """``logical``: the IRIs declared object or data properties."""
        declared = {s for s in store.subjects(TYPE, owl("AnnotationProperty"), graph) if isinstance(s, NamedNode)}
        #: declared an annotation property and read as an object or data property (illegal punning)
        self.punned = declared & (logical | _told_logical_axioms(store, graph))
        #: the annotation properties (declared or built in) whose axioms carry no logical meaning
        self.properties = (declared | BUILTIN_ANNOTATION_PROPERTIES) - logical - self.punned

    def characteristic(self, tb: TBox, name: str, subjects: Iterable[NamedNode],
                       short: Callable[[object], str]) -> set[NamedNode]:
        """The ``subjects`` declared characteristic ``name`` that are not annotation properties; those that are (a
        functional annotation property) are kept in ``tb`` for the notice, the characteristic set aside."""
        kept = set()
        for s in subjects:
            if s in self.properties:
                tb.annotation_axioms.setdefault(s, []).append(f"{short(s)} a {name}")
            else:
                kept.add(s)
        return kept

    def set_aside(self, tb: TBox, t: Triple, short: Callable[[object], str]) -> bool:
        """Whether triple ``t`` is an axiom about an annotation property (its subject's, or a super-property's):
        if so it is kept in ``tb`` for the notice naming the property once, and not read as an axiom."""
        for node in (t.subject, t.object) if t.predicate.value.endswith("subPropertyOf") else (t.subject,):
            if node in self.properties:
                tb.annotation_axioms.setdefault(node, []).append(f"{short(t.subject)} {short(t.predicate)} {short(t.object)}")
                return True
        return False


def annotation_properties(store: Store, graph: NamedNode) -> set[NamedNode]:
    """The annotation properties of ``graph`` as the TBox reader reads them (:class:`AnnotationProperties`): an
    IRI declared an object or data property as well, or told an axiom only those have, is not one."""
    logical = {s for kind in ("ObjectProperty", "DatatypeProperty") for s in store.subjects(TYPE, owl(kind), graph)
               if isinstance(s, NamedNode)}
    return AnnotationProperties(store, graph, logical).properties


def _told_logical_axioms(store: Store, graph: NamedNode) -> set[NamedNode]:
    """The IRIs a property axiom only an object or data property can have names: a characteristic of object
    properties, an inverse, a chain, an equivalent or a disjoint property."""
    out = {s for name in OBJECT_CHARACTERISTICS for s in store.subjects(TYPE, owl(name), graph)}
    for name in ("inverseOf", "equivalentProperty", "propertyDisjointWith"):
        for t in store.triples(None, owl(name), None, graph):
            out |= {t.subject, t.object}
    out |= set(store.subjects(owl("propertyChainAxiom"), None, graph))
    return {s for s in out if isinstance(s, NamedNode)}


__all__ = ["CHARACTERISTICS", "OBJECT_CHARACTERISTICS", "AnnotationProperties", "annotation_properties"]
