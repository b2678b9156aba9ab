"""Reading OWL axioms from the asserted graph into a :class:`~.model.TBox`.

The second half of the compiler's "parser" stage: it walks the axiom triples (subclass, equivalence,
disjointness, keys, property axioms, AllDisjointClasses, ...) of the RDF mapping of OWL 2 and reads each
side through a :class:`~.class_expressions.ClassExpressionReader` (composed, not inherited: the SWRL
compiler reads its atoms' expressions through the same one, and a proof's text through its own).  An
axiom that cannot be read is set aside with its reason, never refusing the ontology.  Nothing here knows
about SPARQL.
"""

from __future__ import annotations

import hashlib
from dataclasses import replace

from pyoxigraph import NamedNode

from ..errors import RuleCompileError
from ..rdf.terms import Term
from ..rdf.vocab import EXPR_PREFIX, NOTHING, OWL, RDFS, THING, TYPE, is_skolem, owl
from ..stores.base import Store
from .annotation_properties import CHARACTERISTICS, AnnotationProperties
from .class_expressions import ClassExpressionReader, boolean
from .datatype_definitions import is_definition, read_definitions
from .model import Expr, TBox, describe, is_datatype
from .notices import UNSUPPORTED


class TBoxReader:
    """Reads a :class:`TBox` from one graph of a :class:`Store`."""

    def __init__(self, store: Store, graph: NamedNode) -> None:
        self.store = store
        self.graph = graph
        #: the reader of each axiom's class and property expressions and data ranges
        self.classes = ClassExpressionReader(store, graph)
        self._declared_object = {s for s in store.subjects(TYPE, owl("ObjectProperty"), graph) if isinstance(s, NamedNode)}
        #: the annotation properties, whose axioms are set aside (:mod:`.annotation_properties`)
        self.annotations = AnnotationProperties(store, graph, self.classes.declared_data | self._declared_object)

    # ---------------------------------------------------------------- axioms
    def _each(self, tb: TBox, pred: str, read) -> None:
        """``read(triple)`` for every triple of ``pred``; an axiom that cannot be read is set aside
        (``tb.unsupported``, named by the profile report) instead of refusing the ontology."""
        for t in self.store.triples(None, NamedNode(pred), None, self.graph):
            try:
                read(t)
            except RuleCompileError as exc:
                tb.unsupported.append((f"{_short(t.subject)} {_short(t.predicate)} {_short(t.object)}", str(exc)))

    def _class_axioms(self, tb: TBox) -> None:
        expr, st, g = self.classes.expr, self.store, self.graph
        self._each(tb, RDFS + "subClassOf", lambda t: tb.subclass.append((expr(t.subject), expr(t.object))))
        check = self.classes.types.check_pair
        self._each(tb, OWL + "equivalentClass", lambda t: is_definition(t, self.classes) or
                   check(t.subject, t.object, "an equivalence") or
                   tb.equivalent.append((expr(t.subject), expr(t.object))))
        self._each(tb, OWL + "disjointWith", lambda t: check(t.subject, t.object, "a disjointness") or
                   tb.disjoint.append((expr(t.subject), expr(t.object))))
        for node in st.subjects(TYPE, owl("AllDisjointClasses"), g):
            try:
                members = [expr(m) for m in self.classes.items(self.classes.one(node, OWL + "members"))]
            except RuleCompileError as exc:
                tb.unsupported.append(("an AllDisjointClasses axiom", str(exc)))
                continue
            tb.disjoint += [(a, b) for i, a in enumerate(members) for b in members[i + 1:]]

        def disjoint_union(t) -> None:
            members = [expr(m) for m in self.classes.items(t.object)]
            tb.disjoint += [(a, b) for i, a in enumerate(members) for b in members[i + 1:]]
            tb.subclass += [(m, expr(t.subject)) for m in members]
            tb.partial.append((f"{_short(t.subject)} DisjointUnionOf ({' '.join(describe(m) for m in members)})",
                               "union or one-of as a superclass", f"{_short(t.subject)} SubClassOf the union of its parts "
                               "needs case analysis: not reasoned"))

        self._each(tb, OWL + "disjointUnionOf", disjoint_union)

    def _named_definitions(self, tb: TBox) -> None:
        """OWL 1 definitions on a named class (``:C owl:intersectionOf (...)``): what the OWL API
        reads as EquivalentClasses(C, ...); and classes made the same (owl:sameAs) as equivalent."""
        for kind, pred in (("and", "intersectionOf"), ("or", "unionOf"), ("oneof", "oneOf"), ("not", "complementOf")):
            def define(t, kind=kind) -> None:
                if not isinstance(t.subject, NamedNode) or is_skolem(t.subject):
                    return
                node = self._definition_node(t.subject, kind)
                if kind == "oneof":
                    e = Expr(node, kind, individuals=tuple(self.classes.items(t.object)))
                elif kind == "not":
                    e = Expr(node, kind, members=(self.classes.expr(t.object),))
                else:
                    e = boolean(node, kind, [self.classes.expr(m) for m in self.classes.items(t.object)])
                tb.equivalent.append((Expr(t.subject, "named"), e))
            self._each(tb, OWL + pred, define)

        def restriction(t) -> None:
            """A restriction named by an IRI, or on several properties (RDF-Based Semantics documents):
            equivalent to the restriction on each of its properties."""
            several = len(self.store.objects(t.subject, NamedNode(OWL + "onProperty"), self.graph)) > 1
            if not isinstance(t.subject, NamedNode) or not (several or not is_skolem(t.subject)):
                return
            e = self.classes.restriction(t.subject, self.classes.prop(t.object))
            node = self._definition_node(t.subject, "r " + t.object.value if several else "r")
            whole = self.classes.expr(t.subject) if is_skolem(t.subject) else Expr(t.subject, "named")
            tb.equivalent.append((whole, replace(e, node=node)))
        self._each(tb, OWL + "onProperty", restriction)
        classes = tb.named_classes

        properties = tb.object_properties | tb.data_properties

        def used_as_property(node: Term) -> bool:
            return node in properties or (isinstance(node, NamedNode) and next(
                iter(self.store.triples(None, node, None, self.graph)), None) is not None)

        def a_datatype(node: Term) -> bool:
            return is_datatype(node) or (isinstance(node, NamedNode) and NamedNode(RDFS + "Datatype") in
                                         self.store.objects(node, TYPE, self.graph))

        def same(t) -> None:
            if t.subject in classes and t.object in classes and t.subject != t.object:
                tb.equivalent.append((self.classes.expr(t.subject), self.classes.expr(t.object)))
            elif t.subject != t.object and (a_datatype(t.subject) or a_datatype(t.object)):
                tb.unsupported.append((f"{_short(t.subject)} sameAs {_short(t.object)}", "datatypes made the same: "
                                       "a literal typed with one name is not read as a value of the other"))
            elif t.subject != t.object and (used_as_property(t.subject) or used_as_property(t.object)):
                tb.same_properties.append((t.subject, t.object))
        self._each(tb, OWL + "sameAs", same)

    @staticmethod
    def _definition_node(cls: NamedNode, kind: str) -> NamedNode:
        """The (internal) node of the expression a named class is defined as."""
        return NamedNode(EXPR_PREFIX + "definition:" + hashlib.md5(f"{cls.value} {kind}".encode()).hexdigest())

    def _keys(self, tb: TBox) -> None:
        self._each(tb, OWL + "hasKey", lambda t: tb.keys.append(
            (self.classes.expr(t.subject), tuple(self.classes.prop(p) for p in self.classes.items(t.object)))))

    def _property_axioms(self, tb: TBox) -> None:
        expr, prop = self.classes.expr, self.classes.prop

        def domain(t) -> None:
            if not self.annotations.set_aside(tb, t, _short):
                self.classes.types.check_domain(t.object)
                tb.domain.append((prop(t.subject), expr(t.object)))

        self._each(tb, RDFS + "domain", domain)

        def range_(t) -> None:
            if self.annotations.set_aside(tb, t, _short):
                return
            p = prop(t.subject)
            if is_datatype(t.object) or p.iri in tb.data_properties or t.object in self.classes.datatype_defs:
                tb.data_properties.add(p.iri)
                if isinstance(t.object, NamedNode) and not is_skolem(t.object):
                    dt = self.classes.datatype_defs.get(t.object, t.object)
                    tb.data_range.append((p.iri, dt))
                    if dt != t.object:
                        tb.data_range_node[(p.iri, dt)] = t.object
                elif isinstance(t.object, NamedNode):
                    dt = self.classes.data_range(t.object, f"the range of {p.iri.value}")
                    tb.data_range.append((p.iri, dt))
                    tb.data_range_node[(p.iri, dt)] = t.object
            else:
                tb.range.append((p, expr(t.object)))

        def equivalent(t) -> None:
            a, b = prop(t.subject), prop(t.object)
            tb.subproperty.extend([(a, b), (b, a)])

        self._each(tb, RDFS + "range", range_)
        self._each(tb, RDFS + "subPropertyOf", lambda t: self.annotations.set_aside(tb, t, _short) or tb.subproperty.append(
            (prop(t.subject), prop(t.object))))
        self._each(tb, OWL + "equivalentProperty", equivalent)
        for t in self.store.triples(None, owl("inverseOf"), None, self.graph):
            if isinstance(t.subject, NamedNode) and not is_skolem(t.subject):
                tb.inverse.append((t.subject, t.object))
        self._each(tb, OWL + "propertyChainAxiom",
                   lambda t: tb.chains.append((t.subject, tuple(prop(p) for p in self.classes.items(t.object)))))

    def _typed_expressions(self, tb: TBox) -> None:
        """The anonymous class expressions used directly as types of individuals, read from the few
        expression nodes (each one's ``rdf:type`` subjects) rather than from every ``rdf:type`` triple."""
        st, g = self.store, self.graph
        for node in _expression_nodes(st, g):
            for subject in st.subjects(TYPE, node, g):
                try:
                    tb.typed_expressions.append(self.classes.expr(node))
                except RuleCompileError as exc:
                    tb.unsupported.append((f"{_short(subject)} Type an anonymous expression", str(exc)))

    def read(self) -> TBox:
        tb = TBox()
        st, g = self.store, self.graph
        tb.data_properties = set(self.classes.declared_data)
        tb.object_properties = set(self._declared_object)
        tb.annotation_punned = set(self.annotations.punned)
        for name in CHARACTERISTICS:
            told = (s for s in st.subjects(TYPE, owl(name), g) if isinstance(s, NamedNode))
            tb.characteristics[name] = self.annotations.characteristic(tb, name, told, _short)
        tb.named_classes = {s for s in st.subjects(TYPE, owl("Class"), g) if not is_skolem(s)}
        self.classes.datatype_defs, aside = read_definitions(self.classes)
        tb.unsupported += aside

        self._class_axioms(tb)
        self._named_definitions(tb)
        self._keys(tb)
        self._property_axioms(tb)
        for t in st.triples(None, owl("propertyDisjointWith"), None, g):
            tb.disjoint_props.append((t.subject, t.object))
        for node in st.subjects(TYPE, owl("AllDisjointProperties"), g):
            members = self.classes.items(self.classes.one(node, OWL + "members"))
            tb.disjoint_props += [(a, b) for i, a in enumerate(members) for b in members[i + 1:]]

        self._typed_expressions(tb)
        for items, fault in self.classes.list_faults.values():
            tb.partial.append((f"a list ({' '.join(_short(m) for m in items)})", UNSUPPORTED,
                               f"a malformed RDF list: {fault}"))
        for e in self.classes.expressions_read():
            if e.is_named and e.node not in (THING, NOTHING) and not is_datatype(e.node):
                tb.named_classes.add(e.node)
        return tb


def _expression_nodes(store: Store, graph: NamedNode) -> list[NamedNode]:
    """The anonymous nodes of ``graph`` that are class expressions (:data:`_EXPRESSION_PREDICATES`), each once.

    Why: the class expressions are a few subjects of the few triples of these predicates, where the
    ``rdf:type`` triples are two a location (200,000 at 100,000 locations, most of a TBox read)."""
    found: dict[NamedNode, None] = {}
    for pred in _EXPRESSION_PREDICATES:
        for t in store.triples(None, NamedNode(OWL + pred), None, graph):
            if isinstance(t.subject, NamedNode) and is_skolem(t.subject):
                found.setdefault(t.subject)
    return list(found)


def _short(t: Term) -> str:
    if is_skolem(t):
        return "an anonymous expression"
    v = t.value if hasattr(t, "value") else str(t)
    return v.rsplit("#", 1)[-1] if "#" in v else v.rsplit("/", 1)[-1]


#: an anonymous node is a class expression when it is the subject of one of these (else an axiom node:
#: AllDifferent, SWRL atoms, ...)
_EXPRESSION_PREDICATES = ("onProperty", "intersectionOf", "unionOf", "complementOf", "oneOf")
