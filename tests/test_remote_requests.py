"""HTTP requests of the robot step's commands on a remote store, and what a refused queued write leaves.

The counts are behaviour, not timing: a REPLACE with its old value given sends nothing of its own
(its write waits in the store's queue and goes with the next update), a query the store can answer
from what it keeps sends nothing, and one it cannot sends one request.  A queued write the server
then refuses is undone in this process too and said (WritesLostError), with the change ledger set
back exactly, so the next REASON and every answer match an ontology that never had the change.
"""

from __future__ import annotations

import itertools
import re
import subprocess
import sys
from collections.abc import Iterator
from pathlib import Path

import pytest
from pyoxigraph import Literal, NamedNode, Triple

from topostore import Ontology
from topostore.armor import ArmorService
from topostore.errors import QueryError, StoreError, WritesLostError
from topostore.rdf.vocab import ASSERTED, ENTAILED, INFERRED, XSD
from topostore.stores import open_store
from topostore.stores.remote import RemoteStore

ROOT = Path(__file__).resolve().parents[1]
IRI = "http://bnc/exp-rob-lab/2022-23"
NS = IRI + "#"
NOW = 1665579740
_names = itertools.count()


def long(v: int) -> Literal:
    return Literal(str(v), datatype=NamedNode(XSD + "long"))


@pytest.fixture
def map_file(tmp_path: Path) -> Path:
    """The tutorial map as one file (TBox, then the example ABox)."""
    path = tmp_path / "map.ttl"
    path.write_text("\n".join((ROOT / "ontology" / name).read_text()
                              for name in ("topological_map.ttl", "topological_map_abox.ttl")))
    return path


class Robot:
    """One reference on the server, driven with aRMOR commands; counts the requests of each command."""

    def __init__(self, url: str, map_file: Path) -> None:
        self.ref = f"requests-{next(_names)}"
        self.service = ArmorService(store=url)
        self.call("LOAD", "FILE", "", str(map_file), IRI, "false", "PELLET", "true")
        self.store: RemoteStore = self.service.reference(self.ref).ontology.store
        self.now, self.place = NOW, "C1"
        self.visits = {"C1": NOW, "R1": NOW - 30, "R2": NOW - 5}

    def call(self, command: str, spec1: str = "", spec2: str = "", *args: str):
        reply = self.service.call({"client_name": "robot", "reference_name": self.ref, "command": command,
                                   "primary_command_spec": spec1, "secondary_command_spec": spec2,
                                   "args": list(args)})
        return reply

    def counted(self, command: str, spec1: str = "", spec2: str = "", *args: str):
        """(requests sent, reply) of one command."""
        before = self.store.requests
        reply = self.call(command, spec1, spec2, *args)
        return self.store.requests - before, reply

    def move(self, to: str, dt: int = 10) -> list[int]:
        """The three REPLACEs of a step; the requests each sent."""
        old_now, self.now = self.now, self.now + dt
        old_place, self.place = self.place, to
        old_visit, self.visits[to] = self.visits[to], self.now
        counts = []
        for args in (("OBJECTPROP", "IND", "isIn", "Robot1", to, old_place),
                     ("DATAPROP", "IND", "now", "Robot1", "LONG", str(self.now), str(old_now)),
                     ("DATAPROP", "IND", "visitedAt", to, "LONG", str(self.now), str(old_visit))):
            n, reply = self.counted("REPLACE", *args)
            assert reply.success and not reply.error_description, reply.error_description
            counts.append(n)
        return counts

    def answers(self) -> tuple[list[str], list[str]]:
        reach = self.call("QUERY", "OBJECTPROP", "IND", "canReach", "Robot1").queried_objects
        urgent = self.call("QUERY", "IND", "CLASS", "URGENT").queried_objects
        return sorted(reach), sorted(urgent)

    def close(self) -> None:
        self.service.close()


@pytest.fixture
def robot(oxigraph_url: str, map_file: Path) -> Iterator[Robot]:
    r = Robot(oxigraph_url, map_file)
    yield r
    r.close()


def sent_updates(store: RemoteStore) -> list[str]:
    """The bodies of the update requests the store sends from now on."""
    bodies: list[str] = []
    real = store._post

    def post(url: str, data: dict, accept: str | None = None):
        if url == store.update_url:
            bodies.append(data["update"])
        return real(url, data, accept)

    store._post = post  # type: ignore[method-assign]
    return bodies


def expected(onto: Ontology) -> tuple[list[str], list[str]]:
    """The two answers from a fresh in-memory ontology with the same asserted graph."""
    fresh = Ontology()
    fresh.add(*onto.store.triples(graph=ASSERTED))
    fresh.reason()
    return (sorted(f"<{NS}{n}>" for n in fresh.object_values("canReach", "Robot1")),
            sorted(f"<{i.value}>" for i in fresh.instances("URGENT")))


def test_a_replace_sends_nothing_of_its_own_and_its_write_goes_with_the_reason(robot: Robot) -> None:
    robot.move("R2")  # the first REPLACE of a (subject, property) reads its values once
    assert robot.call("REASON").success
    # a second place's visit time: the store reads every visit time at once (one request) ...
    assert robot.move("C1") == [0, 0, 1]
    assert robot.call("REASON").success
    assert robot.move("R1") == [0, 0, 0]  # ... so a place never replaced before costs nothing either
    assert robot.call("REASON").success
    assert robot.move("R2") == [0, 0, 0]
    bodies = sent_updates(robot.store)
    assert robot.call("REASON").success
    # the three writes went with the REASON's first update request
    first = re.sub(r"^(PREFIX [^\n]*\n)*", "", bodies[0]).split(" ;\n")
    data = [op for op in first if op.startswith(("DELETE DATA", "INSERT DATA")) and "graph:asserted>" in op]
    assert [op.split(" ")[0] for op in data] == ["DELETE", "INSERT"] * 3
    assert [name in op for name, op in zip(("#isIn>", "#now>", "#visitedAt>"), data[::2])] == [True] * 3
    assert _robot_place(robot.store.url, robot.ref) == [NamedNode(NS + "R2")]
    assert robot.answers() == expected(robot.service.reference(robot.ref).ontology)


def test_a_robot_steps_reason_sends_one_update_and_one_read(robot: Robot) -> None:
    """Once the step is compiled, a REASON after a robot's move is the program's one update request
    and one read: nothing it decides in between may ask the server (a count of a predicate's facts,
    a look-up) on a store where every question is a round trip."""
    for place in ("R2", "C1", "R1"):
        robot.move(place)
        assert robot.call("REASON").success
    for place in ("R2", "C1"):
        robot.move(place)
        sent, reply = robot.counted("REASON")
        assert reply.success and sent <= 2
    assert robot.answers() == expected(robot.service.reference(robot.ref).ontology)


def test_the_step_queries_send_one_request_then_none(robot: Robot) -> None:
    robot.move("R2")
    assert robot.call("REASON").success
    n_reach, reach = robot.counted("QUERY", "OBJECTPROP", "IND", "canReach", "Robot1")
    n_urgent, urgent = robot.counted("QUERY", "IND", "CLASS", "URGENT")
    assert n_reach == 1  # the inferred and entailed values in one query; the asserted ones are known
    assert n_urgent <= 1
    for _ in range(2):  # asked again before the next change: answered from what the store keeps
        assert robot.counted("QUERY", "OBJECTPROP", "IND", "canReach", "Robot1") == (0, reach)
        assert robot.counted("QUERY", "IND", "CLASS", "URGENT") == (0, urgent)
    robot.move("C1")  # R2, visited 10 s ago, becomes URGENT
    n, reply = robot.counted("REASON")
    assert reply.success
    # the class view's touched member is decided by the canReach request, not by one of its own
    assert robot.counted("QUERY", "OBJECTPROP", "IND", "canReach", "Robot1")[0] == 1
    n_urgent, after = robot.counted("QUERY", "IND", "CLASS", "URGENT")
    assert n_urgent == 0 and after.queried_objects != urgent.queried_objects
    assert robot.answers() == expected(robot.service.reference(robot.ref).ontology)
    # alone (no other read to carry it), the view's decision is one request
    robot.move("R2")
    assert robot.call("REASON").success
    assert robot.counted("QUERY", "IND", "CLASS", "URGENT")[0] == 1


def test_a_change_the_store_did_not_make_is_read_again(robot: Robot) -> None:
    """A SPARQL update outside the reasoner may change anything: what the store kept is read again."""
    robot.move("R2")
    assert robot.call("REASON").success
    onto = robot.service.reference(robot.ref).ontology
    robot_now = (NamedNode(NS + "Robot1"), NamedNode(NS + "now"))
    onto.store.update(f"DELETE DATA {{ GRAPH {ASSERTED} {{ {robot_now[0]} {robot_now[1]} {long(robot.now)} }} }} ; "
                      f"INSERT DATA {{ GRAPH {ASSERTED} {{ {robot_now[0]} {robot_now[1]} {long(5)} }} }}")
    assert [int(t.object.value) for t in onto.store.triples(*robot_now, None, ASSERTED)] == [5]


def refuse_next_update(store: RemoteStore, monkeypatch: pytest.MonkeyPatch, error: Exception,
                       times: int = 1) -> list[str]:
    """The server refuses (or does not answer) the next ``times`` update requests; returns their bodies."""
    refused: list[str] = []
    real = store._post

    def post(url: str, data: dict, accept: str | None = None):
        if url == store.update_url and len(refused) < times:
            refused.append(data["update"])
            store.requests += 1
            raise error
        return real(url, data, accept)

    monkeypatch.setattr(store, "_post", post)
    return refused


@pytest.mark.parametrize("error", [QueryError("refused (500)"), StoreError("did not answer")])
def test_a_refused_queued_write_is_undone_and_said(robot: Robot, monkeypatch: pytest.MonkeyPatch,
                                                   error: Exception) -> None:
    robot.move("R2")
    assert robot.call("REASON").success
    onto = robot.service.reference(robot.ref).ontology
    before = (robot.answers(), sorted(map(str, onto.store.triples(graph=ASSERTED))))
    counts = robot.move("C1")
    assert counts == [0, 0, 1]
    assert onto.ledger.net_changes() != ([], [])
    # a refusal comes twice (the REASON's first update with the writes, then the writes alone);
    # no answer once (whether the server applied them is unknown: they are not sent again)
    refused = refuse_next_update(robot.store, monkeypatch, error, times=2 if isinstance(error, QueryError) else 1)
    reply = robot.call("REASON")
    assert refused and "isIn" in refused[0]  # the REPLACEs went with the REASON's first update
    assert not reply.success and "were not written" in reply.error_description
    assert "3 change(s) of the data" in reply.error_description
    monkeypatch.undo()
    # this process and the server agree again: the map as before the three REPLACEs
    assert onto.ledger.net_changes() == ([], [])
    assert sorted(map(str, onto.store.triples(graph=ASSERTED))) == before[1]
    assert robot.answers() == before[0] == expected(onto)
    assert onto.data_values("now", "Robot1") == [long(NOW + 10)]  # the form the user wrote
    # and the robot goes on from there
    robot.now, robot.place, robot.visits["C1"] = NOW + 10, "R2", NOW
    robot.move("C1")
    assert robot.call("REASON").success
    assert robot.answers() == expected(onto)


def test_a_refused_write_seen_by_a_query_sets_the_ledger_back(oxigraph_url: str, map_file: Path,
                                                              monkeypatch: pytest.MonkeyPatch) -> None:
    """The write fails when a later read sends it: the ledger forgets exactly that change, so the next
    incremental REASON starts from what the server holds."""
    onto = Ontology.from_file(map_file, store=open_store(oxigraph_url, reference=f"lost-{next(_names)}"))
    onto.reason()
    robot, is_in, now = NamedNode(NS + "Robot1"), NamedNode(NS + "isIn"), NamedNode(NS + "now")
    onto.replace("Robot1", "isIn", "R1", "C1")
    onto.reason()
    onto.store.send_writes()  # the REASON's drop of its scratch graphs goes (lost, it would make the next one full)
    onto.replace("Robot1", "now", long(NOW + 40), long(NOW))  # queued ...
    onto.remove(Triple(robot, is_in, NamedNode(NS + "R1")))  # ... this one too
    onto.add(Triple(robot, is_in, NamedNode(NS + "R1")))  # ... and this add cancels it in the ledger
    added, removed = onto.ledger.net_changes()  # the isIn removal and re-addition cancel out
    assert [(t.predicate, int(t.object.value)) for t in added + removed] == [(now, NOW + 40), (now, NOW)]
    refuse_next_update(onto.store, monkeypatch, QueryError("refused (503)"))
    with pytest.raises(WritesLostError, match="were not written"):
        onto.store.query(f"ASK {{ GRAPH {ASSERTED} {{ ?s ?p ?o }} }}")
    monkeypatch.undo()
    assert onto.ledger.net_changes() == ([], [])
    assert [t.object for t in onto.store.triples(robot, is_in, None, ASSERTED)] == [NamedNode(NS + "R1")]
    assert onto.data_values("now", "Robot1") == [long(NOW)]
    report = onto.reason()
    assert report.stats.mode == "incremental" and report.consistent
    assert sorted(onto.object_values("canReach", "Robot1")) == ["C1"]


def test_an_update_refused_alone_keeps_the_queued_writes(robot: Robot) -> None:
    robot.move("R2")
    onto = robot.service.reference(robot.ref).ontology
    with pytest.raises(QueryError, match="refused"):
        onto.store.update("THIS IS NOT SPARQL")
    assert _robot_place(robot.store.url, robot.ref) == [NamedNode(NS + "R2")]
    assert robot.call("REASON").success
    assert robot.answers() == expected(onto)


def _robot_place(url: str, ref: str) -> list[NamedNode]:
    """Where Robot1 is, read by a store of its own."""
    check = open_store(url, reference=ref)
    try:
        return [t.object for t in check.triples(NamedNode(NS + "Robot1"), NamedNode(NS + "isIn"), None, ASSERTED)]
    finally:
        check.close()


def test_close_sends_the_queued_writes(oxigraph_url: str, map_file: Path) -> None:
    robot = Robot(oxigraph_url, map_file)
    robot.move("R2")
    robot.close()
    assert _robot_place(oxigraph_url, robot.ref) == [NamedNode(NS + "R2")]


def test_a_script_that_never_closes_its_store_still_writes_at_exit(oxigraph_url: str, map_file: Path) -> None:
    ref = f"exit-{next(_names)}"
    script = (f"from topostore import Ontology\nfrom topostore.stores import open_store\n"
              f"onto = Ontology.from_file({str(map_file)!r}, store=open_store({oxigraph_url!r}, reference={ref!r}))\n"
              f"onto.replace('Robot1', 'isIn', 'R1', 'C1')\n")
    subprocess.run([sys.executable, "-c", script], check=True, timeout=120)
    assert _robot_place(oxigraph_url, ref) == [NamedNode(NS + "R1")]


def test_sync_sends_every_change_before_the_reply(oxigraph_url: str, map_file: Path) -> None:
    store = open_store(oxigraph_url, reference=f"sync-{next(_names)}", sync=True)
    onto = Ontology.from_file(map_file, store=store)
    onto.reason()
    assert onto.prefix == NS  # looked up once, before counting
    before = store.requests
    onto.replace("Robot1", "isIn", "R1", "C1")
    assert store.requests - before == 2  # the values read once, the change written at once
    onto.replace("Robot1", "isIn", "R2", "R1")
    assert store.requests - before == 3  # the values known: the write alone
    store.close()


def test_the_reasoner_drop_of_its_scratch_graphs_waits_for_the_next_request(robot: Robot,
                                                                            monkeypatch: pytest.MonkeyPatch) -> None:
    robot.move("R2")
    assert robot.call("REASON").success
    queued = [q for q in robot.store._queue if q.dropped]
    assert queued and not queued[0].dropped & {ASSERTED, INFERRED, ENTAILED}
    # the questions do not read the scratch graphs: the drop still waits
    robot.answers()
    assert any(q.dropped for q in robot.store._queue)
    # lost, it leaves those graphs unknown: the next REASON is a full one, and right
    robot.move("C1")
    onto = robot.service.reference(robot.ref).ontology
    refuse_next_update(robot.store, monkeypatch, QueryError("refused (503)"), times=2)
    reply = robot.call("REASON")
    assert not reply.success and "update(s) of the reasoner" in reply.error_description
    assert "the next REASON is a full one" in reply.error_description
    monkeypatch.undo()
    assert onto.report.stats.mode == "full"  # the state before the change, recomputed whole
    assert robot.answers() == expected(onto)
    robot.now, robot.place, robot.visits["C1"] = NOW + 10, "R2", NOW
    robot.move("C1")
    assert robot.call("REASON").success
    assert robot.answers() == expected(onto)
