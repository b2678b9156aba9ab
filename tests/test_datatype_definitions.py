"""OWL 2 datatype definitions read as the range they name, or set aside saying so (compile/datatype_definitions.py)."""

from __future__ import annotations

import warnings

from topostore import Ontology, OntologyWarning

PREFIXES = ("@prefix : <http://example.org/dt#> . @prefix owl: <http://www.w3.org/2002/07/owl#> . "
            "@prefix rdfs: <http://www.w3.org/2000/01/rdf-schema#> . @prefix xsd: <http://www.w3.org/2001/XMLSchema#> .\n")


def loaded(text: str) -> Ontology:
    o = Ontology()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", OntologyWarning)
        o.load_data(PREFIXES + text)
    return o


def test_a_defined_datatype_is_no_class_axiom_and_is_checked() -> None:
    o = loaded(":Small a rdfs:Datatype ; owl:equivalentClass [ a rdfs:Datatype ; owl:onDatatype xsd:integer ; "
               "owl:withRestrictions ( [ xsd:maxInclusive 10 ] ) ] . :d a owl:DatatypeProperty ; rdfs:range :Small . "
               ":a :d 50 .")
    assert o.notices == []
    assert not o.reason().consistent


def test_an_unsupported_definition_is_said_and_its_uses_are_not_called_undefined() -> None:
    o = loaded(':Code a rdfs:Datatype ; owl:equivalentClass [ a rdfs:Datatype ; owl:onDatatype xsd:string ; '
               'owl:withRestrictions ( [ xsd:pattern "[A-Z]+" ] ) ] . :d a owl:DatatypeProperty ; rdfs:range :Code . '
               ':a :d "abc" .')
    texts = [str(n) for n in o.notices]
    assert any("Code DatatypeDefinition" in t and "xsd:pattern is not supported" in t for t in texts), texts
    assert any("d range Code" in t and "its definition is set aside" in t for t in texts), texts
    assert not any("nor defined" in t or "anonymous expression" in t for t in texts), texts
    assert o.reason().consistent


def test_a_datatype_defined_twice_is_set_aside_saying_so_whatever_the_order() -> None:
    """Both definitions hold (their intersection); neither one alone may stand for the name, whichever is read
    first: the name stays undefined and its uses are said unchecked."""
    most = ":Small owl:equivalentClass [ a rdfs:Datatype ; owl:onDatatype xsd:integer ; " \
           "owl:withRestrictions ( [ xsd:maxInclusive 10 ] ) ] .\n"
    least = most.replace("maxInclusive 10", "minInclusive 0")
    for first, second in ((most, least), (least, most)):
        o = loaded(":Small a rdfs:Datatype .\n" + first + second +
                   ":d a owl:DatatypeProperty ; rdfs:range :Small . :a :d -5 .")
        texts = [str(n) for n in o.notices]
        assert any("Small DatatypeDefinition" in t and "defined 2 times" in t for t in texts), texts
        assert any("d range Small" in t and "its definition is set aside" in t for t in texts), texts
