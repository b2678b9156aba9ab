"""Two values of a property allowing one make two individuals different (compile/owl.py
difference_rules): the test that both values lie in the restriction's data range is left out when the
property's told ranges already imply it, since a value outside them is a range violation."""

from __future__ import annotations

import pytest
from pyoxigraph import Literal, NamedNode
from support import quiet_turtle

from topostore import Ontology
from topostore.compile.datatypes import surely_in


def XSD_(local: str) -> str:
    return "http://www.w3.org/2001/XMLSchema#" + local


PREFIXES = """@prefix : <http://e.org/v#> . @prefix owl: <http://www.w3.org/2002/07/owl#> .
@prefix rdfs: <http://www.w3.org/2000/01/rdf-schema#> . @prefix xsd: <http://www.w3.org/2001/XMLSchema#> .
<http://e.org/v> a owl:Ontology .
:seen a owl:DatatypeProperty .
:Place owl:equivalentClass [ a owl:Restriction ; owl:onProperty :seen ;
                             owl:qualifiedCardinality "1"^^xsd:nonNegativeInteger ; owl:onDataRange xsd:long ] .
"""


def load(text: str) -> Ontology:
    return quiet_turtle(PREFIXES + text)


def value_rules(o: Ontology) -> list:
    return [r for r in o.rules.compiled_rules() if r.name == "different-values"]


@pytest.mark.parametrize(("ranges", "tested"), [
    (":seen rdfs:range xsd:long .", False),
    (":seen rdfs:range xsd:int .", False),  # every int is a long
    (":seen rdfs:range xsd:integer .", True),  # an integer may lie outside long
    ("", True),
    (":seen rdfs:range xsd:long , xsd:string .", False),  # no value can satisfy both: every value violates
])
def test_the_range_test_is_left_out_only_when_the_told_ranges_imply_it(ranges: str, tested: bool) -> None:
    rules = value_rules(load(ranges))
    assert rules
    assert all(any("FLOOR" in c.expression for c in r.conditions) == tested for r in rules)


def test_a_value_outside_the_range_is_still_an_inconsistency() -> None:
    o = load(':seen rdfs:range xsd:long . :a :seen 5 . :b :seen "five" .')
    report = o.reason()
    assert not report.consistent


def test_two_values_in_range_still_make_two_places_different() -> None:
    o = load(":seen rdfs:range xsd:long . :a a :Place ; :seen 5 . :b a :Place ; :seen 7 .")
    assert o.reason().consistent
    o.load_data(PREFIXES + ":a owl:sameAs :b .")
    assert not o.reason().consistent  # one place cannot have two times


@pytest.mark.parametrize("value,datatype,sure", [
    (Literal("5", datatype=NamedNode(XSD_("long"))), XSD_("long"), True),
    (Literal("-9223372036854775808", datatype=NamedNode(XSD_("long"))), XSD_("long"), True),
    (Literal("9223372036854775808", datatype=NamedNode(XSD_("integer"))), XSD_("long"), False),  # out of range: ask
    (Literal("300", datatype=NamedNode(XSD_("integer"))), XSD_("byte"), False),
    (Literal("5", datatype=NamedNode(XSD_("integer"))), XSD_("decimal"), True),
    (Literal("abc", datatype=NamedNode(XSD_("long"))), XSD_("long"), False),  # ill-typed: ask
    (Literal(" 5", datatype=NamedNode(XSD_("long"))), XSD_("long"), False),  # not decided here: ask
    (Literal("5.0", datatype=NamedNode(XSD_("decimal"))), XSD_("long"), False),
    (Literal("5"), XSD_("long"), False),
    (Literal("5", datatype=NamedNode(XSD_("long"))), XSD_("string"), False),
    (Literal("5", datatype=NamedNode(XSD_("long"))), "http://www.w3.org/2002/07/owl#real", True),
    (Literal("5", datatype=NamedNode(XSD_("long"))), "http://www.w3.org/2002/07/owl#rational", True),
    (Literal("5", datatype=NamedNode(XSD_("long"))), "http://e.org/v#decimal", False),  # not XSD's decimal
    (Literal("-1", datatype=NamedNode(XSD_("nonNegativeInteger"))), XSD_("integer"), False),  # ill-typed
    (Literal("1" * 41, datatype=NamedNode(XSD_("integer"))), XSD_("decimal"), False),  # too long to read here
    (NamedNode(XSD_("long")), XSD_("long"), False),
])
def test_a_known_value_is_decided_only_when_it_surely_lies_in_the_range(value, datatype: str, sure: bool) -> None:
    assert surely_in(value, datatype) is sure


def test_a_replaced_value_outside_the_range_is_still_a_violation() -> None:
    """Range checks decide surely valid new values without a query; the others are still asked."""
    o = load(":seen rdfs:range xsd:long . :a :seen 5 .")
    o.reason()
    o.replace("a", "seen", Literal("7", datatype=NamedNode(XSD_("long"))))
    report = o.reason(mode="incremental")
    assert report.consistent and report.stats.mode == "incremental"
    o.replace("a", "seen", Literal("9223372036854775808", datatype=NamedNode(XSD_("integer"))))
    report = o.reason(mode="incremental")
    assert not report.consistent and [v.rule for v in report.violations] == ["dt-range"]
    o.replace("a", "seen", Literal("8", datatype=NamedNode(XSD_("long"))))
    assert o.reason(mode="incremental").consistent



@pytest.mark.parametrize("narrow_first", [False, True])
def test_one_new_value_is_decided_for_each_range_it_must_lie_in(narrow_first: bool) -> None:
    """A REASON's new value under two range checks (a robot's clock and visit time) is decided once per
    range: in a long, not in a short, whichever check comes first (the checks follow the told ranges)."""
    ranges = [":seen rdfs:range xsd:long .", ":small a owl:DatatypeProperty ; rdfs:range xsd:short ."]
    o = load(" ".join(reversed(ranges) if narrow_first else ranges) + " :a :seen 5 ; :small 5 .")
    assert o.reason().consistent
    for value, consistent in (("7", True), ("40000", False)):
        for p in ("seen", "small"):
            o.replace("a", p, Literal(value, datatype=NamedNode(XSD_("integer"))))
        report = o.reason(mode="incremental")
        assert report.stats.mode == "incremental" and report.consistent is consistent
    assert [v.rule for v in report.violations] == ["dt-range"]
