"""The `topostore` command line: exit codes, outputs, help texts and one-line errors."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest
import rdflib
from click.testing import CliRunner
from support import NS

from topostore.cli.group import cli, main
from topostore.errors import LoadError
from topostore.ontology.named_queries import named_queries
from topostore.resources import default_ontology, ontology_dir

TBOX = str(default_ontology())
ABOX = str(ontology_dir() / "topological_map_abox.ttl")


def run(*args: str):
    return CliRunner().invoke(cli, list(args))


@pytest.fixture
def inconsistent(tmp_path: Path) -> Path:
    """R1 given a location as a door: DOOR and LOCATION are disjoint."""
    path = tmp_path / "bad.ttl"
    path.write_text(f"@prefix : <{NS}> .\n:R1 :hasDoor :C1 .\n")
    return path


@pytest.mark.parametrize("command", sorted(cli.commands))
def test_every_command_has_help_with_an_example(command: str) -> None:
    result = run(command, "--help")
    assert result.exit_code == 0, result.output
    assert "Example" in result.output


def test_top_level_help_and_version() -> None:
    result = run("--help")
    assert result.exit_code == 0
    listed = result.output.split("\nCommands:\n", 1)[1].splitlines()
    assert [line.split()[0] for line in listed if line.strip()] == sorted(cli.commands)
    assert sorted(cli.commands) == ["bench", "check", "demo", "explain", "map", "query", "reason", "repair", "ros", "rules",
                                    "serve"]
    assert main(["--version"]) == 0


def test_reason_consistent_exits_0_and_writes_closure(tmp_path: Path) -> None:
    out = tmp_path / "closure.ttl"
    result = run("reason", TBOX, ABOX, "-o", str(out))
    assert result.exit_code == 0, result.output
    assert "asserted triples" in result.output and "inferred triples" in result.output
    assert "Consistent." in result.output
    graph = rdflib.Graph().parse(out, format="turtle")
    robot, reach, door = (rdflib.URIRef(NS + n) for n in ("Robot1", "canReach", "hasDoor"))
    assert set(graph.objects(robot, reach)) == {rdflib.URIRef(NS + "R1"), rdflib.URIRef(NS + "R2")}
    assert (rdflib.URIRef(NS + "C1"), door, rdflib.URIRef(NS + "D1")) in graph


def test_reason_inferred_only_in_another_format(tmp_path: Path) -> None:
    out = tmp_path / "inferred.out"
    result = run("reason", TBOX, ABOX, "-o", str(out), "--inferred-only", "--format", "ntriples")
    assert result.exit_code == 0, result.output
    graph = rdflib.Graph().parse(out, format="nt")
    assert (rdflib.URIRef(NS + "R1"), rdflib.RDF.type, rdflib.URIRef(NS + "URGENT")) in graph
    assert not list(graph.triples((None, rdflib.URIRef(NS + "hasDoor"), None)))  # asserted, not inferred


def test_reason_inconsistent_exits_3_naming_axiom_and_individual(inconsistent: Path) -> None:
    result = run("reason", TBOX, ABOX, str(inconsistent))
    assert result.exit_code == 3
    assert "INCONSISTENT" in result.stderr
    assert "DOOR DisjointWith LOCATION" in result.stderr
    assert "C1" in result.stderr
    assert main(["reason", TBOX, ABOX, str(inconsistent)]) == 3


def test_rules_are_grouped_with_origin() -> None:
    result = run("rules", TBOX)
    assert result.exit_code == 0, result.output
    out = result.output
    assert "### SWRL rules" in out and "### OWL axioms" in out and "### Consistency checks" in out
    assert "# swrl:Urgency: SWRL rule Urgency" in out
    assert "# cax-dw: one rule over its table disjointWith" in out  # the told pairs: one check, its rows
    assert "(DOOR DisjointWith LOCATION)" in out
    assert "CONSTRUCT {" in out
    assert "Generic OWL 2 RL rules" not in out
    everything = run("rules", "--all", TBOX).output
    assert "Generic OWL 2 RL rules" in everything
    assert "OWL rule files of rules/owl/" not in out


def test_rules_all_prints_the_owl_rule_files_with_their_instantiations(tmp_path: Path) -> None:
    """The files of rules/owl/ are shown as written, with how many compiled rules fill them in."""
    onto = tmp_path / "kinds.ttl"
    onto.write_text("@prefix : <http://example.org/k#> . @prefix owl: <http://www.w3.org/2002/07/owl#> .\n"
                    "@prefix rdfs: <http://www.w3.org/2000/01/rdf-schema#> .\n"
                    ":A a owl:Class ; rdfs:subClassOf :B . :B a owl:Class ; rdfs:subClassOf :C . :C a owl:Class .\n"
                    ":p a owl:ObjectProperty ; rdfs:domain :A .\n")
    result = run("rules", "--all", str(onto))
    assert result.exit_code == 0, result.output
    out = result.output
    assert "### OWL rule files of rules/owl/" in out
    assert "# cax-sco: 2 instantiation(s)" in out
    assert "# prp-dom: 1 instantiation(s)" in out
    assert "# prp-rng: 0 instantiation(s)" in out
    assert "GRAPH ts:graph:schema" in out


def test_rules_prints_each_owl_rule_file_once_whatever_the_axioms(tmp_path: Path) -> None:
    """The OWL axioms of a kind are one rule of rules/owl/ over a table: more axioms are more rows, not
    more rules."""
    def printed(classes: int) -> str:
        onto = tmp_path / f"chain{classes}.ttl"
        onto.write_text("@prefix : <http://example.org/k#> . @prefix owl: <http://www.w3.org/2002/07/owl#> .\n"
                        "@prefix rdfs: <http://www.w3.org/2000/01/rdf-schema#> .\n"
                        + "".join(f":C{i} a owl:Class ; rdfs:subClassOf :C{i + 1} .\n" for i in range(classes)))
        result = run("rules", str(onto))
        assert result.exit_code == 0, result.output
        return result.output

    small, large = printed(2), printed(30)
    assert "# cax-sco: one rule over its table subClassOf (2 rows)" in small
    assert "# cax-sco: one rule over its table subClassOf (30 rows)" in large
    assert large.count("# name: cax-sco") == small.count("# name: cax-sco") == 1
    assert small.splitlines()[-1].split(",")[0] == large.splitlines()[-1].split(",")[0]  # "# N rules"
    assert "(C7 SubClassOf C8)" in large


def test_rules_deltas_are_one_plain_update_per_body_atom(tmp_path: Path) -> None:
    """Each printed delta rule reads its atom from the delta graph, runs as it is on a store, and, with the
    new facts put in the delta graph, inserts what the rule derives from them."""
    import pyoxigraph as ox

    from topostore.compile.generic import PREFIXES
    from topostore.rdf.vocab import DELTA

    rule_file = tmp_path / "chain.ttl"
    rule_file.write_text(
        "@prefix : <http://example.org/#> . @prefix owl: <http://www.w3.org/2002/07/owl#> .\n"
        "@prefix rdfs: <http://www.w3.org/2000/01/rdf-schema#> .\n"
        ":p a owl:ObjectProperty . :q a owl:ObjectProperty . :r a owl:ObjectProperty ; owl:propertyChainAxiom (:p :q) .\n")
    out = run("rules", "--deltas", str(rule_file)).output
    blocks = [b.split("\n", 1)[1].split("\n\n")[0] for b in out.split("#   delta on atom ")[1:]]
    chain = [b for b in blocks if "http://example.org/#r" in b.split("WHERE")[0]]
    assert len(chain) == 2 and all(f"GRAPH {DELTA}" in b and "LATERAL" not in b and "UNION" not in b for b in chain)
    store = ox.Store()
    a, b, c = (ox.NamedNode(f"http://example.org/#{n}") for n in "abc")
    p, q = ox.NamedNode("http://example.org/#p"), ox.NamedNode("http://example.org/#q")
    store.add(ox.Quad(a, p, b, ox.NamedNode("urn:topostore:graph:asserted")))
    store.add(ox.Quad(b, q, c, DELTA))  # the new fact: b q c
    for text in chain:
        store.update(text, prefixes=PREFIXES)
    derived = {(str(x.subject), str(x.object)) for x in store.quads_for_pattern(None, None, None,
                                                                                  ox.NamedNode("urn:topostore:graph:new-inferred"))}
    assert derived == {("<http://example.org/#a>", "<http://example.org/#c>")}


def test_rules_step_prints_the_compiled_step(tmp_path: Path) -> None:
    """``--step`` prints the compiled step of a replacement: a flip for the clock and each operation with
    when it runs (a robot move reaches no recursive component: the difference is joined where it is
    asked, the named classes stand for their equivalent expressions); an unknown property is said."""
    out = run("rules", "--step", "now", TBOX, ABOX)
    assert out.exit_code == 0, out.output
    assert "flips of <http://bnc/exp-rob-lab/2022-23#now>" in out.output
    assert "GRAPH ?flip" in out.output and "# runs " in out.output
    moved = run("rules", "--step", "isIn,now,visitedAt", TBOX, ABOX).output
    assert "operations outside recursive components" in moved and "# ---- recursive component:" not in moved
    assert "# runs when <http://bnc/exp-rob-lab/2022-23#isIn> lost facts" in moved
    assert "(by index look-ups where up to 16 facts are in play, in memory)" in moved
    assert "was replaced: only the branch seeded by its atom" in moved
    same = tmp_path / "same.ttl"
    same.write_text("@prefix : <http://example.org/#> . @prefix owl: <http://www.w3.org/2002/07/owl#> .\n"
                    ":p a owl:ObjectProperty . :a owl:sameAs :b . :a :p :c .\n")
    refused = run("rules", "--step", "p", str(same)).output
    assert "# not compiled: rule " in refused and "any predicate" in refused, refused


def test_query_named_table_json_tsv() -> None:
    table = run("query", TBOX, ABOX, "urgent-locations")
    assert table.exit_code == 0, table.output
    assert "R1" in table.output and "R2" not in table.output and "1 row(s)" in table.output
    js = run("query", TBOX, ABOX, "reachable-locations", "--param", "robot=Robot1", "--format", "json")
    assert js.exit_code == 0, js.output
    assert json.loads(js.output) == [{"location": NS + "R1"}, {"location": NS + "R2"}]
    tsv = run("query", TBOX, ABOX, "connected-locations", "--format", "tsv")
    lines = tsv.output.splitlines()
    assert lines[0] == "location\tconnectedTo"
    assert f"{NS}C1\t{NS}R1" in lines and len(lines) == 5


def test_query_rq_file(tmp_path: Path) -> None:
    rq = tmp_path / "corridors.rq"
    rq.write_text("# param: cls iri\nSELECT ?x ?cls WHERE { ?x a ?cls } ORDER BY ?x\n")
    result = run("query", TBOX, ABOX, str(rq), "-p", "cls=CORRIDOR", "--format", "json")
    assert result.exit_code == 0, result.output
    assert json.loads(result.output) == [{"x": NS + "C1"}]
    rq.write_text("# param: cls iri\nSELECT ?x WHERE { ?x a ?cls } ORDER BY ?x\n")
    result = run("query", TBOX, ABOX, str(rq), "-p", "cls=CORRIDOR")
    assert result.exit_code == 1
    assert "a query parameter must be in the SELECT list (add ?cls to it)" in result.output


def test_query_list() -> None:
    result = run("query", "--list")
    assert result.exit_code == 0
    for name in named_queries():
        assert name in result.output
    assert "reachable-locations robot=iri" in result.output


@pytest.mark.parametrize("args,code,message", [
    (("reason", "missing.ttl"), 1, "no such file: missing.ttl"),
    (("query", TBOX, ABOX, "no-such-query"), 1, "unknown query 'no-such-query'"),
    (("query", TBOX, ABOX, "reachable-locations"), 1, "needs the parameter(s) robot"),
    (("query", TBOX, ABOX, "reachable-locations", "-p", "robot"), 2, "--param takes NAME=VALUE"),
    (("query", TBOX), 2, "give the ontology file(s) and then a query name"),
    (("reason", TBOX, "-o", "x.ttl", "--format", "klingon"), 1, "unknown RDF format 'klingon'"),
    (("serve", "--host", "0.0.0.0"), 1, "without a token"),
    (("map", TBOX, ABOX, "-o", "map.gif"), 1, "use a .png, .svg, .pdf file name"),
])
def test_errors_are_one_line(args: tuple[str, ...], code: int, message: str, tmp_path: Path, monkeypatch) -> None:
    """Errors of the program exit 1 with one "Error: ..." line; usage errors exit 2 with click's usage lines first."""
    monkeypatch.chdir(tmp_path)
    result = run(*args)
    assert result.exit_code == code, result.output
    err = result.stderr.strip()
    assert "Traceback" not in result.output + result.stderr
    if code == 1:
        assert err.startswith("Error: ") and message in err and len(err.splitlines()) == 1, err
    else:
        assert err.startswith(f"Usage: cli {args[0]} ") and err.splitlines()[-1].startswith(f"Error: {message}"), err


def test_malformed_file_is_one_line_unless_debug(tmp_path: Path) -> None:
    bad = tmp_path / "broken.ttl"
    bad.write_text("@prefix : <http://x#> .\n:a :b \n")
    result = run("reason", str(bad))
    assert result.exit_code == 1
    assert result.stderr.startswith("Error: ") and len(result.stderr.strip().splitlines()) == 1
    debug = run("--debug", "reason", str(bad))
    assert isinstance(debug.exception, LoadError)


def test_console_script_entry_point(inconsistent: Path) -> None:
    proc = subprocess.run([sys.executable, "-m", "topostore.cli", "reason", TBOX, ABOX, str(inconsistent)],
                          capture_output=True, text=True, timeout=60)
    assert proc.returncode == 3
    assert "Traceback" not in proc.stderr and "DisjointWith" in proc.stderr


def test_the_shipped_launch_file_is_well_formed_xml() -> None:
    """roslaunch refuses a launch file that is not XML (a comment holding two hyphens in a row is not)."""
    import xml.dom.minidom

    from topostore.ros.launcher import LAUNCH_FILE

    launch = xml.dom.minidom.parse(str(LAUNCH_FILE)).documentElement
    assert launch.tagName == "launch" and launch.getElementsByTagName("node")[0].getAttribute("type") == "execute"
