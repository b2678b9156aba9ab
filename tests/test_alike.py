"""Anonymous class expressions written alike are compiled once (topostore.compile.alike): the same
conclusions and notices, rules that grow with the distinct expressions, not with their copies."""

from __future__ import annotations

from collections import Counter

from support import reasoned_turtle

from topostore import Ontology

PREFIXES = """@prefix : <http://e.org/a#> . @prefix owl: <http://www.w3.org/2002/07/owl#> .
@prefix rdfs: <http://www.w3.org/2000/01/rdf-schema#> . @prefix xsd: <http://www.w3.org/2001/XMLSchema#> .
<http://e.org/a> a owl:Ontology .
:p a owl:ObjectProperty . :q a owl:ObjectProperty . :A a owl:Class . :B a owl:Class .
"""

SOME_A = "[ a owl:Restriction ; owl:onProperty :p ; owl:someValuesFrom :A ]"


def types(o: Ontology, name: str) -> set[str]:
    return {o.short(t) for t in o.types(name)}


def copies(n: int) -> str:
    """``n`` classes, each a subclass of its own copy of ``p some A``, and a class defined by another."""
    lines = [f":K{i} rdfs:subClassOf {SOME_A} ." for i in range(n)]
    return "\n".join(lines) + f"\n:D owl:equivalentClass {SOME_A} .\n"


def rule_names(o: Ontology) -> Counter:
    return Counter(r.name for r in o.rules.all_rules)


def test_copies_of_a_restriction_conclude_what_each_did() -> None:
    o = reasoned_turtle(PREFIXES + copies(3) + ":k a :K1 . :y :p :a . :a a :A .")
    assert types(o, "k") == {"K1", "D"}  # K1 ⊑ (p some A) ≡ D
    assert types(o, "y") == {"D"}


def test_rules_grow_with_the_copies_linearly() -> None:
    """Each copy adds its subclass row, never a rule per pair of copies (ext-card-sub)."""
    few, many = (rule_names(reasoned_turtle(PREFIXES + copies(n))) for n in (2, 30))
    assert many["ext-card-sub"] == few["ext-card-sub"] == 0
    assert many["cls-svf1"] == few["cls-svf1"] == 1
    assert many["cax-sco"] - few["cax-sco"] == 28


def test_an_expression_an_individual_is_typed_with_is_kept() -> None:
    """A node named outside the axioms keeps its rules: its told members reach the copies' classes."""
    o = reasoned_turtle(PREFIXES + copies(2) + f":x a {SOME_A} . :k a :K0 .")
    assert types(o, "x") == {"D"}
    assert types(o, "k") == {"K0", "D"}


def test_nested_copies_are_one_and_keep_their_notices() -> None:
    """Unions inside universal restrictions, written twice: one expression, and each axiom still named
    by the notice that it is not reasoned completely."""
    only = "[ a owl:Restriction ; owl:onProperty :q ; owl:allValuesFrom [ owl:unionOf ( :A :B ) ] ]"
    o = reasoned_turtle(PREFIXES + f":K0 rdfs:subClassOf {only} . :K1 rdfs:subClassOf {only} . "
                        ":k a :K0 ; :q :v . :m a :K1 ; :q :w .")
    names = rule_names(o)
    assert names["cls-avf"] == 1 and names["cls-uni"] == 2
    said = " ".join(str(n) for n in o.notices)
    assert "K0 SubClassOf (q only (A or B))" in said and "K1 SubClassOf (q only (A or B))" in said


def test_restrictions_that_differ_stay_apart() -> None:
    """Another filler, property or number is another class."""
    o = reasoned_turtle(PREFIXES + f":K0 rdfs:subClassOf {SOME_A} . "
                        ":K1 rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :p ; owl:someValuesFrom :B ] . "
                        ":K2 rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :q ; owl:someValuesFrom :A ] . "
                        ":K3 rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :p ; owl:onClass :A ; "
                        "owl:minQualifiedCardinality 2 ] .")
    assert rule_names(o)["cls-svf1"] == 3


def test_a_type_added_later_to_a_merged_copy_is_read() -> None:
    """Which copies are kept is decided when the rules are compiled: typing an individual with a copy
    later is a schema change, so the rules are compiled again and the copy is kept."""
    from pyoxigraph import NamedNode

    from topostore.rdf.vocab import ASSERTED

    o = Ontology()
    o.load_data(PREFIXES + f""":K rdfs:subClassOf {SOME_A} .
        {SOME_A[:-1]} ; rdfs:subClassOf :S ] . :S a owl:Class .""")
    o.reason()
    nodes = [t.subject for t in o.store.triples(None, NamedNode("http://www.w3.org/2002/07/owl#onProperty"),
                                                 NamedNode("http://e.org/a#p"), ASSERTED)]
    assert len(nodes) == 2
    for n, node in enumerate(nodes):
        o.add_type(NamedNode(f"http://e.org/a#i{n}"), node)
    o.reason()
    assert {o.short(i) for i in o.instances("S")} == {"i0", "i1"}
    fresh = Ontology()
    fresh.load_data(o.serialize("turtle"))
    fresh.reason()
    assert {fresh.short(i) for i in fresh.instances("S")} == {"i0", "i1"}
