"""Reading OWL class expressions and axioms from the asserted graph.

This is the "parser" stage of the compiler: it turns the RDF mapping of OWL 2
(restrictions, intersections, AllDisjointClasses, ...) into the values of
:mod:`.model`.  Nothing here knows about SPARQL.
"""

from __future__ import annotations

import hashlib
from dataclasses import replace

from pyoxigraph import Literal, NamedNode

from ..errors import RuleCompileError
from ..rdf.terms import Term
from ..rdf.vocab import EXPR_PREFIX, NOTHING, OWL, RDFS, THING, TYPE, XSD, is_skolem, owl
from ..stores.base import Store
from . import data_ranges
from .annotation_properties import CHARACTERISTICS, AnnotationProperties
from .datatype_definitions import is_definition, read_definitions
from .expression_types import ExpressionTypes
from .model import Expr, Prop, TBox, describe, is_datatype
from .notices import UNSUPPORTED

#: class expressions nested deeper than this are refused: reading, describing and compiling them
#: recurse once per level, and Python's stack ends near 1,000 frames (no real TBox nests 100 deep)
MAX_NESTING = 100


class TBoxReader:
    """Reads a :class:`TBox` from one graph of a :class:`Store`."""

    def __init__(self, store: Store, graph: NamedNode) -> None:
        self.store = store
        self.graph = graph
        self._cache: dict[Term, Expr] = {}
        self._depth = 0
        #: the malformed lists read, by head: (members read, what is wrong)
        self._list_faults: dict[Term, tuple[list[Term], str]] = {}
        self._declared_data = {s for s in store.subjects(TYPE, owl("DatatypeProperty"), graph) if isinstance(s, NamedNode)}
        self._declared_object = {s for s in store.subjects(TYPE, owl("ObjectProperty"), graph) if isinstance(s, NamedNode)}
        #: each named datatype defined as a data range, and the range it stands for (read first by :meth:`read`)
        self.datatype_defs: dict[NamedNode, NamedNode] = {}
        #: the annotation properties, whose axioms are set aside (:mod:`.annotation_properties`)
        self.annotations = AnnotationProperties(store, graph, self._declared_data | self._declared_object)
        #: which blank nodes an axiom reads as class expressions or data ranges (:mod:`.expression_types`)
        self.types = ExpressionTypes(store, graph)

    # ---------------------------------------------------------------- helpers
    def _one(self, s: Term, p: str) -> Term | None:
        values = self.store.objects(s, NamedNode(p), self.graph)
        return values[0] if values else None

    def _list(self, head: Term) -> list[Term]:
        """The members of a list an axiom reads; a malformed one (looping back, a cell with two rdf:first) is
        kept for the notice that names it."""
        items, fault = self.store.list_read(head, self.graph)
        if fault:
            self._list_faults.setdefault(head, (items, fault))
        return items

    def prop(self, node: Term, depth: int = 0) -> Prop:
        """The property expression ``node``: a named property or the inverse of one; an inverse of an
        inverse is the property itself (not OWL 2 DL syntax, but what it means, as Pellet reads it)."""
        if is_skolem(node):
            inner = self._one(node, OWL + "inverseOf")
            if inner is not None and depth < MAX_NESTING:
                p = self.prop(inner, depth + 1)
                return Prop(p.iri, inverse=not p.inverse)
            raise RuleCompileError(f"unsupported property expression {node}")
        if not isinstance(node, NamedNode):
            raise RuleCompileError(f"unsupported property expression {node}")
        return Prop(node)

    # ---------------------------------------------------------------- classes
    def expr(self, node: Term) -> Expr:
        """The class expression whose RDF node is ``node``."""
        if node in self._cache:
            return self._cache[node]
        if not isinstance(node, NamedNode):
            raise RuleCompileError(f"a literal {node} used as a class")
        self._cache[node] = Expr(node, "named")  # guards against cyclic structures
        if self._depth >= MAX_NESTING:
            raise RuleCompileError(f"class expressions nested more than {MAX_NESTING} deep (at {node.value})")
        self._depth += 1
        try:
            expr = self._read(node)
        except RuleCompileError:
            del self._cache[node]  # not a class: an axiom using it is set aside, never read as named
            raise
        finally:
            self._depth -= 1
        self._cache[node] = expr
        return expr

    def _read(self, node: NamedNode) -> Expr:
        if not is_skolem(node):
            return Expr(node, "named")
        for kind, pred in (("and", "intersectionOf"), ("or", "unionOf")):
            head = self._one(node, OWL + pred)
            if head is not None:
                return boolean(node, kind, [self.expr(m) for m in self._list(head)])
        comp = self._one(node, OWL + "complementOf")
        if comp is not None:
            return Expr(node, "not", members=(self.expr(comp),))
        one_of = self._one(node, OWL + "oneOf")
        if one_of is not None:
            return Expr(node, "oneof", individuals=tuple(self._list(one_of)))
        on_prop = self._one(node, OWL + "onProperty")
        if on_prop is not None:
            return self._restriction(node, self.prop(on_prop))
        raise RuleCompileError(f"unsupported or malformed class expression {node.value}")

    def _filler(self, node: NamedNode, prop: Prop, value: Term | None) -> tuple[Expr | None, NamedNode | None]:
        """(class filler, data range) of a restriction; (None, None) when unqualified."""
        for pred in ("onClass", "onDataRange"):
            v = self._one(node, OWL + pred)
            if v is not None:
                value = v
        if value is None:
            return None, None
        if pred_is_data(value, prop, self):
            if is_skolem(value):
                return None, self.data_range(value, f"restriction on {prop.iri.value}")
            if not isinstance(value, NamedNode):
                raise RuleCompileError(f"unsupported data range in restriction on {prop.iri.value}")
            return None, self.datatype_defs.get(value, value)
        if value == THING:
            return None, None
        return self.expr(value), None

    def _single_member(self, filler: Term, prop: Prop) -> Term | None:
        """The one member of ``filler`` when it is a one-of of a single individual (``{b}``, or a named class told
        to be one) or, for a data property, a data one-of of a single literal; None otherwise (read as a filler)."""
        data = pred_is_data(filler, prop, self)
        if not is_skolem(filler):
            return self._named_single(filler) if isinstance(filler, NamedNode) and not data else None
        if data:
            head = self._one(filler, OWL + "oneOf")
            if head is None or not self.types.typed_data_range(filler) or self.types.typed_class(filler):
                return None  # not a data one-of the OWL API reads: set aside by data_range, which says why
            members = set(self._list(head))
            return next(iter(members)) if len(members) == 1 and isinstance(next(iter(members)), Literal) else None
        e = self.expr(filler)
        members = set(e.individuals) if e.kind == "oneof" else set()
        return next(iter(members)) if len(members) == 1 and isinstance(next(iter(members)), NamedNode) else None

    def _named_single(self, cls: NamedNode) -> Term | None:
        """b when the named class ``cls`` is told to be ``{b}`` (``cls owl:oneOf (b)``, or an equivalence with a
        one-of of b): its existential ``∃p.cls`` is ``p value b`` too; None otherwise."""
        if is_datatype(cls) or cls in self.datatype_defs:
            return None
        eq = NamedNode(OWL + "equivalentClass")
        heads = list(self.store.objects(cls, NamedNode(OWL + "oneOf"), self.graph))
        for other in [*self.store.objects(cls, eq, self.graph), *self.store.subjects(eq, cls, self.graph)]:
            if is_skolem(other) and self.types.typed_class(other):
                heads += self.store.objects(other, NamedNode(OWL + "oneOf"), self.graph)
        for head in heads:
            members = set(self._list(head))
            if len(members) == 1 and isinstance(next(iter(members)), NamedNode):
                return next(iter(members))
        return None

    def data_range(self, node: NamedNode, where: str, typed: bool = False) -> NamedNode:
        """A datatype restricted by numeric facets, as the IRI :mod:`.data_ranges` names it;
        RuleCompileError for other data range expressions (data one-of, unions, string facets), and for one
        without its ``rdf:type rdfs:Datatype`` triple unless ``typed`` (its place types it)."""
        if not typed and self.types.typed_class(node):
            raise RuleCompileError(f"a class expression stands where a data range is wanted in {where}")
        if not typed and not self.types.typed_data_range(node):
            raise RuleCompileError(f"the data range in {where} lacks its rdf:type rdfs:Datatype triple: the OWL 2 "
                                   "mapping to RDF (and the OWL API) does not read it as a data range")
        base = self._one(node, OWL + "onDatatype")
        head = self._one(node, OWL + "withRestrictions")
        if not isinstance(base, NamedNode) or head is None:
            raise RuleCompileError(f"unsupported data range in {where} (only datatypes restricted by "
                                   "numeric facets are)")
        facets = []
        for item in self._list(head):
            for t in self.store.triples(item, None, None, self.graph):
                if not isinstance(t.object, Literal) or not t.predicate.value.startswith(XSD):
                    raise RuleCompileError(f"unsupported facet in the data range of {where}")
                facets.append((t.predicate.value[len(XSD):], t.object))
        try:
            return data_ranges.restricted(base, facets)
        except ValueError as exc:
            raise RuleCompileError(f"data range of {where}: {exc}") from None

    def _restriction(self, node: NamedNode, prop: Prop) -> Expr:
        some = self._one(node, OWL + "someValuesFrom")
        if some is not None:
            only = self._single_member(some, prop)
            if only is not None:  # ∃p.{b} is p value b: the value is in {b}, so it is b (likewise for a literal)
                return Expr(node, "value", prop=prop, value=only)
            filler, dt = self._filler(node, prop, some)
            return Expr(node, "some", prop=prop, filler=filler, datatype=dt)
        all_ = self._one(node, OWL + "allValuesFrom")
        if all_ is not None:
            filler, dt = self._filler(node, prop, all_)
            return Expr(node, "all", prop=prop, filler=filler, datatype=dt)
        has_value = self._one(node, OWL + "hasValue")
        if has_value is not None:
            return Expr(node, "value", prop=prop, value=has_value)
        if self._one(node, OWL + "hasSelf") is not None:
            return Expr(node, "self", prop=prop)
        for kind, names in (
            ("min", ("minCardinality", "minQualifiedCardinality")),
            ("max", ("maxCardinality", "maxQualifiedCardinality")),
            ("exact", ("cardinality", "qualifiedCardinality")),
        ):
            for name in names:
                n = self._one(node, OWL + name)
                if n is not None:
                    if not isinstance(n, Literal) or not n.value.strip().isdigit():
                        raise RuleCompileError(f"cardinality {n} of a restriction on {prop.iri.value} is not a number")
                    on = [v for v in (self._one(node, OWL + "onClass"), self._one(node, OWL + "onDataRange"))
                          if v is not None]
                    only = self._single_member(on[0], prop) if kind == "min" and int(n.value) == 1 and on else None
                    if only is not None:  # ≥1 p.{b} is ∃p.{b}, p value b
                        return Expr(node, "value", prop=prop, value=only)
                    filler, dt = self._filler(node, prop, None)
                    if filler is None and dt is None and prop.iri in self._declared_data:
                        prop = replace(prop, data=True)  # named as a data restriction, read as written
                    return Expr(node, kind, prop=prop, filler=filler, datatype=dt, n=int(n.value))
        raise RuleCompileError(f"unsupported restriction on {prop.iri.value}")

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
        expr, st, g = self.expr, self.store, self.graph
        self._each(tb, RDFS + "subClassOf", lambda t: tb.subclass.append((expr(t.subject), expr(t.object))))
        check = self.types.check_pair
        self._each(tb, OWL + "equivalentClass", lambda t: is_definition(t, self) or
                   check(t.subject, t.object, "an equivalence") or
                   tb.equivalent.append((expr(t.subject), expr(t.object))))
        self._each(tb, OWL + "disjointWith", lambda t: check(t.subject, t.object, "a disjointness") or
                   tb.disjoint.append((expr(t.subject), expr(t.object))))
        for node in st.subjects(TYPE, owl("AllDisjointClasses"), g):
            try:
                members = [expr(m) for m in self._list(self._one(node, OWL + "members"))]
            except RuleCompileError as exc:
                tb.unsupported.append(("an AllDisjointClasses axiom", str(exc)))
                continue
            tb.disjoint += [(a, b) for i, a in enumerate(members) for b in members[i + 1:]]

        def disjoint_union(t) -> None:
            members = [expr(m) for m in self._list(t.object)]
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
                    e = Expr(node, kind, individuals=tuple(self._list(t.object)))
                elif kind == "not":
                    e = Expr(node, kind, members=(self.expr(t.object),))
                else:
                    e = boolean(node, kind, [self.expr(m) for m in self._list(t.object)])
                tb.equivalent.append((Expr(t.subject, "named"), e))
            self._each(tb, OWL + pred, define)

        def restriction(t) -> None:
            """A restriction named by an IRI, or on several properties (RDF-Based Semantics documents):
            equivalent to the restriction on each of its properties."""
            several = len(self.store.objects(t.subject, NamedNode(OWL + "onProperty"), self.graph)) > 1
            if not isinstance(t.subject, NamedNode) or not (several or not is_skolem(t.subject)):
                return
            e = self._restriction(t.subject, self.prop(t.object))
            node = self._definition_node(t.subject, "r " + t.object.value if several else "r")
            whole = self.expr(t.subject) if is_skolem(t.subject) else Expr(t.subject, "named")
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
                tb.equivalent.append((self.expr(t.subject), self.expr(t.object)))
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
            (self.expr(t.subject), tuple(self.prop(p) for p in self._list(t.object)))))

    def _property_axioms(self, tb: TBox) -> None:
        expr, prop = self.expr, self.prop

        def domain(t) -> None:
            if not self.annotations.set_aside(tb, t, _short):
                self.types.check_domain(t.object)
                tb.domain.append((prop(t.subject), expr(t.object)))

        self._each(tb, RDFS + "domain", domain)

        def range_(t) -> None:
            if self.annotations.set_aside(tb, t, _short):
                return
            p = prop(t.subject)
            if is_datatype(t.object) or p.iri in tb.data_properties or t.object in self.datatype_defs:
                tb.data_properties.add(p.iri)
                if isinstance(t.object, NamedNode) and not is_skolem(t.object):
                    dt = self.datatype_defs.get(t.object, t.object)
                    tb.data_range.append((p.iri, dt))
                    if dt != t.object:
                        tb.data_range_node[(p.iri, dt)] = t.object
                elif isinstance(t.object, NamedNode):
                    dt = self.data_range(t.object, f"the range of {p.iri.value}")
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
                   lambda t: tb.chains.append((t.subject, tuple(prop(p) for p in self._list(t.object)))))

    def _typed_expressions(self, tb: TBox) -> None:
        """The anonymous class expressions used directly as types of individuals, read from the few
        expression nodes (each one's ``rdf:type`` subjects) rather than from every ``rdf:type`` triple."""
        st, g = self.store, self.graph
        for node in _expression_nodes(st, g):
            for subject in st.subjects(TYPE, node, g):
                try:
                    tb.typed_expressions.append(self.expr(node))
                except RuleCompileError as exc:
                    tb.unsupported.append((f"{_short(subject)} Type an anonymous expression", str(exc)))

    def read(self) -> TBox:
        tb = TBox()
        st, g = self.store, self.graph
        tb.data_properties = set(self._declared_data)
        tb.object_properties = set(self._declared_object)
        tb.annotation_punned = set(self.annotations.punned)
        for name in CHARACTERISTICS:
            told = (s for s in st.subjects(TYPE, owl(name), g) if isinstance(s, NamedNode))
            tb.characteristics[name] = self.annotations.characteristic(tb, name, told, _short)
        tb.named_classes = {s for s in st.subjects(TYPE, owl("Class"), g) if not is_skolem(s)}
        self.datatype_defs, aside = read_definitions(self)
        tb.unsupported += aside

        self._class_axioms(tb)
        self._named_definitions(tb)
        self._keys(tb)
        self._property_axioms(tb)
        for t in st.triples(None, owl("propertyDisjointWith"), None, g):
            tb.disjoint_props.append((t.subject, t.object))
        for node in st.subjects(TYPE, owl("AllDisjointProperties"), g):
            members = self._list(self._one(node, OWL + "members"))
            tb.disjoint_props += [(a, b) for i, a in enumerate(members) for b in members[i + 1:]]

        self._typed_expressions(tb)
        for items, fault in self._list_faults.values():
            tb.partial.append((f"a list ({' '.join(_short(m) for m in items)})", UNSUPPORTED,
                               f"a malformed RDF list: {fault}"))
        for e in self._cache.values():
            if e.is_named and e.node not in (THING, NOTHING) and not is_datatype(e.node):
                tb.named_classes.add(e.node)
        return tb


def boolean(node: NamedNode, kind: str, members: list[Expr]) -> Expr:
    """A union ("or") without its owl:Nothing members, an intersection ("and") without its owl:Thing
    members: they change nothing, and a rule reading them would wait for a fact no rule gives ("x is not in
    owl:Nothing", "x is in owl:Thing" where nothing typed it so).  What is left empty keeps its unit as its
    one member: an empty union is owl:Nothing, an empty intersection owl:Thing."""
    unit = NOTHING if kind == "or" else THING
    kept = tuple(m for m in members if m.node != unit)
    return Expr(node, kind, members=kept or (Expr(unit, "named"),))


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


def pred_is_data(value: Term, prop: Prop, reader: TBoxReader) -> bool:
    """Whether a restriction filler is a data range (by the filler or by the property's declaration)."""
    if is_datatype(value) or value in reader.datatype_defs:
        return True
    if is_skolem(value):
        # a data range expression (datatype restriction, oneOf of literals)
        if reader.store.objects(value, NamedNode(OWL + "onDatatype"), reader.graph):
            return True
        if reader.store.objects(value, TYPE, reader.graph) == [NamedNode(RDFS + "Datatype")]:
            return True
    return prop.iri in reader._declared_data
