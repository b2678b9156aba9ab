"""The TBox reader finds anonymous class expressions used as types from the expression nodes, not by
reading every rdf:type triple (two a location on a map)."""

from __future__ import annotations

import warnings

import pytest

from topostore import Ontology, OntologyWarning
from topostore.compile.tbox_reader import TBoxReader
from topostore.rdf.vocab import ASSERTED, TYPE

DATA = """@prefix : <http://example.org/t#> .
@prefix owl: <http://www.w3.org/2002/07/owl#> .
:p a owl:ObjectProperty . :A a owl:Class . :B a owl:Class .
:i a [ a owl:Restriction ; owl:onProperty :p ; owl:someValuesFrom :A ] , :A .
:j a [ owl:intersectionOf ( :A :B ) ] .
:k a [ a owl:Restriction ; owl:onProperty [ owl:propertyChainAxiom ( :p :p ) ] ; owl:someValuesFrom :A ] .
:m a [ a owl:Class ] .
[] a owl:AllDifferent ; owl:distinctMembers ( :i :j ) .
"""


def reader(monkeypatch: pytest.MonkeyPatch) -> tuple[TBoxReader, list]:
    onto = Ontology()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", OntologyWarning)
        onto.load_data(DATA, "turtle")
    store = onto.store
    asked: list = []
    triples = store.triples

    def spy(s=None, p=None, o=None, graph=None):
        asked.append((s, p, o))
        return triples(s, p, o, graph)

    monkeypatch.setattr(store, "triples", spy)
    return TBoxReader(store, ASSERTED), asked


def test_typed_expressions_are_read_and_bad_ones_named_once_per_individual(monkeypatch: pytest.MonkeyPatch) -> None:
    tb = reader(monkeypatch)[0].read()
    assert sorted(e.kind for e in tb.typed_expressions) == ["and", "some"]
    assert [what for what, _ in tb.unsupported] == ["k Type an anonymous expression"]


def test_the_reader_asks_for_no_rdf_type_triple_of_any_class(monkeypatch: pytest.MonkeyPatch) -> None:
    tbox_reader, asked = reader(monkeypatch)
    tbox_reader.read()
    assert asked and not [a for a in asked if a[1] == TYPE and a[2] is None]
