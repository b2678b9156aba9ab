"""A SWRL rule's DifferentIndividuals atom joined with the difference rules (compile/inline_difference.py):
the same conclusions as the materialised candidates, none of their helper facts."""

from __future__ import annotations

import pytest
from pyoxigraph import NamedNode, Triple
from support import reasoned_turtle
from test_swrl_difference import PREFIXES, siblings

from topostore import Ontology
from topostore.compile.inline_difference import MAX_JOINED
from topostore.compile.snippets import VALUE_CANDIDATE
from topostore.rdf.vocab import AUX, DECLARED_DIFFERENT, DIFFERENCE_CANDIDATE, DIFFERENT, ENTAILED
from topostore.resources import default_ontology_files

HELPERS = (str(DIFFERENCE_CANDIDATE), str(DECLARED_DIFFERENT), str(DIFFERENT), str(VALUE_CANDIDATE))
EX, F = "http://bnc/exp-rob-lab/2022-23#", "http://e.org/f#"
OWL_DIFFERENT_FROM = NamedNode("http://www.w3.org/2002/07/owl#differentFrom")

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


def test_the_example_map_asks_no_declared_difference_at_all() -> None:
    o = Ontology.from_file(*default_ontology_files())
    assert o.reason().consistent
    for name in ("Connectability", "Reachability"):
        rules = swrl_rules(o, name)
        assert 1 < len(rules) <= 2 * MAX_JOINED
        # the conclusions read no difference fact; only the entailed-only one reads ts:different,
        # for the pairs asked by values (visitedAt allows one value)
        assert not any(a.p in (str(DECLARED_DIFFERENT), str(DIFFERENCE_CANDIDATE)) for r in rules
                       for a in (*r.body, r.head))
        assert [r.head.p for r in rules if any(a.p == str(DIFFERENT) for a in r.body)] == [
            f"<urn:topostore:entailed:{EX}{'connectedTo' if name == 'Connectability' else 'canReach'}>"]
        assert [r.head.p for r in rules if r.head.p == str(VALUE_CANDIDATE)]
    # CORRIDOR's two different doors (hasDoor min 2 DOOR) are joined with the AllDifferent keys and
    # owl:differentFrom; a door has no visit time (DOOR and LOCATION are disjoint), so no value rule
    door_rules = [r for r in o.rules.rules if r.origin == "class expression (hasDoor min 2 DOOR)"]
    assert door_rules and not any(a.p in HELPERS or "visitedAt" in a.p for r in door_rules for a in r.body)
    assert helper_count(o, str(DIFFERENCE_CANDIDATE)) == helper_count(o, str(DECLARED_DIFFERENT)) == 0
    # the pairs asked by values: Connectability's ask unless its conclusion is known, every pair of the
    # map is declared different, so none is asked (topostore.reason.negation); Reachability's ask only
    # ever meets declared pairs (every connectedTo is Connectability's), so it is never run either
    asks = [r for r in swrl_rules(o, "Connectability") if r.head.p == str(VALUE_CANDIDATE)]
    assert [r.unless_known.p for r in asks] == [f"<{EX}connectedTo>"]
    assert helper_count(o, str(VALUE_CANDIDATE)) == 0
    assert sorted(o.short(x) for x in o.instances("CORRIDOR")) == ["C1"]  # as before


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


#: a functional data property: two birth years make two individuals different by entailment only
BORN = ":born a owl:DatatypeProperty , owl:FunctionalProperty . "


def entailed_siblings(o: Ontology) -> set[tuple[str, str]]:
    sibling = "http://e.org/f#hasSibling"
    return {(o.short(t.subject), o.short(t.object)) for t in o.store.triples(None, None, None, ENTAILED)
            if t.predicate.value == sibling}


def test_difference_by_values_only_is_asked_by_values_and_published_as_entailed() -> None:
    o = family_with(BORN + ":a :born 1990 . :b :born 1992 .")
    # reported as entailed (as Pellet does), firing no other rule
    assert siblings(o) == {"hasSibling": ["b"], "hasBrother": []}
    assert entailed_siblings(o) == {("a", "b"), ("b", "a")}
    # the pair is asked of the value rules alone: nothing declares it different
    assert helper_count(o, str(VALUE_CANDIDATE)) == 2
    assert helper_count(o, str(DECLARED_DIFFERENT)) == 0 and helper_count(o, str(DIFFERENCE_CANDIDATE)) == 0
    o.replace("b", "born", 1990)
    assert o.reason().consistent
    assert entailed_siblings(o) == set() and siblings(o)["hasSibling"] == []  # the same year: not different
    o.add(Triple(NamedNode(F + "b"), OWL_DIFFERENT_FROM, NamedNode(F + "a")))
    assert o.reason().consistent
    assert siblings(o) == {"hasSibling": ["b"], "hasBrother": ["b"]} and entailed_siblings(o) == set()


def test_the_value_rules_answer_the_pairs_asked_by_values_alone() -> None:
    # a functional property reads its difference negated (sameAs unless different): its pairs stay
    # asked, of both kinds
    o = family_with(BORN + ":hasParent a owl:FunctionalProperty . :a :born 1990 . :b :born 1992 .")
    values = [r for r in o.rules.compiled_rules() if r.name == "different-values"]
    assert values and all({a.p for a in r.body if a.aux} == {str(VALUE_CANDIDATE)} for r in values)
    heads = {r.head.p for r in o.rules.compiled_rules() if r.origin == "hasParent is functional" and r.head is not None}
    assert {str(DIFFERENCE_CANDIDATE), str(VALUE_CANDIDATE)} <= heads


def test_without_value_rules_the_entailed_only_conclusion_is_left_out() -> None:
    o = family_with(":b owl:differentFrom :a .")
    assert not [r for r in swrl_rules(o, "siblings") if "entailment only" in r.origin]
    assert siblings(o) == {"hasSibling": ["b"], "hasBrother": ["b"]}


CARD = """@prefix : <http://e.org/c#> . @prefix owl: <http://www.w3.org/2002/07/owl#> .
@prefix rdfs: <http://www.w3.org/2000/01/rdf-schema#> . @prefix xsd: <http://www.w3.org/2001/XMLSchema#> .
<http://e.org/c> a owl:Ontology . :p a owl:ObjectProperty . :Door a owl:Class . :Room a owl:Class .
:Door owl:disjointWith :Room . :born a owl:DatatypeProperty , owl:FunctionalProperty .
:C owl:equivalentClass [ a owl:Restriction ; owl:onProperty :p ; owl:minCardinality "2"^^xsd:nonNegativeInteger ] .
"""


@pytest.mark.parametrize(("facts", "member"), [
    ("[] a owl:AllDifferent ; owl:distinctMembers ( :a :b ) .", True),
    (":b owl:differentFrom :a .", True),
    (":a a :Door . :b a :Room .", True),
    (":a :born 1990 . :b :born 1992 .", True),  # different by values: a minimum counts them too
    (":a :born 1990 . :b :born 1990 .", False),
    ("", False),
])
def test_a_minimum_of_two_joins_every_way_of_being_different(facts: str, member: bool) -> None:
    o = reasoned_turtle(CARD + ":x :p :a , :b . " + facts)
    assert ("x" in {o.short(i) for i in o.instances("C")}) == member
    card = [r for r in o.rules.rules if r.origin == "class expression (p min 2 Thing)"]
    assert card and not any(a.p in HELPERS for r in card for a in r.body)
    assert helper_count(o, str(DIFFERENCE_CANDIDATE)) == 0


def test_a_maximum_reading_difference_negated_keeps_its_candidates() -> None:
    text = CARD.replace("owl:minCardinality", "owl:maxCardinality").replace('"2"', '"1"')
    o = Ontology()
    o.load_data(text + ":x :p :a , :b . :b owl:differentFrom :a . :x a :C .")
    assert not o.reason().consistent  # two different values of at most one
    assert any(r.head is not None and r.head.p == str(DIFFERENCE_CANDIDATE) for r in o.rules.rules)
