"""rdf:XMLLiteral values compared canonically: loading rewrites them to Canonical XML, so equal XML
written differently is one value; what is not well-formed stays as written and is named."""

from __future__ import annotations

import pytest
from pyoxigraph import Literal, NamedNode
from support import quiet_turtle

from topostore import Ontology, OntologyWarning
from topostore.ontology.xml_literals import canonical

PREFIXES = """@prefix : <http://e.org/x#> . @prefix owl: <http://www.w3.org/2002/07/owl#> .
@prefix rdf: <http://www.w3.org/1999/02/22-rdf-syntax-ns#> .
<http://e.org/x> a owl:Ontology . :f a owl:DatatypeProperty , owl:FunctionalProperty .
"""


def load(text: str) -> Ontology:
    return quiet_turtle(PREFIXES + text)


@pytest.mark.parametrize("a,b", [
    ('<b x="1" y="2"/>', "<b y='2'  x='1'></b>"),
    ('<e:b xmlns:e="http://e.org/" xmlns:u="http://u.org/"/>', '<e:b xmlns:e="http://e.org/"></e:b>'),
    ("text &amp; <i>more</i>", "text &#38; <i >more</i>"),
])
def test_equal_xml_written_differently_has_one_canonical_form(a: str, b: str) -> None:
    assert canonical(a) == canonical(b) is not None


def test_different_xml_stays_different() -> None:
    assert canonical('<b x="1"/>') != canonical('<b x="2"/>')
    assert canonical("<b> a</b>") != canonical("<b>a</b>")  # text is kept as written
    assert canonical("<b/><!-- c -->") != canonical("<b/>")  # comments are content


@pytest.mark.parametrize("text", ["<b>", "</w><w>", '<!DOCTYPE d [<!ENTITY e "boom">]><d>&e;</d>', "&e;",
                                  '<!DOCTYPE d SYSTEM "file:///etc/passwd"><d/>'])
def test_not_well_formed_content_and_declarations_are_refused(text: str) -> None:
    assert canonical(text) is None


def test_a_functional_property_with_equal_xml_values_is_consistent() -> None:
    o = load(""":a :f "<b x='1' y='2'/>"^^rdf:XMLLiteral , "<b y=\\"2\\" x=\\"1\\"></b>"^^rdf:XMLLiteral .""")
    assert o.reason().consistent
    values = {t.object for t in o.store.triples(o.iri("a"), o.iri("f"), None)}
    assert values == {Literal('<b x="1" y="2"></b>', datatype=NamedNode(
        "http://www.w3.org/1999/02/22-rdf-syntax-ns#XMLLiteral"))}
    different = load(""":a :f "<b x='1'/>"^^rdf:XMLLiteral , "<b x='2'/>"^^rdf:XMLLiteral .""")
    assert not different.reason().consistent


def test_rdfxml_parse_type_literal_equals_the_same_xml_in_turtle() -> None:
    o = Ontology()
    o.load_data("""<rdf:RDF xmlns:rdf="http://www.w3.org/1999/02/22-rdf-syntax-ns#" xmlns:ex="http://e.org/x#">
      <rdf:Description rdf:about="http://e.org/x#a"><ex:g rdf:parseType="Literal"><ex:b y="2" x="1"/></ex:g>
      </rdf:Description></rdf:RDF>""", "rdfxml")
    o.load_data("""@prefix ex: <http://e.org/x#> . @prefix rdf: <http://www.w3.org/1999/02/22-rdf-syntax-ns#> .
      ex:a ex:g "<ex:b xmlns:ex='http://e.org/x#' x='1' y='2'/>"^^rdf:XMLLiteral .""")
    a, g = NamedNode("http://e.org/x#a"), NamedNode("http://e.org/x#g")
    assert len(list(o.store.triples(a, g, None))) == 1


def test_a_literal_that_is_not_xml_is_kept_and_named() -> None:
    o = Ontology()
    with pytest.warns(OntologyWarning, match="not well-formed XML"):
        o.load_data(PREFIXES + """:a :f "<b>"^^rdf:XMLLiteral .""")
    assert [t.object.value for t in o.store.triples(o.iri("a"), o.iri("f"), None)] == ["<b>"]
    assert any("not well-formed XML" in str(n) for n in o.notices)
