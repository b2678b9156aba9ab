"""One value rewritten many times with no REASON between: ``python -m benchmarks.rewrites [MAP] [--writes N]``.

A robot's clock written at every tick while the ontology is reasoned only now and then (a buffered reasoner,
or a client that asks for REASON rarely): every REPLACE removes a quad the in-memory store keeps until it is
compacted, and every look-up of the rewritten pair walks the removed versions.  This sends ``writes``
REPLACEs of the robot's ``now`` through ``ArmorService.call`` on a reference with a buffered reasoner and
prints the median REPLACE (CPU µs) of each block of 1,000, first and last beside each other: the ratio
stays near 1 while the store is compacted between changes, and grows with the writes when it is not.
"""

from __future__ import annotations

import argparse
import statistics
import tempfile
import time
from pathlib import Path

from . import maps
from .armor_robot import ArmorRobot
from .limits import lift_time_limit
from .maps import ROBOT
from .report import machine

BLOCK = 1000


def run(size: str, writes: int) -> list[float]:
    """The median REPLACE (µs of CPU) of each block of :data:`BLOCK` REPLACEs."""
    path, _ = maps.write(size, Path(tempfile.mkdtemp()))
    robot = ArmorRobot(path)  # loaded as the bench's step loads it: a buffered reasoner
    old = robot._call("QUERY", "DATAPROP", "IND", ["now", ROBOT]).queried_objects[0].split('"')[1]
    medians: list[float] = []
    clock = time.process_time_ns
    for _ in range(writes // BLOCK):
        times = []
        for _ in range(BLOCK):
            new = str(int(old) + 1)
            start = clock()
            robot._call("REPLACE", "DATAPROP", "IND", ["now", ROBOT, "LONG", new, old])
            times.append((clock() - start) / 1000)
            old = new
        medians.append(statistics.median(times))
    return medians


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("size", nargs="?", default=maps.EXAMPLE, help="map: example or a number of locations")
    parser.add_argument("--writes", type=int, default=10_000, help="REPLACEs sent (in blocks of 1,000)")
    args = parser.parse_args()
    lift_time_limit()
    for key, value in machine().items():
        print(f"{key}: {value}")
    medians = run(args.size, args.writes)
    print("\n| map | REPLACEs | first block (µs) | last block (µs) | last / first |\n|---|---|---|---|---|")
    print(f"| {args.size} | {args.writes:,} | {medians[0]:.1f} | {medians[-1]:.1f} | {medians[-1] / medians[0]:.2f} |")
    print("\nblock medians (µs):", " ".join(f"{m:.0f}" for m in medians))


if __name__ == "__main__":
    main()
