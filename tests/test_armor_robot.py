"""A robot surveys a map of two corridors and four rooms, built and driven only through ArmorClient.

Map (doors in brackets):   R1 [D1] C1 [D2] R2
                                   C1 [D5] C2
                           R3 [D3] C2 [D4] R4
Expectations come from the rules in shared/ontology/README.md:
* Connectability: two different LOCATIONs sharing a door are connectedTo each other, so
  C1↔R1, C1↔R2, C1↔C2, C2↔R3, C2↔R4.
* Reachability: the robot canReach every location connectedTo the one it isIn.
* Urgency: a LOCATION is URGENT iff now - visitedAt > urgencyThreshold (7 for Robot1, strict).
"""

from __future__ import annotations

from support import IRI
from support import TBOX_OWL as TBOX

from topostore.armor import ArmorService
from topostore.armor_api.armor_client import ArmorClient

DOORS = {"C1": ["D1", "D2", "D5"], "C2": ["D5", "D3", "D4"], "R1": ["D1"], "R2": ["D2"], "R3": ["D3"], "R4": ["D4"]}
# connectedTo derived by hand from shared doors (Connectability rule)
NEIGHBOURS = {"C1": ["C2", "R1", "R2"], "C2": ["C1", "R3", "R4"], "R1": ["C1"], "R2": ["C1"], "R3": ["C2"], "R4": ["C2"]}

# (time, destination, URGENT afterwards): URGENT worked out by hand as now - visitedAt > 7
MOVES = [
    (1005, "R1", []),                          # everything else last visited at 1000: 5 ≤ 7
    (1010, "C1", ["C2", "R2", "R3", "R4"]),     # 10 > 7 for the four never revisited; R1 5
    (1012, "R2", ["C2", "R3", "R4"]),          # R1: 1012-1005 = 7, not > 7
    (1014, "C1", ["C2", "R1", "R3", "R4"]),     # R1: 9 > 7; R2: 2
    (1016, "C2", ["R1", "R3", "R4"]),          # C1: 2, R2: 4
    (1020, "R3", ["R1", "R2", "R4"]),          # R2: 8 > 7; C1: 6; C2: 4
    (1022, "C2", ["C1", "R1", "R2", "R4"]),     # C1: 1022-1014 = 8 > 7; R3: 2
    (1025, "R4", ["C1", "R1", "R2"]),          # R3: 5; C2: 3
    (1027, "C2", ["C1", "R1", "R2"]),          # R3: 1027-1020 = 7, not > 7; R4: 2
    (1030, "C1", ["R1", "R2", "R3"]),          # R3: 10; R4: 5; C2: 3
    (1031, "R1", ["R2", "R3"]),                # R2: 1031-1012 = 19; R3: 11; R4: 6; C2: 4; C1: 1
]


def build_map(client: ArmorClient) -> None:
    """Locations, doors, visits at t=1000, the robot in C1, everything declared different."""
    client.utils.load_ref_from_file(str(TBOX), IRI, buffered_manipulation=True, reasoner="PELLET", buffered_reasoner=True)
    for location, doors in DOORS.items():
        for door in doors:
            client.manipulation.add_objectprop_to_ind("hasDoor", location, door)
        client.manipulation.add_dataprop_to_ind("visitedAt", location, "LONG", "1000")
    client.manipulation.replace_one_dataprop_b2_ind("now", "Robot1", "LONG", "1000")
    client.manipulation.add_objectprop_to_ind("isIn", "Robot1", "C1")
    client.utils.apply_buffered_changes()
    assert client.utils.sync_buffered_reasoner() is True
    client.manipulation.disj_inds_of_class("LOCATION")  # hasDoor's domain/range typed them
    client.manipulation.disj_inds_of_class("DOOR")
    assert client.utils.sync_buffered_reasoner() is True


def test_robot_surveys_the_map() -> None:
    client = ArmorClient("surveyor", "robot_map", transport=ArmorService())
    build_map(client)
    # two different doors each: both corridors are CORRIDORs, no room is
    assert sorted(client.query.ind_b2_class("CORRIDOR")) == ["C1", "C2"]
    assert sorted(client.query.ind_b2_class("LOCATION")) == sorted(DOORS)
    assert sorted(client.query.objectprop_b2_ind("canReach", "Robot1")) == NEIGHBOURS["C1"]
    assert client.query.ind_b2_class("URGENT") == []

    here, now = "C1", 1000
    for time, destination, urgent in MOVES:
        assert destination in NEIGHBOURS[here], "the plan only uses doors"
        client.manipulation.replace_objectprop_b2_ind("isIn", "Robot1", destination, here)
        client.manipulation.replace_dataprop_b2_ind("now", "Robot1", "LONG", str(time), str(now))
        client.manipulation.replace_one_dataprop_b2_ind("visitedAt", destination, "LONG", str(time))
        assert client.utils.sync_buffered_reasoner() is True, f"inconsistent after moving to {destination}"
        here, now = destination, time
        assert sorted(client.query.objectprop_b2_ind("canReach", "Robot1")) == NEIGHBOURS[here], (time, here)
        assert sorted(client.query.ind_b2_class("URGENT")) == urgent, (time, here)
        assert client.query.objectprop_b2_ind("isIn", "Robot1") == [here]
        assert client.query.dataprop_b2_ind("visitedAt", here) == [f'"{time}"^^xsd:long']
