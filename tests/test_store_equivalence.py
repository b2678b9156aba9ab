"""The same rules, queries and aRMOR commands give identical answers on every store.

The Pellet-differential scenarios (tests/scenarios.py) and a generated map
with robot moves run in memory, on disk (RocksDB), on ``oxigraph serve`` and on Virtuoso;
each answer must equal the in-memory one (which the differential tests compare with
Pellet).  The scenarios are applied *after* a first REASON, so incremental maintenance runs
on every store too.  Virtuoso is skipped, loudly, only where it cannot be installed.
"""

from __future__ import annotations

import itertools
from pathlib import Path

import pytest
from scenarios import NAMES, SCENARIOS, generated, topostore
from support import ABOX_OWL as ABOX
from support import IRI
from support import TBOX_OWL as TBOX

from topostore import Ontology
from topostore.demo import mapgen
from topostore.stores import open_store

STORES = ["disk", "oxigraph", "virtuoso"]
_counter = itertools.count()


def store_for(kind: str, request, tmp_path: Path):
    """A fresh store of ``kind`` (remote ones get their own reference namespace on the shared server)."""
    if kind == "memory":
        return open_store(None)
    if kind == "disk":
        return open_store(tmp_path / "db")
    url = request.getfixturevalue(f"{kind}_url")
    return open_store(url, reference=f"equivalence-{next(_counter)}")


def scenario_answer(store, name: str) -> dict:
    onto = Ontology(store=store)
    onto.load(ABOX)
    onto.reason()
    SCENARIOS[name](onto)
    return topostore(onto, NAMES)


@pytest.mark.parametrize("kind", STORES)
@pytest.mark.parametrize("name", list(SCENARIOS))
def test_differential_scenarios_equal_in_memory(name: str, kind: str, request, tmp_path: Path) -> None:
    expected = scenario_answer(open_store(None), name)
    store = store_for(kind, request, tmp_path)
    try:
        assert scenario_answer(store, name) == expected
    finally:
        store.close()


def robot_walk(onto: Ontology, size: int, seed: int) -> list[dict]:
    """Answers after each of a few robot steps on a generated map (moves, clock, visits)."""
    m = mapgen.generate(size, seed=seed)
    names = m.locations + m.doors + list(m.robots)
    answers = [topostore(onto, names)]
    here = "C1"
    for step in range(4):
        there = sorted(m.neighbours(here))[step % len(m.neighbours(here))]
        onto.replace("Robot1", "isIn", there, old=here)
        onto.replace("Robot1", "now", onto.value(1665579760 + 10 * step, "long"))
        onto.replace(there, "visitedAt", onto.value(1665579760 + 10 * step, "long"))
        answers.append(topostore(onto, names))
        here = there
    return answers


@pytest.mark.parametrize("kind", STORES)
def test_generated_map_walk_equal_in_memory(kind: str, request, tmp_path: Path) -> None:
    mem, _ = generated(12, 3, True)
    expected = robot_walk(mem, 12, 3)
    onto, _ = generated(12, 3, True)
    store = store_for(kind, request, tmp_path)
    try:
        durable = Ontology(store=store)
        durable.add(*onto.store.triples(graph=onto_graph()))
        assert robot_walk(durable, 12, 3) == expected
    finally:
        store.close()


def onto_graph():
    from topostore.rdf.vocab import ASSERTED

    return ASSERTED


# --------------------------------------------------------------------------- the tutorial through aRMOR

#: The seed tutorial's requests (tests/test_armor_service.py::test_seed_tutorial), then queries of every
#: kind, a removal and raw SPARQL: each response must be the same on every store.
TUTORIAL = [
    ("LOAD", "FILE", "", [str(TBOX), IRI, "true", "PELLET", "true"]),
    ("ADD", "OBJECTPROP", "IND", ["hasDoor", "E", "D6"]),
    ("ADD", "OBJECTPROP", "IND", ["hasDoor", "E", "D7"]),
    ("ADD", "OBJECTPROP", "IND", ["hasDoor", "R3", "D6"]),
    ("ADD", "DATAPROP", "IND", ["visitedAt", "E", "LONG", "1665579700"]),
    ("ADD", "DATAPROP", "IND", ["visitedAt", "R3", "LONG", "1665579735"]),
    ("DISJOINT", "IND", "", ["E", "R3", "D6", "D7"]),
    ("ADD", "OBJECTPROP", "IND", ["isIn", "Robot1", "R3"]),
    ("REPLACE", "OBJECTPROP", "IND", ["isIn", "Robot1", "E", "R3"]),
    ("REASON", "", "", []),
    ("QUERY", "DATAPROP", "IND", ["now", "Robot1"]),
    ("REPLACE", "DATAPROP", "IND", ["now", "Robot1", "LONG", "1665579750", "1665579740"]),
    ("REPLACE", "DATAPROP", "IND", ["visitedAt", "E", "LONG", "1665579750", "1665579700"]),
    ("REASON", "", "", []),
    ("QUERY", "OBJECTPROP", "IND", ["canReach", "Robot1"]),
    ("QUERY", "IND", "CLASS", ["URGENT"]),
    ("QUERY", "CLASS", "IND", ["E", "false"]),
    ("QUERY", "CLASS", "IND", ["E", "true"]),
    ("QUERY", "IND", "", ["R3"]),
    ("QUERY", "OBJECTPROP", "IND", ["connectedTo", "E"]),
    ("QUERY", "SPARQL", "", ["PREFIX : <http://bnc/exp-rob-lab/2022-23#> SELECT ?l ?t WHERE { ?l a :URGENT ; :visitedAt ?t }", "5000"]),
    ("REMOVE", "IND", "", ["D7"]),
    ("REASON", "", "", []),
    ("QUERY", "IND", "CLASS", ["CORRIDOR"]),
    ("ADD", "OBJECTPROP", "IND", ["hasDoor", "R3", "R3"]),  # a location that is a door: inconsistent
    ("REASON", "", "", []),
    ("QUERY", "OBJECTPROP", "IND", ["canReach", "Robot1"]),
]


def tutorial_answers(store) -> list[dict]:
    """The answers of the tutorial's requests, on a reference of its own: no other run's graphs on a shared
    server can be read as its own (the name was one, ``tut``, for every run)."""
    from topostore.armor import ArmorService

    service = ArmorService(store=store)
    reference = f"tutorial-{next(_counter)}"
    try:
        return [service.call({"client_name": "c", "reference_name": reference, "command": c,
                              "primary_command_spec": s1, "secondary_command_spec": s2, "args": list(args)}).to_dict()
                for c, s1, s2, args in TUTORIAL]
    finally:
        service.close()


@pytest.mark.parametrize("kind", STORES)
def test_tutorial_answers_equal_in_memory(kind: str, request, tmp_path: Path) -> None:
    expected = tutorial_answers(None)
    assert all(a["success"] for a in expected) and not expected[-2]["is_consistent"]
    assert expected[20]["queried_objects"] == ["{l=http://bnc/exp-rob-lab/2022-23#R3, t=1665579735^^http://www.w3.org/2001/XMLSchema#long}"]
    spec = str(tmp_path / "refs") if kind == "disk" else request.getfixturevalue(f"{kind}_url")
    answers = tutorial_answers(spec)
    differ = [i for i, (got, want) in enumerate(zip(answers, expected, strict=True)) if got != want]
    assert not differ, (f"command {differ[0]} {TUTORIAL[differ[0]]} answered {answers[differ[0]]}, in memory "
                        f"{expected[differ[0]]}; commands answered otherwise: {differ}")
