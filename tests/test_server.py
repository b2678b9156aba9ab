"""The HTTP service: the seed tutorial as JSON requests, the SPARQL 1.1 endpoint (rdflib's SPARQLStore and plain
HTTP in every result format), ArmorClient over HTTP, the security defaults (loopback without token, data directory,
size and time limits, token, updates) and concurrent clients losing no write.

Most tests call the application in-process through Starlette's TestClient; the clients that need a URL (rdflib,
the armor client, concurrent threads) reach it on a real socket served by uvicorn in a thread; one smoke test and
the refusal to start run the real ``topostore serve`` command.
"""

from __future__ import annotations

import csv
import io
import json
import shutil
import signal
import subprocess
import sys
import threading
import time
import urllib.parse
import xml.etree.ElementTree as ET
from collections.abc import Iterator
from pathlib import Path

import pytest
import rdflib
from http_support import (
    IRI,
    NS,
    TBOX,
    TOKEN,
    Client,
    Live,
    config,
    free_port,
    in_process,
    start_server,
    stop_server,
    threaded,
)
from rdflib.plugins.stores.sparqlstore import SPARQLStore

from topostore.armor_api.armor_client import ArmorClient
from topostore.armor_api.armor_exceptions import ArmorServiceCallError, ArmorServiceInternalError
from topostore.armor_api.http_transport import HttpTransport
from topostore.rdf.declarations import missing_declarations

Server = Live


@pytest.fixture(scope="module")
def server(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Client]:
    with in_process(config(tmp_path_factory.mktemp("data"), sparql_timeout=1, max_request_bytes=65536)) as s:
        yield s


@pytest.fixture(scope="module")
def live(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Live]:
    """The same settings on a real socket, for clients that need a URL."""
    with threaded(config(tmp_path_factory.mktemp("live"), sparql_timeout=1, max_request_bytes=65536)) as s:
        yield s


def run_tutorial(s: Client) -> Client:
    """The seed tutorial's requests, sent as JSON, with their answers checked."""
    s.ok("LOAD", "FILE", "", ["topological_map.owl", IRI, "true", "PELLET", "true"])
    for door in ("D6", "D7"):
        s.ok("ADD", "OBJECTPROP", "IND", ["hasDoor", "E", door])
    s.ok("ADD", "OBJECTPROP", "IND", ["hasDoor", "R3", "D6"])
    s.ok("ADD", "DATAPROP", "IND", ["visitedAt", "E", "LONG", "1665579700"])
    s.ok("ADD", "DATAPROP", "IND", ["visitedAt", "R3", "LONG", "1665579735"])
    s.ok("DISJOINT", "IND", "", ["E", "R3", "D6", "D7"])
    s.ok("ADD", "OBJECTPROP", "IND", ["isIn", "Robot1", "R3"])
    s.ok("REPLACE", "OBJECTPROP", "IND", ["isIn", "Robot1", "E", "R3"])
    assert s.ok("REASON")["is_consistent"] is True
    assert s.ok("QUERY", "DATAPROP", "IND", ["now", "Robot1"])["queried_objects"] == ['"1665579740"^^xsd:long']
    s.ok("REPLACE", "DATAPROP", "IND", ["now", "Robot1", "LONG", "1665579750", "1665579740"])
    s.ok("REPLACE", "DATAPROP", "IND", ["visitedAt", "E", "LONG", "1665579750", "1665579700"])
    s.ok("REASON")
    assert s.ok("QUERY", "OBJECTPROP", "IND", ["canReach", "Robot1"])["queried_objects"] == [f"<{NS}R3>"]
    assert s.ok("QUERY", "IND", "CLASS", ["URGENT"])["queried_objects"] == [f"<{NS}R3>"]
    classes = s.ok("QUERY", "CLASS", "IND", ["E", "false"])["queried_objects"]
    assert classes == [f"<{NS}{c}>" for c in ("CORRIDOR", "LOCATION", "ROOM")]
    assert s.ok("QUERY", "CLASS", "IND", ["E", "true"])["queried_objects"] == ["CORRIDOR"]
    (s.data_dir / "saved").mkdir()
    s.ok("SAVE", "", "", ["saved/tutorial.owl"])
    return s


@pytest.fixture(scope="module")
def tutorial(server: Client) -> Client:
    return run_tutorial(server)


@pytest.fixture(scope="module")
def live_tutorial(live: Live) -> Live:
    run_tutorial(live)
    return live


def saved_graph(s: Client) -> rdflib.Graph:
    return rdflib.Graph().parse(s.data_dir / "saved" / "tutorial.owl", format="xml")


# --------------------------------------------------------------------------- aRMOR over HTTP

def test_tutorial_as_json(tutorial: Client) -> None:
    saved = saved_graph(tutorial)  # SAVE wrote the asserted triples: the changes are in, no inference is
    assert set(saved.objects(rdflib.URIRef(NS + "E"), rdflib.URIRef(NS + "hasDoor"))) == {
        rdflib.URIRef(NS + "D6"), rdflib.URIRef(NS + "D7")}
    assert set(saved.objects(rdflib.URIRef(NS + "Robot1"), rdflib.URIRef(NS + "isIn"))) == {rdflib.URIRef(NS + "E")}
    assert (None, rdflib.URIRef(NS + "canReach"), None) not in saved
    status, _, body = tutorial.request("/health")
    assert status == 200 and json.loads(body)["status"] == "ok"


def test_references_listing(tutorial: Client) -> None:
    status, _, body = tutorial.request("/references")
    refs = {r["name"]: r for r in json.loads(body)["references"]}
    assert status == 200 and list(refs) == ["ontoRef"]
    info = refs["ontoRef"]
    seconds = info.pop("last_reasoning_seconds")
    onto = tutorial.client.app.state.api.service.reference("ontoRef").ontology
    assert seconds == round(onto.report.stats.seconds, 6)  # the last REASON's own duration, in seconds
    everything = tutorial.sparql_get("CONSTRUCT { ?s ?p ?o } WHERE { ?s ?p ?o }", "application/n-triples")[2]
    asserted = len(onto.triples())  # SAVE wrote them and the declarations they lack
    assert len(saved_graph(tutorial)) == asserted + len(missing_declarations(onto.triples()))
    assert info == {"name": "ontoRef", "iri": IRI, "consistent": True, "changed_since_reasoning": False,
                    "buffered_changes": 0, "mounted_by": None, "triples_asserted": asserted,
                    "triples_inferred": len(everything.splitlines()) - asserted}
    # 12 facts about the map and 12 range axioms the xsd:long ranges imply (integer, decimal, rational, real)
    assert info["triples_inferred"] == 24


def test_batch_is_the_serialized_service(tutorial: Server) -> None:
    reqs = [{"client_name": "b", "reference_name": "ontoRef", "command": "QUERY", "primary_command_spec": "IND",
             "secondary_command_spec": "CLASS", "args": ["CORRIDOR"]},
            {"client_name": "b", "reference_name": "ontoRef", "command": "NOPE"}]
    status, _, body = tutorial.request("/armor/batch", json.dumps(reqs).encode(), {"Content-Type": "application/json"})
    result = json.loads(body)
    assert status == 200
    assert result["success"] is False  # the second command fails
    assert result["armor_responses"][0]["queried_objects"] == [f"<{NS}E>"]
    assert result["armor_responses"][1]["exit_code"] == 205


def test_malformed_json_and_request(server: Server) -> None:
    status, _, body = server.request("/armor", b"{not json", {"Content-Type": "application/json"})
    assert status == 400 and "not valid JSON" in json.loads(body)["error"]
    status, _, body = server.request("/armor", b'{"reference_name": "x", "command": "QUERY", "args": "oops"}')
    assert status == 200 and json.loads(body)["success"] is False
    status, _, body = server.request("/armor", b'{"reference_name": "x", "command": "DROP"}',
                                     {"Content-Type": "text/plain"})  # what a cross-site form could send
    assert status == 415 and "application/json" in json.loads(body)["error"]


def test_browser_protections(server: Server) -> None:
    status, _, body = server.request("/health", headers={"Origin": "http://evil.example"})
    assert status == 403 and "--cors-origin" in json.loads(body)["error"]
    status, _, body = server.request("/health", headers={"Host": "rebind.evil.example"})  # Starlette's TrustedHost
    assert (status, body) == (400, b"Invalid host header")
    assert server.request("/health", headers={"Host": "localhost:1234"})[0] == 200


def test_path_outside_data_dir_is_refused(server: Server, tmp_path: Path) -> None:
    outside = tmp_path / "elsewhere.owl"
    shutil.copy(TBOX, outside)
    data = server.data_dir.resolve()
    for path in (str(outside), "../topological_map.owl", "/etc/passwd"):
        res = server.armor("LOAD", "FILE", "", [path, IRI, "false", "PELLET", "false"], ref="escape")
        assert (res["success"], res["exit_code"]) == (False, 210), res
        assert res["error_description"] == f"path {path!r} is outside the data directory {str(data)!r}"
    server.ok("LOAD", "FILE", "", ["topological_map.owl", IRI, "false", "PELLET", "false"], ref="escape")
    leak = str(tmp_path / "leak.owl")
    res = server.armor("SAVE", "", "", [leak], ref="escape")
    assert not (tmp_path / "leak.owl").exists()
    assert (res["success"], res["exit_code"]) == (False, 210), res
    assert res["error_description"] == f"path {leak!r} is outside the data directory {str(data)!r}"
    server.ok("DROP", ref="escape")


def test_oversized_request_gets_413(server: Server) -> None:
    payload = json.dumps({"reference_name": "ontoRef", "command": "QUERY", "args": ["x" * 70000]}).encode()
    status, _, body = server.request("/armor", payload, {"Content-Type": "application/json"})
    assert status == 413
    assert "larger than the limit of 65536 bytes" in json.loads(body)["error"]


# --------------------------------------------------------------------------- SPARQL endpoint

REACH = f"SELECT ?l WHERE {{ <{NS}Robot1> <{NS}canReach> ?l }}"
VISITED = f"SELECT ?l ?t WHERE {{ ?l <{NS}visitedAt> ?t }} ORDER BY ?l"


def test_sparql_json_sees_inferences_and_asserted_literal_forms(tutorial: Server) -> None:
    status, headers, body = tutorial.sparql_get(REACH)
    assert status == 200 and headers["content-type"].startswith("application/sparql-results+json")
    data = json.loads(body)
    assert data["head"]["vars"] == ["l"]
    assert [b["l"]["value"] for b in data["results"]["bindings"]] == [NS + "R3"]  # inferred by Reachability
    status, _, body = tutorial.sparql_get(VISITED, "application/sparql-results+json")
    rows = json.loads(body)["results"]["bindings"]
    assert [(r["l"]["value"], r["t"]["value"], r["t"]["datatype"]) for r in rows] == [
        (NS + "E", "1665579750", "http://www.w3.org/2001/XMLSchema#long"),
        (NS + "R3", "1665579735", "http://www.w3.org/2001/XMLSchema#long"),
    ]


def test_sparql_xml_csv_tsv(tutorial: Server) -> None:
    status, headers, body = tutorial.sparql_get(REACH, "application/sparql-results+xml")
    assert status == 200 and headers["content-type"].startswith("application/sparql-results+xml")
    ns = {"r": "http://www.w3.org/2005/sparql-results#"}
    uris = [e.text for e in ET.fromstring(body).findall(".//r:result/r:binding/r:uri", ns)]
    assert uris == [NS + "R3"]
    status, headers, body = tutorial.sparql_get(VISITED, "text/csv")
    assert status == 200 and headers["content-type"].startswith("text/csv")
    assert list(csv.reader(io.StringIO(body.decode()))) == [["l", "t"], [NS + "E", "1665579750"], [NS + "R3", "1665579735"]]
    status, headers, body = tutorial.sparql_get(VISITED, "text/tab-separated-values")
    assert status == 200 and headers["content-type"].startswith("text/tab-separated-values")
    lines = body.decode().splitlines()
    assert lines[0] == "?l\t?t"
    assert lines[1] == f'<{NS}E>\t"1665579750"^^<http://www.w3.org/2001/XMLSchema#long>'


def test_sparql_ask_construct_describe_formats(tutorial: Server) -> None:
    status, _, body = tutorial.sparql_get(f"ASK {{ <{NS}R3> a <{NS}URGENT> }}")
    assert status == 200 and json.loads(body)["boolean"] is True
    status, _, body = tutorial.sparql_get(f"ASK {{ <{NS}E> a <{NS}URGENT> }}", "application/sparql-results+xml")
    assert status == 200 and b"<boolean>false</boolean>" in body
    construct = f"CONSTRUCT {{ ?r <{NS}canReach> ?l }} WHERE {{ ?r <{NS}canReach> ?l }}"
    expected = {(rdflib.URIRef(NS + "Robot1"), rdflib.URIRef(NS + "canReach"), rdflib.URIRef(NS + "R3"))}
    for accept, fmt in (("text/turtle", "turtle"), ("application/n-triples", "nt"), ("application/rdf+xml", "xml")):
        status, headers, body = tutorial.sparql_get(construct, accept)
        assert status == 200 and headers["content-type"].startswith(accept), (accept, headers)
        assert set(rdflib.Graph().parse(data=body, format=fmt)) == expected, accept
    status, _, body = tutorial.sparql_get(f"DESCRIBE <{NS}Robot1>", "text/turtle")
    graph = rdflib.Graph().parse(data=body, format="turtle")
    assert (rdflib.URIRef(NS + "Robot1"), rdflib.URIRef(NS + "isIn"), rdflib.URIRef(NS + "E")) in graph
    status, _, body = tutorial.sparql_get(REACH, "image/png")
    assert status == 406 and "application/sparql-results+json" in json.loads(body)["error"]


def test_sparql_post_forms(tutorial: Server) -> None:
    form = urllib.parse.urlencode({"query": REACH}).encode()
    status, _, body = tutorial.request("/references/ontoRef/sparql", form,
                                       {"Content-Type": "application/x-www-form-urlencoded"})
    assert status == 200 and json.loads(body)["results"]["bindings"][0]["l"]["value"] == NS + "R3"
    status, _, body = tutorial.request("/references/ontoRef/sparql", REACH.encode(),
                                       {"Content-Type": "application/sparql-query", "Accept": "text/csv"})
    assert status == 200 and body.decode().splitlines() == ["l", NS + "R3"]


def test_sparql_errors(tutorial: Server) -> None:
    status, _, body = tutorial.sparql_get("SELECT WHERE nonsense")
    assert status == 400 and "malformed" in json.loads(body)["error"]
    status, _, body = tutorial.sparql_get(REACH, ref="missing")
    assert status == 404 and "not loaded" in json.loads(body)["error"]
    status, _, body = tutorial.sparql_get("SELECT * WHERE { SERVICE <http://127.0.0.1:1/sparql> { ?s ?p ?o } }")
    assert status == 403 and "SERVICE" in json.loads(body)["error"]
    update = urllib.parse.urlencode({"update": f"INSERT DATA {{ <{NS}X> a <{NS}DOOR> }}"}).encode()
    status, _, body = tutorial.request("/references/ontoRef/sparql", update,
                                       {"Content-Type": "application/x-www-form-urlencoded"})
    assert status == 403 and "--allow-update" in json.loads(body)["error"]
    status, _, body = tutorial.sparql_get(f"ASK {{ <{NS}X> ?p ?o }}")
    assert status == 200 and json.loads(body) == {"head": {}, "boolean": False}  # nothing was inserted


def test_sparql_time_limit(tutorial: Server) -> None:
    slow = "SELECT * WHERE { ?a ?b ?c . ?d ?e ?f . ?g ?h ?i . ?j ?k ?l }"
    status, _, body = tutorial.sparql_get(slow)
    assert status == 503
    assert "time limit of 1 s" in json.loads(body)["error"]
    # the service is still responsive and the reference not left locked
    assert tutorial.sparql_get(REACH)[0] == 200
    assert tutorial.ok("QUERY", "IND", "CLASS", ["URGENT"])["queried_objects"] == [f"<{NS}R3>"]


def test_rdflib_sparqlstore(live_tutorial: Live) -> None:
    graph = rdflib.Graph(store=SPARQLStore(live_tutorial.url + "/references/ontoRef/sparql"))
    rows = list(graph.query(REACH))
    assert [str(r[0]) for r in rows] == [NS + "R3"]
    rows = list(graph.query(VISITED))
    assert [(str(l), int(t.toPython())) for l, t in rows] == [(NS + "E", 1665579750), (NS + "R3", 1665579735)]
    assert graph.query(f"ASK {{ <{NS}R3> a <{NS}URGENT> }}").askAnswer is True
    constructed = graph.query(f"CONSTRUCT {{ ?l a <{NS}URGENT> }} WHERE {{ ?l a <{NS}URGENT> }}").graph
    assert set(constructed) == {(rdflib.URIRef(NS + "R3"), rdflib.RDF.type, rdflib.URIRef(NS + "URGENT"))}
    triples = list(graph.triples((rdflib.URIRef(NS + "Robot1"), rdflib.URIRef(NS + "canReach"), None)))
    assert [t[2] for t in triples] == [rdflib.URIRef(NS + "R3")]


# --------------------------------------------------------------------------- ArmorClient over HTTP

def test_armor_client_over_http(live: Live) -> None:
    client = ArmorClient("robot", "clientRef", url=live.url)
    client.utils.load_ref_from_file("topological_map.owl", IRI, buffered_manipulation=False, reasoner="PELLET",
                                    buffered_reasoner=True)
    for loc, door in (("C1", "D1"), ("C1", "D2"), ("R1", "D1"), ("R2", "D2")):
        client.manipulation.add_objectprop_to_ind("hasDoor", loc, door)
    for loc, t in (("C1", "100"), ("R1", "90"), ("R2", "98")):
        client.manipulation.add_dataprop_to_ind("visitedAt", loc, "LONG", t)
    client.manipulation.add_objectprop_to_ind("isIn", "Robot1", "C1")
    client.manipulation.replace_one_dataprop_b2_ind("now", "Robot1", "LONG", "100")
    client.utils.sync_buffered_reasoner()
    client.manipulation.disj_inds_of_class("LOCATION")
    client.manipulation.disj_inds_of_class("DOOR")
    assert client.utils.sync_buffered_reasoner() is True
    assert sorted(client.query.objectprop_b2_ind("canReach", "Robot1")) == ["R1", "R2"]
    assert client.query.ind_b2_class("URGENT") == ["R1"]  # 100 - 90 > 7, 100 - 98 is not
    assert client.query.ind_b2_class("CORRIDOR") == ["C1"]
    assert client.query.dataprop_b2_ind("now", "Robot1") == ['"100"^^xsd:long']
    result = client.call_serialized([("QUERY", "IND", "CLASS", ["ROOM"]), ("REASON", "", "", [])])
    assert result.success is True
    assert [(r.exit_code, r.queried_objects) for r in result.armor_responses] == [
        (0, [f"<{NS}C1>", f"<{NS}R1>", f"<{NS}R2>"]), (0, [])]
    with pytest.raises(ArmorServiceInternalError) as err:
        client.query.ind_b2_class("")  # refused by the service, reported as in armor_py_api
    assert err.value.code == 208
    dead = ArmorClient("robot", "clientRef", url=f"http://127.0.0.1:{free_port()}", timeout=2)
    with pytest.raises(ArmorServiceCallError):
        dead.query.ind_b2_class("ROOM")


# --------------------------------------------------------------------------- concurrency

def test_concurrent_clients_lose_no_write(live: Live) -> None:
    """8 clients: 4 writers add 60 markers each (single and batched), 4 readers query while they write; every
    write is kept and no reader sees the count go backwards."""
    server = live
    server.ok("LOAD", "FILE", "", ["topological_map.owl", IRI, "false", "PELLET", "true"], ref="busy")
    per_writer = 60
    writers = range(0, 8, 2)
    deadline = time.monotonic() + 120  # a bound for a service that stopped answering, not a figure

    def running(k: int) -> bool:
        """A writer until it has written its markers; a reader until every writer has, and at least twice."""
        if time.monotonic() > deadline:
            return False
        if k in writers:
            return writes[k] < per_writer
        return reads[k] < 2 or any(writes[w] < per_writer for w in writers)

    writes: list[int] = [0] * 8
    reads: list[int] = [0] * 8
    failures: list[str] = []
    marker_query = f"SELECT (COUNT(DISTINCT ?x) AS ?n) WHERE {{ ?x a <{NS}Marker> }}"

    def count_markers() -> int:
        status, _, body = server.sparql_get(marker_query, ref="busy")
        assert status == 200, body
        return int(json.loads(body)["results"]["bindings"][0]["n"]["value"])

    def worker(k: int) -> None:
        try:
            n, seen = 0, 0
            while running(k):
                if k % 2 == 0:  # writer
                    if n % 3 == 2:
                        batch = [{"client_name": f"w{k}", "reference_name": "busy", "command": "ADD",
                                  "primary_command_spec": "IND", "secondary_command_spec": "CLASS",
                                  "args": [f"M{k}_{n + i}", "Marker"]} for i in range(3)]
                        status, _, body = server.request("/armor/batch", json.dumps(batch).encode())
                        assert status == 200 and json.loads(body)["success"], body
                        n += 3
                    else:
                        server.ok("ADD", "IND", "CLASS", [f"M{k}_{n}", "Marker"], ref="busy", client=f"w{k}")
                        n += 1
                    if n % 10 == 0:
                        server.ok("REASON", ref="busy", client=f"w{k}")
                    writes[k] = n
                else:  # reader: counts never go backwards (queries see whole states)
                    now = count_markers() if k % 4 == 1 else len(
                        server.ok("QUERY", "IND", "CLASS", ["Marker"], ref="busy")["queried_objects"])
                    assert now >= seen, (now, seen)
                    seen = now
                    reads[k] += 1
        except BaseException as exc:  # reported by the main thread
            failures.append(f"client {k}: {exc!r}")

    threads = [threading.Thread(target=worker, args=(k,)) for k in range(8)]
    for t in threads:
        t.start()
    for t in threads:
        t.join(90)
    assert not failures, failures
    assert all(writes[w] >= per_writer for w in writers), writes
    assert all(reads[r] >= 2 for r in range(8) if r not in writers), reads
    total = sum(writes)
    assert count_markers() == total
    listed = server.ok("QUERY", "IND", "CLASS", ["Marker"], ref="busy")["queried_objects"]
    assert len(listed) == total
    status, _, body = server.request("/references")
    assert {r["name"]: r for r in json.loads(body)["references"]}["busy"]["consistent"] is True


# --------------------------------------------------------------------------- the real command

def test_real_server_smoke(tmp_path: Path) -> None:
    """`topostore serve` as a subprocess: it listens, answers aRMOR requests and SPARQL, and stops on SIGTERM."""
    s = start_server(tmp_path / "data", "--sparql-timeout", "5")
    try:
        status, _, body = s.request("/health")
        assert status == 200 and json.loads(body)["status"] == "ok"
        s.ok("LOAD", "FILE", "", ["topological_map.owl", IRI, "false", "PELLET", "false"])
        s.ok("ADD", "OBJECTPROP", "IND", ["hasDoor", "E", "D6"])
        s.ok("ADD", "OBJECTPROP", "IND", ["isIn", "Robot1", "E"])
        assert s.ok("QUERY", "IND", "CLASS", ["ROOM"])["queried_objects"] == [f"<{NS}E>"]
        status, _, body = s.sparql_get(f"SELECT ?d WHERE {{ <{NS}E> <{NS}hasDoor> ?d }}", "text/csv")
        assert status == 200 and body.decode().splitlines() == ["d", NS + "D6"]
    finally:
        stop_server(s)
    # uvicorn shuts down gracefully, then re-raises the signal it caught: the process ends by SIGTERM
    assert s.proc is not None and s.proc.returncode == -signal.SIGTERM


# --------------------------------------------------------------------------- security settings

def test_non_loopback_without_token_refuses_to_start(tmp_path: Path) -> None:
    proc = subprocess.run([sys.executable, "-m", "topostore.cli", "serve", "--host", "0.0.0.0", "--port",
                           str(free_port()), "--data-dir", str(tmp_path)], capture_output=True, text=True, timeout=30)
    assert proc.returncode == 1
    assert "without a token" in proc.stderr
    assert len(proc.stderr.strip().splitlines()) == 1  # one clear line, no traceback


def test_token_and_updates(tmp_path: Path) -> None:
    origin = "https://yasgui.example.org"
    settings = config(tmp_path / "data", allow_update=True, cors_origins=(origin,), sparql_max_rows=100, token=TOKEN)
    with threaded(settings) as s:
        status, headers, _ = s.request("/references/upd/sparql", method="OPTIONS",
                                       headers={"Origin": origin, "Access-Control-Request-Method": "POST"})
        assert status == 200 and headers.get("access-control-allow-origin") == origin  # Starlette's CORS preflight
        assert headers.get("access-control-allow-methods") == "GET, POST"
        status, headers, _ = s.request("/health", headers={"Origin": origin})
        assert status == 200 and headers.get("access-control-allow-origin") == origin
        status, headers, body = s.request("/health", headers={"Authorization": "Bearer wrong"})
        assert status == 401 and "bearer token" in json.loads(body)["error"]
        assert headers.get("www-authenticate", headers.get("WWW-Authenticate", "")).startswith("Bearer")
        status, _, _ = s.request("/references", headers={"Authorization": ""})
        assert status == 401
        client = ArmorClient("robot", "upd", transport=HttpTransport(s.url, token=TOKEN))
        client.utils.load_ref_from_file("topological_map.owl", IRI, buffered_manipulation=False, reasoner="PELLET",
                                        buffered_reasoner=False)
        with pytest.raises(ArmorServiceCallError, match="401"):
            ArmorClient("robot", "upd", transport=HttpTransport(s.url, token="nope")).query.ind_b2_class("ROBOT")
        update = f'INSERT DATA {{ <{NS}Robot9> <{NS}now> "5"^^<http://www.w3.org/2001/XMLSchema#long> }}'
        status, _, body = s.request("/references/upd/sparql", update.encode(), {"Content-Type": "application/sparql-update"})
        assert status == 200, body
        assert json.loads(body)["added"] == 1
        assert "Robot9" in client.query.ind_b2_class("ROBOT")  # reasoned after the update (now's domain)
        status, _, body = s.request("/references/upd/sparql", b"LOAD <http://127.0.0.1:1/x.ttl>",
                                    {"Content-Type": "application/sparql-update"})
        assert status == 403 and "LOAD" in json.loads(body)["error"]
        status, _, body = s.request("/references/upd/sparql", b"INSERT DATA { broken",
                                    {"Content-Type": "application/sparql-update"})
        assert status == 400
        big = urllib.parse.urlencode({"query": "SELECT * WHERE { ?a ?b ?c . ?d ?e ?f }"})
        status, _, body = s.request("/references/upd/sparql?" + big)
        assert status == 400 and "more than 100 rows" in json.loads(body)["error"]
        big = urllib.parse.urlencode({"query": "SELECT * WHERE { ?a ?b ?c . ?d ?e ?f } LIMIT 100"})
        assert s.request("/references/upd/sparql?" + big)[0] == 200


# --------------------------------------------------------------------------- the SERVICE/LOAD guard

@pytest.mark.parametrize("text,refused", [
    ("SELECT * WHERE { SERVICE <http://h/> { ?s ?p ?o } }", True),
    ("select * { service silent <http://h/> { ?s ?p ?o } }", True),
    ("SELECT * WHERE { \\u0053ERVICE <http://h/> { ?s ?p ?o } }", True),  # escapes are decoded first
    ("SELECT * WHERE { ?s ?p ?o .SERVICE <http://h/> { } }", True),
    ("LOAD <http://h/x.ttl> INTO GRAPH <urn:g>", True),
    ("SELECT ?service WHERE { ?service ex:LOAD 'SERVICE' } # SERVICE", False),
    ('SELECT * WHERE { ?s <http://h/SERVICE> """LOAD""" }', False),
    ("INSERT DATA { <urn:a> <urn:b> <urn:c> }", False),
])
def test_service_and_load_guard(text: str, refused: bool) -> None:
    from topostore.sparql.guard import UnsafeOperationError, check_safe

    if refused:
        with pytest.raises(UnsafeOperationError):
            check_safe(text)
    else:
        check_safe(text)
