"""Annotation properties carry no logical meaning (OWL 2 Direct Semantics, and Pellet): the domain, range and
super-properties told of one, declared or built in, are set aside with one notice per property, on a load, on a
later change declaring a property an annotation property, and on an incremental REASON alike.  The answers
themselves are Pellet's: tests/test_fidelity_pellet.py."""

from __future__ import annotations

import warnings

from pyoxigraph import NamedNode, Triple

from topostore import Ontology, OntologyWarning
from topostore.compile.notices import ANNOTATION
from topostore.rdf.vocab import INFERRED, TYPE, owl

PREFIXES = """@prefix : <http://example.org/annot/> . @prefix owl: <http://www.w3.org/2002/07/owl#> .
@prefix rdfs: <http://www.w3.org/2000/01/rdf-schema#> . @prefix xsd: <http://www.w3.org/2001/XMLSchema#> .
"""
NS = "http://example.org/annot/"


def ex(name: str) -> NamedNode:
    return NamedNode(NS + name)


def load(body: str) -> tuple[Ontology, list[str]]:
    """The ontology of ``body`` and the texts of the warnings its load gave."""
    o = Ontology()
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        o.load_data(PREFIXES + body)
    return o, [str(w.message) for w in caught if issubclass(w.category, OntologyWarning)]


def test_domain_range_and_super_property_of_annotation_properties_are_set_aside_once_each() -> None:
    o, said = load(""":ap a owl:AnnotationProperty ; rdfs:domain :C ; rdfs:range :D ; rdfs:subPropertyOf :p .
:p a owl:ObjectProperty ; rdfs:domain :E . :C a owl:Class . :D a owl:Class . :E a owl:Class .
:src a owl:AnnotationProperty ; rdfs:range xsd:anyURI .
rdfs:label rdfs:domain :C .
:a a owl:NamedIndividual ; :ap :b, :c ; :src <http://example.org/page> ; rdfs:label "a" .
:b a owl:NamedIndividual . :c a owl:NamedIndividual .
""")
    report = o.reason()
    assert report.consistent
    assert o.types(ex("a")) == [] and o.types(ex("b")) == []
    assert not o.store.contains(Triple(ex("a"), ex("p"), ex("b")), INFERRED)
    line = next(text for text in said if ANNOTATION in text)
    assert line.count("ap (") == 1 and "src (" in line and "label (" in line
    assert not report.incomplete  # Pellet's reading: nothing is missed


def test_declaring_an_annotation_property_later_sets_its_axioms_aside_as_a_load_would() -> None:
    body = """:ap rdfs:domain :C . :C a owl:Class . :a a owl:NamedIndividual ; :ap :b . :b a owl:NamedIndividual .
"""
    o, _ = load(body)
    o.reason()
    assert ex("C") in o.types(ex("a"))
    declaration = Triple(ex("ap"), TYPE, owl("AnnotationProperty"))
    o.add(declaration)
    report = o.reason()
    assert report.consistent and ex("C") not in o.types(ex("a"))
    assert [n.subject for n in o.notices if n.kind == ANNOTATION] == ["ap"]
    o.add(Triple(ex("c"), ex("ap"), ex("d")))  # an assertion after it: an incremental REASON, the same rules
    assert o.reason(mode="incremental").stats.mode == "incremental"
    assert ex("C") not in o.types(ex("c"))
    scratch, _ = load(body + ":ap a owl:AnnotationProperty . :c :ap :d .\n")
    scratch.reason()
    assert set(o.store.triples(graph=INFERRED)) == set(scratch.store.triples(graph=INFERRED))
    o.remove(declaration)
    o.reason()
    assert ex("C") in o.types(ex("a"))


def test_an_annotation_property_also_declared_an_object_property_keeps_the_object_reading_and_says_so() -> None:
    o, said = load(""":p a owl:AnnotationProperty , owl:ObjectProperty ; rdfs:domain :C . :C a owl:Class .
:a a owl:NamedIndividual ; :p :b . :b a owl:NamedIndividual .
""")
    o.reason()
    assert ex("C") in o.types(ex("a"))
    assert any(ANNOTATION in text and "p (declared both" in text for text in said), said


def test_an_annotation_property_told_an_object_property_axiom_keeps_the_object_reading() -> None:
    """Transitive, or the inverse of an object property: Pellet reads it as an object property, its range
    applies (``:b`` is a ``C``), and the punning is said; its range is not set aside."""
    for told in (":ap a owl:TransitiveProperty .", ":q a owl:ObjectProperty ; owl:inverseOf :ap ."):
        o, said = load(f""":ap a owl:AnnotationProperty ; rdfs:range :C . :C a owl:Class . {told}
:a a owl:NamedIndividual ; :ap :b . :b a owl:NamedIndividual .
""")
        assert o.reason().consistent
        assert ex("C") in o.types(ex("b")), told
        assert any("declared both an annotation property" in text for text in said), said
        assert not any("set aside, as Pellet does" in text for text in said), said


def test_an_annotation_property_declared_functional_stays_one_and_its_characteristic_is_set_aside() -> None:
    """Functional (or inverse functional), a characteristic a data property may have too: Pellet's loader gives
    the property no other type and reads its values as annotations, so two values are neither merged nor a clash
    (Pellet's answers: tests/test_fidelity_pellet.py)."""
    for characteristic in ("FunctionalProperty", "InverseFunctionalProperty"):
        o, said = load(f""":ap a owl:AnnotationProperty , owl:{characteristic} . :D a owl:Class . :E a owl:Class .
:a a owl:NamedIndividual ; :ap :b , :c ; :ap "x" , "y" . :z a owl:NamedIndividual ; :ap :c .
:b a owl:NamedIndividual , :D ; owl:differentFrom :c . :c a owl:NamedIndividual , :E .
:C a owl:Class ; :ap "one" , "two" .
""")
        report = o.reason()
        assert report.consistent, characteristic
        assert o.types(ex("b")) == [ex("D")] and o.types(ex("c")) == [ex("E")] and o.types(ex("z")) == []
        assert any(f"ap (an annotation property: ap a {characteristic} set aside" in text for text in said), said
        assert not any("declared both" in text for text in said), said
