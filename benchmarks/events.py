"""What following every REASON costs: ``python -m benchmarks.events [--sizes seed 100 1000] [--steps N]``.

The ROS node's events topic (and any ``every_reason`` subscriber) makes each
REASON take two snapshots of the visible inferred triples and their difference.
This runs the same robot steps as :mod:`benchmarks.workload` on two copies of a
map, one without subscribers and one with an every-REASON subscriber whose
callback serialises the event as the topic does (:func:`topostore.events.event_json`),
and prints the median and p95 step latency of each as JSON.
"""

from __future__ import annotations

import argparse
import json
import statistics
import tempfile
from pathlib import Path

from topostore import Ontology
from topostore.events import event_json
from topostore.resources import default_ontology

from .workload import Robot, map_file, percentile


def steps(size: str, n: int, follow: bool) -> list[float]:
    """Latencies of ``n`` robot steps on a fresh ontology of ``size``, followed or not."""
    with tempfile.TemporaryDirectory() as tmp:
        path, m, _ = map_file(size, Path(tmp))
        onto = Ontology.from_file(default_ontology(), path)
        onto.reason()
        sent: list[int] = []
        if follow:
            onto.events.subscribe(lambda e: sent.append(len(event_json(e, onto.prefix, "ref"))), None, 100,
                                  every_reason=True)
        robot = Robot(onto, m)
        return [robot.step("incremental")[0] for _ in range(n)]


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--sizes", nargs="+", default=["seed", "100", "1000"])
    parser.add_argument("--steps", type=int, default=50)
    args = parser.parse_args(argv)
    rows = []
    for size in args.sizes:
        row: dict = {"size": size}
        for follow in (False, True):
            t = steps(size, args.steps, follow)
            key = "followed" if follow else "alone"
            row[key] = {"median_ms": round(statistics.median(t) * 1000, 3),
                        "p95_ms": round(percentile(t, 0.95) * 1000, 3)}
        rows.append(row)
        print(json.dumps(row), flush=True)


if __name__ == "__main__":
    main()
