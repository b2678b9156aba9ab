"""What following every REASON costs: ``python -m benchmarks.events [--sizes 3 100 1000] [--steps N]``.

The ROS node's events topic (and any ``every_reason`` subscriber) makes each
REASON take two snapshots of the visible inferred triples and their difference.
This runs the same robot steps (move to a neighbour, advance the clock, mark the
new location visited, REASON) on two copies of a generated map (``topostore.demo.mapgen``):
one without subscribers, one with an every-REASON subscriber whose callback
serialises the event as the topic does (:func:`topostore.ontology.events.event_json`).
It prints the median and p95 step latency of each, one JSON line per size.
"""

from __future__ import annotations

import argparse
import json
import random
import statistics
import time
from collections.abc import Callable

from topostore import Ontology
from topostore.demo.mapgen import TopoMap, generate
from topostore.ontology.events import event_json
from topostore.resources import default_ontology


def steps(size: int, n: int, follow: bool, seed: int = 7) -> list[float]:
    """Latencies of ``n`` robot steps on a fresh reasoned map of ``size`` locations, followed or not."""
    m = generate(size)
    onto = Ontology.from_file(default_ontology())
    onto.add(*m.triples())
    onto.reason()
    if follow:
        onto.events.subscribe(lambda e: len(event_json(e, onto.prefix, "ref")), None, 100, every_reason=True)
    return walk(onto, m, n, seed)


def walk(onto: Ontology, m: TopoMap, n: int, seed: int = 7, after: Callable[[], object] = lambda: None) -> list[float]:
    """Latencies of ``n`` robot steps on ``onto`` (the map ``m``, reasoned): move to a random neighbour,
    advance the clock, mark the new location visited, REASON, then ``after`` (inside the timing)."""
    rng = random.Random(seed)
    robot, where = next(iter(m.robots.items()))
    now = m.now
    latencies = []
    for _ in range(n):
        where = rng.choice(sorted(m.neighbours(where)) or [where])
        now += rng.randint(1, 5)
        start = time.perf_counter()
        onto.replace(robot, "isIn", where)
        onto.replace(robot, "now", onto.value(now, "long"))
        onto.replace(where, "visitedAt", onto.value(now, "long"))
        onto.reason()
        after()
        latencies.append(time.perf_counter() - start)
    return latencies


def _ms(values: list[float], q: float) -> float:
    ordered = sorted(values)
    return round(ordered[min(len(ordered) - 1, round(q * (len(ordered) - 1)))] * 1000, 3)


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--sizes", nargs="+", type=int, default=[3, 100, 1000])
    parser.add_argument("--steps", type=int, default=50)
    args = parser.parse_args(argv)
    for size in args.sizes:
        row: dict = {"locations": size}
        for follow in (False, True):
            t = steps(size, args.steps, follow)
            row["followed" if follow else "alone"] = {"median_ms": round(statistics.median(t) * 1000, 3),
                                                      "p95_ms": _ms(t, 0.95)}
        print(json.dumps(row), flush=True)


if __name__ == "__main__":
    main()
