"""Data ranges built of others: a data one-of of literals, ``owl:datatypeComplementOf``, a data ``owl:unionOf`` and
``owl:intersectionOf`` (compile/data_ranges.py, the value tests of compile/snippets.py).

Pellet's answers for them are checked in tests/test_fidelity_pellet.py (the ``data_ranges`` case of
tests/fidelity_cases.py, three inconsistent ones); here the names such a range gets, an incremental REASON
against one from scratch as values come and go, a definition naming another, and what is still said.
"""

from __future__ import annotations

import warnings

import pytest
from fidelity_cases import document, namespace
from pyoxigraph import Literal, NamedNode, Triple

from topostore import Ontology, OntologyWarning
from topostore.compile import data_ranges
from topostore.compile.notices import UNCHECKED_DATATYPE
from topostore.rdf.vocab import ENTAILED, INFERRED, XSD

NS = namespace("data_ranges")
D = NamedNode(NS + "d")


def xsd(local: str) -> NamedNode:
    return NamedNode(XSD + local)


def test_a_composed_range_is_named_by_its_members_as_a_set() -> None:
    """Equal ranges get one name (members in any order, a value written twice); the name reads back."""
    one = data_ranges.composed("oneOf", [Literal("2", datatype=xsd("integer")), Literal("1", datatype=xsd("int")),
                                         Literal("1", datatype=xsd("integer"))])
    other = data_ranges.composed("oneOf", [Literal("1", datatype=xsd("integer")), Literal("2", datatype=xsd("integer"))])
    assert one == other and data_ranges.readable(one) == "{1, 2}"
    kind, members = data_ranges.composition(one)
    assert kind == "oneOf" and {m.value for m in members} == {"1", "2"}
    union = data_ranges.composed("unionOf", [xsd("boolean"), data_ranges.composed("complementOf", [one])])
    assert data_ranges.readable(union) == "(boolean or not {1, 2})"
    assert data_ranges.parts(union) is None and data_ranges.composition(xsd("integer")) is None


def reasoned(text: str) -> Ontology:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", OntologyWarning)
        o = Ontology()
        o.load_data(text)
    assert o.reason().consistent
    return o


def closure(o: Ontology) -> tuple[set[Triple], set[Triple]]:
    return set(o.store.triples(None, None, None, INFERRED)), set(o.store.triples(None, None, None, ENTAILED))


def test_values_coming_and_going_are_reasoned_incrementally_as_from_scratch() -> None:
    o = reasoned(document("data_ranges"))
    assert not o.notices
    g, k = NamedNode(NS + "g"), NamedNode(NS + "k")
    o.remove(Triple(g, D, Literal("3", datatype=xsd("integer"))))  # g keeps 2 alone of {1, 2, 3}
    o.add(Triple(k, D, Literal("b")), Triple(k, D, Literal("2.0", datatype=xsd("decimal"))),
          Triple(k, D, Literal("3", datatype=xsd("byte"))))  # two values of {1, 2, 3}, one of {"a", "b"}
    report = o.reason()
    assert report.consistent and report.stats.mode == "incremental", report.stats.reason
    assert {t.value[len(NS):] for t in o.types(g) if t.value.startswith(NS)} == {
        "BigSmall", "IntOrBool", "NotInt", "NotSmall", "Pick", "Ranged", "SmallOne"}
    assert {t.value[len(NS):] for t in o.types(k) if t.value.startswith(NS)} == {
        "BigSmall", "IntOrBool", "NotInt", "NotSmall", "Pick", "SmallOne", "TwoSmall"}
    scratch = reasoned(o.serialize("nt").decode())
    assert closure(o) == closure(scratch)
    o.add(Triple(NamedNode(NS + "b"), D, Literal("7", datatype=xsd("integer"))))  # b is in :Only: 7 is outside
    assert not o.reason().consistent


def test_a_definition_may_name_another_definition() -> None:
    """``:NotSmall`` the complement of ``:Small``, read before it: the name stands for ``{1, 2, 3}`` (OWL 2 Direct
    Semantics; Pellet 2.3.1 takes ``:Small`` inside another definition as a datatype of its own, and puts 1 in
    ``:NotSmall``)."""
    o = reasoned(document("defined", """:d a owl:DatatypeProperty .
:NotSmall a rdfs:Datatype ; owl:equivalentClass [ a rdfs:Datatype ; owl:datatypeComplementOf :Small ] .
:Small a rdfs:Datatype ; owl:equivalentClass [ a rdfs:Datatype ; owl:oneOf ( 1 2 3 ) ] .
:Big owl:equivalentClass [ a owl:Restriction ; owl:onProperty :d ; owl:someValuesFrom :NotSmall ] .
:a :d 1 . :b :d 7 ."""))
    assert not o.notices
    big = NamedNode(namespace("defined") + "Big")
    assert big not in o.types(NamedNode(namespace("defined") + "a"))
    assert big in o.types(NamedNode(namespace("defined") + "b"))


@pytest.mark.parametrize("member", [":Mine", "[ a rdfs:Datatype ; owl:datatypeComplementOf :Mine ]"])
def test_a_range_built_of_an_own_datatype_is_said_unchecked(member: str) -> None:
    """A union with a datatype topostore does not test: a value surely in another member counts, none is known
    outside it, and the notice says so."""
    ns = namespace("mine")
    o = reasoned(document("mine", f""":Mine a rdfs:Datatype . :d a owl:DatatypeProperty ; rdfs:range
  [ a rdfs:Datatype ; owl:unionOf ( xsd:boolean {member} ) ] .
:C owl:equivalentClass [ a owl:Restriction ; owl:onProperty :d ; owl:someValuesFrom
  [ a rdfs:Datatype ; owl:unionOf ( xsd:boolean {member} ) ] ] .
:x :d true . :y :d 5 ."""))
    assert {n.axiom_kind for n in o.notices} == {UNCHECKED_DATATYPE}
    assert NamedNode(ns + "C") in o.types(NamedNode(ns + "x"))
    assert NamedNode(ns + "C") not in o.types(NamedNode(ns + "y"))


def _loaded(name: str, body: str) -> Ontology:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", OntologyWarning)
        o = Ontology()
        o.load_data(document(name, body))
    return o


def test_nested_unions_are_one_union_and_definitions_stay_small() -> None:
    """``A_i`` the union of ``A_{i+1}`` and ``A_{i+2}``: flattened, every name is ``(integer or string)``, not a
    range twice the size of the next one's."""
    n = 30
    defs = "".join(f":A{i} a rdfs:Datatype ; owl:equivalentClass [ a rdfs:Datatype ; owl:unionOf ( :A{i + 1} :A{i + 2} ) ] .\n"
                   for i in range(n - 2))
    o = _loaded("dag", f""":d a owl:DatatypeProperty ; rdfs:range :A0 . :x :d 1 .
{defs}:A{n - 2} a rdfs:Datatype ; owl:equivalentClass xsd:integer . :A{n - 1} a rdfs:Datatype ; owl:equivalentClass xsd:string .""")
    assert o.reason().consistent and not o.notices
    assert data_ranges.composed("unionOf", [xsd("integer"), data_ranges.composed("unionOf", [xsd("string"), xsd("integer")])]) \
        == data_ranges.composed("unionOf", [xsd("string"), xsd("integer")])


def test_cyclic_definitions_are_set_aside_by_name() -> None:
    defs = "".join(f":A{i} a rdfs:Datatype ; owl:equivalentClass [ a rdfs:Datatype ; owl:unionOf ( :A{(i + 1) % 12} "
                   f"xsd:boolean ) ] .\n" for i in range(12))
    o = _loaded("cyc", f":d a owl:DatatypeProperty ; rdfs:range :A0 . :x :d 1 .\n{defs}")
    assert o.reason().consistent
    said = " ".join(str(n) for n in o.notices)
    assert "cyclic datatype definitions" in said and "A11 DatatypeDefinition" in said


def test_a_range_too_large_is_set_aside_not_the_document() -> None:
    values = " ".join(str(i) for i in range(700))
    o = _loaded("large", f""":d a owl:DatatypeProperty .
:Many a rdfs:Datatype ; owl:equivalentClass [ a rdfs:Datatype ; owl:oneOf ( {values} ) ] .
:C owl:equivalentClass [ a owl:Restriction ; owl:onProperty :d ; owl:someValuesFrom :Many ] . :x :d 1 .""")
    assert o.reason().consistent
    assert "too large" in " ".join(str(n) for n in o.notices)


@pytest.mark.parametrize("range_", ["[ a rdfs:Datatype ; owl:datatypeComplementOf :Mine ]",
                                    "[ a rdfs:Datatype ; owl:unionOf ( xsd:boolean :Mine ) ]"])
def test_a_swrl_data_range_atom_on_a_range_built_of_an_own_datatype_sets_the_rule_aside(range_: str) -> None:
    o = _loaded("swrl_own", f"""@prefix swrl: <http://www.w3.org/2003/11/swrl#> . @prefix var: <urn:fidelity:var#> .
:d a owl:DatatypeProperty . :Mine a rdfs:Datatype . :R a owl:Class . var:x a swrl:Variable . var:v a swrl:Variable .
[ a swrl:Imp ; swrl:body ( [ a swrl:DatavaluedPropertyAtom ; swrl:propertyPredicate :d ; swrl:argument1 var:x ;
  swrl:argument2 var:v ] [ a swrl:DataRangeAtom ; swrl:argument1 var:v ; swrl:dataRange {range_} ] ) ;
  swrl:head ( [ a swrl:ClassAtom ; swrl:classPredicate :R ; swrl:argument1 var:x ] ) ] .
:x a owl:NamedIndividual ; :d 5 .""")
    assert o.reason().consistent
    assert "values topostore does not test" in " ".join(str(n) for n in o.notices)


def _some(range_: str) -> str:
    return (":d a owl:DatatypeProperty . :C a owl:Class ; rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :d ; "
            f"owl:someValuesFrom {range_} ] . :x a owl:NamedIndividual, :C .")


def _dr(body: str) -> str:
    return f"[ a rdfs:Datatype ; {body} ]"


@pytest.mark.parametrize("body", [
    _some(_dr(f"owl:intersectionOf ( xsd:integer {_dr('owl:datatypeComplementOf xsd:integer')} )")),
    _some(_dr("owl:intersectionOf ( " + _dr('owl:oneOf ( "a" )') + " xsd:integer )")),
    _some(_dr(f"owl:intersectionOf ( {_dr('owl:onDatatype xsd:integer ; owl:withRestrictions ( [ xsd:minInclusive 5 ] )')}"
              f" {_dr('owl:oneOf ( 1 2 )')} )")),
    _some(_dr("owl:datatypeComplementOf " + _dr(f"owl:unionOf ( xsd:integer {_dr('owl:datatypeComplementOf xsd:integer')} )"))),
    ":d a owl:DatatypeProperty . :C a owl:Class ; rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :d ; "
    f"owl:minQualifiedCardinality \"2\"^^xsd:nonNegativeInteger ; owl:onDataRange {_dr('owl:oneOf ( 1 )')} ] . "
    ":x a owl:NamedIndividual, :C ."])
def test_a_value_required_in_an_empty_range_is_inconsistent(body: str) -> None:
    assert not _loaded("empty", body).reason().consistent


def test_a_range_whose_emptiness_is_not_decided_is_said() -> None:
    o = _loaded("undecided", _some(_dr(f"owl:intersectionOf ( {_dr('owl:datatypeComplementOf xsd:integer')} "
                                        f"{_dr('owl:datatypeComplementOf xsd:string')} )")))
    assert o.reason().consistent
    assert "has any value is not decided" in " ".join(str(n) for n in o.notices)
    kept = _loaded("decided", _some(_dr("owl:intersectionOf ( " + _dr('owl:oneOf ( 1 "a" )') + " xsd:integer )")))
    assert kept.reason().consistent and not kept.notices


@pytest.mark.parametrize(("left", "right"), [
    ("xsd:byte", _dr("owl:datatypeComplementOf xsd:boolean")),
    (_dr("owl:oneOf ( 1 2 )"), "xsd:integer"),
    (_dr("owl:unionOf ( xsd:byte xsd:short )"), _dr("owl:unionOf ( xsd:integer xsd:string )")),
    (_dr("owl:intersectionOf ( xsd:byte xsd:integer )"), "xsd:short"),
    (_dr("owl:datatypeComplementOf xsd:integer"), _dr("owl:datatypeComplementOf xsd:byte")),
])
def test_an_existential_into_a_range_implies_one_into_a_wider_range(left: str, right: str) -> None:
    ns = namespace("wider")
    o = _loaded("wider", f""":d a owl:DatatypeProperty .
:N a owl:Class ; owl:equivalentClass [ a owl:Restriction ; owl:onProperty :d ; owl:someValuesFrom {right} ] .
:S a owl:Class ; rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :d ; owl:someValuesFrom {left} ] .
:x a owl:NamedIndividual, :S .""")
    assert o.reason().consistent
    assert NamedNode(ns + "N") in o.types(NamedNode(ns + "x"))
    assert not [n for n in o.notices if "is not decided" in str(n)]


def test_an_inclusion_not_decided_is_said() -> None:
    o = _loaded("undecided_inclusion", """:d a owl:DatatypeProperty .
:Mine a rdfs:Datatype .
:N a owl:Class ; owl:equivalentClass [ a owl:Restriction ; owl:onProperty :d ; owl:someValuesFrom
  [ a rdfs:Datatype ; owl:unionOf ( xsd:boolean :Mine ) ] ] .
:S a owl:Class ; rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :d ; owl:someValuesFrom :Other ] .
:Other a rdfs:Datatype . :x a owl:NamedIndividual, :S .""")
    o.reason()
    assert "is not decided" in " ".join(str(n) for n in o.notices)
