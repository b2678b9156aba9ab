"""Every behaviour of the README's "How Pellet reasons on this ontology" section,
each as a scenario that changes facts and reasons again.

Unless a comment says otherwise, expectations come from that README section
(/work/shared/ontology/README.md, confirmed there by running Pellet 2.3.1).
"""

from __future__ import annotations

import pytest
from pyoxigraph import Literal, NamedNode
from support import ABOX_OWL, NOW, NS, TBOX_OWL, connected, instances, long, types_of

from topostore import Ontology
from topostore.rdf.vocab import SAME_AS, XSD


def can_reach(o: Ontology, robot: str = "Robot1") -> set[str]:
    return set(o.object_values("canReach", robot))


def consistent(o: Ontology) -> bool:
    return o.reason().consistent


def example(doors_different: bool = True, locations_different: bool = True) -> Ontology:
    """The README example environment built on topological_map.owl through the API."""
    o = Ontology.from_file(TBOX_OWL)
    for loc, door in (("C1", "D1"), ("C1", "D2"), ("R1", "D1"), ("R2", "D2")):
        o.add_fact(loc, "hasDoor", door)
    for loc, t in (("C1", NOW), ("R1", NOW - 30), ("R2", NOW - 5)):
        o.add_fact(loc, "visitedAt", long(t))
    o.add_fact("Robot1", "isIn", "C1")
    if doors_different:
        o.add_all_different(["D1", "D2"])
    if locations_different:
        o.add_all_different(["C1", "R1", "R2"])
    return o


@pytest.fixture
def onto() -> Ontology:
    o = Ontology.from_file(ABOX_OWL)
    assert consistent(o)
    return o


# ---------------------------------------------------------------- inferences follow the current state

def test_robot_moves_and_can_reach_of_the_old_place_is_gone(onto):
    # README: "after the robot moves, canReach of the old place is gone"
    assert can_reach(onto) == {"R1", "R2"}
    onto.replace("Robot1", "isIn", "R1")
    assert consistent(onto)
    assert can_reach(onto) == {"C1"}
    onto.replace("Robot1", "isIn", "R2")
    assert consistent(onto)
    assert can_reach(onto) == {"C1"}
    onto.replace("Robot1", "isIn", "C1")
    assert consistent(onto)
    assert can_reach(onto) == {"R1", "R2"}


def test_time_advances_then_a_visit_clears_urgency(onto):
    # README: URGENT iff now - visitedAt > urgencyThreshold; "after a visit updates visitedAt, URGENT clears"
    assert instances(onto, "URGENT") == {"R1"}
    onto.replace("Robot1", "now", long(NOW + 10))  # C1: 10 > 7, R1: 40, R2: 15
    assert consistent(onto)
    assert instances(onto, "URGENT") == {"C1", "R1", "R2"}
    onto.replace("R1", "visitedAt", long(NOW + 10))  # R1 just visited: 0
    assert consistent(onto)
    assert instances(onto, "URGENT") == {"C1", "R2"}
    assert types_of(onto, "R1") == {"LOCATION", "ROOM"}


def test_urgent_is_strict(onto):
    # README: "URGENT is strict: now - visitedAt > urgencyThreshold" (swrlb:greaterThan)
    onto.replace("Robot1", "now", long(NOW + 2))  # R2: exactly 7 -> not urgent
    assert consistent(onto)
    assert instances(onto, "URGENT") == {"R1"}
    onto.replace("Robot1", "now", long(NOW + 3))  # R2: 8 -> urgent
    assert consistent(onto)
    assert instances(onto, "URGENT") == {"R1", "R2"}
    onto.replace("Robot1", "urgencyThreshold", long(8))  # R2: 8 is not > 8
    assert consistent(onto)
    assert instances(onto, "URGENT") == {"R1"}


def test_location_visited_in_the_future_is_never_urgent(onto):
    # README: "a location visited in the future is never URGENT" (negative difference)
    onto.replace("R1", "visitedAt", long(NOW + 1000))
    assert consistent(onto)
    assert instances(onto, "URGENT") == set()
    onto.replace("Robot1", "now", long(NOW + 900))  # still before the visit
    assert consistent(onto)
    assert instances(onto, "URGENT") == {"C1", "R2"}


def test_location_without_visited_at_is_never_urgent(onto):
    # README: "a location without visitedAt is never URGENT"
    onto.remove_fact("R1", "visitedAt", long(NOW - 30))
    assert consistent(onto)
    assert instances(onto, "URGENT") == set()
    # R1 is still a LOCATION (hasDoor's domain) and a ROOM
    assert types_of(onto, "R1") == {"LOCATION", "ROOM"}
    onto.add_fact("L9", "hasDoor", "D9")
    assert consistent(onto)
    assert "URGENT" not in types_of(onto, "L9")
    assert types_of(onto, "L9") == {"LOCATION", "ROOM"}


def test_removing_a_door_link_makes_a_corridor_a_room(onto):
    # README: CORRIDOR needs 2 different doors; ROOM needs some door
    onto.remove_fact("C1", "hasDoor", "D2")
    assert consistent(onto)
    assert types_of(onto, "C1") == {"LOCATION", "ROOM"}
    assert connected(onto) == {("C1", "R1"), ("R1", "C1")}
    assert can_reach(onto) == {"R1"}
    onto.remove_fact("C1", "hasDoor", "D1")
    assert consistent(onto)
    # visitedAt still makes it a LOCATION; no door, so no ROOM
    assert types_of(onto, "C1") == {"LOCATION"}
    assert connected(onto) == set()
    onto.add_fact("C1", "hasDoor", "D2")
    onto.add_fact("C1", "hasDoor", "D1")
    assert consistent(onto)
    assert types_of(onto, "C1") == {"LOCATION", "ROOM", "CORRIDOR"}


def test_doors_not_declared_different_give_no_corridor():
    # README: no unique name assumption; CORRIDOR needs at least 2 *different* doors
    o = example(doors_different=False)
    assert consistent(o)
    assert types_of(o, "C1") == {"LOCATION", "ROOM"}
    assert instances(o, "CORRIDOR") == set()
    # connectedTo only needs the locations to be different
    assert connected(o) == {("C1", "R1"), ("R1", "C1"), ("C1", "R2"), ("R2", "C1")}
    o.add_fact("D1", "<http://www.w3.org/2002/07/owl#differentFrom>", "D2")
    assert consistent(o)
    assert types_of(o, "C1") == {"LOCATION", "ROOM", "CORRIDOR"}


def test_locations_not_declared_different_and_not_entailed_different_give_no_connections():
    # README: connectedTo and canReach both have a DifferentIndividuals atom; without visit
    # times nothing makes C1, R1, R2 different (they could be one location), so no rule fires.
    # Checked with Pellet 2.3.1 (scenario: the example without DISJOINT IND, R1 without visitedAt:
    # R1 gets no connectedTo).
    o = example(locations_different=False)
    for loc, t in (("C1", NOW), ("R1", NOW - 30), ("R2", NOW - 5)):
        o.remove_fact(loc, "visitedAt", long(t))
    assert consistent(o)
    assert connected(o) == set()
    assert can_reach(o) == set()
    assert types_of(o, "C1") == {"LOCATION", "ROOM", "CORRIDOR"}
    o.add_all_different(["C1", "R1"])
    assert consistent(o)
    assert connected(o) == {("C1", "R1"), ("R1", "C1")}
    assert can_reach(o) == {"R1"}


def test_locations_different_only_by_entailment_connect_but_do_not_chain():
    # Two locations with different visitedAt values cannot be the same individual (LOCATION allows
    # exactly one visitedAt), so Pellet 2.3.1 entails they are different and infers connectedTo;
    # it finds that conclusion by refutation and does not use it to fire Reachability, so there
    # is no canReach (both observed running Pellet 2.3.1 on this scenario).
    o = example(locations_different=False)
    assert consistent(o)
    assert connected(o) == {("C1", "R1"), ("R1", "C1"), ("C1", "R2"), ("R2", "C1")}
    assert can_reach(o) == set()
    # declaring them different makes the conclusions ordinary ones, which Reachability uses
    o.add_all_different(["C1", "R1", "R2"])
    assert consistent(o)
    assert can_reach(o) == {"R1", "R2"}
    # and the undeclared case again after removing the declaration (nothing stale)
    o.remove_individual("R2")
    assert consistent(o)
    assert connected(o) == {("C1", "R1"), ("R1", "C1")}


def test_a_room_with_two_different_doors_is_a_corridor(onto):
    # README: "A location with two different doors is a CORRIDOR even if it is meant as a room"
    onto.add_fact("R1", "hasDoor", "D3")
    assert consistent(onto)
    assert types_of(onto, "R1") == {"LOCATION", "ROOM", "URGENT"}  # D3 not known different from D1
    onto.add_all_different(["D1", "D2", "D3"])
    assert consistent(onto)
    assert types_of(onto, "R1") == {"LOCATION", "ROOM", "CORRIDOR", "URGENT"}


def test_corridor_is_always_a_room_and_location():
    # README: "CORRIDOR is subsumed by ROOM (a minimum of 2 implies some)"
    o = Ontology.from_file(TBOX_OWL)
    assert {o.short(c) for c in o.superclasses("CORRIDOR")} == {"ROOM", "LOCATION"}
    o.add_type("K1", "CORRIDOR")
    assert consistent(o)
    assert types_of(o, "K1") == {"CORRIDOR", "ROOM", "LOCATION"}


# ---------------------------------------------------------------- domains and ranges

def test_domains_and_ranges_type_individuals():
    # README: "Robot1 is a ROBOT even before it is anywhere"; "visitedAt alone makes a LOCATION"
    o = Ontology.from_file(TBOX_OWL)
    assert consistent(o)
    assert types_of(o, "Robot1") == {"ROBOT"}
    o.add_fact("L5", "visitedAt", long(NOW))
    o.add_fact("Robot2", "urgencyThreshold", long(3))
    o.add_fact("Robot3", "isIn", "L6")
    o.add_fact("L7", "hasDoor", "D7")
    assert consistent(o)
    assert types_of(o, "L5") == {"LOCATION"}
    assert types_of(o, "Robot2") == {"ROBOT"}
    assert types_of(o, "Robot3") == {"ROBOT"}
    assert types_of(o, "L6") == {"LOCATION"}  # isIn range
    assert types_of(o, "L7") == {"LOCATION", "ROOM"}
    assert types_of(o, "D7") == {"DOOR"}


# ---------------------------------------------------------------- inconsistencies and recovery

def _violated(o: Ontology) -> list:
    report = o.reason()
    assert not report.consistent
    assert report.violations
    return report.violations


def test_has_door_pointing_at_a_location_is_inconsistent_then_recovers(onto):
    # README: DOOR, LOCATION and ROBOT are pairwise disjoint
    onto.add_fact("C1", "hasDoor", "R1")
    violations = _violated(onto)
    v = next(v for v in violations if v.rule == "cax-dw")
    assert "DOOR" in v.axiom and "LOCATION" in v.axiom and "Disjoint" in v.axiom
    assert NamedNode(NS + "R1") in v.individuals.values()
    assert "R1" in str(v)
    assert onto.report.violations == violations
    assert not onto.is_consistent
    onto.remove_fact("C1", "hasDoor", "R1")
    assert consistent(onto)
    assert instances(onto, "URGENT") == {"R1"}


def test_two_visited_at_values_are_inconsistent_then_recover(onto):
    # README: LOCATION is exactly one visitedAt; two different values are inconsistent
    onto.add_fact("R2", "visitedAt", long(NOW - 100))
    violations = _violated(onto)
    assert any("visitedAt" in v.axiom and NamedNode(NS + "R2") in v.individuals.values() for v in violations)
    assert {v.individuals["x"] for v in violations} == {NamedNode(NS + "R2")}
    onto.remove_fact("R2", "visitedAt", long(NOW - 5))
    assert consistent(onto)
    assert instances(onto, "URGENT") == {"R1", "R2"}  # now 100 s since R2's only visit


def test_two_visited_at_values_on_a_location_without_doors_are_inconsistent():
    # README: "(also one without doors)": visitedAt's domain makes it a LOCATION
    o = Ontology.from_file(TBOX_OWL)
    o.add_fact("L1", "visitedAt", long(1))
    o.add_fact("L1", "visitedAt", long(2))
    violations = _violated(o)
    assert all(v.individuals["x"] == NamedNode(NS + "L1") for v in violations)
    o.remove_fact("L1", "visitedAt", long(2))
    assert consistent(o)


def test_robot_in_two_different_locations_is_inconsistent_then_recovers(onto):
    # README: isIn is functional and ROBOT is exactly one isIn; C1 and R1 are declared different
    onto.add_fact("Robot1", "isIn", "R1")
    violations = _violated(onto)
    # the functional property and ROBOT's "exactly one isIn", each naming the robot and both places
    assert sorted((v.rule, v.axiom, sorted(n.value for n in v.individuals.values())) for v in violations) == [
        (rule, axiom, [NS + "C1", NS + "R1", NS + "Robot1"])
        for rule, axiom in (("cls-maxqc3", "class expression (isIn exact 1 LOCATION)"), ("prp-fp", "isIn is functional"))]
    onto.remove_fact("Robot1", "isIn", "C1")
    assert consistent(onto)
    assert can_reach(onto) == {"C1"}


@pytest.mark.parametrize("bad", [Literal("abc"), Literal("1665579740.5", datatype=NamedNode(XSD + "decimal")),
                                 Literal("1.0E9", datatype=NamedNode(XSD + "double"))],
                         ids=["string", "decimal", "double"])
def test_literal_outside_the_range_datatype_is_inconsistent_then_recovers(onto, bad):
    # README/OWL 2 semantics: visitedAt's range is xsd:long; a string, a non-integer
    # decimal or a double is not in its value space (OWL 2 datatype map: double is disjoint from long)
    onto.add_fact("L8", "visitedAt", bad)
    violations = _violated(onto)
    v = next(v for v in violations if v.rule == "dt-range")
    assert "visitedAt" in v.axiom and "long" in v.axiom
    assert v.individuals["x"] == NamedNode(NS + "L8")
    onto.remove_fact("L8", "visitedAt", bad)
    assert consistent(onto)


def test_integral_decimal_is_in_the_range_of_long(onto):
    # OWL 2 datatype map: "5.0"^^xsd:decimal and 5 are the same value, which is an xsd:long
    onto.add_fact("L8", "visitedAt", Literal("5.0", datatype=NamedNode(XSD + "decimal")))
    assert consistent(onto)
    assert types_of(onto, "L8") == {"LOCATION", "URGENT"}


# ---------------------------------------------------------------- sameAs merging

def test_robot_in_two_locations_not_declared_different_merges_them(onto):
    # README: "if they are not declared different, Pellet instead concludes they are the same
    # individual (owl:sameAs) and merges their facts"
    onto.add_fact("Robot1", "isIn", "X9")
    assert consistent(onto)
    same = f"ASK {{ <{NS}X9> <{SAME_AS.value}> <{NS}C1> . <{NS}C1> <{SAME_AS.value}> <{NS}X9> }}"
    assert onto.sparql(same)
    # X9 shares C1's facts (OWL 2 RL eq-rep-s / eq-rep-o)
    assert types_of(onto, "X9") == {"LOCATION", "ROOM", "CORRIDOR"}
    assert set(onto.object_values("hasDoor", "X9")) == {"D1", "D2"}
    assert [v.value for v in onto.data_values("visitedAt", "X9")] == [str(NOW)]
    assert set(onto.object_values("connectedTo", "R1")) == {"C1", "X9"}
    # X9 is C1, which the robot is in: it reaches R1 and R2 only
    assert can_reach(onto) == {"R1", "R2"}
    onto.remove_fact("Robot1", "isIn", "X9")
    assert consistent(onto)
    assert not onto.sparql(same)
    assert types_of(onto, "X9") == set()


def test_merging_that_brings_two_visited_at_values_together_is_inconsistent(onto):
    # Derived by hand: isIn is functional, so X9 = C1 would follow; but C1 would then have
    # visitedAt 1665579740 and 100 while a LOCATION has exactly one visitedAt, so X9 and C1
    # are necessarily different, and Robot1 is in two different places -> inconsistent
    # (Pellet 2.3.1: "more than one value for the functional property isIn").
    onto.add_fact("X9", "visitedAt", long(100))
    assert consistent(onto)  # X9 alone is just another LOCATION
    onto.add_fact("Robot1", "isIn", "X9")
    violations = _violated(onto)
    assert sorted((v.rule, v.axiom, sorted(n.value for n in v.individuals.values())) for v in violations) == [
        (rule, axiom, [NS + "C1", NS + "Robot1", NS + "X9"])
        for rule, axiom in (("cls-maxqc3", "class expression (isIn exact 1 LOCATION)"), ("prp-fp", "isIn is functional"))]
    onto.remove_fact("Robot1", "isIn", "X9")
    assert consistent(onto)


# ---------------------------------------------------------------- data values

def test_same_number_as_long_and_integer_is_one_value(onto):
    # README: "The same number as xsd:long and xsd:integer is one data value"
    onto.add_fact("R1", "visitedAt", Literal(str(NOW - 30), datatype=NamedNode(XSD + "integer")))
    assert consistent(onto)  # not two different visitedAt values
    assert len(onto.data_values("visitedAt", "R1")) == 1
    assert instances(onto, "URGENT") == {"R1"}


def test_replace_matches_old_values_by_data_value(onto):
    # README: a REPLACE whose old value has another type leaves the old value in place
    assert onto.replace("R1", "visitedAt", long(NOW), old=Literal(str(NOW - 30))) == 0  # xsd:string: no match
    assert {v.value for v in onto.data_values("visitedAt", "R1")} == {str(NOW - 30), str(NOW)}
    assert not consistent(onto)  # two different visitedAt values
    onto.remove_fact("R1", "visitedAt", long(NOW))
    assert consistent(onto)
    # the same number as xsd:integer matches the stored xsd:long
    assert onto.replace("R1", "visitedAt", long(NOW), old=NOW - 30) == 1
    assert [v.value for v in onto.data_values("visitedAt", "R1")] == [str(NOW)]
    assert consistent(onto)
    assert instances(onto, "URGENT") == set()


def test_reasoning_again_never_keeps_conclusions_of_removed_premises(onto):
    # README: "Reasoning again must never keep conclusions whose premises were removed"
    onto.remove_individual("C1")
    assert consistent(onto)
    assert connected(onto) == set()
    assert can_reach(onto) == set()
    assert types_of(onto, "C1") == set()
    # R1, R2 remain rooms; D1, D2 doors
    assert types_of(onto, "R1") == {"LOCATION", "ROOM", "URGENT"}
    assert types_of(onto, "D2") == {"DOOR"}
