"""The command lanes (armor/lanes.py): the robot's four command shapes answered before the command table, the
same replies as the general path, and what a lane keeps per reference dropped when the rules change."""

from __future__ import annotations

import pytest
from pyoxigraph import Triple
from support import IRI, SHARED

from topostore.armor import ArmorService, lanes
from topostore.armor.service import ArmorService as Service
from topostore.rdf.vocab import TYPE, owl

STEP = [("REPLACE", "OBJECTPROP", "IND", ["isIn", "Robot1", "R1", "C1"]),
        ("REPLACE", "DATAPROP", "IND", ["now", "Robot1", "LONG", "1665579750", "1665579740"]),
        ("REASON", "", "", []),
        ("QUERY", "OBJECTPROP", "IND", ["canReach", "Robot1"]),
        ("QUERY", "IND", "CLASS", ["URGENT"])]


def _service(short_names: bool = False) -> ArmorService:
    service = ArmorService(short_names=short_names)
    reply = service.call({"reference_name": "ref", "command": "LOAD", "primary_command_spec": "FILE",
                          "args": [str(SHARED / "topological_map_abox.owl"), IRI, "false", "PELLET", "true"]})
    assert reply.success, reply
    return service


def _request(command: str, primary: str, secondary: str, args: list[str], client: str = "") -> dict:
    return {"client_name": client, "reference_name": "ref", "command": command, "primary_command_spec": primary,
            "secondary_command_spec": secondary, "args": args}


@pytest.mark.parametrize("short_names", [False, True])
def test_the_robot_step_takes_the_lanes_and_answers_as_the_general_path(monkeypatch: pytest.MonkeyPatch,
                                                                         short_names: bool) -> None:
    """Every command of a robot step but REASON is answered by a lane (the command table is never asked), with
    the replies the general path gives."""
    off = _service(short_names)
    monkeypatch.setattr(lanes, "ENABLED", False)
    expected = [off.call(_request(*c)).to_dict() for c in STEP]
    monkeypatch.setattr(lanes, "ENABLED", True)
    on = _service(short_names)
    dispatched = []
    general = Service._dispatch

    def dispatch(self, req):
        dispatched.append(req.command)
        return general(self, req)

    monkeypatch.setattr(Service, "_dispatch", dispatch)
    assert [on.call(_request(*c)).to_dict() for c in STEP] == expected
    assert dispatched == ["REASON"]
    assert expected[3]["queried_objects"] and expected[4]["queried_objects"]


@pytest.mark.parametrize("command", [
    ("REPLACE", "DATAPROP", "IND", ["now", "Robot1", "LONGISH", "1", "2"]),  # an unknown type
    ("REPLACE", "DATAPROP", "IND", ["now", "Robot1", "LONG", "x", "1665579740"]),  # not a long
    ("REPLACE", "OBJECTPROP", "IND", ["isIn", "Robot 1", "R1", "C1"]),  # an illegal name
    ("REPLACE", "OBJECTPROP", "IND", ["isIn", "Robot1", "R1"]),  # an argument missing
    ("QUERY", "OBJECTPROP", "IND", ["canReach"]),
    ("QUERY", "IND", "CLASS", ["URG ENT"]),
    ("REPLACE", "OBJECTPROP", "IND", ["isIn", "Robot1", "R1", "R2"]),  # the old value not held
])
def test_what_a_lane_does_not_take_is_the_general_paths(monkeypatch: pytest.MonkeyPatch, command: tuple) -> None:
    """A command a lane cannot answer plainly gets the general path's reply, error and exit code included."""
    replies = []
    for enabled in (False, True):
        monkeypatch.setattr(lanes, "ENABLED", enabled)
        service = _service()
        replies.append((service.call(_request(*command)).to_dict(),
                        service.call(_request("QUERY", "OBJECTPROP", "IND", ["isIn", "Robot1"])).to_dict()))
    assert replies[0] == replies[1]


def test_a_reference_mounted_by_another_client_is_refused_as_before() -> None:
    service = _service()
    assert service.call(_request("MOUNT", "", "", [], client="a")).success
    reply = service.call(_request(*STEP[0], client="b"))
    assert not reply.success and "mounted by client" in reply.error_description


def test_a_property_declared_an_object_property_later_gives_a_data_value_its_note() -> None:
    """The lane keeps whether a property is a plain fact property for the compiled rules it read: a TBox
    change (a property declared an object property) makes the next REPLACE of a data value say its note."""
    service = _service()
    call = service.call
    assert call(_request("ADD", "DATAPROP", "IND", ["gauge", "Robot1", "LONG", "1"])).success
    first = call(_request("REPLACE", "DATAPROP", "IND", ["gauge", "Robot1", "LONG", "2", "1"]))
    assert first.success and first.error_description == ""
    onto = service.reference("ref").ontology
    onto.add(Triple(onto.iri("gauge"), TYPE, owl("ObjectProperty")))
    assert call(_request("REASON", "", "", [])).success
    second = call(_request("REPLACE", "DATAPROP", "IND", ["gauge", "Robot1", "LONG", "3", "2"]))
    assert second.success and "is an object property" in second.error_description
