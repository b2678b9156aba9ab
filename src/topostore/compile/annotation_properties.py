"""Which properties are annotation properties, whose axioms the TBox reader sets aside.

Why: OWL 2 gives an annotation property's domain, range and super-properties no logical meaning, and
Pellet ignores them; Protégé writes them all the same (``:source rdfs:range xsd:anyURI``), so reasoning
over them types individuals wrongly and makes ontologies inconsistent.  An IRI declared an annotation
property and also an object or data property (declared so, or told an axiom only those have: a
characteristic, an inverse, a chain, an equivalent or disjoint property) is illegal punning in OWL 2 DL;
it keeps the object or data reading, as Pellet does, and is named.
"""

from __future__ import annotations

from collections.abc import Callable

from pyoxigraph import NamedNode, Triple

from ..rdf.vocab import BUILTIN_ANNOTATION_PROPERTIES, TYPE, owl
from ..stores.base import Store
from .model import TBox

#: the property characteristics OWL 2 gives object and data properties (their ``rdf:type``)
CHARACTERISTICS = (
    "FunctionalProperty", "InverseFunctionalProperty", "TransitiveProperty", "SymmetricProperty",
    "AsymmetricProperty", "IrreflexiveProperty", "ReflexiveProperty",
)


class AnnotationProperties:
    """The annotation properties of one TBox graph, and the IRIs punned as both kinds."""

    def __init__(self, store: Store, graph: NamedNode, logical: set[NamedNode]) -> None:
        """``logical``: the IRIs declared object or data properties."""
        declared = {s for s in store.subjects(TYPE, owl("AnnotationProperty"), graph) if isinstance(s, NamedNode)}
        #: declared an annotation property and read as an object or data property (illegal punning)
        self.punned = declared & (logical | _told_logical_axioms(store, graph))
        #: the annotation properties (declared or built in) whose axioms carry no logical meaning
        self.properties = (declared | BUILTIN_ANNOTATION_PROPERTIES) - logical - self.punned

    def set_aside(self, tb: TBox, t: Triple, short: Callable[[object], str]) -> bool:
        """Whether triple ``t`` is an axiom about an annotation property (its subject's, or a super-property's):
        if so it is kept in ``tb`` for the notice naming the property once, and not read as an axiom."""
        for node in (t.subject, t.object) if t.predicate.value.endswith("subPropertyOf") else (t.subject,):
            if node in self.properties:
                tb.annotation_axioms.setdefault(node, []).append(f"{short(t.subject)} {short(t.predicate)} {short(t.object)}")
                return True
        return False


def _told_logical_axioms(store: Store, graph: NamedNode) -> set[NamedNode]:
    """The IRIs a property axiom only an object or data property can have names: a characteristic, an
    inverse, a chain, an equivalent or a disjoint property."""
    out = {s for name in CHARACTERISTICS for s in store.subjects(TYPE, owl(name), graph)}
    for name in ("inverseOf", "equivalentProperty", "propertyDisjointWith"):
        for t in store.triples(None, owl(name), None, graph):
            out |= {t.subject, t.object}
    out |= set(store.subjects(owl("propertyChainAxiom"), None, graph))
    return {s for s in out if isinstance(s, NamedNode)}


__all__ = ["CHARACTERISTICS", "AnnotationProperties"]
