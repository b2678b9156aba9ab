"""Fuzzing file loading (LOAD FILE, Ontology.load, the CLI) with path escapes and hostile contents.

Invariants: a documented error or success, never a hang (FIFOs, /dev/zero),
nothing outside the data directory read or written, and the CLI exits with
0 (success) or 1/2 (a clear error), never a traceback.
"""

from __future__ import annotations

import os
from pathlib import Path

import pytest
from click.testing import CliRunner
from fuzz_support import count_case, fuzz_settings, text, tree
from hypothesis import given
from hypothesis import strategies as st
from support import IRI, SHARED

from topostore import Ontology
from topostore.armor import ArmorService
from topostore.cli.group import cli
from topostore.errors import TopostoreError

# thousands of generated cases: run without line tracing (coverage comes from the exact tests)
pytestmark = pytest.mark.no_cover


CONTENTS = st.one_of(
    st.binary(max_size=300),
    st.sampled_from([
        b"", b"<rdf:RDF", b"@prefix : <urn:x#> . :a :b :c .", b"<?xml version='1.0'?><!DOCTYPE x [<!ENTITY a 'aa'>"
        b"<!ENTITY b '&a;&a;'>]><rdf:RDF xmlns:rdf='http://www.w3.org/1999/02/22-rdf-syntax-ns#'/>",
        b"<!DOCTYPE x [<!ENTITY e SYSTEM 'file:///etc/passwd'>]><x>&e;</x>",
        (SHARED / "topological_map.owl").read_bytes()[:5000],
        b"@prefix swrl: <http://www.w3.org/2003/11/swrl#> . <urn:r> a swrl:Imp .",
    ]),
)
SUFFIXES = st.sampled_from([".owl", ".ttl", ".nt", ".rdf", ".xml", ".jsonld", "", ".txt"])


@pytest.fixture(scope="module")
def sandbox(tmp_path_factory: pytest.TempPathFactory) -> Path:
    root = tmp_path_factory.mktemp("fuzz-files")
    data = root / "data"
    data.mkdir()
    (root / "secret.owl").write_bytes((SHARED / "topological_map.owl").read_bytes())
    (data / "link.owl").symlink_to(root / "secret.owl")
    (data / "zero.owl").symlink_to("/dev/zero")
    os.mkfifo(data / "fifo.owl")
    (data / "dir.owl").mkdir()
    return root


PATHS = st.one_of(text(), st.sampled_from(["link.owl", "zero.owl", "fifo.owl", "dir.owl", "../secret.owl", "/dev/zero",
                                            "/etc/passwd", "sub/../../secret.owl", "file.owl", "file.ttl", ".", ""]))


@fuzz_settings(1.0)
@given(content=CONTENTS, suffix=SUFFIXES, path=PATHS, save=st.booleans())
def test_fuzz_load_and_save_paths(sandbox: Path, content: bytes, suffix: str, path: str, save: bool) -> None:
    count_case()
    data = sandbox / "data"
    (data / f"file{suffix}").write_bytes(content)
    outside = {k: v for k, v in tree(sandbox).items() if not k.startswith(str(data))}
    service = ArmorService(data_dir=data)
    res = service.call({"reference_name": "r", "command": "LOAD", "primary_command_spec": "FILE",
                        "args": [path if not path.startswith("file") else f"file{suffix}", IRI, "false", "PELLET", "false"]})
    assert res.exit_code in (0, 208, 209, 210), res
    assert "internal error" not in res.error_description
    if res.exit_code == 0 and save:
        res = service.call({"reference_name": "r", "command": "SAVE", "args": [path]})
        assert res.exit_code in (0, 208, 210), res
    assert {k: v for k, v in tree(sandbox).items() if not k.startswith(str(data))} == outside
    assert not [p for p in data.iterdir() if p.name.endswith(".tmp")]


@fuzz_settings(0.5)
@given(content=CONTENTS, suffix=SUFFIXES)
def test_fuzz_ontology_load_data(content: bytes, suffix: str) -> None:
    count_case()
    onto = Ontology()
    fmt = {"owl": "rdfxml", "ttl": "turtle", "nt": "ntriples"}.get(suffix.lstrip("."), "turtle")
    try:
        onto.load_data(content, fmt)
    except TopostoreError:
        assert onto.store.count(onto.visible_graphs()[0]) == 0
        return
    onto.reason()


CLI_ARGS = st.lists(st.one_of(text(), st.sampled_from(["reason", "rules", "query", "map", "--help", "-o", "--format",
                                                       "--param", "x=1", "can-reach", "--debug", "--list"])),
                    max_size=5)


@fuzz_settings(0.5)
@given(args=CLI_ARGS)
def test_fuzz_cli(sandbox: Path, args: list[str]) -> None:
    """Any argument list: exit 0, 1 (error message) or 2 (usage), never an uncaught exception."""
    count_case()
    if "serve" in args or "demo" in args or "bench" in args or "-o" in args:
        return  # long-running or writing commands are exercised by their own tests
    args = [a for a in args if "\x00" not in a and a.encode("utf-8", "surrogatepass") == a.encode("utf-8", "ignore")]
    result = CliRunner().invoke(cli, args, catch_exceptions=True)
    assert result.exit_code in (0, 1, 2), (args, result.output, result.exception)
    if result.exception is not None and not isinstance(result.exception, SystemExit):
        pytest.fail(f"{args}: {result.exception!r}")
