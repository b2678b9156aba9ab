"""Regression tests for the reliability and security findings V1-V10: each is named after what it prevents."""

from __future__ import annotations

import json
import os
import subprocess
import sys
import textwrap
import threading
from pathlib import Path

import pytest
import rdflib
from pyoxigraph import Literal, NamedNode
from rdflib.compare import isomorphic
from support import ABOX_OWL as ABOX
from support import IRI
from swrl_support import PREFIXES, builtin, data, rule

from topostore import Ontology
from topostore.armor import ArmorService
from topostore.compile.notices import RULE_SET_ASIDE
from topostore.errors import LoadError
from topostore.http.app import ServerConfig, create_app
from topostore.rdf.safeio import atomic_write, check_xml_entities, read_regular_file
from topostore.rdf.vocab import ASSERTED, INFERRED
from topostore.reason.limits import ReasonLimitExceeded, ReasonLimits
from topostore.sparql.guard import QueryTooComplex, check_user_sparql

ROOT = Path(__file__).resolve().parents[1]


def call(svc: ArmorService, command: str, spec1: str = "", spec2: str = "", args=(), ref: str = "ref", client: str = "c"):
    return svc.call({"client_name": client, "reference_name": ref, "command": command,
                     "primary_command_spec": spec1, "secondary_command_spec": spec2, "args": list(args)})


def graphs(svc: ArmorService, ref: str = "ref") -> tuple[list[str], list[str]]:
    onto = svc.reference(ref).ontology
    return (sorted(str(t) for t in onto.store.triples(graph=ASSERTED)),
            sorted(str(t) for t in onto.store.triples(graph=INFERRED)))


@pytest.fixture
def data_dir(tmp_path: Path) -> Path:
    d = tmp_path / "data"
    d.mkdir()
    (d / "map.owl").write_bytes(ABOX.read_bytes())
    return d


@pytest.fixture
def svc(data_dir: Path) -> ArmorService:
    s = ArmorService(data_dir=data_dir)
    r = call(s, "LOAD", "FILE", "", ["map.owl", IRI, "false", "PELLET", "false"])
    assert r.exit_code == 0, r
    return s


# --------------------------------------------------------------------------- V1 parser crash

CRASH_SCRIPT = textwrap.dedent("""
    import json, sys
    from starlette.testclient import TestClient
    from topostore import Ontology
    from topostore.armor import ArmorService
    from topostore.http.app import ServerConfig, create_app
    n = int(sys.argv[2])
    texts = {
        "braces": "SELECT * WHERE " + "{" * n + "}" * n,
        "parens": "SELECT * WHERE { FILTER(" + "(" * n + "1" + ")" * n + ") }",
        "calls": "SELECT * WHERE { BIND(" + "CONCAT(" * n + "'a'" + ")" * n + " AS ?x) }",
        "chain": "SELECT * WHERE { FILTER(" + "+".join(["1"] * n) + ") }",
        "escaped": "SELECT * WHERE " + "\\\\u007B" * n + "}" * n,
    }
    text = texts[sys.argv[1]]
    out = {}
    onto = Ontology()
    try:
        onto.sparql(text)
        out["python"] = "ran"
    except Exception as exc:
        out["python"] = type(exc).__name__
    svc = ArmorService(data_dir=sys.argv[3])
    svc.call({"reference_name": "r", "command": "LOAD", "primary_command_spec": "FILE",
              "args": ["map.owl", "http://x", "false", "PELLET", "false"]})
    res = svc.call({"reference_name": "r", "command": "QUERY", "primary_command_spec": "SPARQL", "args": [text]})
    out["armor"] = res.exit_code
    client = TestClient(create_app(ServerConfig(data_dir=sys.argv[3]), svc), base_url="http://127.0.0.1")
    out["get"] = client.get("/references/r/sparql", params={"query": text}).status_code
    out["post"] = client.post("/references/r/sparql", content=text.encode(),
                              headers={"content-type": "application/sparql-query"}).status_code
    print(json.dumps(out))
""")


@pytest.mark.parametrize("kind,n", [("braces", 2500), ("parens", 3000), ("calls", 1000), ("chain", 3500),
                                    ("escaped", 2500)])
def test_deeply_nested_sparql_cannot_crash_the_process(kind: str, n: int, data_dir: Path) -> None:
    """Run in a child process: a SIGSEGV fails this test instead of killing pytest."""
    proc = subprocess.run([sys.executable, "-c", CRASH_SCRIPT, kind, str(n), str(data_dir)], capture_output=True,
                          text=True, timeout=120)
    assert proc.returncode == 0, f"child died with {proc.returncode}: {proc.stderr[-2000:]}"
    out = json.loads(proc.stdout.strip().splitlines()[-1])
    assert out == {"python": "QueryTooComplex", "armor": 209, "get": 400, "post": 400}


def test_sparql_limits_leave_ordinary_queries_alone() -> None:
    check_user_sparql("SELECT ?x WHERE { ?x a <urn:C> . FILTER(?x != <urn:a>) } LIMIT 10")
    with pytest.raises(QueryTooComplex, match="nests brackets 65 deep"):
        check_user_sparql("SELECT * WHERE " + "{" * 65 + "}" * 65)
    with pytest.raises(QueryTooComplex, match="characters"):
        check_user_sparql("#" * 300_000 + "\nSELECT * {}")


# --------------------------------------------------------------------------- V3 SSRF, V4 internal functions

def test_service_through_armor_query_is_refused(svc: ArmorService) -> None:
    for text in ("SELECT * WHERE { SERVICE <http://127.0.0.1:9/x> { ?s ?p ?o } }",
                 "SELECT * WHERE { \\u0053ERVICE <http://127.0.0.1:9/> { ?s ?p ?o } }"):
        res = call(svc, "QUERY", "SPARQL", "", [text])
        assert (res.success, res.exit_code) == (False, 209)
        assert "SERVICE is not allowed" in res.error_description


def test_internal_functions_cannot_be_called_from_user_sparql(svc: ArmorService) -> None:
    text = "SELECT ?x WHERE { BIND(<urn:topostore:fn:pow>(3, 30000000) AS ?x) }"
    res = call(svc, "QUERY", "SPARQL", "", [text])
    assert (res.success, res.exit_code) == (False, 209) and "internal functions" in res.error_description
    # hidden behind a prefix: the guard does not see the IRI, Oxigraph does not know the function
    hidden = "PREFIX f: <urn:topostore:> SELECT ?x WHERE { BIND(f:fn:pow(3, 30000000) AS ?x) }"
    res = call(svc, "QUERY", "SPARQL", "", [hidden])
    assert (res.success, res.exit_code) == (False, 209)
    assert "fn:pow" in res.error_description  # refused by name, never evaluated


def test_pow_builtin_cannot_freeze_the_service() -> None:
    from topostore.compile.builtins import POW_MAX_BITS
    from topostore.compile.builtins import pow_value as _pow

    integer = NamedNode("http://www.w3.org/2001/XMLSchema#integer")

    def power(base: int, exponent: int) -> Literal | None:
        return _pow(Literal(str(base), datatype=integer), Literal(str(exponent), datatype=integer))

    assert power(3, 4).value == "81"
    assert power(2, POW_MAX_BITS // 2).value == str(2 ** (POW_MAX_BITS // 2))  # within the bound: computed
    assert power(2, POW_MAX_BITS + 1) is None  # past it: no value, and nothing computed
    assert power(3, 30000000) is None  # a 47-million-bit number is never built


# --------------------------------------------------------------------------- V4 time limits

def test_query_without_timeout_is_bounded_by_the_service_maximum(svc: ArmorService) -> None:
    svc.max_query_seconds = 0.5
    slow = ("SELECT * WHERE { ?a ?b ?c . ?d ?e ?f . ?g ?h ?i . ?j ?k ?l }")
    for args in ([slow], [slow, "0"], [slow, "-5"], [slow, str(2 ** 70)]):
        res = call(svc, "QUERY", "SPARQL", "", args)
        assert res.exit_code == 0 and res.timeout is True, res  # the service's maximum applied, whatever was asked


def test_huge_timeout_is_not_an_internal_error(svc: ArmorService) -> None:
    res = call(svc, "QUERY", "SPARQL", "FORMATTED", ["SELECT ?x WHERE { ?x a <urn:none> }", str(2 ** 70)])
    assert (res.success, res.exit_code, res.timeout) == (True, 0, False)


# --------------------------------------------------------------------------- V2 runaway reasoning

RUNAWAY = rule([data(":counter", "?x", "?v"), builtin("add", "?w", "?v", 1)], [data(":counter", "?x", "?w")],
               label="Runaway")


def test_runaway_rule_is_stopped_and_rolled_back() -> None:
    onto = Ontology()
    onto.load_data(PREFIXES + ':c1 a owl:NamedIndividual .\n:counter a owl:DatatypeProperty .\n', "turtle")
    onto.reason()
    before = sorted(map(str, onto.store.triples(graph=ASSERTED)))
    inferred = sorted(map(str, onto.store.triples(graph=INFERRED)))
    onto.limits = ReasonLimits(max_rounds=50, max_inferred=10_000, max_seconds=20)
    onto.load_data(PREFIXES + RUNAWAY + ':c1 :counter "0"^^xsd:integer .\n', "turtle")
    with pytest.raises(ReasonLimitExceeded, match="more than 50 rounds") as info:
        onto.reason()
    assert "Runaway" in str(info.value) and "was rolled back" in str(info.value)
    assert sorted(map(str, onto.store.triples(graph=ASSERTED))) == before
    assert sorted(map(str, onto.store.triples(graph=INFERRED))) == inferred
    assert onto.reason().consistent  # the next REASON works


def test_runaway_rule_planted_by_armor_commands_is_refused_and_the_service_answers(svc: ArmorService) -> None:
    from topostore.reason import limits

    svc.reference("ref").ontology.limits = limits.ReasonLimits(max_rounds=100, max_inferred=100_000, max_seconds=30)
    before = graphs(svc)
    text = PREFIXES + RUNAWAY + ':R1 :counter "0"^^xsd:integer .\n'
    onto = svc.reference("ref").ontology
    with svc.reference("ref").lock:
        with pytest.raises(ReasonLimitExceeded):
            onto.load_data(text, "turtle")
            onto.reason()
    assert graphs(svc) == before
    res = call(svc, "QUERY", "CLASS", "IND", ["R1", "true"])
    assert (res.exit_code, res.queried_objects) == (0, ["ROOM", "URGENT"])


def test_a_reason_failing_after_manipulations_gives_back_the_spelling_held(data_dir: Path) -> None:
    """A value held as ``"01665579700"^^xsd:long`` (as loaded), replaced by 5, then by its canonical
    spelling (the same stored term), then by 6, each manipulation on its own and the reasoner buffered: the
    REASON that fails reverts them, and the value comes back as it was held at the last good REASON."""
    svc = ArmorService(data_dir=data_dir)
    assert call(svc, "LOAD", "FILE", "", ["map.owl", IRI, "false", "PELLET", "true"]).exit_code == 0
    onto = svc.reference("ref").ontology
    held = Literal("01665579700", datatype=NamedNode("http://www.w3.org/2001/XMLSchema#long"))
    onto.load_data(f"<{IRI}#R3> <{IRI}#visitedAt> {held} .\n", "turtle")
    assert call(svc, "REASON").exit_code == 0
    for new, old in (("5", "1665579700"), ("1665579700", "5"), ("6", "1665579700")):
        assert call(svc, "REPLACE", "DATAPROP", "IND", ["visitedAt", "R3", "LONG", new, old]).exit_code == 0
    onto.limits = ReasonLimits(max_rounds=50, max_inferred=10_000, max_seconds=20)
    onto.load_data(PREFIXES + RUNAWAY + ':c1 :counter "0"^^xsd:integer .\n', "turtle")
    assert call(svc, "REASON").exit_code != 0
    assert onto.data_values("visitedAt", "R3") == [held]


def test_cardinality_min_check_is_not_exponential(svc: ArmorService) -> None:
    """A minimum of 20 compiles to one counting subquery, not a 20-way join of pairwise different fillers
    (its cost is measured by ``python -m benchmarks.cardinality``)."""
    onto = svc.reference("ref").ontology
    before = {r.sparql() for r in onto.rules.rules}
    res = call(svc, "ADD", "CARDINALITY", "MIN", ["CORRIDOR", "hasDoor", "20", "DOOR"])
    assert res.exit_code == 0, res
    (membership,) = [r for r in onto.rules.rules if r.sparql() not in before and r.name == "ext-min-card"]
    assert "(hasDoor min 20 DOOR)" in membership.origin
    assert "COUNT(DISTINCT" in membership.sparql() and len(membership.body) <= 2
    assert max(len(r.body) for r in onto.rules.rules) < 20


# --------------------------------------------------------------------------- V6 half-applied change

@pytest.mark.parametrize("buffered_reasoner", ["false", "true"])
def test_vocabulary_class_cannot_break_every_later_reason(data_dir: Path, buffered_reasoner: str) -> None:
    svc = ArmorService(data_dir=data_dir)
    assert call(svc, "LOAD", "FILE", "", ["map.owl", IRI, "false", "PELLET", buffered_reasoner]).exit_code == 0
    res = call(svc, "ADD", "IND", "CLASS", ["rx", "<http://www.w3.org/2003/11/swrl#Imp>"])
    assert (res.success, res.exit_code) == (True, 0), res
    res = call(svc, "REASON")
    assert (res.success, res.exit_code) == (True, 0), res
    # a rule of nothing (no body, no head): set aside and named, as Pellet ignores it
    report = svc.reference("ref").ontology.reason()
    assert report.consistent
    assert [n.subject for n in report.incomplete if n.axiom_kind == RULE_SET_ASIDE] == [IRI + "#rx"]


def test_failed_reason_restores_the_state_before_the_change(data_dir: Path) -> None:
    svc = ArmorService(data_dir=data_dir)
    assert call(svc, "LOAD", "FILE", "", ["map.owl", IRI, "true", "PELLET", "true"]).exit_code == 0
    ref = svc.reference("ref")
    ref.ontology.limits = ReasonLimits(max_rounds=100, max_inferred=100_000, max_seconds=8)
    with ref.lock:  # a rule with no finite closure once a counter has a value
        ref.ontology.load_data(PREFIXES + RUNAWAY + ":counter a owl:DatatypeProperty .\n", "turtle")
    assert call(svc, "REASON").exit_code == 0
    before = graphs(svc)
    counter = "<http://example.org/swrltest#counter>"  # the rule's property (swrl_support's namespace)
    assert call(svc, "ADD", "DATAPROP", "IND", [counter, "R1", "INTEGER", "0"]).exit_code == 0  # buffered
    res = call(svc, "REASON")
    assert (res.success, res.exit_code) == (False, 209)
    assert graphs(svc) == before
    assert call(svc, "REASON").exit_code == 0


def test_failed_reason_on_a_reopened_durable_store_restores_the_state_as_reopened(data_dir: Path, tmp_path: Path) -> None:
    """A store closed after a successful REASON and reopened: a change and a REASON that fails are undone
    as in memory (the reopened state is the one to return to), and the reply is true."""
    store = tmp_path / "stores"
    svc = ArmorService(data_dir=data_dir, store=store)
    assert call(svc, "LOAD", "FILE", "", ["map.owl", IRI, "true", "PELLET", "true"]).exit_code == 0
    svc.close()
    svc = ArmorService(data_dir=data_dir, store=store)
    before = graphs(svc)
    assert before[1], "the reopened store keeps its inferred facts"
    ref = svc.reference("ref")
    ref.ontology.limits = ReasonLimits(max_rounds=100, max_inferred=100_000, max_seconds=30)
    with ref.lock:  # a rule with no finite closure, asserted by the Python API: the next REASON fails
        ref.ontology.load_data(PREFIXES + RUNAWAY + ':R1 :counter "0"^^xsd:integer .\n', "turtle")
    res = call(svc, "REASON")
    assert (res.success, res.exit_code) == (False, 209)
    assert "were undone" in res.error_description
    assert graphs(svc) == before
    assert call(svc, "REASON").exit_code == 0
    svc.close()


def test_a_store_closed_with_a_change_that_cannot_be_reasoned_still_opens_and_says_so(
        data_dir: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """A runaway rule asserted without a REASON, then the store closed: its REASON fails and the reply says
    the inferred facts were cleared (not that the changes were undone); a restart opens the reference with
    its asserted facts only instead of failing the whole service."""
    store = tmp_path / "stores"
    svc = ArmorService(data_dir=data_dir, store=store)
    assert call(svc, "LOAD", "FILE", "", ["map.owl", IRI, "true", "PELLET", "true"]).exit_code == 0
    ref = svc.reference("ref")
    with ref.lock:
        ref.ontology.load_data(PREFIXES + RUNAWAY + ':R1 :counter "0"^^xsd:integer .\n', "turtle")
    svc.close()
    svc = ArmorService(data_dir=data_dir, store=store)
    svc.reference("ref").ontology.limits = ReasonLimits(max_rounds=100, max_inferred=100_000, max_seconds=30)
    res = call(svc, "REASON")
    assert (res.success, res.exit_code) == (False, 209)
    assert "inferred ones cleared" in res.error_description and "were undone" not in res.error_description
    assert not graphs(svc)[1]
    svc.close()
    from topostore.reason import limits

    monkeypatch.setattr(limits, "DEFAULTS", ReasonLimits(max_rounds=100))  # what a reopened ontology runs under
    svc = ArmorService(data_dir=data_dir, store=store)  # the rebuild at opening fails: opened all the same
    assert svc.reference("ref").ontology.opened == "asserted only"
    assert call(svc, "QUERY", "IND", "CLASS", ["ROOM"]).exit_code == 0
    svc.close()


def test_a_failed_first_reason_leaves_no_half_written_closure() -> None:
    """With no successful REASON to return to, a failed one keeps the asserted facts and clears what it
    had inferred (never a partial closure that queries would read as an answer)."""
    onto = Ontology()
    onto.load(ABOX)
    asserted = sorted(map(str, onto.store.triples(graph=ASSERTED)))
    onto.limits = ReasonLimits(max_inferred=5)
    with pytest.raises(ReasonLimitExceeded) as info:
        onto.reason()
    # its text says what was left: nothing was rolled back, the inferred facts were cleared
    assert "inferred ones cleared" in str(info.value) and "rolled back" not in str(info.value)
    assert sorted(map(str, onto.store.triples(graph=ASSERTED))) == asserted
    assert not list(onto.store.triples(graph=INFERRED))
    onto.limits = ReasonLimits()
    assert onto.reason().consistent and list(onto.store.triples(graph=INFERRED))


# --------------------------------------------------------------------------- V5 entity expansion, file size

LAUGHS = b"""<?xml version="1.0"?>
<!DOCTYPE rdf:RDF [
 <!ENTITY a "aaaaaaaaaa">
 <!ENTITY b "&a;&a;&a;&a;&a;&a;&a;&a;&a;&a;">
 <!ENTITY c "&b;&b;&b;&b;&b;&b;&b;&b;&b;&b;">
]>
<rdf:RDF xmlns:rdf="http://www.w3.org/1999/02/22-rdf-syntax-ns#" xmlns:x="urn:x#">
 <rdf:Description rdf:about="urn:x#s"><x:p>&c;</x:p></rdf:Description>
</rdf:RDF>
"""


def test_billion_laughs_is_refused_before_parsing(svc: ArmorService, data_dir: Path) -> None:
    (data_dir / "laughs.owl").write_bytes(LAUGHS)
    res = call(svc, "LOAD", "FILE", "", ["laughs.owl", IRI, "false", "PELLET", "false"], ref="laughs")
    assert (res.success, res.exit_code) == (False, 210)
    assert "nested entities are refused" in res.error_description
    with pytest.raises(LoadError, match="external or parameter entity"):
        check_xml_entities(b'<!DOCTYPE x [<!ENTITY e SYSTEM "file:///etc/passwd">]><x>&e;</x>')
    with pytest.raises(LoadError, match="would expand to"):
        check_xml_entities(b'<!DOCTYPE x [<!ENTITY e "' + b"a" * 1000 + b'">]><x>' + b"&e;" * 2000 + b"</x>")
    # Protege's abbreviations stay accepted
    check_xml_entities(b'<!DOCTYPE rdf:RDF [<!ENTITY owl "http://www.w3.org/2002/07/owl#">]><x a="&owl;Thing"/>')


def test_fifo_device_and_oversized_files_cannot_hang_or_exhaust_load(tmp_path: Path) -> None:
    fifo = tmp_path / "pipe.owl"
    os.mkfifo(fifo)
    with pytest.raises(LoadError, match="not a regular file"):
        read_regular_file(fifo)
    with pytest.raises(LoadError, match="not a regular file"):
        read_regular_file("/dev/zero")
    big = tmp_path / "big.ttl"
    big.write_bytes(b"#" * 2000)
    with pytest.raises(LoadError, match="more than the limit of 1000"):
        read_regular_file(big, max_bytes=1000)


# --------------------------------------------------------------------------- V7 file escapes

def test_save_to_the_data_dir_itself_writes_nothing_outside(svc: ArmorService, data_dir: Path) -> None:
    outside = sorted(p.name for p in data_dir.parent.iterdir())
    res = call(svc, "SAVE", "", "", ["."])
    assert (res.success, res.exit_code) == (False, 210)
    assert sorted(p.name for p in data_dir.parent.iterdir()) == outside
    assert sorted(p.name for p in data_dir.iterdir()) == ["map.owl"]


def test_save_never_follows_a_planted_tmp_symlink(svc: ArmorService, data_dir: Path) -> None:
    victim = data_dir.parent / "victim.txt"
    victim.write_text("keep")
    (data_dir / "x.owl.tmp").symlink_to(victim)
    assert call(svc, "SAVE", "", "", ["x.owl"]).exit_code == 0
    assert victim.read_text() == "keep"
    saved = rdflib.Graph().parse(data_dir / "x.owl", format="xml")  # the whole reference was written, not the link
    expected = rdflib.Graph().parse(data=svc.reference("ref").ontology.serialize("nt"), format="nt")
    assert isomorphic(saved, expected)


def test_failed_save_leaves_no_temporary_file(tmp_path: Path) -> None:
    target = tmp_path / "out.ttl"
    with pytest.raises(TypeError):
        atomic_write(target, object())  # type: ignore[arg-type]  # fails half-way through writing
    assert list(tmp_path.iterdir()) == []
    atomic_write(target, b"ok")
    assert [p.name for p in tmp_path.iterdir()] == ["out.ttl"] and target.read_bytes() == b"ok"


# --------------------------------------------------------------------------- V8 LOG FILE

def test_log_file_refuses_ontologies_fifos_and_keeps_the_current_log(svc: ArmorService, data_dir: Path) -> None:
    assert call(svc, "LOG", "FILE", "ON", ["armor.log"]).exit_code == 0
    for bad in ("map.owl", "saved.ttl"):
        res = call(svc, "LOG", "FILE", "ON", [bad])
        assert (res.success, res.exit_code) == (False, 210), bad
    os.mkfifo(data_dir / "pipe.log")
    answers: list = []
    asking = threading.Thread(target=lambda: answers.append(call(svc, "LOG", "FILE", "ON", ["pipe.log"])), daemon=True)
    asking.start()
    asking.join(60)  # opening a FIFO for writing would wait for a reader forever
    if asking.is_alive():  # release the writer so the thread ends, then fail
        os.close(os.open(data_dir / "pipe.log", os.O_RDONLY | os.O_NONBLOCK))
        pytest.fail("LOG FILE opened the FIFO and waited for a reader")
    (res,) = answers
    assert (res.success, res.exit_code) == (False, 210)
    assert call(svc, "QUERY", "IND", "", ["R1"]).exit_code == 0
    assert "QUERY" in (data_dir / "armor.log").read_text()  # the old log is still on
    assert (data_dir / "map.owl").read_bytes() == ABOX.read_bytes()
    assert call(svc, "LOG", "FILE", "OFF").exit_code == 0


# --------------------------------------------------------------------------- V9/V10 client errors

@pytest.fixture
def client(svc: ArmorService, data_dir: Path):
    from starlette.testclient import TestClient

    with TestClient(create_app(ServerConfig(data_dir=data_dir), svc), base_url="http://127.0.0.1") as c:
        yield c


def test_huge_json_numbers_and_deep_nesting_are_client_errors(client) -> None:
    for body in ('{"args": [' + "1" * 5000 + "]}", "[" * 5000 + "]" * 5000):
        res = client.post("/armor", content=body.encode(), headers={"content-type": "application/json"})
        assert res.status_code == 400, res.text
        res = client.post("/armor/batch", content=body.encode(), headers={"content-type": "application/json"})
        assert res.status_code == 400, res.text


def test_lone_surrogates_huge_numbers_are_argument_errors(svc: ArmorService) -> None:
    res = call(svc, "ADD", "IND", "", ["bad\ud800name"])
    assert (res.success, res.exit_code) == (False, 208) and "surrogate" in res.error_description
    res = call(svc, "ADD", "DATAPROP", "IND", ["now", "R1", "LONG", "9" * 5000])
    assert (res.success, res.exit_code) == (False, 208)
    res = call(svc, "ADD", "DATAPROP", "IND", ["now", "R1", "INTEGER", "9" * 5000])
    assert (res.success, res.exit_code) == (False, 208)


# --------------------------------------------------------------------------- lower items

def test_host_header_with_userinfo_cannot_pass_the_loopback_check(client) -> None:
    for host in ("localhost:80@evil.com", "127.0.0.1@evil.com", "localhost/evil.com", "evil.com", "[::1"):
        res = client.get("/health", headers={"host": host})
        assert (res.status_code, res.text) == (400, "Invalid host header"), host
    for host in ("localhost:8765", "[::1]:1", "127.0.0.1", "robot.localhost:8765"):
        assert client.get("/health", headers={"host": host}).status_code == 200, host


def test_rename_cannot_rewrite_vocabulary_terms(svc: ArmorService) -> None:
    before = graphs(svc)
    for old in ("<http://www.w3.org/1999/02/22-rdf-syntax-ns#type>", "<http://www.w3.org/2002/07/owl#Thing>"):
        res = call(svc, "RENAME", "IND", "", [old, "mytype"])
        assert (res.success, res.exit_code) == (False, 208), res
    res = call(svc, "RENAME", "IND", "", ["R1", "<http://www.w3.org/2000/01/rdf-schema#label>"])
    assert (res.success, res.exit_code) == (False, 208)
    assert graphs(svc) == before
