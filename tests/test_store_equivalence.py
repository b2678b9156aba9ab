"""The same rules, queries and aRMOR commands give identical answers on every store.

The Pellet-differential scenarios (tests/test_pellet_differential.py) and a generated map
with robot moves run in memory, on disk (RocksDB), on ``oxigraph serve`` and on Virtuoso;
each answer must equal the in-memory one (which the differential tests compare with
Pellet).  The scenarios are applied *after* a first REASON, so incremental maintenance runs
on every store too.  Virtuoso is skipped, loudly, only where it cannot be installed.
"""

from __future__ import annotations

import itertools
from collections.abc import Iterator
from pathlib import Path

import pytest

from servers import oxigraph_server, virtuoso_available, virtuoso_server
from test_pellet_differential import ABOX, NAMES, SCENARIOS, generated, topostore
from topostore import Ontology, mapgen
from topostore.stores import open_store

STORES = ["disk", "oxigraph", "virtuoso"]
_counter = itertools.count()


@pytest.fixture(scope="module")
def oxigraph_url() -> Iterator[str]:
    with oxigraph_server() as url:
        yield url


@pytest.fixture(scope="module")
def virtuoso_url() -> Iterator[str]:
    if not virtuoso_available():
        pytest.skip("VIRTUOSO NOT INSTALLED: the second SPARQL server is missing; "
                    "apt-get install virtuoso-opensource (make test does this as root on Debian)")
    with virtuoso_server() as url:
        yield url


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
    from topostore.vocab import ASSERTED

    return ASSERTED
