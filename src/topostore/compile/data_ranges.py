"""Datatype restrictions with numeric facets (``xsd:integer[>= 18]``) as self-describing IRIs.

OWL 2 writes a data range such as "an integer of at least 18" as a blank node with
``owl:onDatatype xsd:integer`` and ``owl:withRestrictions ( [ xsd:minInclusive 18 ] )``.  The
compiler names data ranges by IRI (a restriction's ``datatype``), so such a range is named by an
IRI that spells it out — ``urn:topostore:datarange:<base>?minInclusive=18`` — which
:func:`facet_tests` turns back into SPARQL tests.  The IRI is a pure function of the range: equal
ranges get equal names, and no table has to travel with the rules.
"""

from __future__ import annotations

from urllib.parse import parse_qsl, quote, urlencode

from pyoxigraph import Literal, NamedNode

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
    if not datatype.value.startswith(PREFIX):
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
    """``integer[>= 0, < 150]`` for a restricted range (None for any other IRI)."""
    found = parts(datatype)
    if found is None:
        return None
    base, tests = found
    return base.value.rsplit("#", 1)[-1] + "[" + ", ".join(f"{op} {v.split('^^')[0].strip(chr(34))}"
                                                          for op, v in tests) + "]"


__all__ = ["FACETS", "PREFIX", "facet_tests", "parts", "readable", "restricted"]
