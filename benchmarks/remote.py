"""The robot step on a SPARQL server: ``python -m benchmarks.remote SIZE [--steps N]`` prints JSON.

Starts a real ``oxigraph serve`` on a free loopback port (as :mod:`benchmarks.stores` does), LOADs
the map into a reference kept on it (``ArmorService(store=URL)``), walks the planned moves with the
same aRMOR commands as :mod:`benchmarks.compare` and checks every answer.  The HTTP requests are
counted at the transport (:mod:`benchmarks.http_count`), not read from the store: per step (the
median and the most over the counted steps, issue 20's target is <= 3 on the example map), for the
LOAD, by endpoint for the last step, and by command (the median over the counted steps: which
command sends what).
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

from . import maps
from .armor_robot import ArmorRobot
from .http_count import counting
from .stores import oxigraph_server
from .timing import counted, median, p95
from .walk import expected, plan


def run(size: str, steps: int, work: Path) -> dict[str, Any]:
    """LOAD and ``steps`` steps of ``size`` on a fresh ``oxigraph serve``; requests and times."""
    path, bench = maps.write(size, work)
    moves = plan(bench, steps)
    truth = expected(bench, moves)
    row: dict[str, Any] = {"kind": "remote", "size": size, "label": bench.label, "locations": bench.locations,
                           "store": "oxigraph serve", "mismatches": []}
    by_command: dict[str, list[int]] = {}
    with oxigraph_server() as url, counting() as http:
        mark = [0]

        def observe(command: str) -> None:
            by_command.setdefault(command, []).append(http.total - mark[0])
            mark[0] = http.total

        robot = ArmorRobot(path, store=url, observe=observe)
        row["load_requests"] = http.total
        by_command.clear()
        per_step: list[int] = []
        times: list[float] = []
        try:
            for k, move in enumerate(moves, 1):
                before, endpoints = http.total, dict(http.by_endpoint)
                mark[0] = before
                seconds, answers = robot.step(move)
                per_step.append(http.total - before)
                times.append(seconds * 1000)
                if diff := answers.differences(truth[k]):
                    row["mismatches"].append(f"after step {k}: topostore vs expected: {diff}")
            last = {key: n - endpoints.get(key, 0) for key, n in http.by_endpoint.items() if n != endpoints.get(key, 0)}
        finally:
            robot.close()
    kept = counted([float(n) for n in per_step])
    row.update(requests_per_step=per_step, requests_median=statistics.median(kept) if kept else None,
               requests_max=max(kept) if kept else None, last_step_requests=last if moves else {},
               requests_by_command={c: statistics.median(counted([float(n) for n in ns]) or ns)
                                    for c, ns in by_command.items()},
               step_ms=times, median_ms=median(times), p95_ms=p95(times))
    return row


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("size", nargs="?", default=maps.EXAMPLE, help=f"'{maps.EXAMPLE}' or an even number")
    parser.add_argument("--steps", type=int, default=20)
    args = parser.parse_args(argv)
    start = time.perf_counter()
    with tempfile.TemporaryDirectory(prefix="topostore-bench-") as tmp:
        row = run(args.size, args.steps, Path(tmp))
    row["wall_s"] = time.perf_counter() - start
    print(json.dumps(row))
    sys.exit(3 if row["mismatches"] else 0)


if __name__ == "__main__":
    main()
