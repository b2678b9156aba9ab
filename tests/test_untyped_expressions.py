"""Blank-node class expressions and data ranges without their type triple (tests/untyped_cases.py): read where
the OWL API under Pellet reads them, else the axiom is left out and a notice names the missing triple.
tests/test_fidelity_pellet.py checks the same cases against Pellet."""

from __future__ import annotations

import warnings

import pytest
from pyoxigraph import NamedNode, Triple
from untyped_cases import CASES, document, namespace, read_here

from topostore import Ontology, OntologyWarning
from topostore.rdf.vocab import TYPE


def loaded(name: str) -> tuple[Ontology, list[str]]:
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", OntologyWarning)
        o = Ontology()
        o.load_data(document(name))
        o.reason()
    return o, [str(w.message) for w in caught]


@pytest.mark.parametrize("name", list(CASES))
def test_read_only_where_the_owl_api_reads_it(name: str) -> None:
    _, _, (individual, cls) = CASES[name]
    read = read_here(name)
    o, _ = loaded(name)
    ns = namespace(name)
    types = {t.value for t in o.types(NamedNode(ns + individual))}
    assert (ns + cls in types) is read


@pytest.mark.parametrize("name", [n for n in CASES if not read_here(n)])
def test_an_axiom_left_out_is_named(name: str) -> None:
    o, messages = loaded(name)
    text = " ".join(messages)
    assert "lacks its rdf:type" in text, messages
    expected = "rdfs:Datatype" if name.startswith("data_") else (
        "owl:Restriction" if "onProperty" in CASES[name][0].split("equivalentClass")[-1].split("]")[0] else "owl:Class")
    assert f"lacks its rdf:type {expected} triple" in text, messages


@pytest.mark.parametrize("name", [n for n in CASES if read_here(n)])
def test_an_axiom_read_gives_no_such_notice(name: str) -> None:
    _, messages = loaded(name)
    assert not any("lacks its rdf:type" in m for m in messages), messages


def test_typed_in_rdf_xml_as_in_turtle(tmp_path) -> None:
    """The same reading from RDF/XML: the type triple is what counts, not the syntax."""
    import pyoxigraph as ox

    for name in ("eq_restriction_undeclared", "eq_declared"):
        triples = list(ox.parse(document(name), format=ox.RdfFormat.TURTLE))
        path = tmp_path / f"{name}.owl"
        path.write_bytes(ox.serialize(triples, format=ox.RdfFormat.RDF_XML))
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", OntologyWarning)
            o = Ontology.from_file(path)
            o.reason()
        _, read, (individual, cls) = CASES[name]
        ns = namespace(name)
        assert (ns + cls in {t.value for t in o.types(NamedNode(ns + individual))}) is read


def test_an_individual_typed_later_reads_as_a_fresh_load_of_the_same_file() -> None:
    """Which axioms there are depends on schema triples only: the type that makes the OWL API's parser count a
    name as a class, added after the LOAD or removed from it, leaves the reading as a fresh LOAD of the
    result gives it (the axiom set aside, named, either way)."""
    name = "eq_used_as_type"
    ns = namespace(name)
    typed = (NamedNode(ns + "d"), TYPE, NamedNode(ns + "S"))
    fresh, _ = loaded(name)
    without = Ontology()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", OntologyWarning)
        without.load_data(document(name).replace(":d a :S .", ""))
        without.reason()
        without.add(Triple(*typed))
        without.reason()
        fresh.remove(Triple(*typed))
        fresh.reason()
        fresh.add(Triple(*typed))
        fresh.reason()
    for o in (fresh, without):
        assert ns + "S" not in {t.value for t in o.types(NamedNode(ns + "a"))}


def test_a_class_expression_where_a_data_range_is_wanted_is_named_so() -> None:
    """Set aside as before, with the reason that holds: the node is typed, as a class expression."""
    o = Ontology()
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", OntologyWarning)
        o.load_data(document("data_filler_typed")
                    + ":dp rdfs:range [ a owl:Class ; owl:unionOf ( :A :B ) ] .\n")
        o.reason()
    text = " ".join(str(w.message) for w in caught)
    assert "a class expression stands where a data range is wanted" in text and "lacks its rdf:type" not in text
