"""The inspector's JSON routes: entity pages (individuals, classes, properties; short and full names), search,
consistency report, history, named queries, and the service's protections on all of them."""

from __future__ import annotations

import gc
import json
import urllib.parse
import weakref
from collections.abc import Iterator
from pathlib import Path

import pytest
from http_support import NS, TOKEN, InProcess, config, in_process
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from topostore import Ontology
from topostore.ontology.explain import Explainer
from topostore.resources import default_ontology_files

LOAD = ["example.ttl", "http://bnc/exp-rob-lab/2022-23", "false", "PELLET", "false"]  # live reasoner


def load_example(server: InProcess) -> None:
    Ontology.from_file(*default_ontology_files()).save(server.data_dir / "example.ttl")
    server.ok("LOAD", "FILE", "", LOAD)


@pytest.fixture
def server(tmp_path: Path) -> Iterator[InProcess]:
    """The service in-process with the example map as reference ontoRef (every change reasons)."""
    with in_process(config(tmp_path / "data")) as s:
        load_example(s)
        yield s


def get(server: InProcess, path: str, **headers: str) -> tuple[int, dict]:
    status, _, body = server.request(path, headers=headers)
    return status, json.loads(body)


def entity(server: InProcess, name: str) -> dict:
    status, body = get(server, "/references/ontoRef/entities/" + urllib.parse.quote(name, safe=""))
    assert status == 200, body
    return body


def by(facts: list[dict], key: str) -> dict[str, dict]:
    return {f[key].get("name", f[key].get("value")): f for f in facts}


def test_an_individual_with_its_inferred_types_and_their_proofs(server: InProcess) -> None:
    r1 = entity(server, "R1")
    assert (r1["iri"], r1["name"], r1["kind"], r1["consistent"]) == (NS + "R1", "R1", "individual", True)
    types = by(r1["types"], "class")
    assert set(types) == {"LOCATION", "ROOM", "URGENT"}
    urgent = types["URGENT"]
    assert urgent["inferred"] is True and urgent["class"]["iri"] == NS + "URGENT"
    assert (urgent["why"]["triple"], urgent["why"]["rule"]) == ("R1 rdf:type URGENT", "swrl:Urgency")
    assert "R1 visitedAt 1665579710" in [p["triple"] for p in urgent["why"]["premises"]]
    assert urgent["why"]["bindings"]["?d"] == "30"  # the SWRL built-in's value: now - visitedAt
    values = {(v["property"]["name"], v["value"].get("name", v["value"].get("value"))): v for v in r1["values"]}
    assert values[("hasDoor", "D1")]["inferred"] is False and "why" not in values[("hasDoor", "D1")]
    assert values[("visitedAt", "1665579710")]["value"]["datatype"] == "xsd:long"
    assert values[("connectedTo", "C1")]["why"]["rule"] == "swrl:Connectability"
    incoming = {(f["subject"]["name"], f["property"]["name"]): f["inferred"] for f in r1["referenced_by"]}
    assert incoming[("Robot1", "canReach")] is True and incoming[("C1", "connectedTo")] is True
    assert {"R1", "C1", "D1", "Robot1", "LOCATION"} <= set(r1["links"])  # words of the proofs that are entities
    assert "rdf:type" not in r1["links"] and "1665579710" not in r1["links"]
    assert [(d["individual"]["name"], d["axiom"], d["inferred"]) for d in r1["different_from"]] == [
        ("C1", "AllDifferent(C1, R1, R2)", False), ("R2", "AllDifferent(C1, R1, R2)", False)]
    assert r1["warnings"] == [] and r1["truncated"] == {}


def test_short_and_full_names_name_the_same_entity(server: InProcess) -> None:
    short = entity(server, "C1")
    assert entity(server, NS + "C1") == short
    assert entity(server, f"<{NS}C1>") == short
    assert short["kind"] == "individual"
    assert {t["class"]["name"]: t["inferred"] for t in short["types"]} == {
        "CORRIDOR": True, "LOCATION": True, "ROOM": True}


def test_unknown_entities_and_bad_names(server: InProcess) -> None:
    status, body = get(server, "/references/ontoRef/entities/R9")
    assert status == 404 and "R9" in body["error"]
    status, body = get(server, "/references/ontoRef/entities/" + urllib.parse.quote("http://elsewhere.org/x#R1", safe=""))
    assert status == 404
    status, body = get(server, "/references/ontoRef/entities/" + urllib.parse.quote("bad name"))
    assert status == 400 and "bad name" in body["error"]
    assert get(server, "/references/nope/entities/R1")[0] == 404
    assert get(server, "/references/ontoRef/entities/R1?limit=0")[0] == 400


def test_a_class_with_members_hierarchy_axioms_and_rules(server: InProcess) -> None:
    urgent = entity(server, "URGENT")
    assert (urgent["kind"], urgent["types"], urgent["values"]) == ("class", [], [])
    members = by(urgent["members"], "individual")
    assert list(members) == ["R1"] and members["R1"]["why"]["rule"] == "swrl:Urgency"
    assert [(s["class"]["name"], s["inferred"]) for s in urgent["superclasses"]] == [("LOCATION", False)]
    assert "URGENT SubClassOf LOCATION" in [a["text"] for a in urgent["axioms"]]
    assert [r["name"] for r in urgent["rules"]] == ["swrl:Urgency"]
    assert "⇒ ?l a URGENT" in urgent["rules"][0]["text"]
    corridor = entity(server, "CORRIDOR")
    supers = {s["class"]["name"]: s for s in corridor["superclasses"]}
    assert set(supers) == {"LOCATION", "ROOM"} and supers["ROOM"]["inferred"] is True  # ≥2 hasDoor ⊑ ∃hasDoor
    proof = supers["ROOM"]["why"]
    assert (proof["triple"], proof["rule"]) == ("CORRIDOR rdfs:subClassOf ROOM", "classification")
    assert proof["premises"][0]["triple"] == "(any CORRIDOR) rdf:type ROOM"
    assert "(hasDoor min 2 DOOR) is subsumed by (hasDoor some DOOR)" in json.dumps(proof)
    assert '"triple": "(any CORRIDOR) rdf:type CORRIDOR", "status": "assumed"' in json.dumps(proof)
    location = entity(server, "LOCATION")
    assert {s["class"]["name"] for s in location["subclasses"]} == {"CORRIDOR", "ROOM", "URGENT"}
    assert {m["individual"]["name"] for m in location["members"]} == {"C1", "R1", "R2"}


def test_properties_with_characteristics_domains_and_assertions(server: InProcess) -> None:
    is_in = entity(server, "isIn")
    assert (is_in["kind"], is_in["characteristics"]) == ("object property", ["Functional"])
    assert (is_in["domain"], is_in["range"]) == (["ROBOT"], ["LOCATION"])
    assert [(a["subject"]["name"], a["value"]["name"], a["inferred"]) for a in is_in["assertions"]] == [
        ("Robot1", "C1", False)]
    can_reach = entity(server, "canReach")
    assert {a["value"]["name"] for a in can_reach["assertions"]} == {"R1", "R2"}
    assert all(a["inferred"] and a["why"]["rule"] == "swrl:Reachability" for a in can_reach["assertions"])
    visited = entity(server, "visitedAt")
    assert (visited["kind"], visited["range"]) == ("data property", ["xsd:long"])
    assert "visitedAt range xsd:long" in [a["text"] for a in visited["axioms"]]


def test_lists_are_cut_at_the_limit_and_say_so(server: InProcess) -> None:
    status, location = get(server, "/references/ontoRef/entities/LOCATION?limit=2")
    assert status == 200 and len(location["members"]) == 2
    assert location["truncated"] == {"members": 3}
    assert any("members: 3 facts, the first 2 shown" in w for w in location["warnings"])


def test_search(server: InProcess) -> None:
    status, found = get(server, "/references/ontoRef/entities?q=urgent")
    assert status == 200 and found["entities"] == [{"name": "URGENT", "iri": NS + "URGENT", "kind": "class"}]
    assert found["total"] == 1
    status, found = get(server, "/references/ontoRef/entities?q=r")
    names = [e["name"] for e in found["entities"]]
    assert names[:5] == ["R1", "R2", "ROBOT", "Robot1", "ROOM"]  # names starting with it first
    status, found = get(server, "/references/ontoRef/entities?q=r&limit=2")
    assert [e["name"] for e in found["entities"]] == ["R1", "R2"] and found["total"] == len(names)
    assert get(server, "/references/ontoRef/entities?q=zzz")[1]["entities"] == []


def test_the_inconsistency_report_names_the_axiom_and_the_individuals(server: InProcess) -> None:
    assert get(server, "/references/ontoRef/consistency") == (200, {
        "consistent": True, "reasoned": True, "changed_since_reasoning": False, "violations": [], "warnings": [],
        "links": {}})
    server.ok("ADD", "IND", "CLASS", ["R1", "DOOR"])  # a DOOR cannot be a LOCATION
    status, report = get(server, "/references/ontoRef/consistency")
    assert status == 200 and report["consistent"] is False
    [violation] = report["violations"]
    assert violation["axiom"] == "DOOR DisjointWith LOCATION"
    assert [(i["variable"], i["name"]) for i in violation["individuals"]] == [("x", "R1")]
    assert [(p["triple"], p["status"]) for p in violation["why"]["premises"]] == [
        ("R1 rdf:type DOOR", "asserted"), ("R1 rdf:type LOCATION", "inferred")]  # the facts that clash
    location = violation["why"]["premises"][1]  # by visitedAt's or hasDoor's domain: either proof is minimal
    assert location["rule"] == "prp-dom" and location["origin"].endswith(" domain LOCATION")
    assert {"DOOR", "LOCATION", "R1"} <= set(report["links"])
    assert get(server, "/references/ontoRef/consistency?brief=true") == (200, {
        "consistent": False, "reasoned": True, "changed_since_reasoning": False, "violation_count": 1})
    assert get(server, "/references/ontoRef/consistency?brief=yes")[0] == 400
    r1 = entity(server, "R1")
    assert r1["consistent"] is False and "inconsistent" in r1["warnings"][0]
    assert all(not t["inferred"] for t in r1["types"])  # as every query: asserted facts only while inconsistent


def test_history_records_each_reason_from_the_first_look(server: InProcess) -> None:
    status, history = get(server, "/references/ontoRef/history")
    assert status == 200 and history["events"] == []
    server.ok("REPLACE", "DATAPROP", "IND", ["now", "Robot1", "LONG", "1665579750", "1665579740"])
    server.ok("ADD", "IND", "CLASS", ["R1", "DOOR"])
    events = get(server, "/references/ontoRef/history")[1]["events"]
    assert [e["consistency_changed"] for e in events] == [True, False]  # newest first
    became_urgent = events[1]
    assert [(f["s"]["name"], f["p"]["name"], f["o"]["name"]) for f in became_urgent["added"]] == [
        ("C1", "rdf:type", "URGENT"), ("R2", "rdf:type", "URGENT")]
    assert (became_urgent["added_count"], became_urgent["missed"]) == (2, 0)
    assert events[0]["consistent"] is False and events[0]["seq"] == became_urgent["seq"] + 1
    # the reference loaded anew under the same name starts a new history; the dropped one is freed
    dropped = weakref.ref(server.client.app.state.api.service.reference("ontoRef").ontology)
    server.ok("DROP")
    gc.collect()
    assert dropped() is None
    load_example(server)
    assert get(server, "/references/ontoRef/history")[1]["events"] == []
    # recording stops on request: REASON takes no snapshot for it any more
    onto = server.client.app.state.api.service.reference("ontoRef").ontology
    assert onto.events.active
    status, _, body = server.request("/references/ontoRef/history", method="DELETE")
    assert (status, json.loads(body)) == (200, {"recording": False, "stopped": True})
    assert not onto.events.active
    assert json.loads(server.request("/references/ontoRef/history", method="DELETE")[2])["stopped"] is False
    server.ok("REASON")
    assert get(server, "/references/ontoRef/history")[1]["events"] == []  # asking again starts again
    assert get(server, "/references/nope/history")[0] == 404


def test_named_queries_and_the_page(server: InProcess) -> None:
    status, body = get(server, "/references/ontoRef/queries")
    queries = {q["name"]: q for q in body["queries"]}
    assert status == 200 and "urgent-locations" in queries
    assert queries["classes-of-individual"]["params"] == ["ind"]
    assert queries["urgent-locations"]["text"].lstrip().startswith("# name: urgent-locations")
    status, headers, page = server.request("/references/ontoRef/inspector")
    assert status == 200 and headers["content-type"].startswith("text/html")
    assert b"/static/yasgui.min.js" in page and b"/static/inspector.js" in page
    assert b"https://" not in page  # nothing from elsewhere
    policy = headers["content-security-policy"]
    assert "script-src 'self';" in policy and "connect-src 'self';" in policy and "unsafe-eval" not in policy
    assert server.request("/references/nope/inspector")[0] == 404
    for script in ("yasgui.min.js", "yasgui.min.css", "inspector.js", "inspector-render.js", "inspector.css"):
        assert server.request("/static/" + script)[0] == 200
    _, _, map_page = server.request("/references/ontoRef/map")
    assert b'href="inspector"' in map_page  # the live map links to the inspector


def test_off_loopback_every_inspector_route_needs_the_token(tmp_path: Path) -> None:
    with in_process(config(tmp_path / "data", host="0.0.0.0", token=TOKEN)) as s:
        load_example(s)
        for path in ("/references/ontoRef/entities/R1", "/references/ontoRef/entities?q=R",
                     "/references/ontoRef/inspector", "/references/ontoRef/consistency",
                     "/references/ontoRef/history", "/references/ontoRef/queries", "/static/inspector.js"):
            assert s.request(path, headers={"Authorization": "Bearer wrong"})[0] == 401, path
            assert s.request(path, headers={"Authorization": ""})[0] == 401, path
            assert s.request(path)[0] == 200, path  # the client sends the right token


def test_on_loopback_other_sites_and_rebound_names_are_refused(server: InProcess) -> None:
    status, body = get(server, "/references/ontoRef/entities/R1", Origin="https://evil.example")
    assert status == 403 and "origin" in body["error"]
    status, _, _ = server.request("/references/ontoRef/entities/R1", headers={"Host": "evil.example"})
    assert status == 400  # DNS rebinding: the Host must name this machine


def test_the_benchmark_runs(capsys: pytest.CaptureFixture[str]) -> None:
    """benchmarks/inspector.py on a tiny map: it prints what it claims to measure (no timing is asserted)."""
    import sys

    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # the benchmarks package lives beside src/
    from benchmarks.inspector import main

    main(["--sizes", "5", "--steps", "2"])
    row = json.loads(capsys.readouterr().out)
    assert row["locations"] == 5 and set(row["step_ms"]) == {"alone", "recorded"}
    assert set(row["entity_ms"]) == {"room", "corridor", "robot", "URGENT", "LOCATION", "isIn"}


@pytest.fixture(scope="module")
def shared(tmp_path_factory: pytest.TempPathFactory) -> Iterator[InProcess]:
    with in_process(config(tmp_path_factory.mktemp("data"))) as s:
        load_example(s)
        yield s


@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(name=st.text(max_size=40) | st.sampled_from(["R1", "<", "<>", "urn:", "owl:", "http://", "a b", "R1#x", "%",
                                                    "rdf:type", "swrl:Imp", "urn:topostore:graph:asserted"]),
       limit=st.sampled_from(["", "1", "5000", "5001", "-1", "x", "1e3"]))
def test_any_name_gets_an_answer_never_a_crash(shared: InProcess, name: str, limit: str) -> None:
    query = f"?limit={urllib.parse.quote(limit)}" if limit else ""
    status, _, body = shared.request("/references/ontoRef/entities/" + urllib.parse.quote(name, safe="") + query)
    assert status in (200, 400, 404), (name, body)
    assert "error" in json.loads(body) or status == 200
    status, _, body = shared.request("/references/ontoRef/entities?q=" + urllib.parse.quote(name) + "&limit=3")
    assert status == 200 and len(json.loads(body)["entities"]) <= 3


def test_a_hub_individual_is_cut_before_its_proofs_are_built(server: InProcess,
                                                              monkeypatch: pytest.MonkeyPatch) -> None:
    for i in range(5):  # five more locations sharing door D1 with C1: each is connectedTo C1
        server.ok("ADD", "OBJECTPROP", "IND", ["hasDoor", f"R{10 + i}", "D1"])
        server.ok("ADD", "DATAPROP", "IND", ["visitedAt", f"R{10 + i}", "LONG", "1665579730"])
    proved: list[str] = []
    original = Explainer.explain
    monkeypatch.setattr(Explainer, "explain", lambda self, t: proved.append(str(t)) or original(self, t))
    status, c1 = get(server, "/references/ontoRef/entities/C1?limit=3")
    assert status == 200 and len(c1["referenced_by"]) == 3 and c1["truncated"]["referenced_by"] > 3
    shown = [f for key in ("types", "values", "referenced_by") for f in c1[key] if f["inferred"]]
    assert all("why" in f for f in shown) and len(proved) == len(shown)  # no proof of a fact not shown
