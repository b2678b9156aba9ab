"""One large map, topostore only: ``python -m benchmarks.scale SIZE [--steps N] [--budget S]`` prints JSON.

Run in a process of its own so that the peak RSS is this size's.  Measures LOAD (parse + the first,
full REASON) through ArmorService (what the map's making left for the cycle collector collected first, as
a fresh service loading a file has none of it: at 100,000 locations it cost the timed LOAD a full
collection and more), robot steps until ``steps`` are done or ``budget`` seconds have
passed since the start (never fewer than ``min_steps``), then one ``reason(mode="full")`` (with
``--full-if-room``: only when the budget still has room for it, the first REASON's time being the
estimate).  Every answer is checked
against the expected answers of :mod:`benchmarks.walk`.  Run as a program, the REASON time limit
is lifted (:mod:`benchmarks.limits`): the budget and the suite's timeout bound the run instead.
"""

from __future__ import annotations

import argparse
import gc
import json
import sys
import tempfile
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

from pyoxigraph import RdfFormat

from . import maps
from .armor_robot import ArmorRobot
from .limits import lift_time_limit
from .timing import median, p95, peak_rss_mib
from .walk import expected, plan


def run(size: str, steps: int, budget_s: float, work: Path, min_steps: int = 5, always_full: bool = True,
        progress: Callable[[dict[str, Any]], None] = lambda row: None) -> dict[str, Any]:
    """Measure one size; times in ms except ``load_first_s`` and ``full_s``.

    ``always_full``: run the full REASON whatever the budget says (else only when it fits).
    ``progress`` gets the row after the load and after every step, so that a run killed from
    outside still tells how far it got.
    """
    start = time.perf_counter()
    path, bench = maps.write(size, work, RdfFormat.N_TRIPLES)
    moves = plan(bench, steps)
    truth = expected(bench, moves)
    row: dict[str, Any] = {"kind": "scale", "size": size, "label": bench.label, "locations": bench.locations,
                           "doors": bench.doors, "triples": bench.triples, "mismatches": []}
    progress({**row, "doing": "load + first REASON"})
    gc.collect()  # the map's making left garbage a fresh service has not: not the LOAD's to collect
    robot = ArmorRobot(path)
    row["load_first_s"] = robot.load_s
    check(row, "after the load", robot.answers(), truth[0])
    times: list[float] = []
    row.update(step_ms=times, doing="steps")
    progress(row)
    for k, move in enumerate(moves, 1):
        last = times[-1] / 1000 if times else 0.0
        if k > min_steps and time.perf_counter() - start + last > budget_s:
            row["stopped"] = f"time budget of {budget_s:.0f} s"
            break
        seconds, answers = robot.step(move)
        times.append(seconds * 1000)
        check(row, f"after step {k}", answers, truth[k])
        row.update(median_ms=median(times), p95_ms=p95(times), peak_rss_mib=peak_rss_mib())
        progress(row)
    row.update(median_ms=median(times), p95_ms=p95(times), full_s=None, doing="full REASON")
    if always_full or time.perf_counter() - start + robot.load_s <= budget_s:
        progress(row)
        began = time.perf_counter()
        robot.ontology.reason(mode="full")
        row["full_s"] = time.perf_counter() - began
        check(row, "after the full REASON", robot.answers(), truth[len(times)])
    else:
        row["full_skipped"] = f"no room in the time budget of {budget_s:.0f} s"
    row["peak_rss_mib"] = peak_rss_mib()
    row["wall_s"] = time.perf_counter() - start
    del row["doing"]
    return row


def check(row: dict[str, Any], when: str, got: Any, want: Any) -> None:
    if diff := got.differences(want):
        row["mismatches"].append(f"{when}: topostore vs expected: {diff}")


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("size", help="an even number of locations")
    parser.add_argument("--steps", type=int, default=20)
    parser.add_argument("--budget", type=float, default=600.0, help="seconds for this size (default 600)")
    parser.add_argument("--full-if-room", action="store_true", help="skip the full REASON when out of budget")
    args = parser.parse_args(argv)
    lift_time_limit()  # the first REASON of 100,000 locations takes minutes: measure it, do not refuse it
    with tempfile.TemporaryDirectory(prefix="topostore-bench-") as tmp:
        row = run(args.size, args.steps, args.budget, Path(tmp), always_full=not args.full_if_room,
                  progress=lambda r: print(json.dumps(r), flush=True))
    print(json.dumps(row))
    sys.exit(3 if row["mismatches"] else 0)


if __name__ == "__main__":
    main()
