"""Run the benchmark suite: ``python -m benchmarks [--quick] [--sizes ...] [--steps N] [--out DIR]``."""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import time
from pathlib import Path

from .peers import PEERS, measure
from .report import machine, write_csv, write_plot, table

FULL_SIZES = ["seed", "10", "100", "1000", "10000", "100000"]
QUICK_SIZES = ["seed", "10", "100", "1000", "10000"]


def full_steps_for(size: str, steps: int, quick: bool) -> int:
    """Full-rematerialisation steps: as many as incremental ones on small maps; on large
    ones, where each takes seconds, 5 (2 in quick mode, from 1,000 locations on)."""
    limit = 100 if quick else 1000
    return steps if size == "seed" or int(size) <= limit else min(steps, 2 if quick else 5)


def steps_for(size: str, steps: int, quick: bool) -> int:
    """Incremental steps: all of them, except 20 at 10,000 locations and more in quick mode
    (CI's time budget), which still gives a median and a p95."""
    return min(steps, 20) if quick and size != "seed" and int(size) >= 10000 else steps


def run_size(size: str, steps: int, verify: bool, quick: bool) -> dict:
    """One size in a fresh interpreter, so that its peak RSS is its own."""
    cmd = [sys.executable, "-m", "benchmarks.workload", size, "--steps", str(steps_for(size, steps, quick)),
           "--full-steps", str(full_steps_for(size, steps, quick))]
    if not verify:
        cmd.append("--no-verify")
    done = subprocess.run(cmd, capture_output=True, text=True)
    if done.returncode != 0:
        raise SystemExit(f"benchmark of size {size} failed:\n{done.stderr}")
    return json.loads(done.stdout.strip().splitlines()[-1])


def parse_args(argv: list[str] | None) -> argparse.Namespace:
    parser = argparse.ArgumentParser(prog="python -m benchmarks", description=__doc__)
    parser.add_argument("--quick", action="store_true", help=f"sizes {', '.join(QUICK_SIZES)} only")
    parser.add_argument("--sizes", nargs="+", help="map sizes in locations ('seed' = the shipped example map)")
    parser.add_argument("--steps", type=int, default=50, help="robot steps per size (default 50)")
    parser.add_argument("--out", type=Path, default=Path("out/bench"), help="output folder (default out/bench)")
    parser.add_argument("--peer-timeout", type=float, help="seconds per peer run (default 60, 30 with --quick)")
    parser.add_argument("--no-peers", action="store_true", help="measure topostore only")
    parser.add_argument("--no-verify", action="store_true", help="skip comparing with a full rematerialisation")
    return parser.parse_args(argv)


def main(argv: list[str] | None = None) -> None:
    args = parse_args(argv)
    sizes = args.sizes or (QUICK_SIZES if args.quick else FULL_SIZES)
    args.out.mkdir(parents=True, exist_ok=True)
    info = machine()
    print(" | ".join(f"{k}: {v}" for k, v in info.items()), flush=True)
    rows: list[dict] = []
    given_up: dict[str, str] = {}  # a peer that timed out is not tried on larger maps
    for size in sizes:
        start = time.perf_counter()
        row = run_size(size, args.steps, not args.no_verify, args.quick)
        for peer in () if args.no_peers else PEERS:
            row[peer] = {"status": "skipped", "why": given_up[peer]} if peer in given_up else \
                measure(peer, size, args.peer_timeout or (30.0 if args.quick else 60.0))
            if row[peer]["status"] == "timeout":
                given_up[peer] = f"timed out on {size} locations"
        rows.append(row)
        print(f"size {size}: done in {time.perf_counter() - start:.0f} s", flush=True)
    text = table(rows, info)
    print(text)
    (args.out / "results.json").write_text(json.dumps({"machine": info, "rows": rows}, indent=2))
    (args.out / "table.md").write_text(text + "\n")
    write_csv(rows, args.out / "bench.csv")
    plot = write_plot(rows, args.out / "bench.png")
    print(f"wrote {args.out / 'bench.csv'}, {args.out / 'table.md'}, {args.out / 'results.json'}"
          + (f", {plot}" if plot else " (no plot: matplotlib missing)"))


if __name__ == "__main__":
    main()
