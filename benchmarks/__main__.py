"""Run the benchmark suite: ``python -m benchmarks [--quick] [--skip-100k] [--no-pellet] [...]``.

Four parts, each size and engine in a fresh process of its own (its peak RSS is its own; a run
that hangs is killed without taking the suite with it):

* **steps**: the robot step on maps compared with warm Pellet, then topostore alone on big maps;
* **drift**: 4,000 steps on the example map and on 1,000 locations (not in ``--quick``);
* **remote**: the step on a real ``oxigraph serve``, HTTP requests per step counted;
* **full**: full REASON of topostore and its peers on the same files (chain maps, a tutorial-style TBox),
  then robot-like steps on that TBox (the first apart, median and p95 of the others, each held against a
  full REASON from scratch).

The warm Pellet peer is compiled once per run into a temporary folder.  Prints the machine, the
tables, the ratios and the targets of issues 20 and 21 (met/missed), and writes ``table.md``,
``bench.csv``, ``results.json`` and ``bench.png`` to ``--out``.  Exits 1 when any answer differed
or a run failed.
"""

from __future__ import annotations

import argparse
import json
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

from .report import machine, table, write_csv, write_plot
from .tables import extra_tables
from .warm_pellet import PeerError, compile_peer

COMPARE = ["example", "8", "50", "110", "200", "500"]
SCALE = ["1000", "10000", "100000"]
#: seconds each topostore-only size may use: steps stop (never before 5) to stay in it; above 10,000
#: locations the full REASON is left out too when there is no room for it
SCALE_BUDGET = {"1000": 90.0, "10000": 200.0, "100000": 420.0}
QUICK_COMPARE, QUICK_SCALE = ["example", "8", "50", "110", "200"], ["1000", "10000"]
QUICK_SCALE_BUDGET = {"1000": 45.0, "10000": 90.0}
DRIFT, DRIFT_STEPS = ["example", "1000"], 4000
REMOTE, QUICK_REMOTE = ["example", "50"], ["example"]
#: full REASON: chain maps (topostore and reasonable) and the tutorial-style TBox (every engine)
FULL_MAPS, QUICK_FULL_MAPS = ["1000", "10000", "100000"], ["1000", "10000"]
MAP_ENGINES, TBOX_ENGINES, TBOX = ["topostore", "reasonable"], ["topostore", "reasonable", "owlrl", "pellet"], "tbox:100"
TBOX_STEPS = 20
#: robot steps on the maps compared with Pellet: a median over a few steps moves with the machine's load
#: by more than the difference being measured; Pellet's steps still stop at its time budget
COMPARE_STEPS, QUICK_COMPARE_STEPS = 200, 50


def parse_args(argv: list[str] | None) -> argparse.Namespace:
    p = argparse.ArgumentParser(prog="python -m benchmarks", description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--quick", action="store_true",
                   help=f"maps {', '.join(QUICK_COMPARE)} against Pellet (20 s of Pellet steps each), "
                        f"topostore alone at {', '.join(QUICK_SCALE)}, 10 steps: a few minutes")
    p.add_argument("--sizes", nargs="*", help=f"maps compared with Pellet (default {' '.join(COMPARE)})")
    p.add_argument("--scale-sizes", nargs="*", help=f"topostore-only maps (default {' '.join(SCALE)})")
    p.add_argument("--skip-100k", action="store_true", help="leave out the 100,000-location map")
    p.add_argument("--steps", type=int, help="robot steps per topostore-only map (default 20, 10 with --quick); "
                                             "medians are over steps 4 to the last")
    p.add_argument("--compare-steps", type=int,
                   help=f"robot steps on the maps compared with Pellet (default {COMPARE_STEPS}, "
                        f"{QUICK_COMPARE_STEPS} with --quick; Pellet stops earlier at its time budget)")
    p.add_argument("--pellet-budget", type=float,
                   help="seconds of Pellet steps per map before it stops (at least 4 steps; default 45, 20 with --quick)")
    p.add_argument("--pellet-warmup", type=float,
                   help="seconds the Pellet JVM walks a scratch copy of each map before its load (default 20, "
                        "12 with --quick; 0: a cold JVM, as before)")
    p.add_argument("--no-pellet", action="store_true", help="measure topostore only")
    p.add_argument("--parts", nargs="*", choices=["steps", "drift", "remote", "full"],
                   help="which parts to run (default all; --quick leaves out drift)")
    p.add_argument("--drift-steps", type=int, default=DRIFT_STEPS, help=f"steps of the drift walk (default {DRIFT_STEPS})")
    p.add_argument("--full-maps", nargs="*", help=f"chain maps of the full-REASON rows (default {' '.join(FULL_MAPS)}, "
                                                  f"{' '.join(QUICK_FULL_MAPS)} with --quick)")
    p.add_argument("--tbox", default=TBOX, help=f"the TBox-heavy input, tbox:N for N classes (default {TBOX})")
    p.add_argument("--tbox-steps", type=int, default=TBOX_STEPS,
                   help=f"robot-like steps on the TBox-heavy input (default {TBOX_STEPS})")
    p.add_argument("--out", type=Path, default=Path("out/bench"), help="output folder (default out/bench)")
    args = p.parse_args(argv)
    args.sizes = args.sizes if args.sizes is not None else QUICK_COMPARE if args.quick else COMPARE
    args.scale_sizes = args.scale_sizes if args.scale_sizes is not None else QUICK_SCALE if args.quick else SCALE
    if args.skip_100k:
        args.scale_sizes = [s for s in args.scale_sizes if s != "100000"]
    args.steps = args.steps or (10 if args.quick else 20)
    args.compare_steps = args.compare_steps or (QUICK_COMPARE_STEPS if args.quick else COMPARE_STEPS)
    args.pellet_budget = args.pellet_budget or (20.0 if args.quick else 45.0)
    args.budgets = QUICK_SCALE_BUDGET if args.quick else SCALE_BUDGET
    if args.pellet_warmup is None:
        args.pellet_warmup = 12.0 if args.quick else 20.0
    if args.parts is None:
        args.parts = ["steps", "remote", "full"] if args.quick else ["steps", "drift", "remote", "full"]
    args.remote = QUICK_REMOTE if args.quick else REMOTE
    full_maps = args.full_maps if args.full_maps is not None else QUICK_FULL_MAPS if args.quick else FULL_MAPS
    args.full_maps = [s for s in full_maps if not (args.skip_100k and s == "100000")]
    return args


def run_size(cmd: list[str], timeout: float, size: str, kind: str) -> dict[str, Any]:
    """One size in its own interpreter; its JSON row, or a row saying why there is none."""
    try:
        done = subprocess.run([sys.executable, "-m", *cmd], capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired as exc:
        return _killed(kind, size, timeout, exc.stdout)
    lines = done.stdout.strip().splitlines()
    why = f"exit {done.returncode}{_signal_name(done.returncode)}: {done.stderr.strip()[-800:]}"
    if not lines or not lines[-1].startswith("{"):
        return _failed(kind, size, why)
    row = json.loads(lines[-1])
    if done.returncode not in (0, 3):  # 3: answers differ (in the row); anything else died mid-run
        row["error"] = f"{why} (the figures are what it printed before, during {row.pop('doing', 'the run')})"
    return row


def _signal_name(code: int) -> str:
    """' (SIGKILL)' for a process killed by a signal (the kernel's OOM killer sends SIGKILL)."""
    if code >= 0:
        return ""
    try:
        return f" ({signal.Signals(-code).name})"
    except ValueError:
        return ""


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
    """One line per finished run, printed as the suite goes."""
    bits = [f"{row['kind']} {row.get('engine', '')} {row['label']}".replace("  ", " "), f"{seconds:.0f} s"]
    if row["kind"] in ("compare", "scale"):
        topo = row.get("topostore") if row["kind"] == "compare" else row
        bits.append(f"topostore step median {_ms(topo.get('median_ms'))}")
        if row["kind"] == "compare":
            pellet = row.get("pellet", {})
            bits.append(f"Pellet {_ms(pellet.get('median_ms'))} ({pellet.get('status', 'not run')})")
    elif row["kind"] == "drift":
        bits.append(f"steps 10-100 {_ms(row.get('early_ms'))}, last 100 {_ms(row.get('late_ms'))}, "
                    f"longest {_ms(row.get('longest_ms'))}")
    elif row["kind"] == "remote":
        bits.append(f"HTTP requests per step {row.get('requests_median')}, step median {_ms(row.get('median_ms'))}")
    elif row["kind"] == "tbox_steps" and "median_ms" in row:
        bits.append(f"first step {_ms(row['first_ms'])}, then median {_ms(row['median_ms'])}, p95 {_ms(row['p95_ms'])}")
    elif "reason_s" in row:
        bits.append(f"load {row['load_s']:.2f} s, REASON {row['reason_s']:.2f} s, peak RSS {row['peak_rss_mib']:.0f} MiB")
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
    rows = step_rows(args) if "steps" in args.parts else []
    extra: list[dict[str, Any]] = []
    if "drift" in args.parts:
        extra += [_timed(["benchmarks.drift", size, "--steps", str(args.drift_steps)], 1800, size, "drift")
                  for size in DRIFT]
    if "remote" in args.parts:
        extra += [_timed(["benchmarks.remote", size, "--steps", str(args.steps)], 600, size, "remote")
                  for size in args.remote]
    if "full" in args.parts:
        extra += full_rows(args)
    text = "\n\n".join(t for t in (table(rows, info) if rows else "", extra_tables(extra)) if t)
    print("\n" + text)
    (args.out / "table.md").write_text(text + "\n")
    (args.out / "results.json").write_text(json.dumps({"machine": info, "rows": rows, "extra": extra}, indent=1))
    if rows:
        write_csv(rows, args.out / "bench.csv")
        plot = write_plot(rows, args.out / "bench.png")
        print(f"\nwrote {args.out / 'table.md'}, {args.out / 'bench.csv'}, {args.out / 'results.json'}, {plot}")
    bad = [f"{r.get('engine', r['kind'])} {r['label']}" for r in rows + extra
           if r.get("mismatches") or r.get("error")]  # a size out of time is no failure
    if bad:
        print(f"FAILED: answers differ or a run failed on {', '.join(bad)} (see the notes above)", file=sys.stderr)
        sys.exit(1)


def step_rows(args: argparse.Namespace) -> list[dict[str, Any]]:
    """The step table's rows: the compared maps (with warm Pellet), then the topostore-only maps."""
    rows: list[dict[str, Any]] = []
    with tempfile.TemporaryDirectory(prefix="topostore-bench-") as tmp:
        classes = None
        if not args.no_pellet:
            try:
                classes = compile_peer(Path(tmp) / "classes")
            except PeerError as exc:
                print(f"warm Pellet not run: {exc}", flush=True)
        for size in args.sizes:
            cmd = ["benchmarks.compare", size, "--steps", str(args.compare_steps), "--pellet-budget", str(args.pellet_budget),
                   "--pellet-warmup", str(args.pellet_warmup)]
            cmd += ["--classes", str(classes)] if classes else []
            # Pellet: warm-up, load + first REASON (<= 300 s), its budget plus one slow step (<= 120 s); then topostore
            rows.append(_timed(cmd, args.pellet_warmup + 300 + args.pellet_budget + 120 + 300, size, "compare"))
        for size in args.scale_sizes:
            budget = args.budgets.get(size, 300.0)
            cmd = ["benchmarks.scale", size, "--steps", str(args.steps), "--budget", str(budget)]
            cmd += ["--full-if-room"] if int(size) > 10000 else []  # up to 10,000 the full/step ratio is a target
            rows.append(_timed(cmd, budget + 300, size, "scale"))  # killed then, keeping its progress
    return rows


def full_rows(args: argparse.Namespace) -> list[dict[str, Any]]:
    """Full REASON of each engine on each input, one process each (900 s at most)."""
    jobs = [(engine, size) for size in args.full_maps for engine in MAP_ENGINES]
    jobs += [(engine, args.tbox) for engine in TBOX_ENGINES]
    rows = [_timed(["benchmarks.full", engine, spec], 900, spec, "full", engine) for engine, spec in jobs]
    steps = ["benchmarks.tbox_steps", args.tbox, "--steps", str(args.tbox_steps)]
    return rows + [_timed(steps, 300, args.tbox, "tbox_steps", "topostore")]  # killed then, keeping its progress


def _timed(cmd: list[str], timeout: float, size: str, kind: str, engine: str | None = None) -> dict[str, Any]:
    start = time.perf_counter()
    row = run_size(cmd, timeout, size, kind)
    if engine:
        row.setdefault("engine", engine)
    print(progress(row, time.perf_counter() - start), flush=True)
    return row


if __name__ == "__main__":
    main()
