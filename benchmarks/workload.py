"""One benchmark size, run in its own process: ``python -m benchmarks.workload SIZE ...`` prints JSON.

A *robot step* is what a patrolling robot does per move: REPLACE isIn (to a
neighbour of where it is), REPLACE now (a few seconds later), REPLACE
visitedAt of the new location, REASON, then ask where it can go (canReach) and
which locations are URGENT.
"""

from __future__ import annotations

import argparse
import json
import random
import resource
import statistics
import sys
import tempfile
import time
from dataclasses import asdict, dataclass, field
from pathlib import Path

from pyoxigraph import NamedNode, RdfFormat

from topostore import Ontology
from topostore.mapgen import MAP_NS, TopoMap, generate
from topostore.resources import default_ontology, ontology_dir
from topostore.store import serialize
from topostore.vocab import ASSERTED, INFERRED

#: the map the project ships as its example (three locations, one robot)
SEED = "seed"
ROBOT = NamedNode(MAP_NS + "Robot1")


def N(name: str) -> NamedNode:
    return NamedNode(MAP_NS + name)


@dataclass
class SizeResult:
    """Everything measured for one map size (times in seconds unless the name says ms)."""

    size: str
    locations: int
    asserted: int = 0
    inferred: int = 0
    load_s: float = 0.0
    full_reason_s: float = 0.0
    rss_after_reason_mib: float = 0.0
    rss_peak_mib: float = 0.0
    consistent: bool = True
    inc_steps: int = 0
    inc_median_ms: float = 0.0
    inc_p95_ms: float = 0.0
    inc_fallbacks: int = 0
    full_steps: int = 0
    full_median_ms: float = 0.0
    full_p95_ms: float = 0.0
    verified: str = ""
    profile_top: list = field(default_factory=list)


def rss_mib() -> float:
    """Peak resident set size of this process so far (Linux reports KiB)."""
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024


def percentile(values: list[float], q: float) -> float:
    ordered = sorted(values)
    k = min(len(ordered) - 1, max(0, round(q * (len(ordered) - 1))))
    return ordered[k]


def map_file(size: str, folder: Path) -> tuple[Path, TopoMap | None, int]:
    """The ABox to load: the shipped example map, or a generated one written as N-Triples."""
    if size == SEED:
        return ontology_dir() / "topological_map_abox.ttl", None, 3
    m = generate(int(size))
    path = folder / f"map-{size}.nt"
    path.write_bytes(serialize(m.triples(), RdfFormat.N_TRIPLES))
    return path, m, len(m.locations)


class Robot:
    """Drives one robot around the map: each step moves it to a neighbour of where it is."""

    def __init__(self, onto: Ontology, m: TopoMap | None, seed: int = 7) -> None:
        self.onto = onto
        self.rng = random.Random(seed)
        self.neighbours = self._neighbours(m)
        self.where = self.onto.object_values("isIn", ROBOT)[0]
        self.now = int(self.onto.data_values("now", ROBOT)[0].value)

    def _neighbours(self, m: TopoMap | None) -> dict[str, list[str]]:
        if m is not None:
            return {loc: sorted(m.neighbours(loc)) for loc in m.locations}
        return {"C1": ["R1", "R2"], "R1": ["C1"], "R2": ["C1"]}

    def step(self, mode: str) -> tuple[float, str]:
        """One robot step; returns its latency in seconds and the REASON mode used."""
        self.where = self.rng.choice(self.neighbours[self.where] or [self.where])
        self.now += self.rng.randint(1, 5)
        start = time.perf_counter()
        self.onto.replace(ROBOT, N("isIn"), N(self.where))
        self.onto.replace(ROBOT, N("now"), self.now)
        self.onto.replace(N(self.where), N("visitedAt"), self.now)
        report = self.onto.reason(mode=mode)
        reachable = self.onto.object_values("canReach", ROBOT)
        urgent = self.onto.instances("URGENT")
        elapsed = time.perf_counter() - start
        if not report.consistent or not reachable and self.neighbours[self.where]:
            raise AssertionError(f"unexpected state after a step: {report.explain()}, canReach {reachable}")
        del urgent
        return elapsed, report.stats.mode


def run(size: str, steps: int, full_steps: int, verify: bool) -> SizeResult:
    with tempfile.TemporaryDirectory() as tmp:
        path, m, n_locations = map_file(size, Path(tmp))
        result = SizeResult(size, n_locations)
        start = time.perf_counter()
        onto = Ontology.from_file(default_ontology(), path)
        result.load_s = time.perf_counter() - start
    start = time.perf_counter()
    report = onto.reason()
    result.full_reason_s = time.perf_counter() - start
    result.rss_after_reason_mib = rss_mib()
    result.consistent = report.consistent
    result.asserted = onto.store.count(ASSERTED)
    result.inferred = onto.store.count(INFERRED)
    robot = Robot(onto, m)
    robot.step("auto")  # warm-up: compiles the incremental update texts
    latencies, modes = [], []
    for _ in range(steps):
        elapsed, mode = robot.step("auto")
        latencies.append(elapsed)
        modes.append(mode)
    result.inc_steps = steps
    result.inc_median_ms = statistics.median(latencies) * 1000
    result.inc_p95_ms = percentile(latencies, 0.95) * 1000
    result.inc_fallbacks = sum(1 for mode in modes if mode != "incremental")
    profiled = onto
    robot_step_profile(robot, profiled, result)
    if verify:
        result.verified = verify_against_full(onto)
    full = [robot.step("full")[0] for _ in range(full_steps)]
    result.full_steps = full_steps
    if full:  # none when asked for (--full-steps 0: each one costs a full REASON)
        result.full_median_ms = statistics.median(full) * 1000
        result.full_p95_ms = percentile(full, 0.95) * 1000
    result.rss_peak_mib = rss_mib()
    return result


def robot_step_profile(robot: Robot, onto: Ontology, result: SizeResult) -> None:
    """Where the time of one incremental step goes (the five costliest updates)."""
    robot.where = robot.rng.choice(robot.neighbours[robot.where] or [robot.where])
    robot.now += 1
    onto.replace(ROBOT, N("isIn"), N(robot.where))
    onto.replace(ROBOT, N("now"), robot.now)
    onto.replace(N(robot.where), N("visitedAt"), robot.now)
    stats = onto.reason(profile=True).stats
    top = sorted(stats.per_rule.items(), key=lambda kv: -kv[1])[:5]
    result.profile_top = [(name, round(seconds * 1000, 2)) for name, seconds in top]


def verify_against_full(onto: Ontology) -> str:
    """Compare the incrementally maintained graph with a full rematerialisation of the same data."""
    before = set(onto.store.triples(graph=INFERRED))
    onto.reason(mode="full")
    after = set(onto.store.triples(graph=INFERRED))
    return "identical" if before == after else f"DIFFERENT ({len(before ^ after)} triples)"


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("size", help="number of locations, or 'seed' for the shipped example map")
    parser.add_argument("--steps", type=int, default=50)
    parser.add_argument("--full-steps", type=int, default=50)
    parser.add_argument("--no-verify", action="store_true")
    args = parser.parse_args(argv)
    result = run(args.size, args.steps, args.full_steps, not args.no_verify)
    json.dump(asdict(result), sys.stdout)


if __name__ == "__main__":
    main()
