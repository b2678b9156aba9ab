"""The armor_py_api drop-in client: tutorial, return types, exceptions and the fixed client bugs."""

from __future__ import annotations

from pathlib import Path

import pytest
import rdflib
from rdflib.compare import isomorphic
from support import ABOX_OWL as ABOX
from support import IRI
from support import TBOX_OWL as TBOX

from topostore.armor import ArmorRequest, ArmorResponse, ArmorService
from topostore.armor_api import armor_exceptions, transport
from topostore.armor_api.armor_client import ArmorClient
from topostore.armor_api.armor_exceptions import ArmorPyException, ArmorServiceCallError, ArmorServiceInternalError


class Recorder:
    """A transport that records requests and forwards them to a real service."""

    def __init__(self) -> None:
        self.service = ArmorService()
        self.requests: list[ArmorRequest] = []

    def call(self, request: ArmorRequest) -> ArmorResponse:
        self.requests.append(request)
        return self.service.call(request)

    def call_many(self, requests):
        return self.service.call_many(requests)


@pytest.fixture
def rec() -> Recorder:
    return Recorder()


@pytest.fixture
def client(rec: Recorder) -> ArmorClient:
    c = ArmorClient("tester", "ref", transport=rec)
    c.utils.load_ref_from_file(str(ABOX), IRI, True, "PELLET", True)
    return c


def last(rec: Recorder) -> tuple:
    r = rec.requests[-1]
    return (r.client_name, r.reference_name, r.command, r.primary_command_spec, r.secondary_command_spec, r.args)


def test_seed_tutorial_through_client(rec: Recorder, tmp_path: Path) -> None:
    client = ArmorClient("example", "ontoRef", transport=rec)
    client.utils.load_ref_from_file(str(TBOX), IRI, True, "PELLET", True)
    assert last(rec) == ("example", "ontoRef", "LOAD", "FILE", "", [str(TBOX), IRI, "True", "PELLET", "True"])
    for door in ("D6", "D7"):
        client.manipulation.add_objectprop_to_ind("hasDoor", "E", door)
    client.manipulation.add_objectprop_to_ind("hasDoor", "R3", "D6")
    client.manipulation.add_batch_dataprop_to_ind("E", [["visitedAt", "LONG", "1665579700"]])
    client.manipulation.add_dataprop_to_ind("visitedAt", "R3", "LONG", "1665579735")
    client.call("DISJOINT", "IND", "", ["E", "R3", "D6", "D7"])
    client.manipulation.add_objectprop_to_ind("isIn", "Robot1", "R3")
    client.manipulation.replace_objectprop_b2_ind("isIn", "Robot1", "E", "R3")
    assert client.utils.sync_buffered_reasoner() is True
    assert client.query.dataprop_b2_ind("now", "Robot1") == ['"1665579740"^^xsd:long']
    assert client.manipulation.replace_one_dataprop_b2_ind("now", "Robot1", "LONG", "1665579750") is True
    assert last(rec)[2:] == ("REPLACE", "DATAPROP", "IND", ["now", "Robot1", "LONG", "1665579750", "1665579740"])
    client.manipulation.replace_one_dataprop_b2_ind("visitedAt", "E", "LONG", "1665579750")
    client.utils.sync_buffered_reasoner()
    assert client.query.objectprop_b2_ind("canReach", "Robot1") == ["R3"]
    assert client.query.objectprop_b2_ind("canReach", "Robot1", with_URI=True) == [f"<{IRI}#R3>"]
    assert client.query.ind_b2_class("URGENT") == ["R3"]
    assert client.query.dataprop_b2_ind("now", "Robot1") == ['"1665579750"^^xsd:long']
    client.utils.save(str(tmp_path / "out.owl"))
    assert (tmp_path / "out.owl").is_file()


def test_default_transport_is_shared_in_process_service() -> None:
    transport.set_default_service(None)
    a = ArmorClient("a", "shared")
    b = ArmorClient("b", "shared")
    assert a.transport is b.transport is transport.default_service()
    a.utils.load_ref_from_file(str(ABOX), IRI)
    assert b.query.ind_b2_class("URGENT") == ["R1"]
    transport.set_default_service(None)


def test_requests_match_armor_py_api(client: ArmorClient, rec: Recorder) -> None:
    m, q, u = client.manipulation, client.query, client.utils
    expected = [
        (lambda: m.add_ind_to_class("K", "ROOM"), ("ADD", "IND", "CLASS", ["K", "ROOM"])),
        (lambda: m.disj_inds_of_class("DOOR"), ("DISJOINT", "IND", "CLASS", ["DOOR"])),
        (lambda: m.add_dataprop_to_ind("visitedAt", "K", "LONG", "5"), ("ADD", "DATAPROP", "IND", ["visitedAt", "K", "LONG", "5"])),
        (lambda: m.replace_dataprop_b2_ind("visitedAt", "K", "LONG", "6", "5"),
         ("REPLACE", "DATAPROP", "IND", ["visitedAt", "K", "LONG", "6", "5"])),
        (lambda: m.remove_dataprop_from_ind("visitedAt", "K", "LONG", "6"), ("REMOVE", "DATAPROP", "IND", ["visitedAt", "K", "LONG", "6"])),
        (lambda: m.remove_objectprop_from_ind("isIn", "Robot1", "C1"), ("REMOVE", "OBJECTPROP", "IND", ["isIn", "Robot1", "C1"])),
        (lambda: m.remove_ind_from_class("K", "ROOM"), ("REMOVE", "IND", "CLASS", ["K", "ROOM"])),
        (lambda: u.apply_buffered_changes(), ("APPLY", "", "", [])),
        (lambda: u.mount_on_ref(), ("MOUNT", "", "", [])),
        (lambda: u.unmount_from_ref(), ("UNMOUNT", "", "", [])),
        (lambda: u.set_log_to_terminal(False), ("LOG", "SCREEN", "OFF", [])),
        (lambda: u.set_log_to_file(False), ("LOG", "FILE", "OFF", [])),
        (lambda: q.check_ind_exists("R1"), ("QUERY", "IND", "", ["R1"])),
    ]
    for action, request_ in expected:
        action()
        assert last(rec)[2:] == request_
        assert last(rec)[:2] == ("tester", "ref")


def test_return_types(client: ArmorClient, rec: Recorder, tmp_path: Path) -> None:
    assert client.manipulation.add_ind_to_class("K", "ROOM") is True
    assert client.utils.apply_buffered_changes() is True
    assert client.utils.save(str(tmp_path / "a.owl")) is None
    assert client.utils.save_ref_with_inferences(str(tmp_path / "b.owl")) is None
    assert client.utils.mount_on_ref() is None
    assert client.query.check_ind_exists("R1") is True
    assert client.query.check_ind_exists("Nobody") is False
    assert client.call("QUERY", "IND", "CLASS", ["ROOM"]) == ArmorResponse(
        True, 0, "", True, False, [f"<{IRI}#{n}>" for n in ("C1", "K", "R1", "R2")])
    # save wrote the asserted triples (K included), save_ref_with_inferences the inferred ones too
    asserted, inferred = (rdflib.Graph().parse(tmp_path / name, format="xml") for name in ("a.owl", "b.owl"))
    k_room = (rdflib.URIRef(IRI + "#K"), rdflib.RDF.type, rdflib.URIRef(IRI + "#ROOM"))
    reach = (rdflib.URIRef(IRI + "#Robot1"), rdflib.URIRef(IRI + "#canReach"), rdflib.URIRef(IRI + "#R1"))
    assert k_room in asserted and k_room in inferred
    assert reach not in asserted and reach in inferred
    onto = rec.service.reference("ref").ontology
    for graph, with_inferred in ((asserted, False), (inferred, True)):
        expected = rdflib.Graph().parse(data=onto.serialize("nt", inferred=with_inferred), format="nt")
        assert isomorphic(graph, expected)


def test_batch_methods(client: ArmorClient) -> None:
    props = [["visitedAt", "LONG", "10"], ["label", "STRING", "kitchen"]]
    assert client.manipulation.add_batch_dataprop_to_ind("K", props) is True
    client.utils.apply_buffered_changes()
    assert client.query.dataprop_b2_ind("label", "K") == ['"kitchen"^^xsd:string']
    # fixed: individual and property are no longer swapped (pyM:524)
    assert client.manipulation.remove_batch_dataprop_to_ind("K", props) is True
    client.utils.apply_buffered_changes()
    assert client.query.dataprop_b2_ind("visitedAt", "K") == []
    assert client.query.dataprop_b2_ind("label", "K") == []


def test_batch_stops_at_first_inconsistent_reply(rec: Recorder) -> None:
    client = ArmorClient("t", "ref", transport=rec)
    client.utils.load_ref_from_file(str(ABOX), IRI)  # live reasoner: every change is reasoned
    client.call("DISJOINT", "IND", "", ["A", "B"])
    sent = len(rec.requests)
    # LOCATION has exactly one visitedAt: two different values make A inconsistent
    props = [["visitedAt", "LONG", "1"], ["visitedAt", "LONG", "2"], ["visitedAt", "LONG", "3"]]
    client.manipulation.add_objectprop_to_ind("hasDoor", "A", "D1")
    assert client.manipulation.add_batch_dataprop_to_ind("A", props) is False
    assert len(rec.requests) == sent + 3  # hasDoor + two values; the third is never sent


def test_internal_error_exception(client: ArmorClient) -> None:
    with pytest.raises(ArmorServiceInternalError) as info:
        client.manipulation.add_dataprop_to_ind("now", "Robot1", "NUMBER", "1")
    assert info.value.code == 101 and isinstance(info.value.code, int)
    assert str(info.value) == f"ARMOR internal error 101: {info.value.msg}"
    assert isinstance(info.value, ArmorPyException)
    with pytest.raises(ArmorServiceInternalError) as info:
        client.query.ind_b2_class("bad name")
    assert info.value.code == 208


def test_replace_one_with_several_values_raises_206(client: ArmorClient) -> None:
    client.manipulation.add_dataprop_to_ind("visitedAt", "R1", "LONG", "1")
    client.utils.apply_buffered_changes()
    with pytest.raises(ArmorServiceInternalError) as info:
        client.manipulation.replace_one_dataprop_b2_ind("visitedAt", "R1", "LONG", "2")
    assert info.value.code == 206
    client.manipulation.add_objectprop_to_ind("canSee", "Robot1", "D1")
    client.manipulation.add_objectprop_to_ind("canSee", "Robot1", "D2")
    client.utils.apply_buffered_changes()
    with pytest.raises(ArmorServiceInternalError) as info:
        client.manipulation.replace_one_objectprop_b2_ind("canSee", "Robot1", "D3")
    assert info.value.code == 206


def test_replace_one_adds_when_absent_and_string_values_match(client: ArmorClient) -> None:
    client.manipulation.replace_one_dataprop_b2_ind("label", "R1", "STRING", 'a "quoted" name')
    client.utils.apply_buffered_changes()
    client.manipulation.replace_one_dataprop_b2_ind("label", "R1", "STRING", "plain")
    client.utils.apply_buffered_changes()
    assert client.query.dataprop_b2_ind("label", "R1") == ['"plain"^^xsd:string']
    client.manipulation.replace_one_objectprop_b2_ind("isIn", "Robot1", "R2")
    client.utils.sync_buffered_reasoner()
    assert client.query.objectprop_b2_ind("isIn", "Robot1") == ["R2"]
    assert client.query.objectprop_b2_ind("canReach", "Robot1") == ["C1"]


def test_strip_uri_never_raises(client: ArmorClient) -> None:
    q = client.query
    assert q._strip_URI("<http://x.org/onto#E>") == "E"
    assert q._strip_URI("<http://x.org/onto/E>") == "E"
    assert q._strip_URI("owl:Thing") == "owl:Thing"
    assert q._strip_URI("E") == "E"
    client.manipulation.add_ind_to_class("<http://other.org/things/Box>", "DOOR")
    client.utils.apply_buffered_changes()
    client.utils.sync_buffered_reasoner()
    assert "Box" in q.ind_b2_class("DOOR")


def test_set_log_to_file(client: ArmorClient, tmp_path: Path) -> None:
    with pytest.raises(ArmorServiceCallError):
        client.utils.set_log_to_file(True)
    client.utils.set_log_to_file(True, str(tmp_path / "client.log"))
    client.query.ind_b2_class("ROOM")
    client.utils.set_log_to_file(False)
    assert "ROOM" in (tmp_path / "client.log").read_text()


class BrokenTransport:
    def call(self, request):
        raise ConnectionError("service unavailable")

    def call_many(self, requests):
        raise ConnectionError("service unavailable")


def test_transport_failure_is_call_error() -> None:
    client = ArmorClient("x", "ref", transport=BrokenTransport())
    with pytest.raises(ConnectionError):
        client.call("QUERY", "IND", "", ["R1"])  # raw call propagates, as with rospy
    for action in (lambda: client.query.check_ind_exists("R1"), lambda: client.manipulation.add_ind_to_class("a", "b"),
                   lambda: client.utils.sync_buffered_reasoner(), lambda: client.call_serialized([("APPLY", "", "", [])])):
        with pytest.raises(ArmorServiceCallError):
            action()


def test_call_serialized(client: ArmorClient) -> None:
    result = client.call_serialized([("ADD", "IND", "CLASS", ["K", "ROOM"]), ("REASON", "", "", []),
                                     ("QUERY", "IND", "CLASS", ["ROOM"])])
    assert result.success and result.is_consistent
    assert f"<{IRI}#K>" in result.armor_responses[2].queried_objects


def test_url_selects_the_http_transport_and_an_unreachable_server_is_a_call_error() -> None:
    from topostore.armor_api.http_transport import HttpTransport

    client = ArmorClient("x", "ref", url="http://127.0.0.1:1", timeout=1)
    assert isinstance(client.transport, HttpTransport)
    with pytest.raises(ArmorServiceCallError):
        client.utils.mount_on_ref()


def test_module_layout() -> None:
    import topostore.armor_api as api

    exec("from topostore.armor_api import *", {})  # must not fail: __all__ lists real names

    for name in api.__all__:
        assert hasattr(api, name)
    assert armor_exceptions.ArmorServiceCallError is ArmorServiceCallError
    assert ArmorClient("x", "r", transport=ArmorService()).timeout == 5
