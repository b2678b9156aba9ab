"""The aRMOR-style commands QUERY EXPLAIN, ADD/REMOVE/QUERY SWRL (aRMOR's own SWRL key stays undefined)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from support import IRI

from topostore import Ontology
from topostore.armor import ArmorService
from topostore.resources import default_ontology_files

STALE = "LOCATION(?l) ^ visitedAt(?l, ?v) ^ swrlb:lessThan(?v, 1665579736) -> URGENT(?l)"


@pytest.fixture
def armor(tmp_path: Path):
    Ontology.from_file(*default_ontology_files()).save(tmp_path / "example.ttl")
    service = ArmorService(data_dir=tmp_path, short_names=True)

    def call(command: str, spec1: str = "", spec2: str = "", *args: str, ref: str = "ontoRef"):
        return service.call({"client_name": "test", "reference_name": ref, "command": command,
                             "primary_command_spec": spec1, "secondary_command_spec": spec2, "args": list(args)})

    assert call("LOAD", "FILE", "", "example.ttl", IRI, "false", "PELLET", "false").success
    return call


def test_query_explain(armor) -> None:
    lines = armor("QUERY", "EXPLAIN", "", "R1", "rdf:type", "URGENT").queried_objects
    assert lines[0] == "R1 rdf:type URGENT  ← swrl:Urgency: SWRL rule Urgency"
    assert [l.strip() for l in lines if l.startswith("  ") and not l.startswith("   ")] == [
        "where BIND((?t - ?v) AS ?d) FILTER(?d > ?h)  with ?d = 30, ?h = 7, ?l = R1, ?r = Robot1, ?t = 1665579740, ?v = 1665579710",
        "Robot1 rdf:type ROBOT  ← prp-dom: isIn domain ROBOT",
        "Robot1 now 1665579740  [asserted]",
        "R1 rdf:type LOCATION  ← prp-dom: hasDoor domain LOCATION",
        "R1 visitedAt 1665579710  [asserted]",
        "Robot1 urgencyThreshold 7  [asserted]"]
    assert armor("QUERY", "EXPLAIN", "", "R2", "a", "URGENT").queried_objects == ["R2 rdf:type URGENT  [not entailed]"]
    tree = json.loads(armor("QUERY", "EXPLAIN", "JSON", "R1", "visitedAt", "1665579710").queried_objects[0])
    assert tree == {"triple": "R1 visitedAt 1665579710", "status": "asserted"}
    bad = armor("QUERY", "EXPLAIN", "", "R1", "rdf:type")
    assert (bad.success, bad.exit_code) == (False, 208)
    bad = armor("QUERY", "EXPLAIN", "", "R 1", "rdf:type", "URGENT")
    assert (bad.success, bad.exit_code) == (False, 208)


def test_add_query_remove_swrl(armor, tmp_path: Path) -> None:
    assert armor("QUERY", "SWRL").queried_objects == ["Connectability", "Reachability", "Urgency"]
    assert armor("ADD", "SWRL", "", "Stale", STALE, "locations not seen for a while").success
    assert armor("QUERY", "IND", "CLASS", "URGENT").queried_objects == ["R1", "R2"]   # live reasoner
    assert armor("QUERY", "SWRL").queried_objects == ["Connectability", "Reachability", "Stale", "Urgency"]
    assert armor("SAVE", "", "", "saved.owl").success
    assert armor("LOAD", "FILE", "", "saved.owl", IRI, "false", "PELLET", "false", ref="again").success
    assert armor("QUERY", "IND", "CLASS", "URGENT", ref="again").queried_objects == ["R1", "R2"]
    assert armor("REMOVE", "SWRL", "", "Stale").success
    assert armor("QUERY", "IND", "CLASS", "URGENT").queried_objects == ["R1"]
    missing = armor("REMOVE", "SWRL", "", "Stale")
    assert (missing.success, missing.exit_code) == (False, 208)
    assert "no SWRL rule labelled 'Stale'" in missing.error_description


def test_add_swrl_refuses_a_rule_that_cannot_compile(armor) -> None:
    res = armor("ADD", "SWRL", "", "Bad", "LOCATION(?l) ^ swrlb:greaterThan(?v, 3) -> URGENT(?l)")
    assert (res.success, res.exit_code) == (False, 208)
    assert res.error_description == ("SWRL rule 'Bad' refused: SWRL rule 'Bad', atom BuiltinAtom(greaterThan, v, 3): "
                                     "its input variables are never bound (rule is not DL-safe)")
    assert armor("QUERY", "SWRL").queried_objects == ["Connectability", "Reachability", "Urgency"]
    assert armor("SWRL").exit_code == 205


def test_buffered_manipulation_applies_rules_at_reason(tmp_path: Path) -> None:
    Ontology.from_file(*default_ontology_files()).save(tmp_path / "example.ttl")
    service = ArmorService(data_dir=tmp_path)

    def call(command: str, spec1: str = "", spec2: str = "", *args: str):
        return service.call({"client_name": "t", "reference_name": "b", "command": command,
                             "primary_command_spec": spec1, "secondary_command_spec": spec2, "args": list(args)})

    assert call("LOAD", "FILE", "", "example.ttl", IRI, "true", "PELLET", "true").success
    assert call("ADD", "SWRL", "", "Stale", STALE).success
    assert call("QUERY", "SWRL").queried_objects == ["Connectability", "Reachability", "Urgency"]
    assert call("REASON").success
    assert call("QUERY", "SWRL").queried_objects == ["Connectability", "Reachability", "Stale", "Urgency"]
    assert len(call("QUERY", "IND", "CLASS", "URGENT").queried_objects) == 2
