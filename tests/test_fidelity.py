"""Answers that must not depend on how an ontology reached the store, nor on the path a change took.

Each test compares topostore with itself along two paths that must agree (the order axioms were written
in, a streamed LOAD and an ordinary one, SAVE and reload, a REASON after removals and one from scratch,
aRMOR commands and the Python API, a remote store and memory); where the expected answer is stated, it
is what Pellet 2.3.1 answers for the same file (tests/test_fidelity_pellet.py runs Pellet on them).
"""

from __future__ import annotations

from pyoxigraph import NamedNode
from support import ABOX_OWL, NS, quiet_turtle, types_of

from topostore import Ontology

EX = "http://example.org/fidelity#"
HEAD = f"""@prefix : <{EX}> . @prefix owl: <http://www.w3.org/2002/07/owl#> .
@prefix rdfs: <http://www.w3.org/2000/01/rdf-schema#> . @prefix xsd: <http://www.w3.org/2001/XMLSchema#> .
"""
TWO = ':Two owl:equivalentClass [ a owl:Restriction ; owl:onProperty :p ; ' \
      'owl:minQualifiedCardinality "2"^^xsd:nonNegativeInteger ; owl:onClass :F ] .\n'
THREE = TWO.replace(":Two", ":Three").replace('"2"', '"3"')
FILLERS = """:p a owl:ObjectProperty . :F a owl:Class .
:b :p :g1, :g2, :g3 . :g1 a :F . :g2 a :F . :g3 a :F .
:g1 owl:differentFrom :g2 . :g2 owl:differentFrom :g3 . :g1 owl:differentFrom :g3 .
"""


def ex_types(o: Ontology, name: str) -> set[str]:
    return {t.value.removeprefix(EX) for t in o.types(NamedNode(EX + name))}


def test_minima_of_two_and_three_alike_are_reasoned_in_either_order() -> None:
    """Two minimum cardinalities whose fillers are written alike share one rule asking whether two fillers
    are different; joining the minimum of two's difference into its rule must not leave the minimum of three
    unasked when its axiom came first (a document or a saved file writing Three first gave Two alone)."""
    for axioms in (TWO + THREE, THREE + TWO):
        o = quiet_turtle(HEAD + axioms + FILLERS)
        assert o.reason().consistent
        assert ex_types(o, "b") == {"Two", "Three"}, axioms


def test_a_map_class_of_three_doors_defined_before_the_tutorial_file() -> None:
    """A map's own class of locations with three different doors, in a document loaded before the tutorial's
    (CORRIDOR is its minimum of two doors): C1 with three different doors is in both."""
    hub = HEAD.replace(EX, NS) + (':HUB a owl:Class ; owl:equivalentClass [ a owl:Restriction ; '
                                  'owl:onProperty :hasDoor ; owl:minQualifiedCardinality "3"^^xsd:nonNegativeInteger ; '
                                  'owl:onClass :DOOR ] .\n')
    for hub_first in (True, False):
        o = Ontology()
        if hub_first:
            o.load_data(hub)
            o.load(ABOX_OWL)
        else:
            o.load(ABOX_OWL)
            o.load_data(hub)
        o.add_fact("C1", "hasDoor", "D3")
        o.add_all_different(["D1", "D2", "D3"])
        assert o.reason().consistent
        assert types_of(o, "C1") == {"LOCATION", "ROOM", "CORRIDOR", "HUB"}, hub_first
