"""Datatype subsumption: the ranges implied by a data property's told ranges (value spaces nest,
integer types intersect as intervals), and literals of a narrower type in a wider type's value space."""

from __future__ import annotations

import pytest
from pyoxigraph import NamedNode, Triple
from support import reasoned_turtle

from topostore import Ontology
from topostore.compile.datatypes import implied_ranges
from topostore.rdf.vocab import OWL, RDF, RDFS, XSD

PREFIXES = """@prefix : <http://e.org/d#> . @prefix owl: <http://www.w3.org/2002/07/owl#> .
@prefix rdfs: <http://www.w3.org/2000/01/rdf-schema#> . @prefix xsd: <http://www.w3.org/2001/XMLSchema#> .
<http://e.org/d> a owl:Ontology . :n a owl:DatatypeProperty .
"""


def names(*locals_: str) -> set[NamedNode]:
    return {NamedNode(XSD + x) for x in locals_}


def implied(*locals_: str) -> set[str]:
    return {t.value.rsplit("#", 1)[-1] for t in implied_ranges(names(*locals_))}


def reasoned(text: str) -> Ontology:
    return reasoned_turtle(PREFIXES + text)


def has_range(o: Ontology, dt: str) -> bool:
    return bool(o.sparql(f"ASK {{ <http://e.org/d#n> <http://www.w3.org/2000/01/rdf-schema#range> <{dt}> }}"))


def test_integer_types_nest() -> None:
    assert implied("byte") == {"byte", "short", "int", "long", "integer", "decimal", "rational", "real"}
    assert implied("unsignedByte") >= {"unsignedShort", "short", "nonNegativeInteger"}
    assert "byte" not in implied("unsignedByte")  # 200 is an unsigned byte, not a byte
    assert "positiveInteger" not in implied("nonNegativeInteger")


def test_several_ranges_intersect() -> None:
    assert "unsignedShort" in implied("short", "unsignedInt")  # [0, 32767]
    assert {"short", "byte", "unsignedByte"} <= implied("nonNegativeInteger", "nonPositiveInteger")  # {0}
    assert "byte" not in implied("short", "unsignedInt")


def test_string_types_nest() -> None:
    assert implied("NCName") == {"NCName", "Name", "token", "normalizedString", "string", "PlainLiteral"}
    assert "NCName" not in implied("token")


def test_disjoint_families_make_an_empty_range() -> None:
    everything = implied("string", "int")
    assert {"boolean", "dateTime", "byte", "NCName"} <= everything
    assert implied("positiveInteger", "negativeInteger") == everything  # no integer is both


def test_no_range_implies_nothing_beyond_a_datatype_topostore_does_not_know() -> None:
    odd = NamedNode("http://e.org/d#myType")
    assert implied_ranges([odd]) == {odd}
    assert implied_ranges([NamedNode(OWL + "real")]) == {NamedNode(OWL + "real")}
    assert NamedNode(RDF + "PlainLiteral") in implied_ranges(names("string"))


def test_range_byte_entails_range_short() -> None:
    o = reasoned(":n rdfs:range xsd:byte .")
    assert has_range(o, XSD + "short") and has_range(o, XSD + "integer") and has_range(o, OWL + "real")
    assert not has_range(o, XSD + "unsignedByte")


def test_ranges_with_facets_intersect() -> None:
    o = reasoned(":n rdfs:range xsd:nonNegativeInteger , [ a rdfs:Datatype ; owl:onDatatype xsd:integer ; "
                 "owl:withRestrictions ( [ xsd:maxExclusive 100.5 ] ) ] .")
    assert has_range(o, XSD + "byte") and has_range(o, XSD + "unsignedByte")  # [0, 100]
    assert not has_range(o, XSD + "positiveInteger")
    tree = o.explain("n", "rdfs:range", "xsd:byte")
    assert tree.rule == "ext-dt-range" and len(tree.premises) == 2


def test_implied_range_goes_with_the_told_one() -> None:
    o = reasoned(":n rdfs:range xsd:byte .")
    o.remove(Triple(o.iri("n"), NamedNode(RDFS + "range"), NamedNode(XSD + "byte")))
    assert o.reason().consistent
    assert not has_range(o, XSD + "short")


@pytest.mark.parametrize("literal,member", [('"5"^^xsd:byte', True), ('"300"^^xsd:short', True),
                                            ('"3000000000"^^xsd:long', False), ('"5.0"^^xsd:decimal', True)])
def test_a_narrower_literal_is_in_a_wider_value_space(literal: str, member: bool) -> None:
    o = reasoned(f":C owl:equivalentClass [ a owl:Restriction ; owl:onProperty :n ; owl:someValuesFrom xsd:int ] . "
                 f":a :n {literal} .")
    assert ("C" in {o.short(t) for t in o.types("a")}) is member


def restricted_range(base: str, *facets: tuple[str, str, str]) -> NamedNode:
    from pyoxigraph import Literal

    from topostore.compile.data_ranges import restricted
    return restricted(NamedNode(XSD + base), [(f, Literal(v, datatype=NamedNode(XSD + t))) for f, v, t in facets])


@pytest.mark.parametrize("base,facets,empty", [
    ("float", [("minExclusive", "0.0", "float"), ("maxExclusive", "1.401298464324817e-45", "float")], True),
    ("float", [("minExclusive", "0.0", "float"), ("maxExclusive", "3e-45", "float")], False),
    ("float", [("minInclusive", "-1.0", "float"), ("maxExclusive", "-1.0", "float")], True),
    ("double", [("minExclusive", "0.0", "double"), ("maxExclusive", "4.9e-324", "double")], True),
    ("double", [("minExclusive", "0.0", "double"), ("maxExclusive", "1.401298464324817e-45", "double")], False),
    ("integer", [("minExclusive", "5", "integer"), ("maxExclusive", "6", "integer")], True),
    ("integer", [("minInclusive", "5", "integer"), ("maxExclusive", "6", "integer")], False),
    ("byte", [("minInclusive", "200", "integer")], True),
    ("decimal", [("minExclusive", "5", "decimal"), ("maxExclusive", "5.0", "decimal")], True),
    ("decimal", [("minInclusive", "5", "decimal"), ("maxInclusive", "5.0", "decimal")], False),
    ("decimal", [("minExclusive", "5", "decimal"), ("maxExclusive", "5.01", "decimal")], False),
])
def test_empty_data_ranges(base: str, facets: list, empty: bool) -> None:
    from topostore.compile.datatypes import is_empty
    assert is_empty(restricted_range(base, *facets)) is empty


def test_a_value_of_an_empty_range_is_inconsistent() -> None:
    o = Ontology()
    o.load_data(PREFIXES + ":a a [ a owl:Restriction ; owl:onProperty :n ; owl:someValuesFrom [ a rdfs:Datatype ; "
                "owl:onDatatype xsd:float ; owl:withRestrictions ( [ xsd:minExclusive \"0.0\"^^xsd:float ] "
                "[ xsd:maxExclusive \"1.401298464324817e-45\"^^xsd:float ] ) ] ] .")
    report = o.reason()
    assert not report.consistent
    assert report.violations[0].rule == "ext-empty-range"
    ok = reasoned(":a a [ a owl:Restriction ; owl:onProperty :n ; owl:someValuesFrom [ a rdfs:Datatype ; "
                  "owl:onDatatype xsd:float ; owl:withRestrictions ( [ xsd:minExclusive \"0.0\"^^xsd:float ] "
                  "[ xsd:maxExclusive \"3e-45\"^^xsd:float ] ) ] ] .")
    assert ok.reason().consistent


@pytest.mark.parametrize("value,datatype", [("INF", "float"), ("NaN", "double"), ("1e999999999", "decimal"),
                                            ("-1e999999999", "decimal")])
def test_extreme_facets_are_read_without_harm(value: str, datatype: str) -> None:
    from topostore.compile.datatypes import is_empty
    r = restricted_range("integer", ("minInclusive", value, datatype))
    assert is_empty(r) is False
    assert NamedNode(XSD + "integer") in implied_ranges([r])
