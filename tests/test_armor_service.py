"""ArmorService: the seed tutorial, every command combination, error codes, buffering, mounting."""

from __future__ import annotations

from pathlib import Path

import pytest
import rdflib
from pyoxigraph import NamedNode, Triple
from rdflib.compare import isomorphic
from support import ABOX_OWL as ABOX
from support import IRI
from support import TBOX_OWL as TBOX

from topostore import ArmorService as TopLevelArmorService
from topostore.armor import ArmorRequest, ArmorResponse, ArmorService
from topostore.rdf.declarations import missing_declarations
from topostore.rdf.vocab import ASSERTED, TYPE, owl

NS = IRI + "#"


def full(name: str) -> str:
    return f"<{NS}{name}>"


def call(svc: ArmorService, command: str, spec1: str = "", spec2: str = "", args=(), client: str = "c",
         ref: str = "ref") -> ArmorResponse:
    return svc.call({"client_name": client, "reference_name": ref, "command": command,
                     "primary_command_spec": spec1, "secondary_command_spec": spec2, "args": list(args)})


def ok(svc: ArmorService, *a, **k) -> ArmorResponse:
    res = call(svc, *a, **k)
    assert res.success and res.exit_code == 0, (a, res)
    return res


def load(svc: ArmorService, path: Path = ABOX, buf_manip: str = "false", reasoner: str = "PELLET",
         buf_reasoner: str = "false", ref: str = "ref") -> ArmorResponse:
    return ok(svc, "LOAD", "FILE", "", [str(path), IRI, buf_manip, reasoner, buf_reasoner], ref=ref)


def state(svc: ArmorService, ref: str = "ref") -> tuple:
    """Everything a failed command must leave unchanged."""
    r = svc.reference(ref)
    return (sorted(str(t) for t in r.ontology.store.triples(graph=ASSERTED)), len(r.buffer), r.owner,
            r.buffered_manipulation, r.buffered_reasoner)


@pytest.fixture
def svc() -> ArmorService:
    s = ArmorService()
    load(s)
    return s


# ------------------------------------------------------------------ seed tutorial

@pytest.mark.parametrize("short_names", [False, True])
def test_seed_tutorial(short_names: bool, tmp_path: Path) -> None:
    """The topological_map tutorial: build E with two doors, place the robot, reason, query, save."""
    svc = ArmorService(short_names=short_names)
    ok(svc, "LOAD", "FILE", "", [str(TBOX), IRI, "true", "PELLET", "true"])
    for door in ("D6", "D7"):
        ok(svc, "ADD", "OBJECTPROP", "IND", ["hasDoor", "E", door])
    ok(svc, "ADD", "OBJECTPROP", "IND", ["hasDoor", "R3", "D6"])
    ok(svc, "ADD", "DATAPROP", "IND", ["visitedAt", "E", "LONG", "1665579700"])
    ok(svc, "ADD", "DATAPROP", "IND", ["visitedAt", "R3", "LONG", "1665579735"])
    ok(svc, "DISJOINT", "IND", "", ["E", "R3", "D6", "D7"])
    ok(svc, "ADD", "OBJECTPROP", "IND", ["isIn", "Robot1", "R3"])
    ok(svc, "REPLACE", "OBJECTPROP", "IND", ["isIn", "Robot1", "E", "R3"])
    res = ok(svc, "REASON")
    assert res.is_consistent
    now = ok(svc, "QUERY", "DATAPROP", "IND", ["now", "Robot1"]).queried_objects
    assert now == (["1665579740"] if short_names else ['"1665579740"^^xsd:long'])
    ok(svc, "REPLACE", "DATAPROP", "IND", ["now", "Robot1", "LONG", "1665579750", "1665579740"])
    ok(svc, "REPLACE", "DATAPROP", "IND", ["visitedAt", "E", "LONG", "1665579750", "1665579700"])
    ok(svc, "REASON")
    reach = ok(svc, "QUERY", "OBJECTPROP", "IND", ["canReach", "Robot1"]).queried_objects
    assert reach == (["R3"] if short_names else [full("R3")])
    # R3: 1665579750 - 1665579735 = 15 > 7 → URGENT; E was just visited → not URGENT.
    urgent = ok(svc, "QUERY", "IND", "CLASS", ["URGENT"]).queried_objects
    assert urgent == (["R3"] if short_names else [full("R3")])
    classes = ok(svc, "QUERY", "CLASS", "IND", ["E", "false"]).queried_objects
    expected = ["CORRIDOR", "LOCATION", "ROOM"]
    assert classes == (expected if short_names else [full(c) for c in expected])
    assert ok(svc, "QUERY", "CLASS", "IND", ["E", "true"]).queried_objects == ["CORRIDOR"]
    target = tmp_path / "tutorial.owl"
    ok(svc, "SAVE", "", "", [str(target)])
    saved = assert_saved(svc, target)
    assert (rdflib.URIRef(NS + "E"), rdflib.URIRef(NS + "hasDoor"), rdflib.URIRef(NS + "D7")) in saved
    assert (rdflib.URIRef(NS + "Robot1"), rdflib.URIRef(NS + "isIn"), rdflib.URIRef(NS + "E")) in saved
    assert (rdflib.URIRef(NS + "Robot1"), rdflib.URIRef(NS + "canReach"), None) not in saved  # asserted only


def assert_saved(svc: ArmorService, path: Path, ref: str = "ref") -> rdflib.Graph:
    """The file SAVE wrote holds exactly the reference's asserted triples (blank nodes up to renaming) and the
    declarations they lack."""
    saved = rdflib.Graph().parse(path, format="xml")
    onto = svc.reference(ref).ontology
    current = rdflib.Graph().parse(data=onto.serialize("nt"), format="nt")
    assert len(saved) == len(current) == asserted_count(svc, ref=ref) + len(missing_declarations(onto.triples()))
    assert isomorphic(saved, current)
    return saved


def test_top_level_export() -> None:
    assert TopLevelArmorService is ArmorService


# ------------------------------------------------------------------ dispatcher

def test_empty_reference_is_201() -> None:
    res = ArmorService().call({"command": "GET", "primary_command_spec": "ALL", "secondary_command_spec": "REFS"})
    assert (res.success, res.exit_code, res.is_consistent) == (False, 201, False)


def test_empty_command_is_202_with_consistency(svc: ArmorService) -> None:
    res = call(svc, "")
    assert (res.success, res.exit_code, res.is_consistent) == (False, 202, True)


@pytest.mark.parametrize("command,spec1,spec2", [
    ("ADD ", "IND", ""), ("QUERY", "IND", "CLASS "), ("ADD", "IND", "CLASS_X"), ("ADD_IND", "", ""),
    ("QUERY", "DATAPROP", "CLASS"), ("SWRL", "", ""), ("ADD", "DATAPROP", ""),
])
def test_unknown_combination_is_205(svc: ArmorService, command: str, spec1: str, spec2: str) -> None:
    before = state(svc)
    res = call(svc, command, spec1, spec2, ["LOCATION"])
    assert (res.success, res.exit_code, res.is_consistent) == (False, 205, True)
    assert "unknown command" in res.error_description
    assert state(svc) == before


def test_invalid_command_is_205(svc: ArmorService) -> None:
    res = call(svc, "INVALID", "COMMAND")
    assert (res.success, res.exit_code) == (False, 205)


def test_commands_and_specs_case_insensitive_args_not(svc: ArmorService) -> None:
    assert call(svc, "query", "Ind", "class", ["ROOM"]).queried_objects == [full("C1"), full("R1"), full("R2")]
    assert call(svc, "QUERY", "IND", "CLASS", ["room"]).queried_objects == []


def test_empty_spec_is_significant(svc: ArmorService) -> None:
    assert ok(svc, "QUERY", "IND", "", ["R1"]).queried_objects == [full("LOCATION"), full("ROOM"), full("URGENT")]
    assert ok(svc, "QUERY", "IND", "CLASS", ["DOOR"]).queried_objects == [full("D1"), full("D2")]


def test_a_shape_resolved_once_still_checks_what_its_count_does_not_say(svc: ArmorService) -> None:
    """A command's table entry is kept per spelling and argument count; an argument-less command's
    tolerance of ``['']`` is decided by the arguments' contents, every call."""
    for _ in range(2):
        assert ok(svc, "REASON", "", "", [""]).exit_code == 0
        res = call(svc, "REASON", "", "", ["x"])
        assert (res.success, res.exit_code) == (False, 208) and "expected 0 argument(s)" in res.error_description
        res = call(svc, "ADD", "IND", "", ["a", "b"])
        assert (res.success, res.exit_code) == (False, 208)
        assert call(svc, "add", "ind", "", ["A_NEW"]).success
        res = call(svc, "add", "ind", "x", ["A_NEW"])
        assert (res.success, res.exit_code) == (False, 205)


def test_unknown_reference_is_207() -> None:
    svc = ArmorService()
    for command, spec1, spec2, args in [("QUERY", "IND", "CLASS", ["ROOM"]), ("ADD", "IND", "", ["x"]),
                                        ("MOUNT", "", "", []), ("UNMOUNT", "", "", []), ("SAVE", "", "", ["x.owl"]),
                                        ("GET", "REF", "CLIENT", ["nope"]), ("REASON", "", "", [])]:
        res = call(svc, command, spec1, spec2, args, ref="nope")
        assert (res.success, res.exit_code, res.is_consistent) == (False, 207, False), command
        assert "LOAD it first" in res.error_description


def test_each_command_names_entities_in_its_own_references_namespace(tmp_path: Path) -> None:
    """One argument names an entity of the reference the command is sent to: a command on a reference of
    another namespace, between two on this one, reads its own (a name is read as the reference's IRI at
    each command, never as the last command's)."""
    svc = ArmorService()
    other = "http://example.org/other"
    path = tmp_path / "other.ttl"
    path.write_text(f"@prefix : <{other}#> . @prefix owl: <http://www.w3.org/2002/07/owl#> .\n"
                    ":Robot a owl:Class . :r1 a :Robot .")
    load(svc)
    ok(svc, "LOAD", "FILE", "", [str(path), other, "false", "PELLET", "false"], ref="other")
    for ref, ns in (("ref", NS), ("other", other + "#"), ("ref", NS), ("other", other + "#")):
        ok(svc, "ADD", "IND", "CLASS", ["twin", "Robot"], ref=ref)
        members = call(svc, "QUERY", "IND", "CLASS", ["Robot"], ref=ref).queried_objects
        assert f"<{ns}twin>" in members and not any("twin" in m and ns not in m for m in members), (ref, members)


def test_malformed_request_dict_is_208() -> None:
    res = ArmorService().call({"reference_name": "r", "command": "ADD", "args": "notalist"})
    assert (res.success, res.exit_code) == (False, 208)
    res = ArmorService().call({"reference_name": "r", "command": "ADD", "args": [1, 2]})
    assert (res.success, res.exit_code) == (False, 208)


def test_request_dataclass_roundtrip() -> None:
    req = ArmorRequest("c", "r", "QUERY", "IND", "CLASS", ["X"])
    assert ArmorRequest.from_dict(req.to_dict()) == req
    res = ArmorResponse(True, 0, "", True, False, ["a"])
    assert ArmorResponse.from_dict(res.to_dict()) == res


# ------------------------------------------------------------------ queries

def test_query_ind_class_dataprop_objectprop(svc: ArmorService) -> None:
    assert ok(svc, "QUERY", "DATAPROP", "IND", ["visitedAt", "R1"]).queried_objects == ['"1665579710"^^xsd:long']
    assert ok(svc, "QUERY", "OBJECTPROP", "IND", ["connectedTo", "C1"]).queried_objects == [full("R1"), full("R2")]
    assert ok(svc, "QUERY", "OBJECTPROP", "IND", ["canReach", "Robot1"]).queried_objects == [full("R1"), full("R2")]
    assert ok(svc, "QUERY", "IND", "DATAPROP", ["Robot1"]).queried_objects == [full("now"), full("urgencyThreshold")]
    assert ok(svc, "QUERY", "IND", "OBJECTPROP", ["Robot1"]).queried_objects == [full("canReach"), full("isIn")]
    assert ok(svc, "QUERY", "IND", "CLASS", ["URGENT"]).queried_objects == [full("R1")]
    assert ok(svc, "QUERY", "IND", "CLASS", ["Unknown"]).queried_objects == []


def test_query_ind_not_found_and_thing_only(svc: ArmorService) -> None:
    res = call(svc, "QUERY", "IND", "", ["Ghost"])
    assert (res.success, res.exit_code, res.queried_objects) == (False, 0, [])
    ok(svc, "ADD", "IND", "", ["Ghost"])
    assert ok(svc, "QUERY", "IND", "", ["Ghost"]).queried_objects == ["owl:Thing"]


def test_query_class_ind_bottom(svc: ArmorService) -> None:
    assert ok(svc, "QUERY", "CLASS", "IND", ["C1", "true"]).queried_objects == ["CORRIDOR"]
    assert ok(svc, "QUERY", "CLASS", "IND", ["R1", "true"]).queried_objects == ["ROOM", "URGENT"]
    assert ok(svc, "QUERY", "CLASS", "IND", ["R1"]).queried_objects == [full("LOCATION"), full("ROOM"), full("URGENT")]
    assert ok(svc, "QUERY", "CLASS", "IND", ["Nobody", "true"]).queried_objects == []
    # read as aRMOR's Java reads it (Boolean.parseBoolean): "true" in any case, everything else false
    every = [full("LOCATION"), full("ROOM"), full("URGENT")]
    assert ok(svc, "QUERY", "CLASS", "IND", ["R1", "TRUE"]).queried_objects == ["ROOM", "URGENT"]
    for other in ("1", "yes", "maybe", "", " true"):
        assert ok(svc, "QUERY", "CLASS", "IND", ["R1", other]).queried_objects == every


def test_query_class_class_has_no_owl_nothing(svc: ArmorService) -> None:
    assert ok(svc, "QUERY", "CLASS", "CLASS", ["LOCATION"]).queried_objects == [full("CORRIDOR"), full("ROOM"), full("URGENT")]
    assert ok(svc, "QUERY", "CLASS", "CLASS", ["CORRIDOR"]).queried_objects == []


def test_query_class_restrictions(svc: ArmorService) -> None:
    res = ok(svc, "QUERY", "CLASS", "RESTRICTIONS", ["CORRIDOR"]).queried_objects
    assert res == ["[C-DEFINITION_CLASS : CORRIDOR -> (LOCATION), C-DEFINITION_MIN_OBJECT : CORRIDOR -> hasDoor 2(DOOR)]"]
    assert ok(svc, "QUERY", "CLASS", "RESTRICTIONS", ["LOCATION"]).queried_objects == [
        "[C-DEFINITION_EXACT_DATA : LOCATION -> visitedAt 1(xsd:long)]"]
    # SubClassOf restrictions are reported too (spec §7 item 12), e.g. one made by ADD CARDINALITY MIN
    ok(svc, "ADD", "CARDINALITY", "MIN", ["ROOM", "hasDoor", "1", "DOOR"])
    assert ok(svc, "QUERY", "CLASS", "RESTRICTIONS", ["ROOM"]).queried_objects == [
        "[C-DEFINITION_CLASS : ROOM -> (LOCATION), C-DEFINITION_SOME_OBJECT : ROOM -> hasDoor(DOOR)]",
        "[C-DEFINITION_MIN_OBJECT : ROOM -> hasDoor 1(DOOR)]"]


SELECT_LOCATIONS = f"PREFIX x: <{NS}> SELECT ?l ?t WHERE {{ ?l a x:LOCATION OPTIONAL {{ ?l x:doesNotExist ?t }} }} ORDER BY ?l"


def test_sparql_flat_and_formatted_over_inferred(svc: ArmorService) -> None:
    flat = ok(svc, "QUERY", "SPARQL", "", [SELECT_LOCATIONS]).queried_objects
    # LOCATION is only inferred for C1/R1/R2 (from hasDoor's domain): SPARQL sees inferences.
    assert flat == [f"{{l={NS}C1, t=}}, {{l={NS}R1, t=}}, {{l={NS}R2, t=}}"]
    res = ok(svc, "QUERY", "SPARQL", "FORMATTED", [f"PREFIX x: <{NS}> ", "SELECT ?v ", "WHERE { x:R1 x:visitedAt ?v }", "5000"])
    assert [i.to_dict() for i in res.sparql_queried_objects] == [
        {"key": "v", "value": "1665579710^^http://www.w3.org/2001/XMLSchema#long"}]
    assert res.queried_objects == [] and res.timeout is False
    res = ok(svc, "QUERY", "SPARQL", "FORMATTED", [SELECT_LOCATIONS, "0"])
    assert [(i.key, i.value) for i in res.sparql_queried_objects][:2] == [("l", NS + "C1"), ("t", "")]
    assert ok(svc, "QUERY", "SPARQL", "", ["SELECT ?x WHERE { ?x ?y \"[kept]\" }"]).queried_objects == [""]


@pytest.mark.parametrize("args,code", [
    (["ASK { ?s ?p ?o }"], 209), (["SELEC ?x"], 209), (["SELECT * WHERE { ?s ?p ?o }", "soon"], 208),
    ([], 208), (["a", "b", "c", "1", "e"], 208),
])
def test_sparql_errors(svc: ArmorService, args: list[str], code: int) -> None:
    res = call(svc, "QUERY", "SPARQL", "FORMATTED", args)
    assert (res.success, res.exit_code) == (False, code)
    assert res.error_description


def test_sparql_timeout_returns_partial_rows(svc: ArmorService) -> None:
    slow = "SELECT * WHERE { ?a ?b ?c . ?d ?e ?f . ?g ?h ?i . ?j ?k ?l }"
    res = ok(svc, "QUERY", "SPARQL", "FORMATTED", [slow, "200"])
    assert res.timeout is True
    rows, rest = divmod(len(res.sparql_queried_objects), 12)
    assert rows >= 1 and rest == 0  # some rows came back before the limit, and only whole ones
    assert [i.key for i in res.sparql_queried_objects] == list("abcdefghijkl") * rows
    assert ok(svc, "QUERY", "IND", "CLASS", ["URGENT"]).queried_objects == [full("R1")]  # still answering


# ------------------------------------------------------------------ manipulations (success)

def asserted_count(svc: ArmorService, s=None, p=None, o=None, ref: str = "ref") -> int:
    return len(list(svc.reference(ref).ontology.store.triples(s, p, o, ASSERTED)))


def test_add_ind_and_class_and_remove(svc: ArmorService) -> None:
    ok(svc, "ADD", "CLASS", "", ["KITCHEN"])
    ok(svc, "ADD", "CLASS", "CLASS", ["KITCHEN", "ROOM"])
    ok(svc, "ADD", "IND", "CLASS", ["K1", "KITCHEN"])
    assert ok(svc, "QUERY", "IND", "CLASS", ["ROOM"]).queried_objects == [full("C1"), full("K1"), full("R1"), full("R2")]
    assert ok(svc, "QUERY", "CLASS", "CLASS", ["LOCATION"]).queried_objects == [
        full("CORRIDOR"), full("KITCHEN"), full("ROOM"), full("URGENT")]
    ok(svc, "REMOVE", "CLASS", "", ["KITCHEN"])  # only SubClassOf(KITCHEN owl:Thing) goes
    assert ok(svc, "QUERY", "CLASS", "CLASS", ["ROOM"]).queried_objects == [full("CORRIDOR"), full("KITCHEN")]
    ok(svc, "REMOVE", "CLASS", "CLASS", ["KITCHEN", "ROOM"])
    assert ok(svc, "QUERY", "CLASS", "CLASS", ["ROOM"]).queried_objects == [full("CORRIDOR")]
    ok(svc, "REMOVE", "IND", "CLASS", ["K1", "KITCHEN"])
    assert ok(svc, "QUERY", "IND", "CLASS", ["KITCHEN"]).queried_objects == []


def test_dataprop_add_remove_replace_by_value(svc: ArmorService) -> None:
    ok(svc, "ADD", "DATAPROP", "IND", ["label", "R1", "STRING", 'say "hi"\\'])
    assert ok(svc, "QUERY", "DATAPROP", "IND", ["label", "R1"]).queried_objects == ['"say \\"hi\\"\\\\"^^xsd:string']
    ok(svc, "ADD", "DATAPROP", "IND", ["weight", "R1", "DOUBLE", "2.5"])
    assert ok(svc, "QUERY", "DATAPROP", "IND", ["weight", "R1"]).queried_objects == ['"2.5"^^xsd:double']
    ok(svc, "REMOVE", "DATAPROP", "IND", ["weight", "R1", "DOUBLE", "2.50"])
    assert ok(svc, "QUERY", "DATAPROP", "IND", ["weight", "R1"]).queried_objects == []
    # old value given as INTEGER matches the stored xsd:long (same data value, §7 item 10)
    res = ok(svc, "REPLACE", "DATAPROP", "IND", ["visitedAt", "R1", "LONG", "1665579739", "1665579710"])
    assert res.error_description == ""
    res = ok(svc, "REPLACE", "DATAPROP", "IND", ["visitedAt", "R1", "INTEGER", "1665579720", "1665579739"])
    assert ok(svc, "QUERY", "DATAPROP", "IND", ["visitedAt", "R1"]).queried_objects == ['"1665579720"^^xsd:integer']
    res = ok(svc, "REPLACE", "DATAPROP", "IND", ["visitedAt", "R2", "LONG", "1", "42"])
    assert "was not asserted" in res.error_description
    assert sorted(ok(svc, "QUERY", "DATAPROP", "IND", ["visitedAt", "R2"]).queried_objects) == [
        '"1"^^xsd:long', '"1665579735"^^xsd:long']


def test_objectprop_add_remove_replace(svc: ArmorService) -> None:
    ok(svc, "REPLACE", "OBJECTPROP", "IND", ["isIn", "Robot1", "R1", "C1"])
    assert ok(svc, "QUERY", "OBJECTPROP", "IND", ["canReach", "Robot1"]).queried_objects == [full("C1")]
    ok(svc, "REMOVE", "OBJECTPROP", "IND", ["isIn", "Robot1", "R1"])
    assert ok(svc, "QUERY", "OBJECTPROP", "IND", ["canReach", "Robot1"]).queried_objects == []
    ok(svc, "ADD", "OBJECTPROP", "IND", ["isIn", "Robot1", "R2"])
    assert ok(svc, "QUERY", "OBJECTPROP", "IND", ["canReach", "Robot1"]).queried_objects == [full("C1")]


def test_disjoint_ind_is_one_all_different(svc: ArmorService) -> None:
    before = asserted_count(svc, None, TYPE, owl("AllDifferent"))
    ok(svc, "DISJOINT", "IND", "", ["A", "B", "C", "D", "E", "A"])
    assert asserted_count(svc, None, TYPE, owl("AllDifferent")) == before + 1
    assert asserted_count(svc, None, owl("differentFrom")) == 0
    ok(svc, "REMOVE", "IND", "", ["C"])  # drops the whole axiom and everything about C
    assert asserted_count(svc, None, TYPE, owl("AllDifferent")) == before
    assert asserted_count(svc, NamedNode(NS + "C")) == 0


def test_disjoint_ind_class_makes_corridor(svc: ArmorService) -> None:
    ok(svc, "ADD", "OBJECTPROP", "IND", ["hasDoor", "R1", "D8"])
    ok(svc, "ADD", "OBJECTPROP", "IND", ["hasDoor", "R1", "D9"])
    room = [full("LOCATION"), full("ROOM"), full("URGENT")]
    assert ok(svc, "QUERY", "IND", "", ["R1"]).queried_objects == room  # D8, D9 may be the same door
    ok(svc, "DISJOINT", "IND", "CLASS", ["DOOR"])
    assert ok(svc, "QUERY", "IND", "", ["R1"]).queried_objects == [full("CORRIDOR"), *room]


def test_disjoint_class_and_class_class(svc: ArmorService) -> None:
    ok(svc, "ADD", "IND", "CLASS", ["X", "ROBOT"])
    ok(svc, "ADD", "IND", "CLASS", ["X", "DOOR"])
    assert call(svc, "QUERY", "IND", "", ["X"]).is_consistent is False  # DOOR and ROBOT are disjoint
    ok(svc, "REMOVE", "IND", "", ["X"])
    ok(svc, "ADD", "CLASS", "CLASS", ["BLUE", "THING2"])
    ok(svc, "ADD", "CLASS", "CLASS", ["RED", "THING2"])
    ok(svc, "DISJOINT", "CLASS", "CLASS", ["THING2"])
    ok(svc, "ADD", "IND", "CLASS", ["Y", "BLUE"])
    assert ok(svc, "ADD", "IND", "CLASS", ["Y", "RED"]).is_consistent is False
    ok(svc, "REMOVE", "IND", "CLASS", ["Y", "RED"])
    ok(svc, "DISJOINT", "CLASS", "", ["GREEN", "BLUE"])
    assert ok(svc, "ADD", "IND", "CLASS", ["Y", "GREEN"]).is_consistent is False


def test_make_equivalent_class(svc: ArmorService) -> None:
    ok(svc, "ADD", "CLASS", "CLASS", ["BIG_ROOM", "ROOM"])
    ok(svc, "ADD", "CARDINALITY", "MIN", ["BIG_ROOM", "hasDoor", "2", "DOOR"])
    ok(svc, "MAKE", "EQUIVALENT", "CLASS", ["BIG_ROOM"])
    assert ok(svc, "QUERY", "IND", "", ["C1"]).queried_objects == [  # C1: a room with two doors
        full("BIG_ROOM"), full("CORRIDOR"), full("LOCATION"), full("ROOM")]
    assert ok(svc, "QUERY", "IND", "", ["R1"]).queried_objects == [full("LOCATION"), full("ROOM"), full("URGENT")]
    assert ok(svc, "QUERY", "CLASS", "RESTRICTIONS", ["BIG_ROOM"]).queried_objects == [
        "[C-DEFINITION_CLASS : BIG_ROOM -> (ROOM), C-DEFINITION_MIN_OBJECT : BIG_ROOM -> hasDoor 2(DOOR)]"]


@pytest.mark.parametrize("spec1,spec2", [("MIN", "CARDINALITY"), ("CARDINALITY", "MIN")])
def test_add_min_cardinality_alias(svc: ArmorService, spec1: str, spec2: str) -> None:
    """ADD MIN CARDINALITY (the alias) does what ADD CARDINALITY MIN does, on a class that had no restriction."""
    assert ok(svc, "QUERY", "CLASS", "RESTRICTIONS", ["DOOR"]).queried_objects == []
    ok(svc, "ADD", spec1, spec2, ["DOOR", "hasDoor", "1", "DOOR"])
    assert ok(svc, "QUERY", "CLASS", "RESTRICTIONS", ["DOOR"]).queried_objects == [
        "[C-DEFINITION_MIN_OBJECT : DOOR -> hasDoor 1(DOOR)]"]


@pytest.mark.parametrize("kind,old,new,query,answer", [
    ("IND", "R1", "Kitchen", ("QUERY", "IND", "CLASS", ["URGENT"]), [full("Kitchen")]),
    ("CLASS", "URGENT", "TO_VISIT", ("QUERY", "IND", "CLASS", ["TO_VISIT"]), [full("R1")]),
    ("OBJECTPROP", "canReach", "reaches", ("QUERY", "OBJECTPROP", "IND", ["reaches", "Robot1"]), [full("R1"), full("R2")]),
    ("DATAPROP", "visitedAt", "seenAt", ("QUERY", "DATAPROP", "IND", ["seenAt", "R1"]), ['"1665579710"^^xsd:long']),
])
def test_rename(svc: ArmorService, kind: str, old: str, new: str, query: tuple, answer: list[str]) -> None:
    """The new name carries every asserted fact of the old one (as subject, predicate or object); the old has none."""
    old_node, new_node = NamedNode(NS + old), NamedNode(NS + new)
    before = mentioning(svc, old_node)
    assert before and not mentioning(svc, new_node)
    ok(svc, "RENAME", kind, "", [old, new])
    ok(svc, "REASON")
    assert mentioning(svc, old_node) == set()
    assert mentioning(svc, new_node) == {Triple(*(new_node if t == old_node else t for t in q)) for q in before}
    assert ok(svc, *query).queried_objects == answer


def mentioning(svc: ArmorService, node: NamedNode) -> set[Triple]:
    """Asserted triples with ``node`` as subject, predicate or object."""
    store = svc.reference("ref").ontology.store
    return {t for k in range(3) for t in store.triples(*(node if i == k else None for i in range(3)), ASSERTED)}


def test_rename_unknown_warns(svc: ArmorService) -> None:
    assert "nothing renamed" in ok(svc, "RENAME", "IND", "", ["Nobody", "Somebody"]).error_description


def test_full_iri_names(svc: ArmorService) -> None:
    assert ok(svc, "QUERY", "IND", "CLASS", [f"<{NS}DOOR>"]).queried_objects == [full("D1"), full("D2")]
    ok(svc, "ADD", "IND", "CLASS", ["<http://other.org/x#Z>", "DOOR"])
    assert ok(svc, "QUERY", "IND", "CLASS", ["DOOR"]).queried_objects == [full("D1"), full("D2"), "<http://other.org/x#Z>"]


# ------------------------------------------------------------------ manipulation errors leave state unchanged

BAD_MANIPULATIONS = [
    (("ADD", "DATAPROP", "IND", ["now", "Robot1", "NUMBER", "5"]), 101),
    (("REMOVE", "DATAPROP", "IND", ["now", "Robot1", "NUMBER", "5"]), 101),
    (("REPLACE", "DATAPROP", "IND", ["now", "Robot1", "NUMBER", "5", "1665579740"]), 101),
    (("ADD", "DATAPROP", "IND", ["now", "Robot1", "LONG", "12x"]), 208),
    (("ADD", "DATAPROP", "IND", ["now", "Robot1", "INT", "1.0"]), 208),
    (("ADD", "DATAPROP", "IND", ["flag", "Robot1", "BOOLEAN", "yes"]), 208),
    (("REPLACE", "DATAPROP", "IND", ["now", "Robot1", "LONG", "5", "old"]), 208),
    (("ADD", "DATAPROP", "IND", ["now", "Robot1", "LONG"]), 208),
    (("ADD", "DATAPROP", "IND", ["now", "Robot1", "LONG", "1", "2"]), 208),
    (("ADD", "IND", "CLASS", ["R 9", "ROOM"]), 208),
    (("ADD", "IND", "CLASS", ["R9", "RO>OM"]), 208),
    (("ADD", "OBJECTPROP", "IND", ["isIn", "Robot1", "a{b}"]), 208),
    (("ADD", "OBJECTPROP", "IND", ["isIn", "Robot1", ""]), 208),
    (("ADD", "CARDINALITY", "MIN", ["ROOM", "hasDoor", "-1", "DOOR"]), 208),
    (("ADD", "CARDINALITY", "MIN", ["ROOM", "hasDoor", "two", "DOOR"]), 208),
    (("DISJOINT", "IND", "", ["A", "A"]), 208),
    (("DISJOINT", "IND", "", ["A", "B|C"]), 208),
    (("DISJOINT", "CLASS", "", ["A"]), 208),
    (("REMOVE", "IND", "", []), 208),
    (("RENAME", "IND", "", ["R1", "R`1"]), 208),
    (("REPLACE", "OBJECTPROP", "IND", ["isIn", "Robot1", "R1"]), 208),
    (("APPLY", "", "", ["extra"]), 208),
    (("ADD", "IND", "", ["<not an iri>"]), 208),
]


@pytest.mark.parametrize("request_,code", BAD_MANIPULATIONS)
def test_failed_manipulation_changes_nothing(svc: ArmorService, request_: tuple, code: int) -> None:
    before = state(svc)
    res = call(svc, *request_)
    assert (res.success, res.exit_code) == (False, code), res
    assert res.error_description and res.is_consistent is True
    assert state(svc) == before


def test_inconsistency_reported_and_recovered(svc: ArmorService) -> None:
    ok(svc, "DISJOINT", "IND", "", ["C1", "R1", "R2"])
    res = ok(svc, "ADD", "OBJECTPROP", "IND", ["isIn", "Robot1", "R1"])  # isIn is functional; C1 ≠ R1
    assert res.is_consistent is False
    assert call(svc, "QUERY", "IND", "CLASS", ["ROOM"]).is_consistent is False
    res = ok(svc, "REMOVE", "OBJECTPROP", "IND", ["isIn", "Robot1", "R1"])
    assert res.is_consistent is True
    assert ok(svc, "QUERY", "OBJECTPROP", "IND", ["canReach", "Robot1"]).queried_objects == [full("R1"), full("R2")]


# ------------------------------------------------------------------ buffering

def test_manipulation_buffer_and_apply() -> None:
    svc = ArmorService()
    load(svc, buf_manip="true")
    ok(svc, "ADD", "IND", "CLASS", ["K1", "ROOM"])
    assert ok(svc, "QUERY", "IND", "CLASS", ["ROOM"]).queried_objects == [full("C1"), full("R1"), full("R2")]
    ok(svc, "APPLY")
    assert ok(svc, "QUERY", "IND", "CLASS", ["ROOM"]).queried_objects == [full("C1"), full("K1"), full("R1"), full("R2")]
    assert svc.reference("ref").buffer == []


def test_buffered_reasoner_sees_changes_at_reason_only() -> None:
    svc = ArmorService()
    load(svc, buf_manip="false", buf_reasoner="true")
    ok(svc, "REPLACE", "OBJECTPROP", "IND", ["isIn", "Robot1", "R1", "C1"])
    # stale inferences until REASON (spec §2.5: asserted now ∪ inferred at last sync)
    assert ok(svc, "QUERY", "OBJECTPROP", "IND", ["canReach", "Robot1"]).queried_objects == [full("R1"), full("R2")]
    ok(svc, "REASON")
    assert ok(svc, "QUERY", "OBJECTPROP", "IND", ["canReach", "Robot1"]).queried_objects == [full("C1")]


@pytest.mark.parametrize("buffered", [True, False])
def test_a_buffered_reasoner_answers_removed_asserted_facts_until_reason(buffered: bool) -> None:
    """aRMOR's buffered reasoner answers the state it was last flushed with, told facts included (spec §2.5):
    a fact asserted only and removed since the last REASON is still answered, beside its replacement, until
    the next REASON; a live reasoner sees the removal at once."""
    svc = ArmorService()
    load(svc, buf_reasoner=str(buffered).lower())
    ok(svc, "ADD", "IND", "CLASS", ["Foo", "LOCATION"])
    ok(svc, "REASON")
    ok(svc, "REMOVE", "IND", "CLASS", ["Foo", "LOCATION"])
    ok(svc, "REPLACE", "DATAPROP", "IND", ["urgencyThreshold", "Robot1", "LONG", "15", "7"])
    ok(svc, "REMOVE", "OBJECTPROP", "IND", ["hasDoor", "R1", "D1"])
    stale = {
        ("IND", "CLASS", ("LOCATION",)): full("Foo"),
        ("CLASS", "IND", ("Foo", "false")): full("LOCATION"),
        ("DATAPROP", "IND", ("urgencyThreshold", "Robot1")): '"7"^^xsd:long',
        ("OBJECTPROP", "IND", ("hasDoor", "R1")): full("D1"),
    }
    for (s1, s2, args), old in stale.items():
        assert (old in ok(svc, "QUERY", s1, s2, args).queried_objects) is buffered, (s1, s2, args)
    assert '"15"^^xsd:long' in ok(svc, "QUERY", "DATAPROP", "IND", ["urgencyThreshold", "Robot1"]).queried_objects
    ok(svc, "REASON")
    for (s1, s2, args), old in stale.items():
        assert old not in ok(svc, "QUERY", s1, s2, args).queried_objects, (s1, s2, args)


@pytest.mark.parametrize("buffered", [True, False])
def test_a_buffered_reasoner_answers_the_class_hierarchy_of_the_last_reason(buffered: bool) -> None:
    """QUERY CLASS CLASS is the told subclasses now ∪ the reasoner's (spec §2.5): a buffered reasoner's are those
    of its last REASON, both ways: a subclass told since shows under its told superclass only, one retracted
    since still shows; a live reasoner follows each change."""
    svc = ArmorService()
    load(svc, buf_reasoner=str(buffered).lower())
    ok(svc, "ADD", "CLASS", "CLASS", ["KITCHEN", "ROOM"])
    ok(svc, "REASON")
    ok(svc, "ADD", "CLASS", "CLASS", ["PANTRY", "ROOM"])
    ok(svc, "REMOVE", "CLASS", "CLASS", ["KITCHEN", "ROOM"])

    def under(cls: str) -> list[str]:
        return ok(svc, "QUERY", "CLASS", "CLASS", [cls]).queried_objects

    assert full("PANTRY") in under("ROOM")  # told now
    assert (full("PANTRY") in under("LOCATION")) is not buffered
    assert (full("KITCHEN") in under("ROOM")) is buffered
    assert (full("KITCHEN") in under("LOCATION")) is buffered
    ok(svc, "REASON")
    assert full("KITCHEN") not in under("LOCATION") and full("PANTRY") in under("LOCATION")


@pytest.mark.parametrize("buffered", [True, False])
def test_a_class_hierarchy_answer_and_its_unsatisfiable_warning_come_from_one_classification(buffered: bool) -> None:
    """An unsatisfiable class is listed under every class with a warning naming it, both read from the classification
    answered: a buffered reasoner's of its last REASON (U still unsatisfiable until the next REASON, and warned of),
    a live reasoner's the current one (U satisfiable once U ⊑ BAD is retracted: neither listed nor warned of)."""
    svc = ArmorService()
    load(svc, buf_reasoner=str(buffered).lower())
    ok(svc, "ADD", "CLASS", "CLASS", ["BAD", "DOOR"])
    ok(svc, "ADD", "CLASS", "CLASS", ["BAD", "LOCATION"])  # DOOR and LOCATION are disjoint: BAD unsatisfiable
    ok(svc, "ADD", "CLASS", "CLASS", ["U", "BAD"])
    ok(svc, "REASON")
    ok(svc, "REMOVE", "CLASS", "CLASS", ["U", "BAD"])
    reply = ok(svc, "QUERY", "CLASS", "CLASS", ["ROBOT"])
    assert (full("U") in reply.queried_objects) is buffered
    assert ("U" in reply.error_description) is buffered
    assert full("BAD") in reply.queried_objects and "BAD" in reply.error_description


def test_reason_recovers_after_inconsistency_with_buffers() -> None:
    svc = ArmorService()
    load(svc, buf_manip="true", reasoner="", buf_reasoner="true")
    ok(svc, "DISJOINT", "IND", "", ["C1", "R1"])
    ok(svc, "ADD", "OBJECTPROP", "IND", ["isIn", "Robot1", "R1"])
    assert ok(svc, "REASON").is_consistent is False
    ok(svc, "REMOVE", "OBJECTPROP", "IND", ["isIn", "Robot1", "R1"])
    assert call(svc, "APPLY").is_consistent is False  # APPLY does not synchronise a buffered reasoner
    assert ok(svc, "REASON").is_consistent is True


def test_non_buffered_reasoner_reasons_after_each_change() -> None:
    svc = ArmorService()
    load(svc, reasoner="HERMIT")
    ok(svc, "REPLACE", "OBJECTPROP", "IND", ["isIn", "Robot1", "R2", "C1"])
    assert ok(svc, "QUERY", "OBJECTPROP", "IND", ["canReach", "Robot1"]).queried_objects == [full("C1")]


# ------------------------------------------------------------------ utilities

def test_load_options() -> None:
    svc = ArmorService()
    for reasoner in ("", "pellet", "HERMIT", "Fact", "SNOROCKET"):
        load(svc, reasoner=reasoner, ref=f"r{reasoner}")
    res = call(svc, "LOAD", "FILE", "", [str(ABOX), IRI, "false", "org.example.Reasoner", "false"], ref="bad")
    assert (res.success, res.exit_code) == (False, 208) and "unknown reasoner" in res.error_description
    res = call(svc, "LOAD", "FILE", "", [str(ABOX), "not an iri", "false", "PELLET", "false"], ref="bad")
    assert (res.success, res.exit_code) == (False, 208)
    res = call(svc, "LOAD", "FILE", "", [str(ABOX), IRI, "perhaps", "PELLET", "false"], ref="bad")
    assert (res.success, res.exit_code) == (False, 208)
    res = call(svc, "LOAD", "FILE", "", [str(ABOX), IRI, "false", "PELLET"], ref="bad")
    assert (res.success, res.exit_code) == (False, 208)
    res = call(svc, "LOAD", "FILE", "", ["/no/such/file.owl", IRI, "false", "PELLET", "false"], ref="bad")
    assert (res.success, res.exit_code) == (False, 210)
    res = call(svc, "LOAD", "WEB", "", ["http://example.org/x.owl", IRI, "false", "PELLET", "false"], ref="bad")
    assert (res.success, res.exit_code) == (False, 210) and "allow_web" in res.error_description
    assert "bad" not in ok(svc, "GET", "ALL", "REFS").queried_objects


def test_load_existing_reference_is_reused(svc: ArmorService) -> None:
    before = state(svc)
    res = ok(svc, "LOAD", "FILE", "", [str(TBOX), IRI, "true", "PELLET", "true"])
    assert "reused" in res.error_description
    assert state(svc) == before


def test_mount_system() -> None:
    svc = ArmorService()
    ok(svc, "LOAD", "FILE", "MOUNTED", [str(ABOX), IRI, "false", "PELLET", "false"], client="alice")
    assert ok(svc, "GET", "REF", "CLIENT", ["ref"], client="bob").queried_objects == ["alice"]
    res = call(svc, "MOUNT", client="bob")
    assert (res.success, res.exit_code) == (False, 203)
    res = call(svc, "LOAD", "FILE", "MOUNTED", [str(ABOX), IRI, "false", "PELLET", "false"], client="bob")
    assert (res.success, res.exit_code) == (False, 203)
    before = state(svc)
    for request_ in [("ADD", "IND", "", ["X"]), ("REASON",), ("APPLY",), ("REMOVE", "IND", "", ["R1"]),
                     ("RENAME", "IND", "", ["R1", "R9"]), ("DISJOINT", "IND", "", ["A", "B"])]:
        res = call(svc, *request_, client="bob")
        assert (res.success, res.exit_code) == (False, 102), request_
    assert state(svc) == before
    assert ok(svc, "QUERY", "IND", "CLASS", ["URGENT"], client="bob").queried_objects == [full("R1")]
    assert "not mounted" in ok(svc, "UNMOUNT", client="bob").error_description
    ok(svc, "ADD", "IND", "", ["X"], client="alice")
    ok(svc, "UNMOUNT", client="alice")
    assert ok(svc, "GET", "REF", "CLIENT", ["ref"]).queried_objects == ["none"]
    ok(svc, "ADD", "IND", "", ["Y"], client="bob")
    res = call(svc, "GET", "REF", "CLIENT", ["unknown"])
    assert (res.success, res.exit_code) == (False, 207)


def test_get_all_refs_and_drop() -> None:
    svc = ArmorService()
    assert ok(svc, "GET", "ALL", "REFS", ref="any").queried_objects == []
    load(svc, ref="b")
    load(svc, ref="a")
    assert ok(svc, "GET", "ALL", "REFS", ref="any").queried_objects == ["a", "b"]
    res = ok(svc, "DROP", ref="a")
    assert res.is_consistent is False and res.error_description == ""
    assert "not loaded" in ok(svc, "DROP", ref="a").error_description
    assert ok(svc, "GET", "ALL", "REFS", ref="any").queried_objects == ["b"]


def test_call_many_serialized() -> None:
    svc = ArmorService()
    base = {"client_name": "c", "reference_name": "ref"}
    result = svc.call_many([
        {**base, "command": "LOAD", "primary_command_spec": "FILE", "args": [str(ABOX), IRI, "false", "PELLET", "false"]},
        {**base, "command": "QUERY", "primary_command_spec": "IND", "secondary_command_spec": "CLASS", "args": ["URGENT"]},
    ])
    assert result.success and result.is_consistent
    assert [r.queried_objects for r in result.armor_responses] == [[], [full("R1")]]
    failed = svc.call_many([{**base, "command": "NOPE"}, ArmorRequest("c", "ref", "QUERY", "IND", "", ["R1"])])
    assert failed.success is False and failed.is_consistent is True
    assert [r.exit_code for r in failed.armor_responses] == [205, 0]
    assert failed.to_dict()["armor_responses"][0]["success"] is False
    assert svc.call_many([]).to_dict() == {"success": True, "is_consistent": False, "armor_responses": []}


def test_log_screen_and_file(svc: ArmorService, tmp_path: Path) -> None:
    log = tmp_path / "armor.log"
    ok(svc, "LOG", "FILE", "ON", [str(log)])
    ok(svc, "LOG", "SCREEN", "ON")
    ok(svc, "QUERY", "IND", "CLASS", ["URGENT"])
    ok(svc, "LOG", "SCREEN", "OFF")
    ok(svc, "LOG", "FILE", "OFF")
    ok(svc, "QUERY", "IND", "CLASS", ["ROOM"])
    text = log.read_text()
    assert "URGENT" in text and "'ROOM'" not in text
    res = call(svc, "LOG", "FILE", "ON", [str(tmp_path / "missing" / "dir" / "x.log")])
    assert (res.success, res.exit_code) == (False, 210)


def test_ros_style_message_objects_are_accepted() -> None:
    # a client shimming rospy passes message objects (attributes, possibly wrapped in armor_request)
    from types import SimpleNamespace

    service = ArmorService()
    message = SimpleNamespace(client_name="c", reference_name="r", command="GET", primary_command_spec="ALL",
                              secondary_command_spec="REFS", args=())
    assert service.call(message).success
    assert service.call(SimpleNamespace(armor_request=message)).success
    assert service.call({"armor_request": {"reference_name": "r", "command": "GET", "primary_command_spec": "ALL",
                                           "secondary_command_spec": "REFS", "args": []}}).success
    refused = service.call(SimpleNamespace(command="GET"))
    assert not refused.success and "mapping or a message" in refused.error_description


@pytest.mark.parametrize("buffered", ["false", "true"])
def test_a_data_value_given_to_an_object_property_is_stored_reasoned_and_said(buffered: str) -> None:
    """aRMOR's OWL API makes such a property a data property too; here the value is kept as given, the next
    REASON succeeds and answers as before for the individuals, and the reply says what the value does."""
    s = ArmorService()
    load(s, buf_reasoner=buffered)
    ok(s, "REASON")
    before = sorted(ok(s, "QUERY", "OBJECTPROP", "IND", ["canReach", "Robot1"]).queried_objects)
    res = ok(s, "REPLACE", "DATAPROP", "IND", ["isIn", "Robot1", "LONG", "1", "1"])
    assert "isIn is an object property" in res.error_description
    added = ok(s, "ADD", "DATAPROP", "IND", ["isIn", "Robot1", "LONG", "2"])
    assert "isIn is an object property" in added.error_description
    ok(s, "REASON")
    assert sorted(ok(s, "QUERY", "OBJECTPROP", "IND", ["canReach", "Robot1"]).queried_objects) == before
    assert sorted(ok(s, "QUERY", "DATAPROP", "IND", ["isIn", "Robot1"]).queried_objects) == ['"1"^^xsd:long', '"2"^^xsd:long']
    clock = ok(s, "REPLACE", "DATAPROP", "IND", ["now", "Robot1", "LONG", "1665579750", "1665579740"])
    assert "object property" not in clock.error_description  # a data property says nothing of the kind


@pytest.mark.parametrize("buffered", ["false", "true"])
def test_an_individual_given_to_a_data_property_is_stored_reasoned_and_said(buffered: str) -> None:
    """The reverse mistake: the individual is kept as given, its data range does not check it (Pellet, on the
    SAVEd file, reads the two uses as two properties and stays consistent), and the reply says so."""
    s = ArmorService()
    load(s, buf_reasoner=buffered)
    added = ok(s, "ADD", "OBJECTPROP", "IND", ["visitedAt", "R1", "C1"])
    assert "visitedAt is a data property" in added.error_description
    assert ok(s, "REASON").is_consistent
    assert ok(s, "QUERY", "IND", "CLASS", ["ROOM"]).is_consistent
    link = ok(s, "ADD", "OBJECTPROP", "IND", ["isIn", "Robot1", "C1"])
    assert "data property" not in link.error_description  # an object property says nothing of the kind
    replaced = ok(s, "REPLACE", "OBJECTPROP", "IND", ["visitedAt", "R1", "C2", "C1"])  # a REPLACE says it as ADD does
    assert "REPLACE OBJECTPROP IND" in replaced.error_description and "visitedAt is a data property" in replaced.error_description
    moved = ok(s, "REPLACE", "OBJECTPROP", "IND", ["isIn", "Robot1", "R1", "C1"])
    assert "data property" not in moved.error_description
