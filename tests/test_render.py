"""armor/render.py: how answers are written in ``queried_objects``, in aRMOR's full form and in short-name mode."""

from __future__ import annotations

import pytest
from pyoxigraph import BlankNode, Literal, NamedNode
from support import NS

from topostore.armor.render import (
    Renderer,
    abbreviate,
    escape_lexical,
    full_entity,
    full_literal,
    local_name,
    short_name,
)

XSD = "http://www.w3.org/2001/XMLSchema#"


@pytest.mark.parametrize("iri,expected", [
    ("http://www.w3.org/2002/07/owl#Thing", "owl:Thing"),
    ("http://www.w3.org/1999/02/22-rdf-syntax-ns#type", "rdf:type"),
    ("http://www.w3.org/2000/01/rdf-schema#Literal", "rdfs:Literal"),
    (XSD + "long", "xsd:long"),
    ("http://www.w3.org/XML/1998/namespacelang", "xml:lang"),
    ("http://www.w3.org/2002/07/owl#", None),  # the namespace alone is not abbreviated
    (NS + "R1", None),
])
def test_abbreviate(iri: str, expected: str | None) -> None:
    assert abbreviate(iri) == expected


@pytest.mark.parametrize("iri,expected", [
    (NS + "R1", "R1"), ("http://example.org/a/b", "b"), ("http://example.org/a/b/", "b"),
    ("http://example.org/a#b/c", "b/c"), ("urn:x", "urn:x"),
])
def test_local_name(iri: str, expected: str) -> None:
    assert local_name(iri) == expected


def test_full_forms() -> None:
    assert escape_lexical('say "hi"\\') == 'say \\"hi\\"\\\\'
    assert full_entity(NS + "R1") == f"<{NS}R1>"
    assert full_entity("http://www.w3.org/2002/07/owl#Nothing") == "owl:Nothing"
    assert full_literal(Literal("1665579740", datatype=NamedNode(XSD + "long"))) == '"1665579740"^^xsd:long'
    assert full_literal(Literal('a"b')) == '"a\\"b"^^xsd:string'
    assert full_literal(Literal("chat", language="fr")) == '"chat"@fr'
    assert full_literal(Literal("1", datatype=NamedNode("http://example.org/dt"))) == '"1"^^<http://example.org/dt>'


def test_renderer_full_and_short_modes() -> None:
    terms = [NamedNode(NS + "R1"), Literal("5", datatype=NamedNode(XSD + "long")), NamedNode(NS + "R1"),
             BlankNode("b7"), NamedNode("http://www.w3.org/2002/07/owl#Thing")]
    assert Renderer().terms(terms) == [f"<{NS}R1>", '"5"^^xsd:long', "_:b7", "owl:Thing"]  # duplicates dropped
    assert Renderer(short_names=True).terms(terms) == ["R1", "5", "_:b7", "Thing"]


def test_short_name_keeps_the_xsd_prefix_of_datatypes() -> None:
    assert short_name(NamedNode(XSD + "long")) == "xsd:long"
    assert short_name(NamedNode(NS + "hasDoor")) == "hasDoor"
    assert short_name(Literal("2", datatype=NamedNode(XSD + "nonNegativeInteger"))) == "2"
    assert short_name(BlankNode("b1")) == "_:b1"
