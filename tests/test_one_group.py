"""A full run leaves the "two keys of one group" test out while the store holds one AllDifferent group
(reason/one_group.py): the same closure, and the test kept wherever a second group may exist."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest
from support import closure, full_run_updates, map_or_text, same_closure_without

from topostore import Ontology
from topostore.compile.counting import group_of
from topostore.reason import materialize
from topostore.reason.one_group import keys_kept_by_group, without_group_tests

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))  # the benchmarks package lives beside src/
from benchmarks.cardinality import PREFIXES  # noqa: E402

GROUP_PART = group_of("?")[:8]  # the text every group test starts its comparison with (STRBEFORE)

MIN2 = PREFIXES + """@prefix swrl: <http://www.w3.org/2003/11/swrl#> .
:p a owl:ObjectProperty . :D a owl:Class .
:C owl:equivalentClass [ a owl:Restriction ; owl:onProperty :p ; owl:minQualifiedCardinality 2 ; owl:onClass :D ] .
:Link a owl:Class .
[] a swrl:Imp ;
   swrl:body ( [ a swrl:IndividualPropertyAtom ; swrl:propertyPredicate :p ; swrl:argument1 :vx ; swrl:argument2 :va ]
               [ a swrl:IndividualPropertyAtom ; swrl:propertyPredicate :p ; swrl:argument1 :vx ; swrl:argument2 :vb ]
               [ a swrl:DifferentIndividualsAtom ; swrl:argument1 :va ; swrl:argument2 :vb ] ) ;
   swrl:head ( [ a swrl:ClassAtom ; swrl:classPredicate :Link ; swrl:argument1 :va ] ) .
:vx a swrl:Variable . :va a swrl:Variable . :vb a swrl:Variable .
:a a :D . :b a :D . :c a :D . :d a :D .
"""
ONE_GROUP = ":x :p :a, :b . [] a owl:AllDifferent ; owl:distinctMembers (:a :b :c) ."
CASES = {
    "one group": ONE_GROUP,
    "two groups": ":x :p :a, :b . [] a owl:AllDifferent ; owl:distinctMembers (:a :c) . "
                  "[] a owl:AllDifferent ; owl:members (:b :d) .",
    "a second group by sameAs": ":x :p :a, :b . :g a owl:AllDifferent ; owl:distinctMembers (:a :c) . "
                                ":h owl:distinctMembers (:b :d) . :g owl:sameAs :h .",
    "one group and a same member": ":x :p :a, :b2 . :b2 owl:sameAs :b . "
                                   "[] a owl:AllDifferent ; owl:distinctMembers (:a :b) .",
    "one node with two lists": ":x :p :a, :b . [] a owl:AllDifferent ; owl:distinctMembers (:a :c) ; "
                               "owl:members (:b :d) .",
    "one node with two member lists": ":x :p :a, :b . [] a owl:AllDifferent ; owl:members (:a :c), (:b :d) .",
    "one node with one list twice": ":x :p :a, :b . :l <http://www.w3.org/1999/02/22-rdf-syntax-ns#first> :a ; "
                                    "<http://www.w3.org/1999/02/22-rdf-syntax-ns#rest> (:b) . "
                                    "[] a owl:AllDifferent ; owl:members :l ; owl:distinctMembers :l .",
}


@pytest.mark.parametrize("source", ["map", "one group"])
def test_a_full_run_over_one_group_compares_no_group_parts(source: str, monkeypatch: pytest.MonkeyPatch) -> None:
    onto = loaded(source)
    assert keys_kept_by_group(onto.rules.inference_rules)
    grouped = [r for r in onto.rules.inference_rules if without_group_tests(r) is not None]
    assert grouped  # the rules read keys of one group: the test is there to leave out
    texts = full_run_updates(onto, monkeypatch)
    assert any("differentKeyOf" in t for t in texts)
    assert not any(GROUP_PART in t and "differentKeyOf" in t for t in texts)


@pytest.mark.parametrize("source", ["two groups", "a second group by sameAs", "one node with two lists",
                                    "one node with two member lists"])
def test_a_second_group_keeps_the_test(source: str, monkeypatch: pytest.MonkeyPatch) -> None:
    texts = full_run_updates(loaded(source), monkeypatch)
    assert any(GROUP_PART in t and "differentKeyOf" in t for t in texts)


@pytest.mark.parametrize("source", ["map", *CASES])
def test_a_full_reason_reaches_the_same_closure_with_and_without_the_shortcut(
        source: str, monkeypatch: pytest.MonkeyPatch) -> None:
    same_closure_without(loaded(source), monkeypatch, materialize, "one_group", lambda store, queued: False)


def test_only_members_of_one_group_are_different_by_keys() -> None:
    """The cases' answers themselves: two groups never make their members different, and the group is
    the list (OWL 2 RL eq-diff2/eq-diff3), not the AllDifferent node: one node with two lists is two groups."""
    expected = {"one group": True, "two groups": False, "a second group by sameAs": False,
                "one group and a same member": True, "one node with two lists": False,
                "one node with two member lists": False, "one node with one list twice": True}
    for source, different in expected.items():
        onto = loaded(source)
        onto.reason(mode="full")
        classes = {str(c) for c in onto.store.objects(*_x_type())}
        assert (f"<{PREFIXES_NS}C>" in classes) == different, source


PREFIXES_NS = next(line.split("<", 1)[1].rstrip(" .>") for line in PREFIXES.splitlines()
                   if line.startswith("@prefix : "))


def _x_type():
    from pyoxigraph import NamedNode

    from topostore.rdf.vocab import INFERRED, TYPE
    return NamedNode(PREFIXES_NS + "x"), TYPE, INFERRED


def loaded(source: str) -> Ontology:
    return map_or_text(None if source == "map" else MIN2 + CASES[source])



def test_a_list_added_to_a_node_later_is_a_group_of_its_own() -> None:
    """A second member list given to an AllDifferent node by a later change (the robot step's path): its
    members are not different from the first list's, as a full REASON from scratch says."""
    onto = map_or_text(MIN2 + ":x :p :a, :b . :g a owl:AllDifferent ; owl:distinctMembers (:a :c) .")
    onto.reason()
    onto.load_data(PREFIXES + ":g owl:members (:b :d) .", "turtle")
    onto.reason()
    stepped = closure(onto)
    assert f"<{PREFIXES_NS}C>" not in {str(c) for c in onto.store.objects(*_x_type())}
    onto.reason(mode="full")
    assert closure(onto) == stepped
