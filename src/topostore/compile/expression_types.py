"""Which anonymous nodes an axiom reads as class expressions or data ranges.

The OWL 2 mapping to RDF graphs (Table 13) parses a blank node as a class expression only with its
``rdf:type owl:Class`` or ``owl:Restriction`` triple, and as a data range only with ``rdf:type
rdfs:Datatype``.  The OWL API 3.4.3 that Pellet 2.3.1 runs on is laxer, and topostore answers as Pellet
does, so it follows the OWL API where they differ (measured against Pellet, Turtle and RDF/XML alike):

* a node typed ``owl:Class``, ``owl:Restriction`` or ``rdfs:Class`` is a class expression anywhere;
* a node nested in a class expression that is read (a filler, a member of a list, a complement) and the
  class of an ``rdf:type`` triple, a ``rdfs:range``, a ``rdfs:subClassOf`` side or a SWRL class atom are read
  untyped: the position says what they are;
* an untyped node in ``owl:equivalentClass`` or ``owl:disjointWith`` is read only when the other side is known
  as a class (a node typed as above, or a name declared a class or in a ``rdfs:subClassOf`` triple); a name
  made equivalent to an untyped node and nothing else is no class to the OWL API, and the axiom is not there
  (the OWL API also counts a name used as an individual's type: topostore does not, see ``known_class``);
* an untyped node as a ``rdfs:domain`` is not read;
* a data range (``owl:onDatatype`` …) is read only typed ``rdfs:Datatype`` (or OWL 1's ``owl:DataRange``), or as the definition of a name
  declared ``rdfs:Datatype``.

An axiom that is not read is set aside with its reason (a named notice), never read silently.
"""

from __future__ import annotations

from pyoxigraph import NamedNode

from ..errors import RuleCompileError
from ..rdf.terms import Term
from ..rdf.vocab import NOTHING, OWL, RDFS, THING, TYPE, is_skolem
from ..stores.base import Store

#: the rdf:type triples that make a blank node a class expression (the OWL API accepts rdfs:Class too)
CLASS_TYPES = frozenset({NamedNode(OWL + "Class"), NamedNode(OWL + "Restriction"), NamedNode(RDFS + "Class")})
DATATYPE = NamedNode(RDFS + "Datatype")
#: the rdf:type triples that make a blank node a data range (OWL 1's owl:DataRange, which the mapping and the
#: OWL API still read)
DATA_RANGE_TYPES = frozenset({DATATYPE, NamedNode(OWL + "DataRange")})
_SUBCLASS = NamedNode(RDFS + "subClassOf")


class ExpressionTypes:
    """Answers whether a node is typed as a class expression or a data range, and which names are classes."""

    def __init__(self, store: Store, graph: NamedNode) -> None:
        self.store = store
        self.graph = graph
        self._named: dict[Term, bool] = {}

    def types(self, node: Term) -> list[Term]:
        return self.store.objects(node, TYPE, self.graph)

    def typed_class(self, node: Term) -> bool:
        """Whether ``node`` carries a triple that types it a class expression."""
        return any(t in CLASS_TYPES for t in self.types(node))

    def untyped_expression(self, node: Term) -> bool:
        """Whether ``node`` is a blank class expression without its type triple."""
        return isinstance(node, NamedNode) and is_skolem(node) and not self.typed_class(node)

    def known_class(self, node: Term) -> bool:
        """Whether ``node`` is known as a class before an equivalence or disjointness with an untyped node: a
        typed expression, or a name declared a class or in a subclass triple.  The OWL API also counts a name
        used as an individual's type; topostore does not, so that what a LOAD reads depends on the schema
        alone (an ABox type added or removed later recompiles nothing, and a fresh LOAD must agree with it):
        such an axiom is set aside with its notice."""
        if not isinstance(node, NamedNode):
            return False
        if is_skolem(node):
            return self.typed_class(node)
        if node in (THING, NOTHING):
            return True
        if node not in self._named:
            st, g = self.store, self.graph
            self._named[node] = (self.typed_class(node)
                                 or next(iter(st.triples(node, _SUBCLASS, None, g)), None) is not None
                                 or next(iter(st.triples(None, _SUBCLASS, node, g)), None) is not None)
        return self._named[node]

    def check_pair(self, a: Term, b: Term, axiom: str) -> None:
        """RuleCompileError when an equivalence or disjointness ``a``–``b`` is not read: an untyped blank
        expression on one side and no known class on the other."""
        for node, other in ((a, b), (b, a)):
            if self.untyped_expression(node) and not self.known_class(other):
                raise RuleCompileError(self.untyped_reason(node, axiom))

    def check_domain(self, node: Term) -> None:
        """RuleCompileError for an untyped blank expression as a domain (the OWL API does not read it)."""
        if self.untyped_expression(node):
            raise RuleCompileError(self.untyped_reason(node, "a domain"))

    def typed_data_range(self, node: Term) -> bool:
        return any(t in DATA_RANGE_TYPES for t in self.types(node))

    def untyped_reason(self, node: Term, where: str) -> str:
        """Why an axiom with an untyped blank class expression is left out."""
        restriction = bool(self.store.objects(node, NamedNode(OWL + "onProperty"), self.graph))
        missing = "owl:Restriction" if restriction else "owl:Class"
        return (f"the anonymous class expression in {where} lacks its rdf:type {missing} triple: the OWL 2 "
                "mapping to RDF (and the OWL API) does not read it as a class expression, so the axiom is not there")


__all__ = ["CLASS_TYPES", "DATATYPE", "ExpressionTypes"]
