"""N-ary axioms as RDF lists (topostore.ontology.nary): the one builder and remover used by Ontology and the aRMOR commands."""

from __future__ import annotations

import pytest
from pyoxigraph import NamedNode, Triple
from support import quiet_turtle
from test_fidelity import canonical

from topostore import Ontology
from topostore.ontology.nary import (
    all_different,
    all_disjoint_classes,
    axiom_of_list_node,
    individual_triples,
    is_structure,
    rdf_list,
)
from topostore.rdf.vocab import ASSERTED, FIRST, NIL, REST, TYPE, is_skolem, owl

NS = "http://example.org/m#"
A, B, C = (NamedNode(NS + n) for n in "ABC")


def list_items(triples: list[Triple], head) -> list:
    """Walk an RDF list written as triples."""
    first = {t.subject: t.object for t in triples if t.predicate == FIRST}
    rest = {t.subject: t.object for t in triples if t.predicate == REST}
    items = []
    while head != NIL:
        items.append(first[head])
        head = rest[head]
    return items


def test_rdf_list_shape() -> None:
    assert rdf_list([]) == (NIL, [])
    head, triples = rdf_list([A, B, C])
    assert len(triples) == 6 and list_items(triples, head) == [A, B, C]


def test_group_axioms_are_linear_and_typed() -> None:
    for build, kind, link in ((all_different, "AllDifferent", "distinctMembers"),
                              (all_disjoint_classes, "AllDisjointClasses", "members")):
        triples = build([A, B, C])
        group = triples[0].subject
        assert triples[0] == Triple(group, TYPE, owl(kind))
        assert triples[1].subject == group and triples[1].predicate == owl(link)
        assert len(triples) == 2 + 2 * 3 and list_items(triples, triples[1].object) == [A, B, C]


def test_removing_a_member_takes_the_whole_axiom_and_nothing_else() -> None:
    onto = Ontology(prefix=NS)
    onto.add_all_different([A, B])
    onto.add_all_different([B, C])
    fact = Triple(A, NamedNode(NS + "p"), C)
    onto.add(fact, Triple(A, TYPE, NamedNode(NS + "Room")))
    list_of_first = next(t.subject for t in onto.store.triples(None, FIRST, A, ASSERTED))
    assert len(axiom_of_list_node(onto.store, list_of_first)) == 2 + 4  # group, its link, two cells
    doomed = individual_triples(onto.store, A)
    assert len(doomed) == 2 + 6  # A's own two facts and the whole first AllDifferent
    assert onto.remove_individual(A) == 8
    remaining = set(onto.store.triples(None, None, None, ASSERTED))
    assert fact not in remaining and len(remaining) == 6  # C stays in the AllDifferent over B, C, untouched
    assert {t.object for t in remaining if t.predicate == FIRST} == {B, C}


def test_a_list_outside_an_axiom_is_not_removed() -> None:
    onto = Ontology(prefix=NS)
    head, triples = rdf_list([A, B])  # e.g. a SWRL argument list: no AllDifferent owns it
    onto.add(*triples)
    assert axiom_of_list_node(onto.store, head) == []
    assert len(individual_triples(onto.store, A)) == 1  # only the cell's rdf:first naming A


RI = "http://example.org/ri#"
RI_HEAD = f"""@prefix : <{RI}> . @prefix owl: <http://www.w3.org/2002/07/owl#> .
@prefix rdfs: <http://www.w3.org/2000/01/rdf-schema#> .
:C a owl:Class . :D a owl:Class . :E a owl:Class . :p a owl:ObjectProperty . :q a owl:ObjectProperty .
:r a owl:ObjectProperty . :a a owl:NamedIndividual . :c a owl:NamedIndividual . :d a owl:NamedIndividual .
"""


def remaining_after_removing_a(text: str):
    """The asserted graph of ``text`` after REMOVE IND :a, canonically (blank nodes by structure)."""
    onto = quiet_turtle(RI_HEAD + text)
    onto.remove_individual(NamedNode(RI + "a"))
    return canonical(onto, ASSERTED)


def graph_of(text: str):
    return canonical(quiet_turtle(RI_HEAD + text), ASSERTED)


def test_an_anonymous_individual_naming_the_removed_one_keeps_its_other_facts() -> None:
    """``_:b :p :a`` is one property assertion: removing :a removes it, never ``_:b``'s type, its other
    values or the assertions naming ``_:b`` (OWL API's entity remover keeps every axiom not mentioning :a)."""
    kept = "_:b a :C ; :q :c . :d :r _:b ."
    expected = {t for t in graph_of(kept) if t.subject != NamedNode(RI + "a")}
    assert remaining_after_removing_a("_:b a :C ; :p :a ; :q :c . :d :r _:b .") == expected


def test_a_negative_assertion_goes_whole_but_its_anonymous_target_stays() -> None:
    doc = """_:b a :C ; :q :c .
[ a owl:NegativePropertyAssertion ; owl:sourceIndividual :a ; owl:assertionProperty :p ; owl:targetIndividual _:b ] ."""
    expected = {t for t in graph_of("_:b a :C ; :q :c .") if t.subject != NamedNode(RI + "a")}
    assert remaining_after_removing_a(doc) == expected


def test_a_class_assertion_of_an_anonymous_individual_goes_without_the_individual() -> None:
    """``_:b a [ owl:hasValue :a ]`` is one class assertion: it goes whole (with its restriction); ``_:b``
    keeps its other facts."""
    doc = "_:b a :C , [ a owl:Restriction ; owl:onProperty :p ; owl:hasValue :a ] ; :q :c ."
    expected = {t for t in graph_of("_:b a :C ; :q :c .") if t.subject != NamedNode(RI + "a")}
    assert remaining_after_removing_a(doc) == expected


def test_a_class_expression_shared_by_two_axioms_goes_from_both() -> None:
    """Both axioms naming the shared expression mention :a, so both go whole; neither is left pointing at
    an expression cut out of the graph."""
    doc = """_:x a owl:Restriction ; owl:onProperty :p ; owl:hasValue :a .
:C owl:equivalentClass [ a owl:Class ; owl:intersectionOf ( :D _:x ) ] .
:E rdfs:subClassOf _:x ."""
    assert remaining_after_removing_a(doc) == {t for t in graph_of("") if t.subject != NamedNode(RI + "a")}


def test_a_shared_sub_expression_not_naming_the_individual_stays_for_the_other_axiom() -> None:
    """An axiom that does not mention :a keeps every part, even one the removed axiom shared."""
    doc = """_:s a owl:Restriction ; owl:onProperty :q ; owl:someValuesFrom :D .
:C owl:equivalentClass [ a owl:Class ; owl:intersectionOf ( _:s [ a owl:Restriction ; owl:onProperty :p ; owl:hasValue :a ] ) ] .
:E rdfs:subClassOf _:s ."""
    kept = ":E rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :q ; owl:someValuesFrom :D ] ."
    assert remaining_after_removing_a(doc) == {t for t in graph_of(kept) if t.subject != NamedNode(RI + "a")}


def test_an_anonymous_individual_is_not_structure() -> None:
    onto = quiet_turtle(RI_HEAD + "_:b a :C ; :p :a . :E owl:equivalentClass [ a owl:Class ; owl:oneOf ( :a ) ] .")
    anonymous = {t.subject for t in onto.store.triples(None, None, None, ASSERTED) if is_skolem(t.subject)}
    kinds = {is_structure(onto.store, node): node for node in anonymous}
    assert set(kinds) == {True, False}
    assert onto.store.contains(Triple(kinds[False], TYPE, NamedNode(RI + "C")), ASSERTED)


def test_a_class_assertion_of_the_removed_individual_takes_its_class_expression() -> None:
    """``:a a [ owl:Restriction ... ]`` is one axiom: its restriction goes with it, never left without an
    axiom holding it; a restriction another axiom shares stays for it."""
    restriction = "[ a owl:Restriction ; owl:onProperty :p ; owl:someValuesFrom :C ]"
    assert remaining_after_removing_a(f":a a {restriction} .") == {
        t for t in graph_of("") if t.subject != NamedNode(RI + "a")}
    shared = "_:x a owl:Restriction ; owl:onProperty :p ; owl:someValuesFrom :C . :a a _:x . :E rdfs:subClassOf _:x ."
    assert remaining_after_removing_a(shared) == {
        t for t in graph_of(f":E rdfs:subClassOf {restriction} .") if t.subject != NamedNode(RI + "a")}


OTHERS = ":c a :C ; :q :d . :d :r :c ."


UNTYPED_AXIOMS_NAMING_A = (
    "[ owl:onProperty :p ; owl:hasValue :a ] rdfs:subClassOf :C .",
    "[ owl:intersectionOf ( :D [ owl:onProperty :p ; owl:hasValue :a ] ) ] rdfs:subClassOf :E .",
    ":a :p :c . [ owl:annotatedSource :a ; owl:annotatedProperty :p ; owl:annotatedTarget :c ;"
    ' rdfs:comment "seen twice" ] .',
    ":d :p :a . [ owl:annotatedSource :d ; owl:annotatedProperty :p ; owl:annotatedTarget :a ;"
    ' rdfs:label "from the map" ] .',
    "[ owl:sourceIndividual :a ; owl:assertionProperty :p ; owl:targetIndividual :c ] .",
    "[ owl:sourceIndividual :d ; owl:assertionProperty :q ; owl:targetIndividual :a ] .",
)


@pytest.mark.parametrize("axiom", UNTYPED_AXIOMS_NAMING_A)
def test_an_untyped_anonymous_axiom_naming_the_removed_individual_goes_whole(axiom: str) -> None:
    """A topmost anonymous structure without ``rdf:type`` is still an axiom when its structural predicates say
    so (a general class axiom's restriction, an owl:Axiom, an owl:NegativePropertyAssertion): removing :a takes
    every triple of it, and every other individual's facts stay."""
    expected = {t for t in graph_of(OTHERS) if t.subject != NamedNode(RI + "a")}
    assert remaining_after_removing_a(f"{OTHERS}\n{axiom}") == expected


def test_an_untyped_axiom_not_naming_the_individual_stays() -> None:
    """Only the untyped axioms mentioning :a go: one naming :c alone is kept, every triple of it."""
    kept = f"""{OTHERS}
[ owl:onProperty :p ; owl:hasValue :c ] rdfs:subClassOf :C .
[ owl:sourceIndividual :c ; owl:assertionProperty :p ; owl:targetIndividual :d ] ."""
    doc = kept + "\n[ owl:onProperty :q ; owl:hasValue :a ] rdfs:subClassOf :D ."
    assert remaining_after_removing_a(doc) == {t for t in graph_of(kept) if t.subject != NamedNode(RI + "a")}
