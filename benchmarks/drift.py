"""Step latency over a long walk: ``python -m benchmarks.drift SIZE [--steps 4000]`` prints JSON.

Removed quads stay in the store until it is compacted, so a step can get slower the longer a robot
runs.  This walks ``steps`` moves on one map (aRMOR commands through ``ArmorService.call``, the
same step as :mod:`benchmarks.compare`), checks every answer, and reports the step median over
steps 10-100 and over the last 100 (3,900-4,000 by default), their ratio (the drift; issue 20's
target is <= 1.5) and the longest step seen: a compaction, or any other pause, shows up there.
"""

from __future__ import annotations

import argparse
import json
import statistics
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

from pyoxigraph import RdfFormat

from . import maps
from .armor_robot import ArmorRobot
from .timing import peak_rss_mib
from .walk import expected, plan

#: steps 10 to 100 (1-based) are the early window; the last 100 steps the late one
EARLY = slice(9, 100)
LATE = 100


def windows(times: list[float]) -> tuple[float | None, float | None]:
    """Median step of the early window (steps 10-100) and of the last 100 steps, in the unit given."""
    early, late = times[EARLY], times[-LATE:]
    return (statistics.median(early) if early else None, statistics.median(late) if late else None)


def longest(times: list[float]) -> tuple[float | None, int | None]:
    """The longest step and its number (1-based)."""
    if not times:
        return None, None
    k = max(range(len(times)), key=times.__getitem__)
    return times[k], k + 1


def run(size: str, steps: int, work: Path) -> dict[str, Any]:
    """Walk ``steps`` moves on ``size``; every step's time (ms) and the summary figures."""
    fmt = RdfFormat.RDF_XML if size == maps.EXAMPLE else RdfFormat.N_TRIPLES
    path, bench = maps.write(size, work, fmt)
    moves = plan(bench, steps)
    truth = expected(bench, moves)
    row: dict[str, Any] = {"kind": "drift", "size": size, "label": bench.label, "locations": bench.locations,
                           "steps": steps, "mismatches": []}
    robot = ArmorRobot(path)
    times: list[float] = []
    start = time.perf_counter()
    for k, move in enumerate(moves, 1):
        seconds, answers = robot.step(move)
        times.append(seconds * 1000)
        if diff := answers.differences(truth[k]):
            row["mismatches"].append(f"after step {k}: topostore vs expected: {diff}")
    early, late = windows(times)
    pause, at = longest(times)
    row.update(early_ms=early, late_ms=late, drift=late / early if early and late else None, longest_ms=pause,
               longest_step=at, walk_s=time.perf_counter() - start, peak_rss_mib=peak_rss_mib(), step_ms=times)
    return row


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("size", help=f"'{maps.EXAMPLE}' or an even number of locations")
    parser.add_argument("--steps", type=int, default=4000)
    args = parser.parse_args(argv)
    with tempfile.TemporaryDirectory(prefix="topostore-bench-") as tmp:
        row = run(args.size, args.steps, Path(tmp))
    print(json.dumps(row))
    sys.exit(3 if row["mismatches"] else 0)


if __name__ == "__main__":
    main()
