"""A SWRL variable bound only by a ``sameAs`` body atom: DL-safe, it ranges over the other argument and
its aliases (sameAs is reflexive).  Pellet's answers: tests/test_fidelity_pellet.py (``swrl_same_as``)."""

from __future__ import annotations

import warnings

from test_incremental import from_scratch

from topostore import Ontology, OntologyWarning
from topostore.rdf.vocab import INFERRED

NS = "http://example.org/s#"
PREFIXES = f"""@prefix : <{NS}> . @prefix owl: <http://www.w3.org/2002/07/owl#> .
@prefix swrl: <http://www.w3.org/2003/11/swrl#> .
"""
FACTS = ":D a owl:Class . :E a owl:Class . :a a :D . :b owl:sameAs :c . :c a :D . :e a owl:Thing . "
#: the rule as Protégé writes it: D(?x) ^ sameAs(?x, ?y) -> E(?y)
PROTEGE = """:x a swrl:Variable . :y a swrl:Variable .
:r a swrl:Imp ; swrl:body ( [ a swrl:ClassAtom ; swrl:classPredicate :D ; swrl:argument1 :x ]
                            [ a swrl:SameIndividualAtom ; swrl:argument1 :x ; swrl:argument2 :y ] ) ;
   swrl:head ( [ a swrl:ClassAtom ; swrl:classPredicate :E ; swrl:argument1 :y ] ) ."""


def loaded(text: str) -> Ontology:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", OntologyWarning)
        o = Ontology(prefix=NS)
        o.load_data(PREFIXES + text)
    return o


def members(o: Ontology, name: str) -> set[str]:
    return {i.value.removeprefix(NS) for i in o.instances(name)}


def test_a_variable_bound_by_same_as_alone_loads_and_ranges_over_aliases_and_itself() -> None:
    o = loaded(FACTS + PROTEGE)
    assert o.reason().consistent
    assert members(o, "E") == {"a", "b", "c"}


def test_the_text_form_is_accepted_and_an_incremental_reason_equals_one_from_scratch() -> None:
    o = loaded(FACTS)
    o.add_rule("D(?x) ^ sameAs(?y, ?x) -> E(?y)", "alias")
    assert o.reason().consistent
    assert members(o, "E") == {"a", "b", "c"}
    o.load_data(PREFIXES + ":e owl:sameAs :a . :f a :D .")
    report = o.reason()
    assert report.consistent and report.stats.mode == "incremental"
    assert members(o, "E") == {"a", "b", "c", "e", "f"}
    inferred, _aux, _entailed, _ok = from_scratch(o)
    assert set(o.store.triples(graph=INFERRED)) == inferred


def test_a_chain_of_same_as_atoms_binds_each_in_turn() -> None:
    o = loaded(FACTS)
    o.add_rule("D(?x) ^ sameAs(?x, ?y) ^ sameAs(?y, ?z) -> E(?z)", "chain")
    assert o.reason().consistent
    assert members(o, "E") == {"a", "b", "c"}
