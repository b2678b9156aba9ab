"""The values the compiler reads an ontology into: class and property expressions and the TBox.

Small immutable values with no SPARQL and no store: :mod:`.class_expressions` and :mod:`.tbox_reader` build them from the
RDF mapping of OWL 2, the rest of :mod:`topostore.compile` turns them into rules.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property

from pyoxigraph import Literal, NamedNode

from ..rdf.terms import Term, sparql
from ..rdf.vocab import OWL, RDF, RDFS, XSD, is_skolem
from . import data_ranges


@dataclass(frozen=True)
class Prop:
    """An object or data property, possibly inverse (``owl:inverseOf`` expression)."""

    iri: NamedNode
    inverse: bool = False
    #: a declared data property, as an unqualified cardinality's text says (``d min 1 Literal``); no part of
    #: the property's identity
    data: bool = field(default=False, compare=False)


@dataclass(frozen=True)
class Expr:
    """A class expression.  ``node`` is its IRI (named class or skolemised blank node).

    ``kind`` is one of: named, and, or, not, oneof, some, all, value, self,
    min, max, exact.  Restrictions carry ``prop`` and, when qualified,
    ``filler`` (an :class:`Expr`) or ``datatype`` (a data range IRI).
    """

    node: NamedNode
    kind: str
    members: tuple[Expr, ...] = ()
    individuals: tuple[Term, ...] = ()
    prop: Prop | None = None
    filler: Expr | None = None
    datatype: NamedNode | None = None
    n: int = 0
    value: Term | None = None

    @property
    def is_named(self) -> bool:
        return self.kind == "named"

    @property
    def is_data(self) -> bool:
        return self.datatype is not None

    def __str__(self) -> str:  # used in rule origins and error messages
        return describe(self)

    @cached_property
    def term(self) -> str:
        """The node as SPARQL text (what a rule or a schema row writes), built once."""
        return sparql(self.node)

    @cached_property
    def description(self) -> str:
        """:func:`describe`'s text, built once: every rule made from the expression names it in its origin
        (tens of thousands of rules on a large TBox)."""
        return _describe(self)


def short_name(t: Term) -> str:
    """A term as the notices name it: an IRI by its local name, a literal as written, an unnamed node (a
    skolem IRI) as ``[]``."""
    if not isinstance(t, NamedNode) or is_skolem(t):
        return "[]" if not isinstance(t, Literal) else str(t)
    v = t.value
    return v.rsplit("#", 1)[-1] if "#" in v else v.rsplit("/", 1)[-1]


def describe(e: Expr) -> str:
    """The expression in Manchester-like syntax, as the origins of rules and the notices show it."""
    return e.description


def _describe(e: Expr) -> str:
    def short(t: Term | None) -> str:
        if t is None:
            return "?"
        if isinstance(t, NamedNode) and data_ranges.readable(t):
            return data_ranges.readable(t)
        v = t.value if hasattr(t, "value") else str(t)
        return v.rsplit("#", 1)[-1] if "#" in v else v.rsplit("/", 1)[-1]

    if e.kind == "named":
        return short(e.node)
    p = ("inverse " if e.prop and e.prop.inverse else "") + short(e.prop.iri if e.prop else None)
    f = short(e.datatype) if e.datatype is not None else (
        describe(e.filler) if e.filler else "Literal" if e.prop and e.prop.data else "Thing")
    if e.kind in ("and", "or"):
        joiner = " and " if e.kind == "and" else " or "
        return "(" + joiner.join(describe(m) for m in e.members) + ")"
    if e.kind == "not":
        return f"not {describe(e.members[0])}"
    if e.kind == "oneof":
        return "{" + ", ".join(short(i) for i in e.individuals) + "}"
    if e.kind == "some":
        return f"({p} some {f})"
    if e.kind == "all":
        return f"({p} only {f})"
    if e.kind == "value":
        return f"({p} value {short(e.value)})"
    if e.kind == "self":
        return f"({p} Self)"
    return f"({p} {e.kind} {e.n} {f})"


@dataclass
class TBox:
    """The axioms of an ontology that the compiler turns into rules."""

    subclass: list[tuple[Expr, Expr]] = field(default_factory=list)
    equivalent: list[tuple[Expr, Expr]] = field(default_factory=list)
    disjoint: list[tuple[Expr, Expr]] = field(default_factory=list)
    domain: list[tuple[Prop, Expr]] = field(default_factory=list)
    range: list[tuple[Prop, Expr]] = field(default_factory=list)
    data_range: list[tuple[NamedNode, NamedNode]] = field(default_factory=list)
    #: the node each data range of ``data_range`` was told as (a restricted range's blank node)
    data_range_node: dict[tuple[NamedNode, NamedNode], NamedNode] = field(default_factory=dict)
    subproperty: list[tuple[Prop, Prop]] = field(default_factory=list)
    inverse: list[tuple[NamedNode, NamedNode]] = field(default_factory=list)
    chains: list[tuple[NamedNode, tuple[Prop, ...]]] = field(default_factory=list)
    disjoint_props: list[tuple[NamedNode, NamedNode]] = field(default_factory=list)
    characteristics: dict[str, set[NamedNode]] = field(default_factory=dict)
    data_properties: set[NamedNode] = field(default_factory=set)
    object_properties: set[NamedNode] = field(default_factory=set)
    named_classes: set[NamedNode] = field(default_factory=set)
    typed_expressions: list[Expr] = field(default_factory=list)  # anonymous classes used in rdf:type
    #: axioms read but not translated: (axiom as text, why); the profile report names them
    unsupported: list[tuple[str, str]] = field(default_factory=list)
    #: properties made the same by owl:sameAs (named by the profile report: not substituted)
    same_properties: list[tuple[NamedNode, NamedNode]] = field(default_factory=list)
    #: keys (owl:hasKey): class, the properties whose values identify an individual
    keys: list[tuple[Expr, tuple[Prop, ...]]] = field(default_factory=list)
    #: axioms read without rules of their own (hasKey, disjoint unions' covering, ...): (axiom, kind, why)
    partial: list[tuple[str, str, str]] = field(default_factory=list)
    #: annotation properties whose axioms were set aside, each with those axioms (as text): no logical meaning
    annotation_axioms: dict[NamedNode, list[str]] = field(default_factory=dict)
    #: IRIs declared both an annotation property and an object or data property: read as the latter
    annotation_punned: set[NamedNode] = field(default_factory=set)

    def has(self, characteristic: str, p: NamedNode) -> bool:
        return p in self.characteristics.get(characteristic, set())


_DATATYPE_NAMESPACES = (XSD, RDFS + "Literal", RDF + "PlainLiteral", RDF + "langString", RDF + "XMLLiteral",
                        OWL + "real", OWL + "rational")


def is_datatype(node: Term) -> bool:
    """Whether ``node`` names a datatype by its namespace (XSD, rdfs:Literal, ...): such a node is a
    data range, never a class, wherever an axiom uses it."""
    return isinstance(node, NamedNode) and any(node.value.startswith(ns) for ns in _DATATYPE_NAMESPACES)
