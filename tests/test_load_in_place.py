"""The first document of an empty in-memory ontology is compiled where it is added, not on a copy.

A refused document must still leave the ontology as it was (empty), and a big add into an empty
graph must keep what the look-up path keeps (the first spelling of a value, the count of new
triples)."""

from __future__ import annotations

import re
import warnings

import pytest
from pyoxigraph import Literal, NamedNode, Triple

from topostore import IncompleteOntologyError, Ontology, RuleCompileError
from topostore.rdf.vocab import ASSERTED
from topostore.stores import memory_store
from topostore.stores.work import BULK_ADD

PREFIXES = """@prefix : <http://e.org/a#> . @prefix owl: <http://www.w3.org/2002/07/owl#> .
@prefix rdfs: <http://www.w3.org/2000/01/rdf-schema#> . @prefix xsd: <http://www.w3.org/2001/XMLSchema#> .
"""
FACTS = " ".join(f":i{n} :p :i{n + 1} ." for n in range(50))
TOO_LARGE = ":C owl:equivalentClass [ a owl:Class ; owl:intersectionOf ({}) ] .".format(" ".join(f":A{i}" for i in range(300)))
INCOMPLETE = ":A rdfs:subClassOf [ owl:unionOf (:B :C) ] ."
GOOD = ":p rdfs:domain :D . :D rdfs:subClassOf :E ."
XSD_INT = NamedNode("http://www.w3.org/2001/XMLSchema#int")


def test_a_refused_first_document_leaves_the_ontology_empty_and_usable() -> None:
    onto = Ontology()
    dirty = onto.dirty
    with pytest.raises(RuleCompileError, match="too large to evaluate safely"):
        onto.load_data(PREFIXES + TOO_LARGE + FACTS, "turtle")
    assert onto.store.count(ASSERTED) == 0 and onto.dirty == dirty
    onto.load_data(PREFIXES + GOOD + FACTS, "turtle")
    assert onto.reason().consistent
    assert NamedNode("http://e.org/a#i3") in onto.instances(NamedNode("http://e.org/a#E"))


def test_strict_refusal_of_a_first_document_leaves_it_empty() -> None:
    onto = Ontology(strict=True)
    with pytest.raises(IncompleteOntologyError, match="A SubClassOf"):
        onto.load_data(PREFIXES + INCOMPLETE + FACTS, "turtle")
    assert onto.store.count(ASSERTED) == 0 and onto.notices == []


def rule_texts(onto: Ontology) -> list[str]:
    """The compiled rules, with the names of anonymous class expressions (fresh per parse) left out."""
    return sorted(re.sub(r"urn:topostore:bnode:[0-9a-f]+", "bnode", r.sparql()) for r in onto.rules.rules)


def test_a_first_document_compiles_as_on_a_copy() -> None:
    """The same rules and notices as a load into a non-empty ontology, which compiles on a copy."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        fresh = Ontology()
        fresh.load_data(PREFIXES + GOOD + INCOMPLETE + FACTS, "turtle")
        seeded = Ontology()
        seeded.load_data(PREFIXES + ":seed :p :seed2 .", "turtle")
        seeded.load_data(PREFIXES + GOOD + INCOMPLETE + FACTS, "turtle")
    assert rule_texts(fresh) == rule_texts(seeded)
    assert [n.kind for n in fresh.notices] == [n.kind for n in seeded.notices]


def big_add(store, triples: list[Triple]) -> tuple[int, list[Triple]]:
    added = store.add(triples, ASSERTED)
    return added, sorted(store.triples(graph=ASSERTED), key=str)


def test_a_big_add_into_an_empty_graph_keeps_what_the_look_up_path_keeps() -> None:
    s, p = NamedNode("http://e.org/s"), NamedNode("http://e.org/p")
    triples = [Triple(NamedNode(f"http://e.org/x{i}"), p, NamedNode(f"http://e.org/y{i}")) for i in range(BULK_ADD)]
    spellings = [Triple(s, p, Literal("01", datatype=XSD_INT)), Triple(s, p, Literal("1", datatype=XSD_INT))]
    batch = [*spellings, *triples, triples[0]]
    other = Triple(s, s, s)
    bulk = big_add(memory_store(), batch)
    looked_up = memory_store()
    looked_up.add([other], ASSERTED)  # not empty: every quad is looked up
    count, content = big_add(looked_up, batch)
    assert bulk == (count, [t for t in content if t != other])
    assert len([t for t in bulk[1] if t.subject == s]) == 1


def test_a_big_add_inside_a_transaction_sees_its_pending_writes() -> None:
    store = memory_store()
    p = NamedNode("http://e.org/p")
    triples = [Triple(NamedNode(f"http://e.org/x{i}"), p, NamedNode("http://e.org/y")) for i in range(BULK_ADD)]
    with store.transaction():
        assert store.add(triples[:10], ASSERTED) == 10
        assert store.add(triples, ASSERTED) == BULK_ADD - 10
    assert store.count(ASSERTED) == BULK_ADD
