"""A SWRL rule's DifferentIndividuals atom joined with the difference rules (compile/inline_difference.py):
the same conclusions as the materialised candidates, none of their helper facts."""

from __future__ import annotations

from support import reasoned_turtle
from test_swrl_difference import PREFIXES, siblings

from topostore import Ontology
from topostore.compile.inline_difference import MAX_JOINED
from topostore.rdf.vocab import AUX, DECLARED_DIFFERENT, DIFFERENCE_CANDIDATE, DIFFERENT
from topostore.resources import default_ontology_files

HELPERS = (str(DIFFERENCE_CANDIDATE), str(DECLARED_DIFFERENT), str(DIFFERENT))

#: a third rule with two DifferentIndividuals atoms: its candidates stay materialised
THREE = """:z a swrl:Variable . :hasTwoSiblings a owl:ObjectProperty .
[] a swrl:Imp ; rdfs:label "two siblings" ;
   swrl:body ( [ a swrl:IndividualPropertyAtom ; swrl:propertyPredicate :hasSibling ; swrl:argument1 :x ; swrl:argument2 :y ]
               [ a swrl:IndividualPropertyAtom ; swrl:propertyPredicate :hasSibling ; swrl:argument1 :x ; swrl:argument2 :z ]
               [ a swrl:DifferentIndividualsAtom ; swrl:argument1 :y ; swrl:argument2 :z ]
               [ a swrl:DifferentIndividualsAtom ; swrl:argument1 :x ; swrl:argument2 :z ] ) ;
   swrl:head ( [ a swrl:IndividualPropertyAtom ; swrl:propertyPredicate :hasTwoSiblings ; swrl:argument1 :x ; swrl:argument2 :z ] ) .
"""


def swrl_rules(o: Ontology, name: str) -> list:
    return [r for r in o.rules.rules if r.name == f"swrl:{name}"]


def helper_count(o: Ontology, predicate: str) -> int:
    return sum(1 for t in o.store.triples(None, None, None, AUX) if str(t.predicate) == predicate)


def test_one_difference_atom_reads_and_writes_no_difference_facts() -> None:
    o = family_with(":b owl:differentFrom :a .")
    rules = swrl_rules(o, "siblings")
    assert rules and not any(a.p in HELPERS for r in rules for a in (*r.body, r.head))
    assert siblings(o) == {"hasSibling": ["b"], "hasBrother": ["b"]}
    assert all(helper_count(o, p) == 0 for p in HELPERS)  # nothing else here asks about a pair


def test_a_disjoint_pair_contradicting_the_body_is_left_out() -> None:
    # brothers-like rule: x is a Man, so "x a Woman" (Woman disjoint with Man) cannot hold consistently
    o = family_with(":Man owl:disjointWith :Woman . :a a :Woman . " + MAN_RULE)
    rules = swrl_rules(o, "manSiblings")
    woman_x = [r for r in rules if any(a.s == "?x" and a.o.endswith("#Woman>") for a in r.body)]
    assert rules and not woman_x
    assert sorted(o.object_values("hasManSibling", "b")) == ["a"]  # b (a Man) and a (a Woman) differ
    assert siblings(o) == {"hasSibling": ["b"], "hasBrother": ["b"]}


def test_two_difference_atoms_keep_their_candidates_with_the_same_answers() -> None:
    o = family_with(":b owl:differentFrom :a . :c :hasParent :t . :c owl:differentFrom :a , :b . " + THREE)
    assert any(r.head.p == str(DIFFERENCE_CANDIDATE) for r in swrl_rules(o, "two siblings"))
    assert sorted(o.object_values("hasTwoSiblings", "a")) == ["b", "c"]
    assert sorted(o.object_values("hasSibling", "c")) == ["a", "b"]


def test_the_example_map_asks_only_for_the_door_pairs_of_its_cardinality() -> None:
    o = Ontology.from_file(*default_ontology_files())
    assert o.reason().consistent
    for name in ("Connectability", "Reachability"):
        assert 1 < len(swrl_rules(o, name)) <= 2 * MAX_JOINED
        assert not any(a.p in HELPERS for r in swrl_rules(o, name) for a in (*r.body, r.head))
    # the candidates left are pairs of doors of one location (hasDoor min 2 DOOR), never two locations
    door_pairs = {(str(t.subject), str(t.object)) for t in o.store.triples(None, DIFFERENCE_CANDIDATE, None, AUX)}
    assert door_pairs and all("#D" in s and "#D" in t for s, t in door_pairs)
    assert sorted(o.short(x) for x in o.object_values("canReach", "Robot1")) == sorted(
        o.short(x) for x in o.object_values("connectedTo", o.object_values("isIn", "Robot1")[0]))


MAN_RULE = """:hasManSibling a owl:ObjectProperty .
[] a swrl:Imp ; rdfs:label "manSiblings" ;
   swrl:body ( [ a swrl:ClassAtom ; swrl:classPredicate :Man ; swrl:argument1 :x ]
               [ a swrl:IndividualPropertyAtom ; swrl:propertyPredicate :hasParent ; swrl:argument1 :x ; swrl:argument2 :p ]
               [ a swrl:IndividualPropertyAtom ; swrl:propertyPredicate :hasParent ; swrl:argument1 :y ; swrl:argument2 :p ]
               [ a swrl:DifferentIndividualsAtom ; swrl:argument1 :x ; swrl:argument2 :y ] ) ;
   swrl:head ( [ a swrl:IndividualPropertyAtom ; swrl:propertyPredicate :hasManSibling ; swrl:argument1 :x ; swrl:argument2 :y ] ) .
"""


def family_with(text: str) -> Ontology:
    return reasoned_turtle(PREFIXES + text)
