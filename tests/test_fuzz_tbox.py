"""Fuzzing LOAD with generated TBoxes: long lists, long chains, deep nesting, big cardinalities.

Each TBox is LOADed and REASONed through the aRMOR service in a child process
(tests/tbox_worker.py), so that a native crash inside the store shows as a dead
child instead of ending the test run.  Invariants: the child survives every case;
it answers within the reasoning time limit plus a margin (no hang); every reply
is a documented exit code; a refusal (209, a rule compile error) says what was
too large or malformed.  ``make test`` tries a few dozen modest TBoxes, ``make fuzz``
hundreds with lists and numbers several times bigger.
"""

from __future__ import annotations

import json
import os
import select
import subprocess
import sys
import time
from collections.abc import Iterator
from pathlib import Path

import pytest
from fuzz_support import DOCUMENTED_CODES, FUZZ_EXAMPLES, count_case, fuzz_settings
from hypothesis import given
from hypothesis import strategies as st

pytestmark = pytest.mark.no_cover

#: a full fuzz run (make fuzz) also draws lists and nesting several times longer
BIG = FUZZ_EXAMPLES > 500
MAX_LIST = 1000 if BIG else 300
MAX_DEPTH = 400 if BIG else 150
#: reasoning time limit in the child, and the margin one evaluation may overrun it by
MAX_SECONDS, MARGIN = 10.0, 50.0
WORKER = Path(__file__).with_name("tbox_worker.py")

PREFIXES = """@prefix : <http://example.org/fuzz#> .
@prefix owl: <http://www.w3.org/2002/07/owl#> .
@prefix rdfs: <http://www.w3.org/2000/01/rdf-schema#> .
@prefix xsd: <http://www.w3.org/2001/XMLSchema#> .
<http://example.org/fuzz> a owl:Ontology .
:p a owl:ObjectProperty . :d a owl:DatatypeProperty .
"""


class Worker:
    """The child process; restarted after a case that killed or hung it."""

    def __init__(self) -> None:
        self.proc: subprocess.Popen | None = None

    def start(self) -> subprocess.Popen:
        if self.proc is None or self.proc.poll() is not None:
            self.proc = subprocess.Popen([sys.executable, str(WORKER)], stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                                         stderr=subprocess.DEVNULL, text=True, cwd=WORKER.parent,
                                         env={**os.environ, "PYTHONPATH": str(WORKER.parent)})
        return self.proc

    def run(self, ttl: str) -> dict | str:
        """The child's answer, or "died (exit N)" / "hung" (the child is then gone)."""
        proc = self.start()
        proc.stdin.write(json.dumps({"ttl": ttl, "max_seconds": MAX_SECONDS}) + "\n")
        proc.stdin.flush()
        deadline = time.monotonic() + MAX_SECONDS + MARGIN
        while time.monotonic() < deadline:
            ready, _, _ = select.select([proc.stdout], [], [], 0.5)
            if ready:
                line = proc.stdout.readline()
                if line:
                    return json.loads(line)
                return f"died (exit {proc.wait()})"
            if proc.poll() is not None:
                return f"died (exit {proc.returncode})"
        self.stop()
        return "hung"

    def stop(self) -> None:
        if self.proc is not None and self.proc.poll() is None:
            self.proc.kill()
            self.proc.wait()
        self.proc = None


@pytest.fixture(scope="module")
def worker() -> Iterator[Worker]:
    w = Worker()
    yield w
    w.stop()


def names(prefix: str, n: int) -> str:
    return " ".join(f":{prefix}{i}" for i in range(n))


@st.composite
def long_lists(draw: st.DrawFn) -> str:
    kind = draw(st.sampled_from(["unionOf", "intersectionOf", "oneOf"]))
    n = draw(st.integers(0, MAX_LIST))
    members = names("i" if kind == "oneOf" else "A", n)
    facts = " ".join(f":x a :A{i} ." for i in draw(st.lists(st.integers(0, max(n - 1, 0)), max_size=5)))
    return f":C owl:equivalentClass [ owl:{kind} ({members}) ] .\n{facts}\n"


@st.composite
def chains(draw: st.DrawFn) -> str:
    n = draw(st.integers(1, MAX_LIST))
    links = draw(st.integers(0, min(n, 50)))
    facts = " ".join(f":x{i} :p{i} :x{i + 1} ." for i in range(links))
    return f":q owl:propertyChainAxiom ({names('p', n)}) .\n{facts}\n"


@st.composite
def nesting(draw: st.DrawFn) -> str:
    depth = draw(st.integers(1, MAX_DEPTH))
    wrappers = draw(st.lists(st.sampled_from([
        "[ owl:complementOf {} ]", "[ a owl:Restriction ; owl:onProperty :p ; owl:someValuesFrom {} ]",
        "[ owl:unionOf ( :A {} ) ]", "[ owl:intersectionOf ( :B {} ) ]",
        "[ a owl:Restriction ; owl:onProperty :p ; owl:allValuesFrom {} ]",
    ]), min_size=depth, max_size=depth))
    expression = ":A"
    for wrapper in wrappers:
        expression = wrapper.format(expression)
    return f":C owl:equivalentClass {expression} .\n:x a :C ; :p :y . :y a :A .\n"


@st.composite
def cardinalities(draw: st.DrawFn) -> str:
    kind = draw(st.sampled_from(["minCardinality", "maxCardinality", "cardinality", "minQualifiedCardinality",
                                 "maxQualifiedCardinality", "qualifiedCardinality"]))
    n = draw(st.one_of(st.integers(0, 700), st.sampled_from([2 ** 31, 2 ** 62, 2 ** 63, 2 ** 64, 10 ** 30])))
    data = draw(st.booleans())
    prop, filler = (":d", "owl:onDataRange xsd:integer") if data else (":p", "owl:onClass :D")
    qualified = f" ; {filler}" if "Qualified" in kind else ""
    values = draw(st.integers(0, min(n + 1, 700)))
    member = draw(st.booleans())
    text = (f":C owl:equivalentClass [ a owl:Restriction ; owl:onProperty {prop} ; "
            f"owl:{kind} \"{n}\"^^xsd:nonNegativeInteger{qualified} ] .\n" + (":x a :C .\n" if member else ""))
    if data:
        return text + " ".join(f":x :d {i} ." for i in range(values)) + "\n"
    ys = names("y", values)
    text += " ".join(f":x :p :y{i} . :y{i} a :D ." for i in range(values)) + "\n"
    if values and draw(st.booleans()):
        text += f"[] a owl:AllDifferent ; owl:distinctMembers ({ys}) .\n"
    return text


TBOXES = st.one_of(long_lists(), chains(), nesting(), cardinalities())


@fuzz_settings(0.06)
@given(body=TBOXES)
def test_fuzz_load_generated_tboxes(worker: Worker, body: str) -> None:
    count_case()
    answer = worker.run(PREFIXES + body)
    assert isinstance(answer, dict), f"{answer} on a TBox of {len(body)} characters: {body[:300]}"
    for step in ("load", "reason"):
        reply = answer[step]
        assert reply["code"] in DOCUMENTED_CODES, (step, reply)
        assert "internal error" not in reply["error"], (step, reply)
        if reply["code"] == 209:
            assert reply["error"], (step, reply)
