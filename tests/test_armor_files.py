"""SAVE / SAVE INFERENCE round trips, saved SWRL structure, and data_dir confinement."""

from __future__ import annotations

import os
from pathlib import Path

import pytest
import rdflib
from support import ABOX_OWL as ABOX
from support import IRI

from topostore import Ontology
from topostore.armor import ArmorResponse, ArmorService

NS = IRI + "#"
SWRL = rdflib.Namespace("http://www.w3.org/2003/11/swrl#")


def call(svc: ArmorService, command: str, spec1: str = "", spec2: str = "", args=(), ref: str = "ref") -> ArmorResponse:
    return svc.call({"client_name": "c", "reference_name": ref, "command": command,
                     "primary_command_spec": spec1, "secondary_command_spec": spec2, "args": list(args)})


def ok(svc: ArmorService, *a, **k) -> ArmorResponse:
    res = call(svc, *a, **k)
    assert res.success and res.exit_code == 0, (a, res)
    return res


def loaded(path: Path | str = ABOX, **options) -> ArmorService:
    svc = ArmorService(**options)
    ok(svc, "LOAD", "FILE", "", [str(path), IRI, "false", "PELLET", "false"])
    return svc


def asserted(svc: ArmorService) -> int:
    return len(svc.reference("ref").ontology.triples())


@pytest.mark.parametrize("name,fmt", [("saved.owl", "xml"), ("saved.rdf", "xml"), ("saved.ttl", "turtle")])
def test_save_round_trip(tmp_path: Path, name: str, fmt: str) -> None:
    svc = loaded()
    ok(svc, "REPLACE", "DATAPROP", "IND", ["now", "Robot1", "LONG", "1665579700", "1665579740"])
    target = tmp_path / name
    ok(svc, "SAVE", "", "", [str(target)])
    graph = rdflib.Graph().parse(target, format=fmt)  # a standard parser reads it
    assert len(list(graph.subjects(rdflib.RDF.type, SWRL.Imp))) == 3  # rules stay rules
    variables = set(graph.subjects(rdflib.RDF.type, SWRL.Variable))
    assert variables and all(isinstance(v, rdflib.URIRef) for v in variables)
    assert all(isinstance(a, rdflib.URIRef) for a in graph.objects(None, SWRL.argument1)
               if (a, rdflib.RDF.type, SWRL.Variable) in graph)
    assert len(list(graph.subjects(rdflib.RDF.type, rdflib.OWL.AllDifferent))) == 2  # as in the loaded file

    again = ArmorService()
    ok(again, "LOAD", "FILE", "", [str(target), IRI, "false", "PELLET", "false"])
    for query in (["URGENT"], ["CORRIDOR"], ["ROOM"]):
        assert ok(again, "QUERY", "IND", "CLASS", query).queried_objects == ok(svc, "QUERY", "IND", "CLASS", query).queried_objects
    # now - visitedAt: R1 1665579700-1665579710 < 0 → nothing is URGENT any more, in both
    assert ok(again, "QUERY", "IND", "CLASS", ["URGENT"]).queried_objects == []
    assert ok(again, "QUERY", "DATAPROP", "IND", ["now", "Robot1"]).queried_objects == ['"1665579700"^^xsd:long']


def test_save_inference_writes_inferred_and_leaves_reference_unchanged(tmp_path: Path) -> None:
    svc = loaded()
    before = asserted(svc)
    target = tmp_path / "inferred.ttl"
    ok(svc, "SAVE", "INFERENCE", "", [str(target)])
    assert asserted(svc) == before
    onto = Ontology.from_file(target, prefix=NS)
    assert sorted(onto.short(v) for v in onto.store.objects(
        onto.iri("Robot1"), onto.iri("canReach"), onto.visible_graphs()[0])) == ["R1", "R2"]
    plain = tmp_path / "plain.ttl"
    ok(svc, "SAVE", "", "", [str(plain)])
    # canReach(Robot1, R1) is inferred only: present in the inference file, absent from the plain one
    plain_graph = rdflib.Graph().parse(plain, format="turtle")
    inferred_graph = rdflib.Graph().parse(target, format="turtle")
    fact = (rdflib.URIRef(NS + "Robot1"), rdflib.URIRef(NS + "canReach"), rdflib.URIRef(NS + "R1"))
    assert fact in inferred_graph and fact not in plain_graph


def test_save_empty_path_overwrites_source(tmp_path: Path) -> None:
    source = tmp_path / "map.owl"
    source.write_bytes(ABOX.read_bytes())
    svc = loaded(source)
    ok(svc, "ADD", "IND", "CLASS", ["K1", "ROOM"])
    ok(svc, "SAVE", "", "", [""])
    assert NS + "K1" in source.read_text()


def test_save_errors(tmp_path: Path) -> None:
    svc = loaded()
    res = call(svc, "SAVE", "", "", [str(tmp_path / "no" / "such" / "dir.owl")])
    assert (res.success, res.exit_code) == (False, 210)
    res = call(svc, "SAVE", "", "", [])
    assert (res.success, res.exit_code) == (False, 208)


def test_save_reports_unsaved_buffer(tmp_path: Path) -> None:
    svc = ArmorService()
    ok(svc, "LOAD", "FILE", "", [str(ABOX), IRI, "true", "PELLET", "false"])
    ok(svc, "ADD", "IND", "CLASS", ["K1", "ROOM"])
    res = ok(svc, "SAVE", "", "", [str(tmp_path / "x.owl")])
    assert "not saved" in res.error_description
    assert NS + "K1" not in (tmp_path / "x.owl").read_text()


@pytest.fixture
def data_dir(tmp_path: Path) -> Path:
    root = tmp_path / "data"
    root.mkdir()
    (root / "map.owl").write_bytes(ABOX.read_bytes())
    (tmp_path / "outside.owl").write_bytes(ABOX.read_bytes())
    os.symlink(tmp_path / "outside.owl", root / "link.owl")
    os.symlink(tmp_path, root / "up")
    return root


def test_data_dir_allows_paths_inside(data_dir: Path) -> None:
    svc = loaded("map.owl", data_dir=data_dir)
    ok(svc, "SAVE", "", "", ["sub.ttl"])
    assert (data_dir / "sub.ttl").is_file()
    ok(svc, "SAVE", "", "", [str(data_dir / "abs.owl")])
    assert (data_dir / "abs.owl").is_file()


@pytest.mark.parametrize("path", ["../outside.owl", "link.owl", "up/outside.owl", "/etc/hostname", "a/../../outside.owl"])
def test_data_dir_refuses_escapes(data_dir: Path, path: str) -> None:
    svc = ArmorService(data_dir=data_dir)
    res = call(svc, "LOAD", "FILE", "", [path, IRI, "false", "PELLET", "false"])
    assert (res.success, res.exit_code) == (False, 210) and "outside the data directory" in res.error_description
    svc2 = loaded("map.owl", data_dir=data_dir)
    res = call(svc2, "SAVE", "", "", [path])
    assert (res.success, res.exit_code) == (False, 210)
    res = call(svc2, "LOG", "FILE", "ON", [path])
    assert (res.success, res.exit_code) == (False, 210)
    assert (data_dir.parent / "outside.owl").read_bytes() == ABOX.read_bytes()
