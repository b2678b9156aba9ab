"""The AllDifferent keys' form (topostore.compile.key_form): a member is its own key while the asserted
graph holds one member list, a key names its list and member otherwise; a change that makes one list two
(or two one) compiles the rules again and reasons in full, and every answer is the one a fresh ontology
gives on the same asserted facts."""

from __future__ import annotations

import pytest
from pyoxigraph import NamedNode, Triple

from topostore import Ontology
from topostore.compile.key_form import one_member_list
from topostore.rdf.vocab import ASSERTED, AUX, DIFFERENT_KEY_OF, INFERRED, KEY_PREFIX, OWL

NS = "http://example.org/keys#"
HEAD = f"""@prefix : <{NS}> . @prefix owl: <http://www.w3.org/2002/07/owl#> .
<http://example.org/keys> a owl:Ontology .
:p a owl:ObjectProperty . :D a owl:Class . :C a owl:Class .
:C owl:equivalentClass [ a owl:Restriction ; owl:onProperty :p ; owl:minQualifiedCardinality 2 ; owl:onClass :D ] .
:a a :D . :b a :D . :c a :D . :d a :D .
"""
ONE_LIST = HEAD + "[] a owl:AllDifferent ; owl:distinctMembers (:a :b :c) .\n:x :p :a, :b .\n"


def _n(name: str) -> NamedNode:
    return NamedNode(NS + name)


def _instances(onto: Ontology, cls: str = "C") -> set[str]:
    return {onto.short(i) for i in onto.instances(cls)}


def _keys(onto: Ontology) -> set[tuple[str, str]]:
    return {(t.subject.value, t.object.value) for t in onto.store.triples(None, DIFFERENT_KEY_OF, None, AUX)}


def _closure(onto: Ontology) -> tuple[set, set, bool]:
    """The inferred and helper graphs (the keys left out: their form may differ) and the consistency."""
    report = onto.reason()
    inferred = set(onto.store.triples(graph=INFERRED))
    aux = {t for t in onto.store.triples(graph=AUX) if t.predicate != DIFFERENT_KEY_OF}
    return inferred, aux, report.consistent


def _fresh(onto: Ontology) -> tuple[set, set, bool]:
    """What a fresh ontology holding ``onto``'s asserted facts concludes."""
    fresh = Ontology()
    fresh.add(*onto.store.triples(graph=ASSERTED))
    return _closure(fresh)


def test_one_member_list_keys_each_member_by_itself() -> None:
    onto = Ontology()
    onto.load_data(ONE_LIST, "turtle")
    assert onto.rules.one_list
    assert onto.reason().consistent
    assert _keys(onto) == {(_n(m).value, _n(m).value) for m in "abc"}
    assert _instances(onto) == {"x"}


def test_members_merged_in_the_one_list_are_a_clash() -> None:
    onto = Ontology()
    onto.load_data(ONE_LIST + ":a owl:sameAs :b .\n", "turtle")
    assert onto.rules.one_list
    assert not onto.reason().consistent


def test_a_member_the_same_as_an_outsider_is_not_different_from_it() -> None:
    onto = Ontology()
    onto.load_data(ONE_LIST + ":a owl:sameAs :d .\n:y :p :a, :d .\n", "turtle")
    assert onto.rules.one_list
    assert onto.reason().consistent
    assert _instances(onto) == {"x"}  # a and d are one value of y


@pytest.mark.parametrize("lists", [
    "[] a owl:AllDifferent ; owl:distinctMembers (:a :b :c) . [] a owl:AllDifferent ; owl:distinctMembers (:d :a) .",
    "[] a owl:AllDifferent ; owl:members (:a :b) , (:c :d) .",  # one node, two lists
])
def test_two_lists_key_by_list(lists: str) -> None:
    onto = Ontology()
    onto.load_data(HEAD + lists + "\n:x :p :a, :b .\n:y :p :b, :c .\n", "turtle")
    assert not onto.rules.one_list
    onto.reason()
    assert _keys(onto) and all(k.startswith(KEY_PREFIX) for k, _ in _keys(onto))
    assert _instances(onto) == {"x", "y"} if "(:a :b :c)" in lists else _instances(onto) == {"x"}


def test_a_tbox_list_does_not_count() -> None:
    onto = Ontology()
    onto.load_data(ONE_LIST + ":E a owl:Class . :F a owl:Class .\n[] a owl:AllDisjointClasses ; owl:members (:E :F) .\n",
                   "turtle")
    assert onto.rules.one_list


def test_a_second_list_told_later_changes_the_form_and_reasons_in_full() -> None:
    """Two members of two lists, told the same: consistent (they are not in one group).  Had the second
    list's members been their own keys too, the two lists would be one group and the merge a clash."""
    onto = Ontology()
    onto.load_data(ONE_LIST, "turtle")
    assert onto.reason().consistent and onto.rules.one_list
    onto.load_data(f"@prefix : <{NS}> . @prefix owl: <http://www.w3.org/2002/07/owl#> .\n"
                   "[] a owl:AllDifferent ; owl:distinctMembers (:d :x) .\n:a owl:sameAs :d .\n", "turtle")
    report = onto.reason()
    assert report.stats.mode == "full"
    assert not onto.rules.one_list
    assert all(k.startswith(KEY_PREFIX) for k, _ in _keys(onto))
    assert report.consistent and _instances(onto) == {"x"}
    assert _closure(onto) == _fresh(onto)


def test_a_list_removed_later_turns_back_to_members_as_keys() -> None:
    onto = Ontology()
    onto.load_data(HEAD + "[] a owl:AllDifferent ; owl:distinctMembers (:a :b) .\n"
                   "[] a owl:AllDifferent ; owl:distinctMembers (:c :d) .\n:x :p :a, :b .\n:y :p :b, :c .\n", "turtle")
    assert onto.reason().consistent and not onto.rules.one_list
    assert _instances(onto) == {"x"}  # b and c are of two lists: not known different
    second = [t for t in onto.store.triples(None, NamedNode(str(OWL) + "distinctMembers"), None, ASSERTED)
              if _n("c") in onto.store.list_items(t.object, ASSERTED)]
    onto.remove(*second)
    report = onto.reason()
    assert report.stats.mode == "full" and onto.rules.one_list
    assert {k for k, _ in _keys(onto)} == {_n("a").value, _n("b").value}
    assert _instances(onto) == {"x"}
    onto.add(*(Triple(_n("y"), _n("p"), _n(m)) for m in "ab"))
    assert onto.reason().stats.mode == "incremental" and _instances(onto) == {"x", "y"}
    assert _closure(onto) == _fresh(onto)


def test_a_change_within_the_one_list_stays_incremental() -> None:
    onto = Ontology()
    onto.load_data(ONE_LIST, "turtle")
    onto.reason()
    onto.add(Triple(_n("y"), _n("p"), _n("c")), Triple(_n("y"), _n("p"), _n("a")))
    report = onto.reason()
    assert report.stats.mode == "incremental", report.stats.reason
    assert _closure(onto) == _fresh(onto)


def test_one_member_list_counts_lists_not_nodes() -> None:
    onto = Ontology()
    onto.load_data(HEAD + "_:g a owl:AllDifferent ; owl:distinctMembers _:l .\n"
                   "_:h a owl:AllDifferent ; owl:distinctMembers _:l .\n_:l <http://www.w3.org/1999/02/22-rdf-syntax-ns#first> :a ;"
                   " <http://www.w3.org/1999/02/22-rdf-syntax-ns#rest> () .\n", "turtle")
    assert one_member_list(onto.store, ASSERTED)


def test_cells_of_the_one_list_edited_incrementally() -> None:
    """A member appended to the one list and another taken out, each maintained incrementally: the keys
    follow (a member its own key) and the closure is a fresh ontology's."""
    rest, first, nil = (NamedNode(f"http://www.w3.org/1999/02/22-rdf-syntax-ns#{n}") for n in ("rest", "first", "nil"))
    onto = Ontology()
    onto.load_data(ONE_LIST + ":y :p :c, :d .\n", "turtle")
    assert onto.reason().consistent and _instances(onto) == {"x"}
    last = next(iter(onto.store.triples(None, rest, nil, ASSERTED)))
    cell = NamedNode("urn:topostore:bnode:appended")
    onto.remove(last)
    onto.add(Triple(last.subject, rest, cell), Triple(cell, first, _n("d")), Triple(cell, rest, nil))
    report = onto.reason(mode="incremental")
    assert report.stats.mode == "incremental" and onto.rules.one_list
    assert _instances(onto) == {"x", "y"} and (_n("d").value, _n("d").value) in _keys(onto)
    assert _closure(onto) == _fresh(onto)
    onto.remove(next(iter(onto.store.triples(None, first, _n("a"), ASSERTED))))
    assert onto.reason(mode="incremental").stats.mode == "incremental"
    assert _instances(onto) == {"y"} and len(_keys(onto)) == 3
    assert _closure(onto) == _fresh(onto)


@pytest.mark.parametrize("lists", [
    # a node typed AllDifferent and AllDisjointClasses: its list is not counted, yet the key rule walks it
    "[] a owl:AllDifferent , owl:AllDisjointClasses ; owl:members (:a :b) .\n"
    "[] a owl:AllDifferent ; owl:distinctMembers (:c :d) .",
    # a member link only inferred (a sub-property of owl:members)
    ":m rdfs:subPropertyOf owl:members .\n:g a owl:AllDifferent ; owl:members (:a :b) ; :m (:c :d) .",
    # an AllDisjointClasses node the same as the AllDifferent one: its list reached through sameAs
    ":g a owl:AllDifferent ; owl:members (:a :b) .\n:h a owl:AllDisjointClasses ; owl:members (:c :d) .\n"
    ":h owl:sameAs :g .",
    # a property equivalent to owl:distinctMembers linking a second node
    ":m owl:equivalentProperty owl:distinctMembers .\n:g a owl:AllDifferent ; owl:members (:a :b) .\n"
    ":h a owl:AllDifferent ; :m (:c :d) .",
])
def test_a_list_reached_only_by_inference_is_a_group_of_its_own(lists: str) -> None:
    """Members of the counted list and of a list the key rule reaches otherwise are not different: a
    member of each told the same is no clash (OWL 2 RL reads each list apart)."""
    onto = Ontology()
    onto.load_data(HEAD.replace("@prefix owl:", "@prefix rdfs: <http://www.w3.org/2000/01/rdf-schema#> . @prefix owl:")
                   + lists + "\n:a owl:sameAs :c .\n", "turtle")
    assert onto.rules.one_list
    assert onto.reason().consistent
    merged = Ontology()  # the same with a clash inside the counted list: found
    merged.load_data(HEAD.replace("@prefix owl:", "@prefix rdfs: <http://www.w3.org/2000/01/rdf-schema#> . @prefix owl:")
                     + lists + "\n:a owl:sameAs :b .\n", "turtle")
    assert not merged.reason().consistent


def test_a_first_document_compiled_as_streamed_is_not_read_for_its_lists_again(monkeypatch: pytest.MonkeyPatch) -> None:
    """The rules compiled right after a document is streamed into the empty graph are the graph's own: the
    first REASON does not walk its member lists again (a cut list's notice is still the one said), while a
    list edited later is (its notice follows the edit)."""
    from topostore.ontology import reasoning

    walked: list[int] = []
    real = reasoning.malformed_now

    def counted(*args, **kwargs):
        walked.append(1)
        return real(*args, **kwargs)

    monkeypatch.setattr(reasoning, "malformed_now", counted)
    onto = Ontology()
    cut = ONE_LIST.replace("owl:distinctMembers (:a :b :c)", "owl:distinctMembers _:l1 .\n"
                           "_:l1 rdf:first :a ; rdf:rest _:l2 .\n_:l2 rdf:first :b").replace(
        "@prefix owl:", "@prefix rdf: <http://www.w3.org/1999/02/22-rdf-syntax-ns#> . @prefix owl:")
    onto.load_data(cut, "turtle")
    report = onto.reason()
    assert walked == [] and onto.rules.one_list
    assert any("does not end in rdf:nil" in n.subject for n in report.incomplete)
    cell = next(t for t in onto.store.triples(None, NamedNode("http://www.w3.org/1999/02/22-rdf-syntax-ns#first"),
                                               _n("b"), ASSERTED))
    onto.add(Triple(cell.subject, NamedNode("http://www.w3.org/1999/02/22-rdf-syntax-ns#rest"),
                    NamedNode("http://www.w3.org/1999/02/22-rdf-syntax-ns#nil")))
    report = onto.reason()
    assert walked == [1]
    assert not any("does not end in rdf:nil" in n.subject for n in report.incomplete)
    assert _closure(onto) == _fresh(onto)
