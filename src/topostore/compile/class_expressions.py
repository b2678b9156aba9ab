"""Reading OWL class expressions, property expressions and data ranges from the asserted graph.

The first half of the compiler's "parser" stage (:mod:`.tbox_reader` is the other): it turns the RDF
mapping of one OWL 2 expression (a restriction, an intersection, a one-of, a datatype restriction, ...)
into the values of :mod:`.model`.  Why a module of its own: an expression is read wherever one may stand
(an axiom's side, a restriction's filler, a SWRL atom, a proof's text), so the axiom reader and the SWRL
compiler share one :class:`ClassExpressionReader`, and with it one memo of the expressions read (the same
node is one :class:`~.model.Expr`) and one record of the malformed lists met.  Nothing here knows about
axioms or SPARQL.
"""

from __future__ import annotations

from dataclasses import replace

from pyoxigraph import Literal, NamedNode

from ..errors import RuleCompileError
from ..rdf.terms import Term
from ..rdf.vocab import NOTHING, OWL, RDFS, THING, TYPE, XSD, is_skolem, owl
from ..stores.base import Store
from . import data_ranges
from .expression_types import ExpressionTypes
from .model import Expr, Prop, is_datatype

#: class expressions nested deeper than this are refused: reading, describing and compiling them
#: recurse once per level, and Python's stack ends near 1,000 frames (no real TBox nests 100 deep)
MAX_NESTING = 100


class ClassExpressionReader:
    """Reads the class expressions, property expressions and data ranges of one graph of a :class:`Store`,
    each node once (memoised: a node reached again, or through a cycle, is the same value)."""

    def __init__(self, store: Store, graph: NamedNode) -> None:
        self.store = store
        self.graph = graph
        self._cache: dict[Term, Expr] = {}
        self._depth = 0
        #: the malformed lists read, by head: (members read, what is wrong)
        self.list_faults: dict[Term, tuple[list[Term], str]] = {}
        #: the properties declared data properties: a restriction on one reads its filler as a data range
        self.declared_data = {s for s in store.subjects(TYPE, owl("DatatypeProperty"), graph) if isinstance(s, NamedNode)}
        #: each named datatype defined as a data range, and the range it stands for (set by the axiom reader,
        #: which reads the definitions before any axiom: :mod:`.datatype_definitions`)
        self.datatype_defs: dict[NamedNode, NamedNode] = {}
        #: which blank nodes are read as class expressions or data ranges (:mod:`.expression_types`)
        self.types = ExpressionTypes(store, graph)

    # ---------------------------------------------------------------- helpers
    def one(self, s: Term, p: str) -> Term | None:
        """One value of ``s``'s property ``p`` (the IRI), None when it has none."""
        values = self.store.objects(s, NamedNode(p), self.graph)
        return values[0] if values else None

    def items(self, head: Term) -> list[Term]:
        """The members of a list an axiom reads; a malformed one (looping back, a cell with two rdf:first) is
        kept for the notice that names it (:attr:`list_faults`)."""
        items, fault = self.store.list_read(head, self.graph)
        if fault:
            self.list_faults.setdefault(head, (items, fault))
        return items

    def expressions_read(self) -> list[Expr]:
        """The expressions read so far, named classes among them (a class used but never declared is one)."""
        return list(self._cache.values())

    def is_data(self, value: Term, prop: Prop) -> bool:
        """Whether a restriction filler is a data range (by the filler or by the property's declaration)."""
        if is_datatype(value) or value in self.datatype_defs:
            return True
        if is_skolem(value):
            # a data range expression (datatype restriction, oneOf of literals)
            if self.store.objects(value, NamedNode(OWL + "onDatatype"), self.graph) or \
                    self.store.objects(value, NamedNode(OWL + "datatypeComplementOf"), self.graph):
                return True
            if self.store.objects(value, TYPE, self.graph) == [NamedNode(RDFS + "Datatype")]:
                return True
        return prop.iri in self.declared_data

    def prop(self, node: Term, depth: int = 0) -> Prop:
        """The property expression ``node``: a named property or the inverse of one; an inverse of an
        inverse is the property itself (not OWL 2 DL syntax, but what it means, as Pellet reads it)."""
        if is_skolem(node):
            inner = self.one(node, OWL + "inverseOf")
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
            head = self.one(node, OWL + pred)
            if head is not None:
                return boolean(node, kind, [self.expr(m) for m in self.items(head)])
        comp = self.one(node, OWL + "complementOf")
        if comp is not None:
            return Expr(node, "not", members=(self.expr(comp),))
        one_of = self.one(node, OWL + "oneOf")
        if one_of is not None:
            return Expr(node, "oneof", individuals=tuple(self.items(one_of)))
        on_prop = self.one(node, OWL + "onProperty")
        if on_prop is not None:
            return self.restriction(node, self.prop(on_prop))
        raise RuleCompileError(f"unsupported or malformed class expression {node.value}")

    def _filler(self, node: NamedNode, prop: Prop, value: Term | None) -> tuple[Expr | None, NamedNode | None]:
        """(class filler, data range) of a restriction; (None, None) when unqualified."""
        for pred in ("onClass", "onDataRange"):
            v = self.one(node, OWL + pred)
            if v is not None:
                value = v
        if value is None:
            return None, None
        if self.is_data(value, prop):
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
        data = self.is_data(filler, prop)
        if not is_skolem(filler):
            return self._named_single(filler) if isinstance(filler, NamedNode) and not data else None
        if data:
            head = self.one(filler, OWL + "oneOf")
            if head is None or not self.types.typed_data_range(filler) or self.types.typed_class(filler):
                return None  # not a data one-of the OWL API reads: set aside by data_range, which says why
            members = set(self.items(head))
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
            members = set(self.items(head))
            if len(members) == 1 and isinstance(next(iter(members)), NamedNode):
                return next(iter(members))
        return None

    def data_range(self, node: NamedNode, where: str, typed: bool = False) -> NamedNode:
        """A data range expression (a datatype restricted by numeric facets, a data one-of of literals, a
        complement, a union or an intersection of data ranges), as the IRI :mod:`.data_ranges` names it;
        RuleCompileError for others (string facets), and for one without its ``rdf:type rdfs:Datatype`` triple
        unless ``typed`` (its place types it)."""
        if not typed and self.types.typed_class(node):
            raise RuleCompileError(f"a class expression stands where a data range is wanted in {where}")
        if not typed and not self.types.typed_data_range(node):
            raise RuleCompileError(f"the data range in {where} lacks its rdf:type rdfs:Datatype triple: the OWL 2 "
                                   "mapping to RDF (and the OWL API) does not read it as a data range")
        if self._depth >= MAX_NESTING:
            raise RuleCompileError(f"data ranges nested more than {MAX_NESTING} deep in {where}")
        base = self.one(node, OWL + "onDatatype")
        head = self.one(node, OWL + "withRestrictions")
        if not isinstance(base, NamedNode) or head is None:
            self._depth += 1
            try:
                return self._composed_range(node, where)
            finally:
                self._depth -= 1
        facets = []
        for item in self.items(head):
            for t in self.store.triples(item, None, None, self.graph):
                if not isinstance(t.object, Literal) or not t.predicate.value.startswith(XSD):
                    raise RuleCompileError(f"unsupported facet in the data range of {where}")
                facets.append((t.predicate.value[len(XSD):], t.object))
        try:
            return data_ranges.restricted(base, facets)
        except ValueError as exc:
            raise RuleCompileError(f"data range of {where}: {exc}") from None

    def _composed_range(self, node: NamedNode, where: str) -> NamedNode:
        """A data one-of, complement, union or intersection (:func:`.data_ranges.composed`)."""
        try:
            return self._composed(node, where)
        except ValueError as exc:  # too large
            raise RuleCompileError(f"{exc} in {where}") from None

    def _composed(self, node: NamedNode, where: str) -> NamedNode:
        head = self.one(node, OWL + "oneOf")
        if head is not None:
            values = self.items(head)
            if not values or not all(isinstance(v, Literal) for v in values):
                raise RuleCompileError(f"the data one-of in {where} has a member that is not a literal, or none")
            return data_ranges.composed("oneOf", values)
        inner = self.one(node, OWL + "datatypeComplementOf")
        if inner is not None:
            return data_ranges.composed("complementOf", [self._data_member(inner, where)])
        for kind in ("unionOf", "intersectionOf"):
            head = self.one(node, OWL + kind)
            if head is not None:
                members = [self._data_member(m, where) for m in self.items(head)]
                if not members:
                    raise RuleCompileError(f"the data {kind} in {where} has no member")
                return data_ranges.composed(kind, members)
        raise RuleCompileError(f"unsupported data range in {where} (only datatypes restricted by numeric facets, "
                               "data one-ofs, complements, unions and intersections are)")

    def _data_member(self, node: Term, where: str) -> NamedNode:
        """A member of a composed data range: a named datatype (one defined stands for its range), or a range."""
        if not isinstance(node, NamedNode):
            raise RuleCompileError(f"a literal stands where a data range is wanted in {where}")
        if is_skolem(node):
            return self.data_range(node, where, typed=True)
        return self.datatype_defs.get(node, node)

    def restriction(self, node: NamedNode, prop: Prop) -> Expr:
        """The restriction at ``node`` on ``prop``; public because the axiom reader also reads a restriction
        named by an IRI, or on several properties, as one on each (:meth:`expr` reads a named node as named)."""
        some = self.one(node, OWL + "someValuesFrom")
        if some is not None:
            only = self._single_member(some, prop)
            if only is not None:  # ∃p.{b} is p value b: the value is in {b}, so it is b (likewise for a literal)
                return Expr(node, "value", prop=prop, value=only)
            filler, dt = self._filler(node, prop, some)
            return Expr(node, "some", prop=prop, filler=filler, datatype=dt)
        all_ = self.one(node, OWL + "allValuesFrom")
        if all_ is not None:
            filler, dt = self._filler(node, prop, all_)
            return Expr(node, "all", prop=prop, filler=filler, datatype=dt)
        has_value = self.one(node, OWL + "hasValue")
        if has_value is not None:
            return Expr(node, "value", prop=prop, value=has_value)
        if self.one(node, OWL + "hasSelf") is not None:
            return Expr(node, "self", prop=prop)
        for kind, names in (
            ("min", ("minCardinality", "minQualifiedCardinality")),
            ("max", ("maxCardinality", "maxQualifiedCardinality")),
            ("exact", ("cardinality", "qualifiedCardinality")),
        ):
            for name in names:
                n = self.one(node, OWL + name)
                if n is not None:
                    if not isinstance(n, Literal) or not n.value.strip().isdigit():
                        raise RuleCompileError(f"cardinality {n} of a restriction on {prop.iri.value} is not a number")
                    on = [v for v in (self.one(node, OWL + "onClass"), self.one(node, OWL + "onDataRange"))
                          if v is not None]
                    only = self._single_member(on[0], prop) if kind == "min" and int(n.value) == 1 and on else None
                    if only is not None:  # ≥1 p.{b} is ∃p.{b}, p value b
                        return Expr(node, "value", prop=prop, value=only)
                    filler, dt = self._filler(node, prop, None)
                    if filler is None and dt is None and prop.iri in self.declared_data:
                        prop = replace(prop, data=True)  # named as a data restriction, read as written
                    return Expr(node, kind, prop=prop, filler=filler, datatype=dt, n=int(n.value))
        raise RuleCompileError(f"unsupported restriction on {prop.iri.value}")


def boolean(node: NamedNode, kind: str, members: list[Expr]) -> Expr:
    """A union ("or") without its owl:Nothing members, an intersection ("and") without its owl:Thing
    members: they change nothing, and a rule reading them would wait for a fact no rule gives ("x is not in
    owl:Nothing", "x is in owl:Thing" where nothing typed it so).  What is left empty keeps its unit as its
    one member: an empty union is owl:Nothing, an empty intersection owl:Thing."""
    unit = NOTHING if kind == "or" else THING
    kept = tuple(m for m in members if m.node != unit)
    return Expr(node, kind, members=kept or (Expr(unit, "named"),))


__all__ = ["MAX_NESTING", "ClassExpressionReader", "boolean"]
