"""The README's and the manual's examples run as written (documentation that cannot rot).

Every Python block of README.md and docs/*.md runs on its own, in a fresh
namespace, so a block cannot lean on a name defined by an earlier one.  The
"Use it from ..." section of docs/service.md runs in order against a real
server started with the section's own `topostore serve` line: its shell blocks
through bash, its Python blocks in-process; the one change is the port (8765
becomes a free one).  The front page's tour runs its `topostore reason` and
`topostore explain` lines.  Shell blocks that are not run are listed below,
each with the reason; every relative link of the pages names a file that exists, and every link
to a heading names one the page has.
"""

from __future__ import annotations

import os
import re
import shlex
import signal
import socket
import subprocess
import sys
import time
import unicodedata
from dataclasses import dataclass
from pathlib import Path

import pytest
import rdflib
from http_support import free_port
from servers import stop

from topostore.armor_api import transport

ROOT = Path(__file__).resolve().parents[1]
PAGES = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]
SERVED = ("docs/service.md", "## Use it from armor_py_api, rdflib, SPARQLWrapper or curl")


@dataclass(frozen=True)
class Block:
    page: str
    language: str
    code: str
    section: str

    @property
    def served(self) -> bool:
        return (self.page, self.section) == SERVED


def page_blocks(path: Path) -> list[Block]:
    """Fenced code blocks with a language, with the `## ` section they are in."""
    out, section = [], ""
    page = str(path.relative_to(ROOT))
    pattern = re.compile(r"(^## [^\n]*$|^```\w+\n.*?^```$)", re.M | re.S)
    for part in pattern.split(path.read_text(encoding="utf-8")):
        if part.startswith("## "):
            section = part.strip()
        elif part.startswith("```"):
            language, code = re.match(r"```(\w+)\n(.*)```", part, re.S).groups()
            out.append(Block(page, language, code, section))
    return out


def blocks() -> list[Block]:
    return [b for page in PAGES for b in page_blocks(page)]


def standalone_python() -> list[Block]:
    return [b for b in blocks() if b.language == "python" and not b.served]


def first_words(block: Block) -> list[str]:
    return block.code.split()[:4]


#: Shell blocks not run here, page by page, with why.
NOT_RUN = {
    # the set-up pair is the suite itself
    "README.md": [["make", "run", "#", "set"]],
    # the --store forms; the page's Python block (run here) exercises each store
    "docs/stores.md": [["topostore", "reason", "--store", "out/mapdb"]],
    # run by tests/test_ros.py against a real roscore
    "docs/ros.md": [["export", 'PATH="$PWD/.venv/bin:$PATH"', "roscore", "-p"]],
    # a server on a fixed port, then the same requests the "Use it from" section runs
    "docs/service.md": [["topostore", "serve", "--port", "8765"], ["curl", "-s", "localhost:8765/armor", "-H"]],
    "docs/cli.md": [["topostore", "reason", "FILE...", "[-o"]],  # a synopsis, not commands
    "docs/inspector.md": [["topostore", "serve", "--data-dir", "data"]],  # starts a server and waits
}


def test_the_pages_have_the_blocks_they_should() -> None:
    found = blocks()
    assert len(standalone_python()) >= 8
    assert {b.page for b in standalone_python()} >= {"README.md", "docs/api.md", "docs/armor.md", "docs/explain.md",
                                                     "docs/reliability.md", "docs/stores.md", "docs/incremental.md"}
    served = [b for b in found if b.served]
    assert [b.language for b in served] == ["sh", "sh", "python", "python", "python"]
    not_run: dict[str, list[list[str]]] = {}
    for b in found:
        if b.language in ("sh", "bash") and not b.served and b != tour_shell():
            not_run.setdefault(b.page, []).append(first_words(b))
    assert not_run == NOT_RUN


def tour_shell() -> Block:
    (block,) = [b for b in page_blocks(ROOT / "README.md") if b.section == "## A tour" and b.language == "sh"]
    return block


def test_the_tour_commands_run(tmp_path: Path) -> None:
    """The tour's one-shot commands, as written, from the repository root (serve and ros are long-running)."""
    env = {**os.environ, "PATH": f"{Path(sys.executable).parent}{os.pathsep}{os.environ.get('PATH', '')}"}
    lines = [line.split("#", 1)[0].strip() for line in tour_shell().code.splitlines()]
    commands = [shlex.split(line) for line in lines if line]
    assert [c[:2] for c in commands] == [["topostore", "reason"], ["topostore", "explain"],
                                        ["topostore", "serve"], ["topostore", "ros"]]
    reason, explain = (subprocess.run(c, cwd=ROOT, env=env, capture_output=True, text=True, timeout=120)
                       for c in commands[:2])
    assert reason.returncode == 0, reason.stderr
    assert "Consistent." in reason.stdout
    assert explain.returncode == 0, explain.stderr
    assert explain.stdout.startswith("R1 rdf:type URGENT  ← swrl:Urgency")


def link_targets(path: Path) -> list[str]:
    """The targets of a page's links outside code: inline ``[text](target)`` and reference ``[label]: target``."""
    text = re.sub(r"^```.*?^```$", "", path.read_text(encoding="utf-8"), flags=re.M | re.S)
    return re.findall(r"\]\(([^)\s]+)\)", text) + re.findall(r"^ {0,3}\[[^\]]+\]:\s*(\S+)", text, flags=re.M)


def relative_links(path: Path) -> list[str]:
    return [t for t in link_targets(path) if not re.match(r"[a-z]+:|#", t)]


@pytest.mark.parametrize("page", PAGES, ids=lambda p: str(p.relative_to(ROOT)))
def test_every_relative_link_names_a_file(page: Path) -> None:
    missing = [t for t in relative_links(page) if not (page.parent / t.split("#")[0]).exists()]
    assert not missing, f"{page.name} links to files that do not exist: {missing}"


def heading_anchors(path: Path) -> set[str]:
    """The anchors a Markdown renderer gives a page's headings, GitHub's way: lower case, every character
    but letters, digits, spaces, hyphens and underscores dropped, spaces made hyphens, a repeat numbered."""
    text = re.sub(r"^```.*?^```$", "", path.read_text(encoding="utf-8"), flags=re.M | re.S)
    anchors: set[str] = set()
    seen: dict[str, int] = {}
    for title in re.findall(r"^#{1,6} +(.+?) *$", text, flags=re.M):
        slug = "".join(c for c in title.lower()
                       if c in " -_" or unicodedata.category(c)[0] in "LN" or unicodedata.category(c) == "Mn")
        slug = slug.replace(" ", "-")
        anchors.add(f"{slug}-{seen[slug]}" if slug in seen else slug)
        seen[slug] = seen.get(slug, 0) + 1
    return anchors


def anchored_links(path: Path) -> list[tuple[Path, str]]:
    """Each link of a page to a heading (``#anchor`` or ``page.md#anchor``): the page it names and the anchor."""
    links = [t for t in link_targets(path) if "#" in t and not re.match(r"[a-z]+:", t)]
    return [(path.parent / t.split("#")[0] if not t.startswith("#") else path, t.split("#", 1)[1]) for t in links]


@pytest.mark.parametrize("page", PAGES, ids=lambda p: str(p.relative_to(ROOT)))
def test_every_anchor_names_a_heading(page: Path) -> None:
    """A section moved to another page (the benchmarks' history, say) leaves no link pointing at nothing."""
    broken = [f"{target.name}#{anchor}" for target, anchor in anchored_links(page)
              if target.suffix == ".md" and target.exists() and anchor not in heading_anchors(target)]
    assert not broken, f"{page.name} links to headings that do not exist: {broken}"


def test_every_page_is_in_the_index() -> None:
    index = {t.split("#")[0] for t in relative_links(ROOT / "docs" / "README.md")}
    assert {p.name for p in PAGES if p.parent.name == "docs" and p.name != "README.md"} <= index


@pytest.mark.parametrize("index", range(len(standalone_python())))
def test_python_block_runs_alone(index: int, monkeypatch: pytest.MonkeyPatch,
                                 capsys: pytest.CaptureFixture[str]) -> None:
    monkeypatch.chdir(ROOT)
    block = standalone_python()[index]
    transport.set_default_service(None)  # the in-process service a fresh interpreter would have
    try:
        exec(compile(block.code, f"{block.page} block {index}", "exec"), {})  # noqa: S102 - our own documentation
    finally:
        transport.set_default_service(None)
    out = capsys.readouterr().out
    if "service.call" in block.code and block.page == "docs/armor.md":  # the tutorial as dicts
        assert "['\"1665579740\"^^xsd:long']" in out and "['CORRIDOR']" in out
    if "armor_api.armor_client import" in block.code and block.page == "docs/armor.md":
        assert "\"1665579740\"^^xsd:long 1665579740" in out


def test_use_it_from_section(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                             capsys: pytest.CaptureFixture[str]) -> None:
    port = str(free_port())
    (tmp_path / "ontology").symlink_to(ROOT / "ontology")
    env = {**os.environ, "PATH": f"{Path(sys.executable).parent}{os.pathsep}{os.environ.get('PATH', '')}"}
    served = [Block(b.page, b.language, b.code.replace("8765", port), b.section) for b in blocks() if b.served]
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
                assert server.poll() is None and time.monotonic() < deadline, "the service page's server did not start"
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
            exec(compile(block.code, block.page, "exec"), {})  # noqa: S102 - our own documentation
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
