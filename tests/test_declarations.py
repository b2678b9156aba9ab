"""The declarations a written ontology file gets for what its facts use (rdf/declarations.py)."""

from __future__ import annotations

from pathlib import Path

from pyoxigraph import NamedNode, Triple

from topostore import Ontology
from topostore.rdf.declarations import missing_declarations
from topostore.rdf.vocab import TYPE, owl

NS = "http://example.org/d#"
PREFIXES = f"@prefix : <{NS}> . @prefix owl: <http://www.w3.org/2002/07/owl#> . " \
           "@prefix rdfs: <http://www.w3.org/2000/01/rdf-schema#> . "


def n(name: str) -> NamedNode:
    return NamedNode(NS + name)


def declarations(text: str) -> set[tuple[str, str]]:
    o = Ontology()
    o.load_data(PREFIXES + text)
    return {(t.subject.value.removeprefix(NS), t.object.value.rsplit("#", 1)[1])
            for t in missing_declarations(o.triples())}


def test_facts_declare_individuals_properties_and_classes() -> None:
    assert declarations(':a :p :b . :a :d "1" . :c a :K .') == {
        ("a", "NamedIndividual"), ("b", "NamedIndividual"), ("c", "NamedIndividual"),
        ("p", "ObjectProperty"), ("d", "DatatypeProperty"), ("K", "Class")}


def test_declared_entities_are_not_declared_again() -> None:
    assert declarations(":a a owl:NamedIndividual ; :p :b . :b a owl:NamedIndividual . :p a owl:ObjectProperty .") == set()


def test_an_iri_used_both_ways_is_declared_both_ways() -> None:
    """Punning, as the OWL API writes it: a class with an object property's value is an individual too."""
    assert declarations(":C a owl:Class . :p a owl:ObjectProperty . :C :p :x . :C rdfs:subClassOf :D .") == {
        ("C", "NamedIndividual"), ("x", "NamedIndividual")}
    assert ("p", "DatatypeProperty") in declarations(':a :p :b . :a :p "v" .')


def test_annotations_declare_nothing() -> None:
    """An annotation property's value, or an undeclared predicate on the ontology or a class, is no fact."""
    assert declarations(':note a owl:AnnotationProperty . :a a owl:NamedIndividual ; :note "x" . '
                        '<http://example.org/d> a owl:Ontology ; :version "1" . :C a owl:Class ; :seeAlso :D .') == set()


def test_built_in_and_blank_terms_are_not_declared() -> None:
    assert declarations('[] :p :b . :a rdfs:label "x" .') == {("p", "ObjectProperty"), ("b", "NamedIndividual")}


def test_saved_file_declares_while_the_graph_does_not(tmp_path: Path) -> None:
    o = Ontology()
    o.load_data(PREFIXES + ":a :p :b .")
    before = o.triples()
    saved = Ontology.from_file(o.save(tmp_path / "x.ttl"))
    assert o.triples() == before
    assert Triple(n("a"), TYPE, owl("NamedIndividual")) in saved.triples()
    assert Triple(n("p"), TYPE, owl("ObjectProperty")) in saved.triples()
    assert Triple(n("a"), n("p"), n("b")) in saved.triples()
    assert missing_declarations(saved.triples()) == []
