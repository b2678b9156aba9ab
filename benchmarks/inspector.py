"""What the inspector costs: ``python -m benchmarks.inspector [--sizes 100 1000] [--steps N]``.

On a generated map (``topostore.demo.mapgen``) of each size, reasoned:

* ``entity_ms``: the time to build the JSON of one entity page (:func:`topostore.http.inspector.describe_entity`,
  every inferred fact with its proof): a room, a corridor, the robot, the URGENT and LOCATION classes
  (their member lists cut at the default limit) and the isIn property; the first call for a class
  includes building the classification prototypes, so each page is built twice and both times printed;
* ``search_ms``: one search-box query;
* ``step_ms``: the median robot step (move, advance the clock, mark visited, REASON) without and with
  the inspector's history recording (:class:`topostore.http.history.History`, drained every step).

One JSON line per size.
"""

from __future__ import annotations

import argparse
import json
import statistics
import time
from collections.abc import Callable

from topostore import Ontology
from topostore.demo.mapgen import TopoMap, generate
from topostore.http.entities import resolve_entity, search_entities
from topostore.http.history import History
from topostore.http.inspector import describe_entity
from topostore.resources import default_ontology

from .events import walk


def reasoned(m: TopoMap) -> Ontology:
    onto = Ontology.from_file(default_ontology())
    onto.add(*m.triples())
    onto.reason()
    return onto


def _ms(work: Callable[[], object]) -> float:
    start = time.perf_counter()
    work()
    return round((time.perf_counter() - start) * 1000, 2)


def pages(onto: Ontology, m: TopoMap) -> dict[str, list[float]]:
    robot = next(iter(m.robots))
    names = {"room": m.rooms[0], "corridor": m.corridors[0], "robot": robot, "URGENT": "URGENT",
             "LOCATION": "LOCATION", "isIn": "isIn"}
    return {kind: [_ms(lambda n=name: describe_entity(onto, resolve_entity(onto, n))) for _ in range(2)]
            for kind, name in names.items()}


def steps(m: TopoMap, n: int, record: bool, seed: int = 7) -> list[float]:
    """Latencies of ``n`` robot steps on a fresh reasoned copy of the map, its history recorded or not."""
    onto = reasoned(m)
    if not record:
        return walk(onto, m, n, seed)
    return walk(onto, m, n, seed, after=History(onto).drain)


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--sizes", nargs="+", type=int, default=[100, 1000])
    parser.add_argument("--steps", type=int, default=30)
    args = parser.parse_args(argv)
    for size in args.sizes:
        m = generate(size)
        onto = reasoned(m)
        row: dict = {"locations": size, "entity_ms": pages(onto, m),
                     "search_ms": _ms(lambda o=onto: search_entities(o, "R1"))}
        row["step_ms"] = {("recorded" if record else "alone"): round(statistics.median(steps(m, args.steps, record))
                                                                      * 1000, 3)
                          for record in (False, True)}
        print(json.dumps(row), flush=True)


if __name__ == "__main__":
    main()
