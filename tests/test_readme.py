"""The README's examples run as written (documentation that cannot rot).

Every Python block runs on its own, in a fresh namespace, so a block cannot
lean on a name defined by an earlier one.  The "Use it from ..." section runs
in order against a real server started with the section's own `topostore serve`
line: its shell blocks through bash, its Python blocks in-process; the one
change is the port (8765 becomes a free one).  The only block not run is the
`make run` / `make test` pair at the top: `make test` is this test suite.
"""

from __future__ import annotations

import os
import re
import signal
import socket
import subprocess
import sys
import time
from dataclasses import dataclass
from pathlib import Path

import pytest
import rdflib
from servers import stop
from test_server import free_port

from topostore.armor_api import transport

ROOT = Path(__file__).resolve().parents[1]
SECTION = "## Use it from armor_py_api, rdflib, SPARQLWrapper or curl"


@dataclass(frozen=True)
class Block:
    language: str
    code: str
    section: str


def blocks() -> list[Block]:
    """Fenced code blocks with a language, with the `## ` section they are in."""
    out, section = [], ""
    pattern = re.compile(r"(^## [^\n]*$|^```\w+\n.*?^```$)", re.M | re.S)
    for part in pattern.split((ROOT / "README.md").read_text()):
        if part.startswith("## "):
            section = part.strip()
        elif part.startswith("```"):
            language, code = re.match(r"```(\w+)\n(.*)```", part, re.S).groups()
            out.append(Block(language, code, section))
    return out


def standalone_python() -> list[Block]:
    return [b for b in blocks() if b.language == "python" and b.section != SECTION]


def test_readme_has_the_blocks_it_should() -> None:
    found = blocks()
    assert len(standalone_python()) >= 3
    served = [b for b in found if b.section == SECTION]
    assert [b.language for b in served] == ["sh", "sh", "python", "python", "python"]
    not_run = [b for b in found if b.section != SECTION and b.language != "python"]
    # the set-up block is the suite itself; the ROS section's block is run by tests/test_ros.py; the
    # durable-store section lists the --store forms, which its Python block (run below) exercises
    assert [b.code.split()[:4] for b in not_run] == [["make", "run", "#", "set"],
                                                     ["export", 'PATH="$PWD/.venv/bin:$PATH"', "roscore", "-p"],
                                                     ["topostore", "reason", "--store", "out/mapdb"]]


@pytest.mark.parametrize("index", range(len(standalone_python())))
def test_python_block_runs_alone(index: int, monkeypatch: pytest.MonkeyPatch,
                                 capsys: pytest.CaptureFixture[str]) -> None:
    monkeypatch.chdir(ROOT)
    transport.set_default_service(None)  # the in-process service a fresh interpreter would have
    try:
        exec(compile(standalone_python()[index].code, f"README.md block {index}", "exec"), {})  # noqa: S102
    finally:
        transport.set_default_service(None)
    out = capsys.readouterr().out
    block = standalone_python()[index]
    if "service.call" in block.code and block.section.startswith("## aRMOR commands"):  # the tutorial as dicts
        assert "['\"1665579740\"^^xsd:long']" in out and "['CORRIDOR']" in out
    if "armor_api.armor_client import" in standalone_python()[index].code:
        assert "\"1665579740\"^^xsd:long 1665579740" in out


def test_use_it_from_section(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                             capsys: pytest.CaptureFixture[str]) -> None:
    port = str(free_port())
    (tmp_path / "ontology").symlink_to(ROOT / "ontology")
    env = {**os.environ, "PATH": f"{Path(sys.executable).parent}{os.pathsep}{os.environ.get('PATH', '')}"}
    served = [Block(b.language, b.code.replace("8765", port), b.section) for b in blocks() if b.section == SECTION]
    serve_line = served[0].code.strip()
    assert serve_line.startswith("topostore serve ") and "\n" not in serve_line
    server = subprocess.Popen(["bash", "-c", f"exec {serve_line}"], cwd=tmp_path, env=env,
                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        deadline = time.monotonic() + 30
        while True:
            try:
                socket.create_connection(("127.0.0.1", int(port)), timeout=1).close()
                break
            except OSError:
                assert server.poll() is None and time.monotonic() < deadline, "the README's server did not start"
                time.sleep(0.1)
        curl = subprocess.run(["bash", "-e", "-c", served[1].code], cwd=tmp_path, env=env, capture_output=True,
                              text=True, timeout=120)
        assert curl.returncode == 0, curl.stderr
        lines = curl.stdout.splitlines()
        assert lines[0].startswith('{"reference":"map","iri":"http://bnc/exp-rob-lab/2022-23"')
        assert lines[1].startswith('{"added":') and '"is_consistent":true' in lines[1]
        assert lines[2:4] == ["l", "http://bnc/exp-rob-lab/2022-23#R1"]
        assert lines[4].startswith('[{"@id":')
        assert '"queried_objects":["<http://bnc/exp-rob-lab/2022-23#R1>"]' in lines[5]
        monkeypatch.chdir(tmp_path)
        outputs = []
        for block in served[2:]:
            exec(compile(block.code, "README.md", "exec"), {})  # noqa: S102 - our own documentation
            outputs.append(capsys.readouterr().out)
        assert outputs[0] == "['R1']\n['C1', 'R1', 'R2']\n"
        ns = "http://bnc/exp-rob-lab/2022-23#"
        assert outputs[1] == f"['{ns}R1', '{ns}R2']\nTrue\n"
        corridors, constructed = outputs[2].split("\n", 1)
        assert corridors == f"['{ns}C1']"
        graph = rdflib.Graph().parse(data=constructed, format="turtle")
        reach = (rdflib.URIRef(ns + "Robot1"), rdflib.URIRef(ns + "canReach"))
        assert set(graph) == {(*reach, rdflib.URIRef(ns + "R1")), (*reach, rdflib.URIRef(ns + "R2"))}
    finally:
        stop(server, signal.SIGINT)
