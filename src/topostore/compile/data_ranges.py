"""Data ranges other than a named datatype (``xsd:integer[>= 18]``, ``{1, 2}``, ``not xsd:integer``) as
self-describing IRIs.

OWL 2 writes a data range such as "an integer of at least 18" as a blank node with
``owl:onDatatype xsd:integer`` and ``owl:withRestrictions ( [ xsd:minInclusive 18 ] )``.  The
compiler names data ranges by IRI (a restriction's ``datatype``), so such a range is named by an
IRI that spells it out — ``urn:topostore:datarange:<base>?minInclusive=18`` — which
:func:`facet_tests` turns back into SPARQL tests.  The ranges built of others (OWL 2 §7: a one-of of
literals, ``owl:datatypeComplementOf``, a data ``owl:unionOf`` or ``owl:intersectionOf``) are named
alike, ``urn:topostore:datarange:unionOf?m=<member IRI>&m=…`` (:func:`composed`), their members being
named datatypes or such IRIs in turn; :func:`composition` reads one back.  The IRI is a pure function of
the range: equal ranges get equal names, and no table has to travel with the rules.
"""

from __future__ import annotations

from urllib.parse import parse_qsl, quote, urlencode

from pyoxigraph import Literal, NamedNode

from ..rdf.terms import Term, parse_term, sparql, value_key
from ..rdf.vocab import INTERNAL, XSD

PREFIX = INTERNAL + "datarange:"
#: the numeric facets, as SPARQL comparison operators
FACETS = {"minInclusive": ">=", "minExclusive": ">", "maxInclusive": "<=", "maxExclusive": "<"}
_NUMERIC = {"integer", "decimal", "double", "float", "int", "long", "short", "byte", "nonNegativeInteger",
            "positiveInteger", "nonPositiveInteger", "negativeInteger", "unsignedLong", "unsignedInt",
            "unsignedShort", "unsignedByte"}


def restricted(base: NamedNode, facets: list[tuple[str, Literal]]) -> NamedNode:
    """The IRI of ``base`` restricted by numeric ``facets`` (facet local name, numeric literal)."""
    for facet, value in facets:
        if facet not in FACETS:
            raise ValueError(f"the facet xsd:{facet} is not supported (only {', '.join(FACETS)})")
        local = value.datatype.value[len(XSD):] if value.datatype.value.startswith(XSD) else ""
        if local not in _NUMERIC:
            raise ValueError(f"the value {value.value!r} of xsd:{facet} is not a number")
    query = urlencode([(f, f"{v.value}^^{v.datatype.value[len(XSD):]}") for f, v in facets])
    return NamedNode(f"{PREFIX}{quote(base.value, safe='')}?{query}")


def parts(datatype: NamedNode) -> tuple[NamedNode, list[tuple[str, str]]] | None:
    """(base datatype, [(SPARQL operator, SPARQL literal)]) of a restricted range; None for any other IRI."""
    if not datatype.value.startswith(PREFIX) or _kind(datatype) is not None:
        return None
    from urllib.parse import unquote

    base, _, query = datatype.value[len(PREFIX):].partition("?")
    tests = []
    for facet, text in parse_qsl(query):
        value, _, local = text.rpartition("^^")
        tests.append((FACETS[facet], f'"{value}"^^<{XSD}{local}>'))
    return NamedNode(unquote(base)), tests


def facet_tests(var: str, datatype: NamedNode) -> list[str] | None:
    """The facet comparisons of a restricted range (None for any other IRI)."""
    found = parts(datatype)
    if found is None:
        return None
    return [f"{var} {op} {value}" for op, value in found[1]]


def readable(datatype: NamedNode) -> str | None:
    """``integer[>= 0, < 150]`` for a restricted range, ``{1, 2}``, ``not integer``, ``(integer or boolean)``
    for a composed one (None for any other IRI)."""
    built = composition(datatype)
    if built is not None:
        kind, members = built
        if kind == "oneOf":
            return "{" + ", ".join(_written(m) for m in members if isinstance(m, Literal)) + "}"
        names = [readable(m) or m.value.rsplit("#", 1)[-1] for m in members if isinstance(m, NamedNode)]
        if kind == "complementOf":
            return f"not {names[0]}"
        return "(" + f" {_WORDS[kind]} ".join(names) + ")"
    found = parts(datatype)
    if found is None:
        return None
    base, tests = found
    return base.value.rsplit("#", 1)[-1] + "[" + ", ".join(f"{op} {v.split('^^')[0].strip(chr(34))}"
                                                          for op, v in tests) + "]"


#: the data ranges built of others, as the OWL 2 RDF mapping names their predicate
COMPOSED = ("oneOf", "complementOf", "unionOf", "intersectionOf")
_WORDS = {"unionOf": "or", "intersectionOf": "and"}


def composed(kind: str, members: list[Term]) -> NamedNode:
    """The IRI of the data range of ``kind`` (one of :data:`COMPOSED`) over ``members``: literals for a one-of,
    data range IRIs for the others.  Members are a set (a value written twice, ``1`` and ``"1"^^xsd:int``, is
    one), kept in the order of their text so that equal ranges get one name."""
    if kind not in COMPOSED:
        raise ValueError(f"unknown data range kind {kind}")
    if kind == "oneOf":
        texts = {value_key(m): sparql(m) for m in members}.values()
    else:
        if kind in _WORDS:  # a union of unions is one union, an intersection of intersections one intersection
            members = [m for member in members for m in _flat(kind, member)]
        texts = (m.value for m in members)
    name = NamedNode(f"{PREFIX}{kind}?" + urlencode([("m", t) for t in sorted(set(texts))]))
    if len(name.value) > MAX_LENGTH:
        raise ValueError(f"the data range is too large ({len(name.value)} characters written out, at most "
                         f"{MAX_LENGTH} are read)")
    return name


#: the longest composed range read (written out as its IRI): a longer one is set aside with its notice rather
#: than compiled into a query too large for the store
MAX_LENGTH = 30000


def _flat(kind: str, member: Term) -> list[Term]:
    """The members a union (intersection) ``member`` contributes to a union (intersection): its own members
    when it is one, else itself."""
    built = composition(member) if isinstance(member, NamedNode) else None
    if built is not None and built[0] == kind:
        return [m for inner in built[1] for m in _flat(kind, inner)]
    return [member]


def composition(datatype: NamedNode) -> tuple[str, list[Term]] | None:
    """(kind, members) of a range :func:`composed` named (literals of a one-of, IRIs otherwise); None for any
    other IRI."""
    kind = _kind(datatype)
    if kind is None:
        return None
    query = datatype.value[len(PREFIX) + len(kind) + 1:]
    texts = [text for _, text in parse_qsl(query)]
    if kind == "oneOf":
        return kind, [t for t in map(parse_term, texts) if t is not None]
    return kind, [NamedNode(t) for t in texts]


def _written(value: Literal) -> str:
    """A one-of's member as a person writes it: ``1``, ``true``, ``"a"``, ``"a"@en``, ``"2020-01-01"^^date``."""
    local = value.datatype.value[len(XSD):] if value.datatype.value.startswith(XSD) else ""
    if value.language:
        return f'"{value.value}"@{value.language}'
    if local in ("integer", "decimal", "boolean"):
        return value.value
    return f'"{value.value}"' + ("" if local == "string" else f"^^{local or value.datatype.value}")


def _kind(datatype: NamedNode) -> str | None:
    """The kind of a composed range's IRI (None: another IRI, a restricted datatype among them)."""
    v = datatype.value
    if not v.startswith(PREFIX):
        return None
    kind = v[len(PREFIX):].partition("?")[0]
    return kind if kind in COMPOSED else None


__all__ = ["COMPOSED", "FACETS", "PREFIX", "MAX_LENGTH", "composed", "composition", "facet_tests", "parts", "readable",
           "restricted"]
