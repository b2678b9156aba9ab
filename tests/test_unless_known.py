"""Asks a full REASON leaves out where a conclusion is known (topostore.reason.negation), kept exact.

Connectability's pairs are asked of the value rules only where ``connectedTo`` is not known, and
Reachability's ask is not run while every ``connectedTo`` is Connectability's.  What is published
(inferred and entailed-only facts) must stay what it was whenever a declaration, an asserted link or a
value comes or goes; the helper graph holds what a REASON from scratch holds, and beyond it only such
asks on pairs whose conclusion is known.
"""

from __future__ import annotations

from pyoxigraph import NamedNode, Triple
from test_incremental import (
    N,
    all_different,
    assert_same_as_scratch,
    different_from,
    drop_all_different,
    new_map,
    robot_step,
    visit,
)

from topostore.rdf.vocab import ASSERTED, AUX, ENTAILED, ENTAILED_PREFIX, INFERRED, owl

RDFS_SUB_PROPERTY = NamedNode("http://www.w3.org/2000/01/rdf-schema#subPropertyOf")


def _entailed(onto, name: str) -> set[tuple[str, str]]:
    return {(onto.short(t.subject), onto.short(t.object)) for t in onto.store.triples(None, N(name), None, ENTAILED)}


def _asked(onto) -> int:
    return sum(1 for t in onto.store.triples(graph=AUX) if t.predicate.value.endswith("valueCandidate"))


def test_declared_pairs_are_not_asked_and_undeclared_ones_are() -> None:
    grouped, plain = new_map(12, 3, True), new_map(12, 3, False)
    assert_same_as_scratch(grouped)
    assert_same_as_scratch(plain)
    assert _asked(grouped) == 0 and not _entailed(grouped, "connectedTo")
    twin = N("connectedTo").value
    links = {(plain.short(t.subject), plain.short(t.object)) for t in plain.store.triples(graph=AUX)
             if t.predicate.value == ENTAILED_PREFIX + twin}
    assert _asked(plain) > 0 and links and _entailed(plain, "connectedTo") == links
    assert not any(t.predicate == N("connectedTo") for t in plain.store.triples(graph=INFERRED))


def test_a_group_added_and_removed_in_steps() -> None:
    onto = new_map(10, 4, False)
    assert_same_as_scratch(onto)
    published = _entailed(onto, "connectedTo")
    assert published
    all_different(onto, [f"R{k}" for k in range(1, 40)] + [f"C{k}" for k in range(1, 10)])
    assert_same_as_scratch(onto)
    assert not _entailed(onto, "connectedTo")
    drop_all_different(onto, 0)
    assert_same_as_scratch(onto)  # the pairs left out are asked again
    assert _entailed(onto, "connectedTo") == published


def test_a_withdrawn_declaration_in_a_grouped_map_asks_its_pair_again() -> None:
    onto = new_map(8, 5, False)
    all_different(onto, [f"R{k}" for k in range(1, 30)] + [f"C{k}" for k in range(1, 8)])
    assert_same_as_scratch(onto)
    links = sorted((onto.short(t.subject), onto.short(t.object)) for t in onto.store.triples(None, N("connectedTo"), None, INFERRED))
    a, b = links[0]
    # declared twice (group and differentFrom), then the group goes: the differentFrom keeps the link
    different_from(onto, a, b, True)
    assert_same_as_scratch(onto)
    drop_all_different(onto, 0)
    assert_same_as_scratch(onto)
    assert (a, b) not in _entailed(onto, "connectedTo")
    different_from(onto, a, b, False)
    report = onto.reason()
    assert report.stats.mode == "incremental", report.stats.reason
    assert_same_as_scratch(onto)
    assert (a, b) in _entailed(onto, "connectedTo")


def test_an_asserted_link_to_an_undeclared_place_is_asked_by_reachability() -> None:
    onto = new_map(8, 6, True)
    assert_same_as_scratch(onto)
    robot_step(onto, "C1", 1_665_579_750)
    assert_same_as_scratch(onto)
    # a place outside the group, linked by an asserted fact, with its own visit time
    onto.add(Triple(N("C1"), N("connectedTo"), N("Outside")))
    visit(onto, "Outside", 1_665_579_000)
    assert_same_as_scratch(onto)
    assert ("Robot1", "Outside") in _entailed(onto, "canReach")
    robot_step(onto, "R1", 1_665_579_760)
    assert_same_as_scratch(onto)
    robot_step(onto, "C1", 1_665_579_770)
    assert_same_as_scratch(onto)
    assert ("Robot1", "Outside") in _entailed(onto, "canReach")
    onto.remove(Triple(N("C1"), N("connectedTo"), N("Outside")))
    assert_same_as_scratch(onto)
    assert ("Robot1", "Outside") not in _entailed(onto, "canReach")


def test_an_alias_of_a_member_and_members_of_two_groups() -> None:
    onto = new_map(8, 7, False)
    places = [f"R{k}" for k in range(1, 30)] + [f"C{k}" for k in range(1, 8)]
    all_different(onto, places[: len(places) // 2 + 2])
    all_different(onto, places[len(places) // 2 - 2:])  # four members in both groups
    assert_same_as_scratch(onto)
    alias = Triple(N("Alias"), owl("sameAs"), N("C1"))
    onto.add(alias)
    assert_same_as_scratch(onto)
    drop_all_different(onto, 0)
    assert_same_as_scratch(onto)
    onto.remove(alias)
    assert_same_as_scratch(onto)
    drop_all_different(onto, 0)
    assert_same_as_scratch(onto)
    assert _entailed(onto, "connectedTo")  # no group left: the pairs different by visit times


def test_visit_times_made_equal_and_apart_on_an_undeclared_link() -> None:
    onto = new_map(6, 8, False)
    assert_same_as_scratch(onto)
    a, b = sorted(_entailed(onto, "connectedTo"))[0]
    same = next(iter(onto.store.triples(N(a), N("visitedAt"), None))).object
    before = next(iter(onto.store.triples(N(b), N("visitedAt"), None))).object
    visit(onto, b, int(same.value))
    assert_same_as_scratch(onto)
    assert (a, b) not in _entailed(onto, "connectedTo")
    visit(onto, b, int(before.value))
    assert_same_as_scratch(onto)
    assert (a, b) in _entailed(onto, "connectedTo")



def test_reachability_is_asked_where_equality_also_writes_links() -> None:
    """Reachability's ask is left out only while every rule that may write ``connectedTo`` is
    Connectability's conclusion: owl:sameAs replacement writes any predicate, so an alias's link is asked."""
    from pyoxigraph import NamedNode

    from topostore import Ontology
    from topostore.resources import default_ontology_files

    ns = "http://bnc/exp-rob-lab/2022-23#"
    onto = Ontology.from_file(*default_ontology_files())
    onto.load_data(f"""@prefix : <{ns}> . @prefix owl: <http://www.w3.org/2002/07/owl#> .
        @prefix xsd: <http://www.w3.org/2001/XMLSchema#> .
        :Y a :LOCATION ; :visitedAt "1665579000"^^xsd:long . :Z owl:sameAs :Y .""")
    onto.reason()
    onto.add(Triple(NamedNode(ns + "C1"), NamedNode(ns + "connectedTo"), NamedNode(ns + "Y")))

    def reach() -> set[str]:
        return {onto.short(t.object) for t in onto.store.triples(NamedNode(ns + "Robot1"), NamedNode(ns + "canReach"),
                                                                 None, ENTAILED)}

    onto.reason()
    assert {"Y", "Z"} <= reach()
    onto.reason(mode="full")
    assert {"Y", "Z"} <= reach()


def test_a_derived_door_of_an_undeclared_place_is_asked() -> None:
    """The deferred ask reads a key in the asserted graph alone only while no rule derived it: a door
    derived through a subproperty must still be asked about (and its twin published)."""
    onto = new_map(8, 7, True)
    room, _, door = next(iter(onto.store.triples(None, N("hasDoor"), None, ASSERTED)))
    onto.add(Triple(N("hasEntrance"), RDFS_SUB_PROPERTY, N("hasDoor")),
             Triple(N("Annex"), N("hasEntrance"), door))
    visit(onto, "Annex", 3)
    report = onto.reason(mode="full")
    assert report.consistent
    short = onto.short(room)
    assert {("Annex", short), (short, "Annex")} <= _entailed(onto, "connectedTo")
    sharing = {t.subject for t in onto.store.triples(None, N("hasDoor"), door, ASSERTED)}
    assert _asked(onto) == 2 * len(sharing)  # Annex and each place of the door, both ways
    assert_same_as_scratch(onto)
