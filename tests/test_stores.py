"""The store interface: the three settings, transactions, persisted literal forms and state."""

from __future__ import annotations

from pathlib import Path

import pytest
from pyoxigraph import Literal, NamedNode, Triple

from topostore.errors import StoreError
from topostore.rdf.vocab import ASSERTED, XSD
from topostore.stores import kind, list_references, memory_store, open_store, reference_dir
from topostore.stores.oxigraph import OxigraphStore
from topostore.stores.remote import RemoteStore

A, P, B = NamedNode("urn:x:a"), NamedNode("urn:x:p"), NamedNode("urn:x:b")
SEVEN_LONG = Literal("7", datatype=NamedNode(XSD + "long"))


def test_the_three_settings(tmp_path: Path, oxigraph_url: str) -> None:
    assert [kind(None), kind(""), kind(tmp_path), kind("https://example.org/sparql")] == \
        ["memory", "memory", "directory", "remote"]
    memory = open_store(None)
    assert type(memory) is OxigraphStore and not memory.durable and memory.supports_lateral
    disk = open_store(tmp_path, reference="robot/1")
    assert disk.durable and disk.path == tmp_path / "robot%2F1"  # one path component, never a traversal
    remote = open_store(oxigraph_url, reference="r")
    assert isinstance(remote, RemoteStore) and remote.durable
    assert (remote.query_url, remote.update_url) == (oxigraph_url + "/query", oxigraph_url + "/update")
    assert not remote.supports_lateral and not remote.custom_functions
    for s in (disk, remote):
        s.close()
    with pytest.raises(StoreError):
        reference_dir(tmp_path, "..")
    assert type(memory_store()) is OxigraphStore


def test_transaction_is_all_or_nothing_and_reads_its_own_writes(tmp_path: Path) -> None:
    store = open_store(tmp_path / "db")
    store.add([Triple(A, P, B)], ASSERTED)
    with pytest.raises(RuntimeError):
        with store.transaction():
            store.remove([Triple(A, P, B)], ASSERTED)
            store.add([Triple(B, P, A)], ASSERTED)
            assert list(store.triples(None, P, None, ASSERTED)) == [Triple(B, P, A)]
            assert not store.contains(Triple(A, P, B), ASSERTED)
            raise RuntimeError("the process dies here")
    assert list(store.triples(None, P, None, ASSERTED)) == [Triple(A, P, B)]
    store.close()


def test_literal_forms_and_state_survive_reopening(tmp_path: Path) -> None:
    store = open_store(tmp_path / "db")
    store.add([Triple(A, P, SEVEN_LONG)], ASSERTED)
    store.meta_set("dirty", True)
    store.close()
    again = open_store(tmp_path / "db")
    stored = list(again.triples(A, P, None, ASSERTED))[0].object
    assert again.original_literal(ASSERTED, A, P, stored) == SEVEN_LONG   # Oxigraph keeps "7"^^xsd:integer
    assert again.dump([ASSERTED]) == [Triple(A, P, SEVEN_LONG)]
    assert again.meta == {"dirty": True}
    again.remove([Triple(A, P, Literal("7", datatype=NamedNode(XSD + "integer")))], ASSERTED)
    again.close()
    third = open_store(tmp_path / "db")
    assert third.dump([ASSERTED]) == [] and third.forms._literal_forms == {}
    third.close()


def test_references_are_listed_per_setting(tmp_path: Path, oxigraph_url: str) -> None:
    from topostore.armor import ArmorService

    ttl = Path(__file__).resolve().parents[1] / "ontology" / "topological_map.ttl"
    for spec in (tmp_path / "refs", oxigraph_url):
        service = ArmorService(store=spec)
        for name in ("b ref", "a/ref"):
            assert service.call({"reference_name": name, "command": "LOAD", "primary_command_spec": "FILE",
                                 "args": [str(ttl), "http://bnc/exp-rob-lab/2022-23", "false", "", "false"]}).success
        service.close()
        assert {"a/ref", "b ref"} <= set(list_references(spec))
        service = ArmorService(store=spec)
        for name in ("b ref", "a/ref"):
            assert service.call({"reference_name": name, "command": "DROP"}).success
        service.close()
        assert not {"a/ref", "b ref"} & set(list_references(spec))
    assert list_references(None) == []


def test_a_missing_server_is_a_clear_error() -> None:
    with pytest.raises(StoreError, match="did not answer"):
        open_store("http://127.0.0.1:9/")


def test_sync_store_commits_and_reopens(tmp_path: Path) -> None:
    from topostore.armor import ArmorService

    ttl = Path(__file__).resolve().parents[1] / "ontology" / "topological_map.ttl"
    service = ArmorService(store=tmp_path / "refs", sync=True)
    base = {"client_name": "c", "reference_name": "r"}
    assert service.call({**base, "command": "LOAD", "primary_command_spec": "FILE",
                         "args": [str(ttl), "http://bnc/exp-rob-lab/2022-23", "false", "", "false"]}).success
    assert service.call({**base, "command": "ADD", "primary_command_spec": "OBJECTPROP", "secondary_command_spec": "IND",
                         "args": ["isIn", "Robot1", "C1"]}).success
    assert service.reference("r").ontology.store.sync is True
    service.close()
    service = ArmorService(store=tmp_path / "refs")
    assert service.call({**base, "command": "QUERY", "primary_command_spec": "OBJECTPROP", "secondary_command_spec": "IND",
                         "args": ["isIn", "Robot1"]}).queried_objects == ["<http://bnc/exp-rob-lab/2022-23#C1>"]
    service.close()


def test_cli_reason_and_query_on_a_store(tmp_path: Path) -> None:
    from click.testing import CliRunner

    from topostore.cli.group import cli

    root = Path(__file__).resolve().parents[1] / "ontology"
    db = str(tmp_path / "mapdb")
    first = CliRunner().invoke(cli, ["reason", "--store", db, str(root / "topological_map.ttl"),
                                     str(root / "topological_map_abox.ttl")])
    assert first.exit_code == 0 and "Consistent." in first.output, first.output
    # no files: the stored ontology, reopened
    answer = CliRunner().invoke(cli, ["query", "--store", db, "reachable-locations", "--param", "robot=Robot1",
                                      "--format", "json"])
    assert answer.exit_code == 0, answer.output
    assert '"location": "http://bnc/exp-rob-lab/2022-23#R1"' in answer.output
    assert '"location": "http://bnc/exp-rob-lab/2022-23#R2"' in answer.output
    missing = CliRunner().invoke(cli, ["reason"])
    assert missing.exit_code == 2 and "--store" in missing.output


def test_two_spellings_of_one_value_in_one_load_keep_the_value() -> None:
    """``1`` and ``"01"^^xsd:int`` are stored as one canonical literal: the second spelling in the
    same transaction must not cancel the first (both used to vanish)."""
    from topostore import Ontology

    onto = Ontology()
    onto.load_data('@prefix : <http://e.org/#> . @prefix xsd: <http://www.w3.org/2001/XMLSchema#> . '
                   ':x :p 1, "01"^^xsd:int, true, "1"^^xsd:boolean, 5 .', "turtle")
    rows = onto.sparql("SELECT ?v WHERE { <http://e.org/#x> <http://e.org/#p> ?v }")
    assert sorted(r["v"].value for r in rows) == ["1", "5", "true"]


def test_an_in_memory_store_is_compacted_after_a_fiftieth_of_its_quads_in_writes() -> None:
    """Removed quads stay in an in-memory store until it is rebuilt: after 200 writes for a small one, after
    a fiftieth of its live quads for a big one (not after its first 200 writes: a rebuild costs the map)."""
    small, big = memory_store(), memory_store()
    small.add([Triple(A, P, B)], ASSERTED)  # one write each
    big.add([Triple(NamedNode(f"urn:x:s{k}"), P, B) for k in range(20_000)], ASSERTED)

    def writes(store, n: int) -> None:
        for k in range(n):
            store.update(f"INSERT DATA {{ GRAPH {ASSERTED} {{ <urn:x:w> <urn:x:p> {k} }} }} ; "
                         f"DELETE DATA {{ GRAPH {ASSERTED} {{ <urn:x:w> <urn:x:p> {k} }} }}")

    for store in (small, big):
        writes(store, 198)
        assert not store.maybe_compact()  # 199 writes
        writes(store, 1)
    assert small.maybe_compact()  # 200 writes
    assert not big.maybe_compact()  # 20,000 live quads: once every 400 writes
    writes(big, 199)
    assert not big.maybe_compact()
    writes(big, 1)
    assert big.maybe_compact()
    assert small.count(ASSERTED) == 1 and big.count(ASSERTED) == 20_000  # the live quads, all of them


def test_memory_discard_removes_a_literal_triple_in_any_spelling() -> None:
    """An in-memory discard finds a literal triple by subject and predicate and compares stored forms:
    the same value written another way is removed, another value and other graphs are left."""
    store = memory_store()
    s, p = NamedNode("urn:x:s"), NamedNode("urn:x:p")
    scratch, other = NamedNode("urn:x:g1"), NamedNode("urn:x:g2")
    kept = Triple(s, p, Literal("6", datatype=NamedNode(XSD + "integer")))
    for g in (scratch, other):
        store.add_scratch([Triple(s, p, Literal("5", datatype=NamedNode(XSD + "integer"))), kept], g)
    store.discard([Triple(s, p, Literal("05", datatype=NamedNode(XSD + "long")))], (scratch,))
    assert [t.object.value for t in store.triples(s, p, None, scratch)] == ["6"]
    assert sorted(t.object.value for t in store.triples(s, p, None, other)) == ["5", "6"]
