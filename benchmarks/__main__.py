"""Run the benchmark suite: ``python -m benchmarks [--quick] [--skip-100k] [--no-pellet] [...]``.

Every map size runs in a fresh process of its own (its peak RSS is its own; a size that hangs is
killed without taking the run with it).  The warm Pellet peer is compiled once per run into a
temporary folder.  Prints the machine, the table, the ratios and the targets, and writes
``table.md``, ``bench.csv``, ``results.json`` and ``bench.png`` to ``--out``.  Exits 1 when any
answer differed or a size failed.
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

from .report import machine, table, write_csv, write_plot
from .warm_pellet import PeerError, compile_peer

COMPARE = ["example", "8", "50", "200", "500"]
SCALE = ["1000", "10000", "100000"]
#: seconds each topostore-only size may use: steps stop (never before 5) to stay in it; above 10,000
#: locations the full REASON is left out too when there is no room for it
SCALE_BUDGET = {"1000": 90.0, "10000": 200.0, "100000": 420.0}
QUICK_COMPARE, QUICK_SCALE = ["example", "8", "50", "200"], ["1000", "10000"]
QUICK_SCALE_BUDGET = {"1000": 45.0, "10000": 90.0}


def parse_args(argv: list[str] | None) -> argparse.Namespace:
    p = argparse.ArgumentParser(prog="python -m benchmarks", description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--quick", action="store_true",
                   help=f"maps {', '.join(QUICK_COMPARE)} against Pellet (20 s of Pellet steps each), "
                        f"topostore alone at {', '.join(QUICK_SCALE)}, 10 steps: a few minutes")
    p.add_argument("--sizes", nargs="*", help=f"maps compared with Pellet (default {' '.join(COMPARE)})")
    p.add_argument("--scale-sizes", nargs="*", help=f"topostore-only maps (default {' '.join(SCALE)})")
    p.add_argument("--skip-100k", action="store_true", help="leave out the 100,000-location map")
    p.add_argument("--steps", type=int, help="robot steps per map (default 20, 10 with --quick); "
                                             "medians are over steps 4 to the last")
    p.add_argument("--pellet-budget", type=float,
                   help="seconds of Pellet steps per map before it stops (at least 4 steps; default 45, 20 with --quick)")
    p.add_argument("--no-pellet", action="store_true", help="measure topostore only")
    p.add_argument("--out", type=Path, default=Path("out/bench"), help="output folder (default out/bench)")
    args = p.parse_args(argv)
    args.sizes = args.sizes if args.sizes is not None else QUICK_COMPARE if args.quick else COMPARE
    args.scale_sizes = args.scale_sizes if args.scale_sizes is not None else QUICK_SCALE if args.quick else SCALE
    if args.skip_100k:
        args.scale_sizes = [s for s in args.scale_sizes if s != "100000"]
    args.steps = args.steps or (10 if args.quick else 20)
    args.pellet_budget = args.pellet_budget or (20.0 if args.quick else 45.0)
    args.budgets = QUICK_SCALE_BUDGET if args.quick else SCALE_BUDGET
    return args


def run_size(cmd: list[str], timeout: float, size: str, kind: str) -> dict[str, Any]:
    """One size in its own interpreter; its JSON row, or a row saying why there is none."""
    try:
        done = subprocess.run([sys.executable, "-m", *cmd], capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired as exc:
        return _killed(kind, size, timeout, exc.stdout)
    lines = done.stdout.strip().splitlines()
    if not lines or not lines[-1].startswith("{"):
        return _failed(kind, size, f"exit {done.returncode}: {done.stderr.strip()[-800:]}")
    return json.loads(lines[-1])


def _killed(kind: str, size: str, timeout: float, stdout: str | bytes | None) -> dict[str, Any]:
    """A size that ran out of time: the last progress row it printed (scale runs print them), marked."""
    text = stdout.decode(errors="replace") if isinstance(stdout, bytes) else stdout or ""
    rows = [line for line in text.strip().splitlines() if line.startswith("{")]
    if not rows:
        return {**_failed(kind, size, ""), "error": None, "killed": f"killed after {timeout:.0f} s"}
    row = json.loads(rows[-1])
    row["killed"] = f"killed after {timeout:.0f} s, during {row.pop('doing', 'the run')}"
    return row


def _failed(kind: str, size: str, why: str) -> dict[str, Any]:
    return {"kind": kind, "size": size, "label": size, "locations": 0 if not size.isdigit() else int(size),
            "doors": 0, "triples": 0, "error": why, "mismatches": [], "topostore": {}}


def progress(row: dict[str, Any], seconds: float) -> str:
    topo = row.get("topostore") if row["kind"] == "compare" else row
    pellet = row.get("pellet", {})
    bits = [f"{row['label']}: {seconds:.0f} s", f"topostore step median {_ms(topo.get('median_ms'))}"]
    if row["kind"] == "compare":
        bits.append(f"Pellet {_ms(pellet.get('median_ms'))} ({pellet.get('status', 'not run')})")
    if row.get("error"):
        bits.append(f"FAILED: {row['error']}")
    if row.get("killed"):
        bits.append(row["killed"])
    if row.get("mismatches"):
        bits.append(f"ANSWERS DIFFER ({len(row['mismatches'])}): {row['mismatches'][0]}")
    return ", ".join(bits)


def _ms(x: float | None) -> str:
    return "–" if x is None else f"{x:.1f} ms"


def main(argv: list[str] | None = None) -> None:
    args = parse_args(argv)
    args.out.mkdir(parents=True, exist_ok=True)
    info = machine()
    print("Machine: " + ", ".join(f"{k} {v}" for k, v in info.items()), flush=True)
    rows: list[dict[str, Any]] = []
    with tempfile.TemporaryDirectory(prefix="topostore-bench-") as tmp:
        classes = None
        if not args.no_pellet:
            try:
                classes = compile_peer(Path(tmp) / "classes")
            except PeerError as exc:
                print(f"warm Pellet not run: {exc}", flush=True)
        for size in args.sizes:
            cmd = ["benchmarks.compare", size, "--steps", str(args.steps), "--pellet-budget", str(args.pellet_budget)]
            cmd += ["--classes", str(classes)] if classes else []
            # Pellet: load + first REASON (<= 300 s), its budget plus one slow step (<= 120 s); topostore after it
            rows.append(_timed(cmd, 300 + args.pellet_budget + 120 + 300, size, "compare"))
        for size in args.scale_sizes:
            budget = args.budgets.get(size, 300.0)
            cmd = ["benchmarks.scale", size, "--steps", str(args.steps), "--budget", str(budget)]
            cmd += ["--full-if-room"] if int(size) > 10000 else []  # up to 10,000 the full/step ratio is a target
            rows.append(_timed(cmd, budget + 300, size, "scale"))  # killed then, keeping its progress
    text = table(rows, info)
    print("\n" + text)
    (args.out / "table.md").write_text(text + "\n")
    (args.out / "results.json").write_text(json.dumps({"machine": info, "rows": rows}, indent=1))
    write_csv(rows, args.out / "bench.csv")
    plot = write_plot(rows, args.out / "bench.png")
    print(f"\nwrote {args.out / 'table.md'}, {args.out / 'bench.csv'}, {args.out / 'results.json'}, {plot}")
    bad = [r["label"] for r in rows if r.get("mismatches") or r.get("error")]  # a size out of time is no failure
    if bad:
        print(f"FAILED: answers differ or a run failed on {', '.join(bad)} (see the notes above)", file=sys.stderr)
        sys.exit(1)


def _timed(cmd: list[str], timeout: float, size: str, kind: str) -> dict[str, Any]:
    start = time.perf_counter()
    row = run_size(cmd, timeout, size, kind)
    print(progress(row, time.perf_counter() - start), flush=True)
    return row


if __name__ == "__main__":
    main()
