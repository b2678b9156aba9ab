"""One map, topostore against warm Pellet: ``python -m benchmarks.compare SIZE --classes DIR`` prints JSON.

Both reasoners get the same file and the same planned moves (:mod:`benchmarks.walk`).  Pellet
runs first, in its own JVM, warmed on a scratch copy of the map (:mod:`benchmarks.warm_pellet`),
until its steps are done or its time budget is spent (never fewer than ``min_steps``); topostore
then runs every step in this process.  After the load and after
every step both answers are compared with each other and with the expected answers: any
difference is listed in ``mismatches``, which the suite reports loudly and fails on.
"""

from __future__ import annotations

import argparse
import json
import statistics
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from topostore.demo.mapgen import MAP_NS

from . import maps
from .armor_robot import ArmorRobot
from .timing import median, p95, peak_rss_mib
from .walk import Answers, Move, expected, plan
from .warm_pellet import WARM_STEPS, PeerError, WarmPellet, unavailable


@dataclass
class Limits:
    """How long each side may take on one map."""

    steps: int = 20
    pellet_budget_s: float = 45.0  # Pellet's steps stop once the next one would exceed this
    min_steps: int = 4  # ... but not before this many (so that step 4, the first counted, is there)
    ready_timeout_s: float = 300.0  # Pellet's load + first REASON
    step_timeout_s: float = 120.0  # one Pellet step
    pellet_warmup_s: float = 20.0  # the JVM walks a scratch copy of the map this long before the load


def run(size: str, classes: Path | None, limits: Limits, work: Path) -> dict[str, Any]:
    """Measure one map; ``classes`` is the compiled peer (None: Pellet not run)."""
    path, bench = maps.write(size, work)
    moves = plan(bench, limits.steps)
    truth = expected(bench, moves)
    row: dict[str, Any] = {"kind": "compare", "size": size, "label": bench.label, "locations": bench.locations,
                           "doors": bench.doors, "triples": bench.triples}
    pellet_answers: list[Answers] = []
    if classes is None:
        row["pellet"] = {"status": "skipped", "why": unavailable() or "not asked for (--no-pellet)"}
    else:
        warmup = plan(bench, WARM_STEPS) if limits.pellet_warmup_s > 0 else []
        row["pellet"] = run_pellet(classes, path, moves, limits, work, pellet_answers, warmup)
    topo_answers: list[Answers] = []
    row["topostore"] = run_topostore(path, moves, topo_answers)
    row["mismatches"] = mismatches(truth, topo_answers, pellet_answers)
    row["compared_steps"] = max(0, len(pellet_answers) - 1)
    return row


def run_pellet(classes: Path, path: Path, moves: list[Move], limits: Limits, work: Path,
               answers: list[Answers], warmup: list[Move] | None = None) -> dict[str, Any]:
    """Pellet's warm-up (on a scratch copy), load, first REASON and steps; answers go to ``answers``."""
    out: dict[str, Any] = {"status": "ok", "step_ms": []}
    try:
        with WarmPellet(classes, path, MAP_NS, work / "pellet.log", limits.ready_timeout_s, warmup,
                        limits.pellet_warmup_s) as peer:
            out.update(load_ms=peer.ready["load_ms"], first_ms=peer.ready["first_ms"], java=peer.ready["java"])
            out.update(warmup_summary(peer.ready))
            answers.append(_answers(peer.ready))
            spent = 0.0
            for k, move in enumerate(moves, 1):
                last = out["step_ms"][-1] / 1000 if out["step_ms"] else 0.0
                if k > limits.min_steps and spent + last > limits.pellet_budget_s:
                    out["stopped"] = f"time budget of {limits.pellet_budget_s:.0f} s"
                    break
                reply = peer.step(move, limits.step_timeout_s)
                out["step_ms"].append(reply["ms"])
                answers.append(_answers(reply))
                spent += reply["ms"] / 1000
    except PeerError as exc:
        out["status"] = "timeout" if str(exc).startswith("timeout") else "error"
        out["why"] = str(exc)
    out["median_ms"], out["p95_ms"] = median(out["step_ms"]), p95(out["step_ms"])
    return out


def warmup_summary(ready: dict[str, Any]) -> dict[str, Any]:
    """The warm-up's extent and the JIT's curve: step medians of its first and last 20 steps."""
    times = ready.get("warm_step_ms") or []
    return {"warm_steps": len(times), "warm_s": ready.get("warm_ms", 0.0) / 1000,
            "warm_first_ms": statistics.median(times[:20]) if times else None,
            "warm_last_ms": statistics.median(times[-20:]) if times else None}


def run_topostore(path: Path, moves: list[Move], answers: list[Answers]) -> dict[str, Any]:
    """topostore's LOAD (with its first REASON) and every step, through ArmorService.call."""
    robot = ArmorRobot(path)
    answers.append(robot.answers())
    times = []
    for move in moves:
        seconds, reply = robot.step(move)
        times.append(seconds * 1000)
        answers.append(reply)
    return {"status": "ok", "load_first_ms": robot.load_s * 1000, "step_ms": times, "median_ms": median(times),
            "p95_ms": p95(times), "peak_rss_mib": peak_rss_mib()}


def mismatches(truth: list[Answers], topo: list[Answers], pellet: list[Answers]) -> list[str]:
    """Every step where topostore, Pellet (as far as it went) and the expected answers disagree."""
    out = []
    for k, want in enumerate(truth):
        when = "after the load" if k == 0 else f"after step {k}"
        if k < len(topo) and (diff := topo[k].differences(want)):
            out.append(f"{when}: topostore vs expected: {diff}")
        if k < len(pellet) and k < len(topo) and (diff := topo[k].differences(pellet[k])):
            out.append(f"{when}: topostore vs Pellet: {diff}")
        if k < len(pellet) and (diff := pellet[k].differences(want)):
            out.append(f"{when}: Pellet vs expected: {diff}")
    return out


def _answers(reply: dict[str, Any]) -> Answers:
    return Answers(tuple(reply["canReach"]), tuple(reply["urgent"]))


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("size", help=f"'{maps.EXAMPLE}' or an even number of locations")
    parser.add_argument("--classes", type=Path, help="the compiled peer (benchmarks.warm_pellet.compile_peer)")
    parser.add_argument("--steps", type=int, default=Limits.steps)
    parser.add_argument("--pellet-budget", type=float, default=Limits.pellet_budget_s)
    parser.add_argument("--pellet-warmup", type=float, default=Limits.pellet_warmup_s,
                        help="seconds the JVM walks a scratch copy of the map first (0: none)")
    args = parser.parse_args(argv)
    limits = Limits(steps=args.steps, pellet_budget_s=args.pellet_budget, pellet_warmup_s=args.pellet_warmup)
    start = time.perf_counter()
    with tempfile.TemporaryDirectory(prefix="topostore-bench-") as tmp:
        row = run(args.size, args.classes, limits, Path(tmp))
    row["wall_s"] = time.perf_counter() - start
    print(json.dumps(row))
    sys.exit(3 if row["mismatches"] else 0)


if __name__ == "__main__":
    main()
