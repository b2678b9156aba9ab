"""Fuzzing the ROS node: bad ArmorDirective requests to a running `topostore ros` through rospy service calls.

One roscore, one node and one long-lived rospy client (tests/ros_fuzz_client.py)
per module.  Every case sends a request (or a serialized list) with wrong
arities, unknown commands, empty, huge, NUL, control and non-UTF-8 strings,
injection names and path escapes, and checks: a reply within a bounded time
(never a service error), only documented exit codes and no internal error,
the asserted and inferred graphs of every reference unchanged after a failing
request (read back with a follow-up QUERY SPARQL through the node), no file
outside the data directory touched, and the node still answering.
"""

from __future__ import annotations

import json
import os
import select
import subprocess
import sys
from collections.abc import Iterator
from pathlib import Path

import pytest
from fuzz_support import DOCUMENTED_CODES, count_case, fuzz_settings, nested_sparql, text, tree
from hypothesis import given
from hypothesis import strategies as st
from ros_support import IRI, RosWorld, prepare_data, skip_without_ros, start_world, stop, stop_world

from topostore.armor.commands import COMMANDS

# thousands of generated cases: run without line tracing (coverage comes from the exact tests)
pytestmark = pytest.mark.no_cover

CLIENT = str(Path(__file__).with_name("ros_fuzz_client.py"))
REPLY_SECONDS = 60.0
DUMP = "SELECT ?g ?s ?p ?o WHERE { GRAPH ?g { ?s ?p ?o } }"
#: limits of the fuzzed node: small, so a planted runaway rule or a slow query costs seconds, not minutes
NODE_LIMITS = ("--query-max-seconds", "5", "--reason-max-seconds", "10")


class RosFuzz:
    """The world, the node's sandbox and the client process, with the calls the invariants need."""

    def __init__(self, tmp: Path) -> None:
        self.sandbox = tmp / "sandbox"
        self.data = prepare_data(self.sandbox / "data")
        (self.sandbox / "outside.owl").write_text("keep")
        (self.data / "escape.owl").symlink_to(self.sandbox / "outside.owl")
        os.mkfifo(self.data / "fifo.owl")
        self.world: RosWorld = start_world(tmp)
        self.client: subprocess.Popen | None = None
        try:
            self.node = self.world.start_node(self.data, *NODE_LIMITS)
            self.client = subprocess.Popen([sys.executable, CLIENT], env=self.world.env, stdin=subprocess.PIPE,
                                           stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, start_new_session=True)
            assert "ready" in self._read(), "the fuzz client did not start"
            self.outside = self.outside_tree()
        except BaseException:
            self.close()
            raise

    def close(self) -> None:
        if self.client is not None:
            self.client.stdin.close()
            stop(self.client)
        stop_world(self.world)

    def _read(self) -> dict:
        assert self.client is not None and self.client.stdout is not None
        ready, _, _ = select.select([self.client.stdout], [], [], REPLY_SECONDS)
        assert ready, f"no reply within {REPLY_SECONDS:g} s (node alive: {self.node.poll() is None})"
        line = self.client.stdout.readline()
        assert line, f"the fuzz client died (node alive: {self.node.poll() is None})"
        return json.loads(line)

    def send(self, service: str, requests: list[dict]) -> dict:
        """One service call; the client's answer (replies, or the error of the call itself)."""
        assert self.client is not None and self.client.stdin is not None
        self.client.stdin.write(json.dumps({"service": service, "requests": requests}).encode() + b"\n")
        self.client.stdin.flush()
        return self._read()

    def ok(self, *requests: dict) -> list[dict]:
        answer = self.send("serialized", list(requests))
        assert "error" not in answer, answer
        for reply in answer["replies"]:
            assert reply["exit_code"] == 0 and not reply["timeout"], reply
        return answer["replies"]

    def ensure(self) -> list[str]:
        """Keep reference "ref" loaded; the names of all references."""
        (refs,) = self.ok(req("GET", "ALL", "REFS", ref="x"))
        if "ref" not in refs["queried_objects"]:
            self.ok(req("LOAD", "FILE", "", "topological_map.owl", IRI, "false", "PELLET", "false"))
            (refs,) = self.ok(req("GET", "ALL", "REFS", ref="x"))
        return sorted(refs["queried_objects"])

    def graphs(self, names: list[str]) -> dict[str, list]:
        """Every quad of every reference, read back through the node."""
        replies = self.ok(*(req("QUERY", "SPARQL", "FORMATTED", DUMP, ref=n) for n in names))
        return {n: sorted(_rows(r["sparql_queried_objects"])) for n, r in zip(names, replies, strict=True)}

    def outside_tree(self) -> dict:
        return {k: v for k, v in tree(self.sandbox).items() if not k.startswith(str(self.data))}


def _rows(items: list[list[str]]) -> list[tuple[str, ...]]:
    """(g, s, p, o) rows from FORMATTED's flat key/value items (four per row, in the projection's order)."""
    assert [k for k, _ in items] == ["g", "s", "p", "o"] * (len(items) // 4)
    return [tuple(v for _, v in items[i:i + 4]) for i in range(0, len(items), 4)]


def req(command: str, spec1: str = "", spec2: str = "", *args: str, ref: str = "ref", client: str = "c") -> dict:
    return {"client_name": client, "reference_name": ref, "command": command, "primary_command_spec": spec1,
            "secondary_command_spec": spec2, "args": list(args)}


@pytest.fixture(scope="module")
def fuzz(tmp_path_factory: pytest.TempPathFactory) -> Iterator[RosFuzz]:
    skip_without_ros()
    harness = RosFuzz(tmp_path_factory.mktemp("fuzz-ros"))
    try:
        yield harness
    finally:
        harness.close()


def paths(sandbox_marker: str) -> st.SearchStrategy[str]:
    """Path escapes; ``sandbox_marker`` is replaced by the sandbox (an absolute path outside the data dir)."""
    return st.sampled_from(["../outside.owl", "../new.owl", "escape.owl", "fifo.owl", "/dev/zero", "/etc/passwd", ".",
                            "..", "", "sub/../../x.owl", f"{sandbox_marker}/abs.owl", f"{sandbox_marker}/outside.owl",
                            "topological_map.owl", "saved.owl", "log.txt", "%2e%2e/x.owl", "a\x00b.owl"])


MARKER = "\x01SANDBOX\x01"
HUGE = st.sampled_from(["x" * 300_000, "9" * 5000, "{" * 20_000, "é" * 100_000])
KEYS = sorted(COMMANDS)


def value() -> st.SearchStrategy[str]:
    surrogates = st.characters(min_codepoint=0xD800, max_codepoint=0xDFFF)
    return st.one_of(text(), text(), nested_sparql(), paths(MARKER), HUGE,
                     st.text(alphabet=surrogates, min_size=1, max_size=3))


def directive() -> st.SearchStrategy[dict]:
    """An ArmorDirectiveReq: a known command (any arity) or an unknown one, every string possibly hostile."""
    known = st.sampled_from(KEYS).map(lambda k: k)
    unknown = st.tuples(text(), text(), text())
    return st.builds(
        lambda key, client, ref, args: {"client_name": client, "reference_name": ref, "command": key[0],
                                        "primary_command_spec": key[1], "secondary_command_spec": key[2],
                                        "args": args},
        st.one_of(known, known, known, unknown),
        st.sampled_from(["c", "c", "other", "", "\udcff", "a\x00b"]),
        st.one_of(st.sampled_from(["ref", "ref", "ref", "other", "", "../ref", "\udcff", "ref\x00"]), text()),
        st.lists(value(), max_size=7),
    )


def _place(requests: list[dict], sandbox: Path) -> list[dict]:
    """Put the real sandbox path where the generator left its marker."""
    return [{**r, "args": [a.replace(MARKER, str(sandbox)) for a in r["args"]]} for r in requests]


def _failed(reply: dict) -> bool:
    return not reply["success"] and reply["exit_code"] != 0


@fuzz_settings(0.12)
@given(requests=st.lists(directive(), min_size=1, max_size=4), serialized=st.booleans())
def test_fuzz_ros_node(fuzz: RosFuzz, requests: list[dict], serialized: bool) -> None:
    count_case()
    requests = _place(requests if serialized else requests[:1], fuzz.sandbox)
    names = fuzz.ensure()
    before = fuzz.graphs(names)
    answer = fuzz.send("serialized" if serialized else "single", requests)
    assert "error" not in answer, answer
    assert len(answer["replies"]) == len(requests)
    for reply in answer["replies"]:
        assert reply["exit_code"] in DOCUMENTED_CODES, reply
        assert "internal error" not in reply["error_description"].lower(), reply
    if all(_failed(r) for r in answer["replies"]):
        assert fuzz.ensure() == names
        assert fuzz.graphs(names) == before
    assert fuzz.outside_tree() == fuzz.outside
    assert fuzz.node.poll() is None


def test_the_invariants_can_see_a_change(fuzz: RosFuzz) -> None:
    """The follow-up query sees one added fact (and its inference), and a refused escape changes nothing."""
    probe = dict(ref="probe", client="probe")
    fuzz.ok(req("LOAD", "FILE", "", "topological_map.owl", IRI, "false", "PELLET", "false", **probe))
    before = fuzz.graphs(["probe"])["probe"]
    (added,) = fuzz.send("single", [req("ADD", "IND", "CLASS", "FuzzProbe", "ROOM", **probe)])["replies"]
    assert (added["success"], added["exit_code"]) == (True, 0)
    after = fuzz.graphs(["probe"])["probe"]
    assert sorted(set(after) - set(before)) == [
        ("urn:topostore:graph:asserted", f"{IRI}#FuzzProbe", "http://www.w3.org/1999/02/22-rdf-syntax-ns#type",
         f"{IRI}#ROOM"),
        ("urn:topostore:graph:inferred", f"{IRI}#FuzzProbe", "http://www.w3.org/1999/02/22-rdf-syntax-ns#type",
         f"{IRI}#LOCATION")]
    (refused,) = fuzz.send("single", [req("SAVE", "", "", str(fuzz.sandbox / "abs.owl"), **probe)])["replies"]
    assert (refused["success"], refused["exit_code"]) == (False, 210)
    (bad,) = fuzz.send("single", [req("ADD", "IND", "CLASS", "x\udcff", "\ud800", **probe)])["replies"]
    assert bad["exit_code"] in DOCUMENTED_CODES
    assert fuzz.graphs(["probe"])["probe"] == after and fuzz.outside_tree() == fuzz.outside
