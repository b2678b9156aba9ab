"""Durable references: what an acknowledged manipulation leaves behind survives kill -9 and restarts.

* the kill -9 loop: ``topostore serve --store DIR`` takes acknowledged writes over HTTP and is
  killed at a random moment, 20 times; each time every acknowledged write is in the store,
  the write in flight is there whole or not at all, and the inferred graphs are the closure of
  the asserted ones (reopened or rebuilt, never stale);
* buffered changes, the mounted client and the LOAD settings survive a restart, on disk and on
  ``oxigraph serve``;
* REASON interrupted half-way is rebuilt on reopening; SAVE interrupted keeps the old file;
* two services on one remote store: the second writer of a reference is refused, clearly.
"""

from __future__ import annotations

import hashlib
import random
import shutil
import signal
import threading
import time
from pathlib import Path

import httpx
import pytest
from pyoxigraph import NamedNode, Triple
from serve_fork import ForkedServe
from servers import free_port, stop
from support import IRI
from swrl_support import PREFIXES, builtin, data, rule

from topostore import Ontology, RuleCompileError
from topostore.armor import ArmorService
from topostore.demo import mapgen
from topostore.ontology import state
from topostore.rdf import safeio
from topostore.rdf.vocab import ASSERTED, AUX, DIFFERENT_KEY_OF, INFERRED, KEY_PREFIX, LEGACY_DIFFERENT_KEY, OWL, TYPE
from topostore.stores import open_store

ROOT = Path(__file__).resolve().parents[1]
TBOX = ROOT / "ontology" / "topological_map.ttl"
REPETITIONS = 20


def request(command: str, spec1: str = "", spec2: str = "", *args: str, client: str = "robot",
            ref: str = "ontoRef") -> dict:
    return {"client_name": client, "reference_name": ref, "command": command, "primary_command_spec": spec1,
            "secondary_command_spec": spec2, "args": list(args)}


# --------------------------------------------------------------------------- kill -9 loop

def start_serve(store: Path, data: Path, port: int) -> ForkedServe:
    """``topostore serve --store DIR`` on ``port``, answering; forked from a process that imported topostore
    (tests/serve_fork.py: a fresh interpreter per restart was most of this test's time)."""
    proc = ForkedServe(["--port", str(port), "--data-dir", str(data), "--store", str(store)],
                       store.parent / f"serve-{port}.log")
    deadline = time.monotonic() + 60
    while time.monotonic() < deadline:
        if proc.poll() is not None:
            raise RuntimeError(f"topostore serve exited: {proc.stderr_text()[-2000:]}")
        try:
            httpx.get(f"http://127.0.0.1:{port}/health", timeout=1)
            return proc
        except httpx.HTTPError:
            time.sleep(0.05)
    proc.kill()
    raise RuntimeError("topostore serve did not start within 60 s")


class Writer(threading.Thread):
    """Sends manipulations until the server dies; remembers which were acknowledged."""

    def __init__(self, url: str, first: int, now: int) -> None:
        super().__init__(daemon=True)
        self.url, self.next, self.now = url, first, now
        self.acked: list[int] = []   # door numbers whose ADD was acknowledged
        self.acked_now = now        # the last acknowledged clock value
        self.in_flight_now: int | None = None

    def run(self) -> None:
        with httpx.Client(timeout=30) as http:
            while True:
                i = self.next
                try:
                    r = http.post(self.url, json=request("ADD", "OBJECTPROP", "IND", "hasDoor", f"L{i}", f"D{i}"))
                    if not r.json()["success"]:
                        raise AssertionError(r.text)
                    self.acked.append(i)
                    self.next += 1
                    new = self.now + 1
                    self.in_flight_now = new
                    r = http.post(self.url, json=request("REPLACE", "DATAPROP", "IND", "now", "Robot1", "LONG",
                                                         str(new), str(self.now)))
                    if not r.json()["success"]:
                        raise AssertionError(r.text)
                    self.now = self.acked_now = new
                    self.in_flight_now = None
                except httpx.HTTPError:
                    return


def check_store(store: Path, writer: Writer, expected_doors: list[int]) -> tuple[int, bool]:
    """Open the killed server's store in-process and check it against what was acknowledged.

    Returns the clock value found and whether the ADD in flight at the kill made it in.
    """
    service = ArmorService(store=store)
    try:
        assert service.reference_names() == ["ontoRef"]
        ref = service.reference("ontoRef")
        onto = ref.ontology
        assert (ref.iri, ref.buffered_manipulation, ref.reasoner, ref.buffered_reasoner) == (IRI, False, "PELLET", False)
        doors = {int(onto.short(t.subject)[1:]) for t in onto.store.triples(None, onto.iri("hasDoor"), None, ASSERTED)
                 if onto.short(t.subject).startswith("L")}
        assert set(expected_doors) <= doors, "an acknowledged ADD is missing"
        assert doors <= set(expected_doors) | {writer.next}, "a write nobody sent is present"
        nows = [int(v.value) for v in onto.data_values("now", "Robot1")]
        allowed = {writer.acked_now} | ({writer.in_flight_now} if writer.in_flight_now else set())
        assert len(nows) == 1 and nows[0] in allowed, f"REPLACE half-applied or lost: now={nows}, allowed {allowed}"
        # the inferred graphs as reopened equal a full rematerialisation of the asserted ones
        before = sorted(map(str, onto.store.triples(graph=INFERRED)))
        onto.reason(mode="full")
        assert sorted(map(str, onto.store.triples(graph=INFERRED))) == before
        return nows[0], writer.next in doors
    finally:
        service.close()


def test_kill_minus_nine_loses_no_acknowledged_write(tmp_path: Path) -> None:
    store, data = tmp_path / "store", tmp_path / "data"
    data.mkdir()
    shutil.copy(TBOX, data / "map.ttl")
    rng = random.Random(11)
    port = free_port()
    url = f"http://127.0.0.1:{port}/armor"
    proc = start_serve(store, data, port)
    try:
        load = httpx.post(url, json=request("LOAD", "FILE", "", "map.ttl", IRI, "false", "PELLET", "false"), timeout=60)
        assert load.json()["success"], load.text
        assert httpx.post(url, json=request("ADD", "DATAPROP", "IND", "now", "Robot1", "LONG", "1000"), timeout=60).json()["success"]
        acked: list[int] = []
        first, now = 0, 1000
        for _ in range(REPETITIONS):
            writer = Writer(url, first, now)
            writer.start()
            deadline = time.monotonic() + 30
            while not writer.acked and writer.is_alive() and time.monotonic() < deadline:
                time.sleep(0.01)  # at least one acknowledged write per repetition, then a random moment
            time.sleep(rng.uniform(0.0, 0.5))
            proc.send_signal(signal.SIGKILL)
            proc.wait(10)
            writer.join(30)
            acked += writer.acked
            # continue from what the store holds (the write in flight may or may not be there, whole)
            now, in_flight_added = check_store(store, writer, acked)
            if in_flight_added:
                acked.append(writer.next)
            first = writer.next + 1
            proc = start_serve(store, data, port)
        assert len(acked) >= REPETITIONS  # every repetition had acknowledged writes before its kill
        # after the last restart the service answers from the reopened state
        answer = httpx.post(url, json=request("QUERY", "DATAPROP", "IND", "now", "Robot1"), timeout=60).json()
        assert answer["queried_objects"] == [f'"{now}"^^xsd:long']
    finally:
        stop(proc)


# --------------------------------------------------------------------------- restarts in-process

def store_setting(kind: str, request, tmp_path: Path) -> str:
    return str(tmp_path / "refs") if kind == "disk" else request.getfixturevalue("oxigraph_url")


def armor(service: ArmorService, *args: str, client: str = "robot", ref: str = "ontoRef"):
    return service.call(request(*args, client=client, ref=ref))


@pytest.mark.parametrize("kind", ["disk", "oxigraph"])
def test_buffered_changes_and_mount_owner_survive_restart(kind: str, request, tmp_path: Path) -> None:
    spec = store_setting(kind, request, tmp_path)
    ref = f"buffered-{kind}"
    service = ArmorService(data_dir=ROOT, store=spec)
    assert armor(service, "LOAD", "FILE", "MOUNTED", str(TBOX), IRI, "true", "HERMIT", "true", ref=ref).success
    for args in [("hasDoor", "C1", "D1"), ("hasDoor", "C1", "D2"), ("hasDoor", "R1", "D1"), ("isIn", "Robot1", "C1")]:
        assert armor(service, "ADD", "OBJECTPROP", "IND", *args, ref=ref).success
    assert armor(service, "DISJOINT", "IND", "", "C1", "R1", "D1", "D2", ref=ref).success
    assert armor(service, "QUERY", "OBJECTPROP", "IND", "canReach", "Robot1", ref=ref).queried_objects == []
    service.close()

    service = ArmorService(data_dir=ROOT, store=spec)
    restored = service.reference(ref)
    assert (restored.iri, restored.buffered_manipulation, restored.reasoner, restored.buffered_reasoner,
            restored.owner, len(restored.buffer)) == (IRI, True, "HERMIT", True, "robot", 5)
    assert armor(service, "GET", "REF", "CLIENT", ref, ref=ref).queried_objects == ["robot"]
    other = armor(service, "ADD", "OBJECTPROP", "IND", "hasDoor", "R2", "D2", client="intruder", ref=ref)
    assert (other.success, other.exit_code) == (False, 102)
    assert armor(service, "REASON", ref=ref).success
    assert armor(service, "QUERY", "OBJECTPROP", "IND", "canReach", "Robot1", ref=ref).queried_objects == [f"<{IRI}#R1>"]
    assert armor(service, "UNMOUNT", ref=ref).success
    service.close()

    service = ArmorService(data_dir=ROOT, store=spec)
    restored = service.reference(ref)
    assert (restored.owner, restored.buffer, restored.ontology.opened) == (None, [], "reopened")
    assert armor(service, "QUERY", "OBJECTPROP", "IND", "canReach", "Robot1", ref=ref).queried_objects == [f"<{IRI}#R1>"]
    assert armor(service, "QUERY", "CLASS", "IND", "C1", "true", ref=ref).queried_objects == ["CORRIDOR"]
    assert armor(service, "DROP", ref=ref).success
    service.close()
    assert ref not in ArmorService(store=spec).reference_names()


def test_reason_interrupted_is_rebuilt_on_reopening(tmp_path: Path) -> None:
    onto = Ontology.from_file(TBOX, ROOT / "ontology" / "topological_map_abox.ttl", store=tmp_path / "db")
    onto.reason()
    expected = sorted(map(str, onto.store.triples(graph=INFERRED)))
    # what a process killed inside REASON leaves: the mark, and a half-written inferred graph
    onto.store.meta_set("inferred", "building")
    junk = Triple(NamedNode(IRI + "#R1"), NamedNode(IRI + "#canReach"), NamedNode(IRI + "#Nowhere"))
    onto.store.add([junk], INFERRED)
    onto.store.close()
    again = Ontology(store=tmp_path / "db")
    assert again.opened == "rebuilt"
    assert sorted(map(str, again.store.triples(graph=INFERRED))) == expected
    assert again.store.meta["inferred"] == "valid"


def test_keys_of_an_earlier_format_are_rebuilt_on_reopening(tmp_path: Path) -> None:
    """A store whose helper graph holds the AllDifferent keys member first (``m ts:differentKey k``, as
    earlier versions wrote them) is rebuilt when opened: read as it is, an incremental REASON would find
    no key of the old members and miss their differences."""
    onto = Ontology.from_file(TBOX, ROOT / "ontology" / "topological_map_abox.ttl", store=tmp_path / "db")
    onto.reason()
    expected = sorted(map(str, onto.store.triples(graph=INFERRED)))
    keys = list(onto.store.triples(None, DIFFERENT_KEY_OF, None, AUX))
    assert keys
    onto.store.remove(keys, AUX)
    onto.store.add([Triple(t.object, LEGACY_DIFFERENT_KEY, t.subject) for t in keys], AUX)
    onto.store.close()
    again = Ontology(store=tmp_path / "db")
    assert again.opened == "rebuilt"
    assert sorted(map(str, again.store.triples(graph=INFERRED))) == expected
    assert sorted(map(str, again.store.triples(None, DIFFERENT_KEY_OF, None, AUX))) == sorted(map(str, keys))
    assert not list(again.store.triples(None, LEGACY_DIFFERENT_KEY, None, AUX))
    # the old members' keys serve an incremental REASON: a door shared by R1 and R2 connects them
    r1, r2, door = (NamedNode(IRI + "#" + name) for name in ("R1", "R2", "D2"))
    again.add(Triple(r1, NamedNode(IRI + "#hasDoor"), door))
    again.reason()
    assert Triple(r1, NamedNode(IRI + "#connectedTo"), r2) in set(again.store.triples(graph=INFERRED))
    reopened = Ontology(store=tmp_path / "db2")
    assert reopened.opened == "new"


def test_keys_grouped_by_node_are_rebuilt_on_reopening(tmp_path: Path) -> None:
    """A store whose last REASON wrote the AllDifferent keys grouped by the AllDifferent node (earlier
    versions: members of one node's two lists then shared a group) is rebuilt when opened, its keys
    grouped by list again."""
    onto = Ontology.from_file(TBOX, ROOT / "ontology" / "topological_map_abox.ttl", store=tmp_path / "db")
    onto.reason()
    keys = sorted(map(str, onto.store.triples(None, DIFFERENT_KEY_OF, None, AUX)))
    assert keys
    node = next(iter(onto.store.subjects(TYPE, NamedNode(str(OWL) + "AllDifferent"), ASSERTED)))
    by_node = NamedNode(KEY_PREFIX + hashlib.md5(node.value.encode()).hexdigest() + ":x")
    onto.store.add([Triple(by_node, DIFFERENT_KEY_OF, node)], AUX)
    onto.store.meta_set(state.KEY_FORMAT, None)
    onto.store.close()
    again = Ontology(store=tmp_path / "db")
    assert again.opened == "rebuilt"
    assert sorted(map(str, again.store.triples(None, DIFFERENT_KEY_OF, None, AUX))) == keys
    again.store.close()
    assert Ontology(store=tmp_path / "db").opened == "reopened"


def test_keys_of_a_one_list_store_made_by_list_are_rebuilt_on_reopening(tmp_path: Path) -> None:
    """A store holding one AllDifferent member list whose last REASON wrote its keys by list (earlier
    versions: ``urn:topostore:key:<md5(list)>:<md5(member)>``) is rebuilt when opened, its members now
    their own keys: read as it is, an incremental REASON would write the keys of new members in the other
    form, and an old member and a new one would not share a group."""
    onto = Ontology.from_file(TBOX, store=tmp_path / "db")
    onto.add(*mapgen.generate(8, seed=2).triples())
    onto.reason()
    assert onto.rules.one_list
    keys = list(onto.store.triples(None, DIFFERENT_KEY_OF, None, AUX))
    assert keys and all(t.subject == t.object for t in keys)
    head = next(iter(onto.store.objects(next(iter(onto.store.subjects(TYPE, NamedNode(str(OWL) + "AllDifferent"),
                                                                          ASSERTED))),
                                        NamedNode(str(OWL) + "distinctMembers"), ASSERTED)))
    group = hashlib.md5(head.value.encode()).hexdigest()
    onto.store.remove(keys, AUX)
    onto.store.add([Triple(NamedNode(f"{KEY_PREFIX}{group}:{hashlib.md5(t.object.value.encode()).hexdigest()}"),
                           DIFFERENT_KEY_OF, t.object) for t in keys], AUX)
    onto.store.meta_set(state.KEY_FORMAT, "by-list")
    onto.store.close()
    again = Ontology(store=tmp_path / "db")
    assert again.opened == "rebuilt"
    assert sorted(map(str, again.store.triples(None, DIFFERENT_KEY_OF, None, AUX))) == sorted(map(str, keys))
    again.store.close()
    assert Ontology(store=tmp_path / "db").opened == "reopened"


def test_save_interrupted_keeps_the_old_file(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    onto = Ontology.from_file(TBOX, ROOT / "ontology" / "topological_map_abox.ttl", store=tmp_path / "db")
    target = tmp_path / "map.ttl"
    onto.save(target)
    good = target.read_bytes()
    onto.add_fact("R1", "hasDoor", "D9")

    def disk_full(fd: int) -> None:  # the temporary file is written, then the disk fills up
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(safeio.os, "fsync", disk_full)
    with pytest.raises(OSError):
        onto.save(target)
    monkeypatch.undo()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["db", "map.ttl"]  # no temporary file left
    assert target.read_bytes() == good
    assert Ontology.from_file(target).reason().consistent


def test_rule_needing_an_extension_function_is_refused_on_a_remote_store(oxigraph_url: str) -> None:
    text = PREFIXES + ":a :v 2 ; :e 3 .\n" + rule(
        [data(":v", "?x", "?b"), data(":e", "?x", "?n"), builtin("pow", "?r", "?b", "?n")], [data(":p", "?x", "?r")], "power")
    assert Ontology().load_data(text) > 0  # in memory the extension function runs
    remote = Ontology(store=open_store(oxigraph_url, reference="pow-rule"))
    with pytest.raises(RuleCompileError, match="swrlb:pow"):
        remote.load_data(text)
    assert remote.store.is_empty(ASSERTED)


@pytest.mark.parametrize("server", ["oxigraph", "virtuoso"])
def test_two_services_on_one_remote_store(server: str, request) -> None:
    url = request.getfixturevalue(f"{server}_url")
    first = ArmorService(data_dir=ROOT, store=url)
    second = None
    try:
        assert armor(first, "LOAD", "FILE", "", str(TBOX), IRI, "false", "PELLET", "false", ref="shared").success
        second = ArmorService(data_dir=ROOT, store=url)
        assert "shared" not in second.reference_names()  # held by the first service: not opened
        refused = armor(second, "LOAD", "FILE", "", str(TBOX), IRI, "false", "PELLET", "false", ref="shared")
        assert (refused.success, refused.exit_code) == (False, 102)
        assert "written by another topostore process" in refused.error_description
        # each service writes its own reference; neither disturbs the other
        assert armor(second, "LOAD", "FILE", "", str(TBOX), IRI, "false", "PELLET", "false", ref="own").success
        assert armor(first, "ADD", "OBJECTPROP", "IND", "isIn", "Robot1", "C1", ref="shared").success
        assert armor(second, "ADD", "OBJECTPROP", "IND", "isIn", "Robot1", "R1", ref="own").success
        assert armor(first, "QUERY", "OBJECTPROP", "IND", "isIn", "Robot1", ref="shared").queried_objects == [f"<{IRI}#C1>"]
        assert armor(second, "QUERY", "OBJECTPROP", "IND", "isIn", "Robot1", ref="own").queried_objects == [f"<{IRI}#R1>"]
        first.close()  # releases its writer lock: the reference can move to the second service
        taken = armor(second, "LOAD", "FILE", "", str(TBOX), IRI, "false", "PELLET", "false", ref="shared")
        assert taken.success and "reused" in taken.error_description
        assert armor(second, "QUERY", "OBJECTPROP", "IND", "isIn", "Robot1", ref="shared").queried_objects == [f"<{IRI}#C1>"]
        for name in ("shared", "own"):
            assert armor(second, "DROP", ref=name).success
    finally:
        first.close()
        if second is not None:
            second.close()


def test_fleet_demo_shares_one_map_through_a_remote_store(oxigraph_url: str) -> None:
    from topostore.demo import run_demo

    lines: list[str] = []
    first = run_demo(None, steps=2, robots=3, store=oxigraph_url, picture=None, emit=lines.append)
    assert sorted((m.robot, m.step) for m in first.moves) == [(r, s) for r in ("Robot1", "Robot2", "Robot3") for s in (1, 2)]
    assert all(m.consistent for m in first.moves)
    trace = [line for line in lines if line.startswith("[")]
    assert len(trace) == 3 * 2 * 3 and {line[1:7] for line in trace} == {"Robot1", "Robot2", "Robot3"}
    # a second fleet run continues on the stored map: each robot's clock goes on from where it stopped
    last = {m.robot: m.time for m in first.moves if m.step == 2}
    again = run_demo(None, steps=1, robots=3, store=oxigraph_url, picture=None, emit=lambda _: None)
    assert all(m.time > last[m.robot] for m in again.moves)
