"""Removed quads are compacted away between changes too, not only at a REASON: a client that writes many
values and rarely reasons (a buffered reasoner, a clock rewritten between REASONs) keeps its look-ups as
cheap as after a REASON (every look-up of a rewritten pair otherwise walks all its removed versions)."""

from __future__ import annotations

import pytest
from support import IRI, SHARED

from topostore import Ontology
from topostore.armor import ArmorService
from topostore.stores import oxigraph


@pytest.fixture
def rebuilds(monkeypatch: pytest.MonkeyPatch) -> list[int]:
    """The live quads of each rebuild of an in-memory store (the store's own compaction policy)."""
    seen: list[int] = []
    policy = oxigraph.compacted

    def counted(store, writes: int, live: int):
        fresh, live = policy(store, writes, live)
        if fresh is not None:
            seen.append(live)
        return fresh, live

    monkeypatch.setattr(oxigraph, "compacted", counted)
    return seen


def _call(service: ArmorService, command: str, primary: str, secondary: str, args: list[str]):
    return service.call({"reference_name": "ref", "command": command, "primary_command_spec": primary,
                         "secondary_command_spec": secondary, "args": args})


@pytest.mark.parametrize("buffered", [True, False])
def test_armor_replaces_without_reason_compact_the_store(rebuilds: list[int], buffered: bool) -> None:
    """600 REPLACEs of one clock with no REASON between (buffered manipulation off; a buffered reasoner, or a
    live one that reasons at each change): the store is rebuilt about every 200 writes, and the answers stay."""
    service = ArmorService()
    loaded = _call(service, "LOAD", "FILE", "", [str(SHARED / "topological_map_abox.owl"), IRI, "false", "PELLET",
                                                 str(buffered).lower()])
    assert loaded.success, loaded
    now = _call(service, "QUERY", "DATAPROP", "IND", ["now", "Robot1"]).queried_objects
    first = old = now[0].split('"')[1]
    for _ in range(600):
        new = str(int(old) + 1)
        reply = _call(service, "REPLACE", "DATAPROP", "IND", ["now", "Robot1", "LONG", new, old])
        assert reply.success, reply
        old = new
    assert len(rebuilds) >= 2
    answer = _call(service, "QUERY", "DATAPROP", "IND", ["now", "Robot1"]).queried_objects
    # a buffered reasoner answers the value at the last REASON beside the asserted one until the next REASON
    assert sorted(a.split('"')[1] for a in answer) == sorted({old, first} if buffered else {old})


def test_python_replaces_without_reason_compact_the_store(rebuilds: list[int]) -> None:
    """The Python API alike: values replaced with no unit of work open, never reasoned."""
    onto = Ontology.from_file(SHARED / "topological_map_abox.owl")
    onto.reason()
    del rebuilds[:]
    for k in range(600):
        onto.replace("Robot1", "now", 10_000 + k)
    assert len(rebuilds) >= 2
    assert [t.object.value for t in onto.store.triples(onto.iri("Robot1"), onto.iri("now"), None)] == ["10599"]


def test_a_compaction_out_of_memory_leaves_the_store_and_the_command_succeeds(monkeypatch: pytest.MonkeyPatch,
                                                                              caplog: pytest.LogCaptureFixture) -> None:
    """A rebuild that does not fit in memory is said and skipped: the change it followed stands."""
    def no_room(store, writes: int, live: int):
        raise MemoryError

    monkeypatch.setattr(oxigraph, "compacted", no_room)
    onto = Ontology.from_file(SHARED / "topological_map_abox.owl")
    onto.reason()
    onto.replace("Robot1", "now", 7)
    assert [t.object.value for t in onto.store.triples(onto.iri("Robot1"), onto.iri("now"), None)] == ["7"]
    assert "could not be compacted" in caplog.text
