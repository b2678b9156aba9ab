"""Generators and invariants shared by the fuzz suites (tests/test_fuzz_*.py).

``FUZZ_EXAMPLES`` (environment ``TOPOSTORE_FUZZ_EXAMPLES``) scales every suite:
small in ``make test`` so the suites stay under three minutes, large in
``make fuzz``.  Every case calls :func:`count_case`; tests/conftest.py prints
the total and the violations (failed fuzz tests) at the end of the run.
"""

from __future__ import annotations

import os
import sys
from collections import Counter
from pathlib import Path

from hypothesis import HealthCheck, settings
from hypothesis import strategies as st

from topostore.armor import ArmorService
from topostore.armor.commands import COMMANDS
from topostore.rdf.vocab import ASSERTED, AUX, INFERRED

#: examples per fuzz test
FUZZ_EXAMPLES = int(os.environ.get("TOPOSTORE_FUZZ_EXAMPLES", "500"))
CASES = {"tried": 0}
#: cases per fuzz test (the calling function's name), for the per-entry-point figures
CASES_BY_TEST: Counter[str] = Counter()


def count_case() -> None:
    CASES["tried"] += 1
    CASES_BY_TEST[sys._getframe(1).f_code.co_name] += 1


def fuzz_settings(scale: float = 1.0):
    return settings(max_examples=max(10, int(FUZZ_EXAMPLES * scale)), deadline=None, database=None,
                    suppress_health_check=list(HealthCheck), derandomize=os.environ.get("TOPOSTORE_FUZZ_RANDOM") is None)


#: exit codes the protocol documents (topostore.armor.codes)
DOCUMENTED_CODES = {0, 101, 102, 201, 202, 203, 205, 206, 207, 208, 209, 210}

NASTY_TEXT = [
    "", " ", "\x00", "a\x00b", "\ud800", "x\udfffy", "\u202e", "\ufeff", "\n", "\r\n", "\t", "'", '"', "\\", "<", ">",
    "}", "{", "?x", "$x", "#", "a b", "> ; DROP ALL ; <", "} } DROP ALL { {", "\" . <urn:x> <urn:y> \"", "<urn:x>",
    "<http://127.0.0.1:9/x>", "<javascript:alert(1)>", "<>", "<a b>", "urn:topostore:fn:pow", "<urn:topostore:fn:pow>",
    "rdf:type", "<http://www.w3.org/1999/02/22-rdf-syntax-ns#type>", "<http://www.w3.org/2003/11/swrl#Imp>",
    "<http://www.w3.org/2002/07/owl#Restriction>", "owl:Thing", "R1", "E", "C1", "D5", "Robot1", "ROOM", "CORRIDOR",
    "URGENT", "hasDoor", "visitedAt", "now", "canReach", "isIn", "DOOR", "LOCATION", "9" * 5000, "-" + "9" * 30,
    "1e99999", "NaN", "INF", "-0", "0x10", "true", "TRUE", "2147483648", "9223372036854775808", "1.5", "é", "日本",
    "\U0001F916", "a" * 10_000, "../x", "/etc/passwd", "..", ".", "/dev/zero", "x.owl", "sub/../../x", "%2e%2e/x",
]
TYPE_NAMES = ["STRING", "INTEGER", "INT", "LONG", "FLOAT", "DOUBLE", "BOOLEAN", "DECIMAL", "DATETIME", "SHORT", "BYTE",
              "UNKNOWN", "", "long", "xsd:long"]


def text() -> st.SearchStrategy[str]:
    """Any string, biased to values that broke services before."""
    return st.one_of(st.sampled_from(NASTY_TEXT), st.text(max_size=40),
                     st.text(alphabet=st.characters(codec="utf-8"), max_size=20), st.sampled_from(TYPE_NAMES))


def nested_sparql() -> st.SearchStrategy[str]:
    """Deeply nested, long or malformed SPARQL."""
    depth = st.integers(0, 5000)
    return st.one_of(
        depth.map(lambda n: "SELECT * WHERE " + "{" * n + "}" * n),
        depth.map(lambda n: "SELECT * WHERE { FILTER(" + "(" * n + "1" + ")" * n + ") }"),
        depth.map(lambda n: "SELECT * WHERE { FILTER(" + "+".join(["1"] * max(n, 1)) + ") }"),
        depth.map(lambda n: "SELECT * WHERE { BIND(" + "CONCAT(" * n + "'a'" + ")" * n + " AS ?x) }"),
        st.sampled_from([
            "SELECT * WHERE { SERVICE <http://127.0.0.1:9/> { ?s ?p ?o } }",
            "SELECT (<urn:topostore:fn:pow>(3, 30000000) AS ?x) WHERE {}",
            "ASK {}", "CONSTRUCT WHERE { ?s ?p ?o }", "DESCRIBE <urn:x>", "SELECT", "}", "SELECT * WHERE { ?s ?p ?o } LIMIT 3",
            "SELECT ?s WHERE { ?s a ?c }", "LOAD <file:///etc/passwd>", "DROP ALL", "INSERT DATA { <urn:a> <urn:b> <urn:c> }",
            "SELECT * WHERE { ?a ?b ?c . ?d ?e ?f } LIMIT 5", "SELECT * WHERE { FILTER(REGEX(\"aaaa\", \"(a+)+b\")) }",
        ]),
        text(),
    )


def request() -> st.SearchStrategy[object]:
    """aRMOR requests: known commands with wrong arities and nasty values, unknown commands, wrong types."""
    keys = sorted(COMMANDS)
    known = st.sampled_from(keys).flatmap(lambda k: st.fixed_dictionaries({
        "client_name": st.sampled_from(["c", "other", "", "\ud800"]),
        "reference_name": st.sampled_from(["ref", "ref", "ref", "other", ""]),
        "command": st.just(k[0]), "primary_command_spec": st.just(k[1]), "secondary_command_spec": st.just(k[2]),
        "args": st.lists(st.one_of(text(), nested_sparql()), max_size=6),
    }))
    wrong = st.one_of(
        st.none(), st.integers(), st.lists(st.integers(), max_size=3), st.text(max_size=5),
        st.dictionaries(st.sampled_from(["command", "args", "reference_name", "x"]),
                        st.one_of(st.none(), st.integers(), st.text(max_size=5), st.lists(st.integers(), max_size=2)),
                        max_size=4),
        st.fixed_dictionaries({"reference_name": st.just("ref"), "command": text(), "primary_command_spec": text(),
                               "secondary_command_spec": text(), "args": st.lists(text(), max_size=4)}),
    )
    return st.one_of(known, known, wrong)


def graphs(service: ArmorService) -> dict[str, tuple]:
    """The asserted, inferred and helper graphs of every reference (what a failed request must not change)."""
    out = {}
    for name in sorted(service.reference_names()):
        store = service.reference(name).ontology.store
        out[name] = tuple(frozenset(store.triples(graph=g)) for g in (ASSERTED, INFERRED, AUX))
    return out


def tree(path: Path) -> dict[str, tuple[int, int]]:
    """Every file under ``path`` with its size and modification time (to prove nothing outside was touched)."""
    out = {}
    for p in sorted(path.rglob("*")):
        try:
            info = p.lstat()
        except OSError:
            continue
        out[str(p)] = (info.st_size, info.st_mtime_ns)
    return out


__all__ = ["FUZZ_EXAMPLES", "CASES", "CASES_BY_TEST", "count_case", "fuzz_settings", "DOCUMENTED_CODES", "text", "nested_sparql",
           "request", "graphs", "tree"]
