"""Documents in OWL's own syntaxes are refused by name, nothing loaded (rdf/owl_syntaxes.py)."""

from __future__ import annotations

from pathlib import Path

import pytest

from topostore import Ontology
from topostore.armor import ArmorService
from topostore.errors import LoadError
from topostore.rdf.owl_syntaxes import owl_syntax

OWL_XML = """<?xml version="1.0"?>
<!-- saved by Protégé -->
<Ontology xmlns="http://www.w3.org/2002/07/owl#" xml:base="http://example.org/h"
     xmlns:rdf="http://www.w3.org/1999/02/22-rdf-syntax-ns#" ontologyIRI="http://example.org/h">
    <Declaration><Class IRI="#C"/></Declaration>
    <ClassAssertion><Class IRI="#C"/><NamedIndividual IRI="#a"/></ClassAssertion>
</Ontology>
"""
MANCHESTER = """Prefix: : <http://example.org/h#>
Ontology: <http://example.org/h>
Class: C
Individual: a
    Types: C
"""
FUNCTIONAL = """# a comment
Prefix(:=<http://example.org/h#>)
Ontology(<http://example.org/h>
ClassAssertion(:C :a)
)
"""
DOCUMENTS = {"owlxml.owl": (OWL_XML, "OWL/XML"), "manch.omn": (MANCHESTER, "Manchester OWL"),
             "manch.owl": (MANCHESTER, "Manchester OWL"), "func.ofn": (FUNCTIONAL, "OWL Functional"),
             "func.ttl": (FUNCTIONAL, "OWL Functional")}


@pytest.mark.parametrize("name", list(DOCUMENTS))
def test_armor_load_names_the_syntax_and_loads_nothing(tmp_path: Path, name: str) -> None:
    text, syntax = DOCUMENTS[name]
    (tmp_path / name).write_text(text)
    svc = ArmorService()
    reply = svc.call({"client_name": "c", "reference_name": "ref", "command": "LOAD", "primary_command_spec": "FILE",
                      "secondary_command_spec": "", "args": [str(tmp_path / name), "http://example.org/h", "false",
                                                             "PELLET", "false"]})
    assert not reply.success and reply.exit_code == 210
    assert f"in the {syntax} syntax, which topostore does not read" in reply.error_description
    assert "RDF/XML" in reply.error_description and "Turtle" in reply.error_description
    assert "not valid" not in reply.error_description
    assert "ref" not in svc.reference_names()


def test_ontology_load_refuses_and_keeps_the_graph(tmp_path: Path) -> None:
    o = Ontology()
    o.load_data("@prefix : <http://example.org/h#> . :x :p :y .")
    before = o.triples()
    (tmp_path / "o.owl").write_text(OWL_XML)
    with pytest.raises(LoadError, match="OWL/XML syntax"):
        o.load(tmp_path / "o.owl")
    assert o.triples() == before


@pytest.mark.parametrize("text,fmt", [
    ("""<?xml version="1.0"?><owl:Ontology xmlns:owl="http://www.w3.org/2002/07/owl#"
        xmlns:rdf="http://www.w3.org/1999/02/22-rdf-syntax-ns#" rdf:about="http://example.org/h"/>""", "xml"),
    ("PREFIX : <http://example.org/h#>\n:Prefix :Ontology :Class .", "turtle"),
])
def test_rdf_alike_documents_still_load(text: str, fmt: str) -> None:
    """RDF whose root element is an owl:Ontology node, or Turtle naming such words, is RDF."""
    o = Ontology()
    assert o.load_data(text, fmt=fmt) == 1


def test_rdf_xml_with_an_owl_ontology_root_and_no_about_is_rdf() -> None:
    """A typed node element as the root, without rdf:about: RDF/XML, not OWL/XML (which names an ontologyIRI or
    holds axioms as elements of their own)."""
    data = b'''<?xml version="1.0"?>
<owl:Ontology xmlns:rdf="http://www.w3.org/1999/02/22-rdf-syntax-ns#" xmlns:owl="http://www.w3.org/2002/07/owl#"
    xmlns:rdfs="http://www.w3.org/2000/01/rdf-schema#">
  <rdfs:comment>a map</rdfs:comment>
</owl:Ontology>'''
    assert owl_syntax(data) is None
    assert owl_syntax(data.replace(b"<rdfs:comment>a map</rdfs:comment>", b'<Declaration><Class IRI="#C"/></Declaration>')
                      .replace(b"owl:Ontology", b"Ontology").replace(b"xmlns:owl=", b"xmlns=")) == "OWL/XML"
