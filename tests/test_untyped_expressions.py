"""Blank-node class expressions and data ranges without their type triple (tests/untyped_cases.py): read where
the OWL API under Pellet reads them, else the axiom is left out and a notice names the missing triple.
tests/test_fidelity_pellet.py checks the same cases against Pellet."""

from __future__ import annotations

import warnings

import pytest
from pyoxigraph import NamedNode
from untyped_cases import CASES, document, namespace

from topostore import Ontology, OntologyWarning


def loaded(name: str) -> tuple[Ontology, list[str]]:
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", OntologyWarning)
        o = Ontology()
        o.load_data(document(name))
        o.reason()
    return o, [str(w.message) for w in caught]


@pytest.mark.parametrize("name", list(CASES))
def test_read_only_where_the_owl_api_reads_it(name: str) -> None:
    _, read, (individual, cls) = CASES[name]
    o, _ = loaded(name)
    ns = namespace(name)
    types = {t.value for t in o.types(NamedNode(ns + individual))}
    assert (ns + cls in types) is read


@pytest.mark.parametrize("name", [n for n, (_, read, _) in CASES.items() if not read])
def test_an_axiom_left_out_is_named(name: str) -> None:
    o, messages = loaded(name)
    text = " ".join(messages)
    assert "lacks its rdf:type" in text, messages
    expected = "rdfs:Datatype" if name.startswith("data_") else (
        "owl:Restriction" if "onProperty" in CASES[name][0].split("equivalentClass")[-1].split("]")[0] else "owl:Class")
    assert f"lacks its rdf:type {expected} triple" in text, messages


@pytest.mark.parametrize("name", [n for n, (_, read, _) in CASES.items() if read])
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
