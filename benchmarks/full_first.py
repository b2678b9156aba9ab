"""LOAD + the first REASON of a chain map, wall and CPU, with and without the second thread.

    python -m benchmarks.full_first 10000 [100000] [--runs 3] [--maps DIR] [--ways overlap sequential]

A robot fleet's first REASON comes right after LOAD: this is what ``benchmarks.scale`` reports as
``load_first_s``, measured here alone (no robot steps), phase by phase: the LOAD, the first REASON
(a full run), and within it the rules to their fixpoint and what comes after it (census, checks,
publication, counts: :mod:`topostore.reason.closing`).  Each run is a fresh process (its peak RSS is
its own); ``sequential`` runs it with ``TOPOSTORE_OVERLAP=0`` (:mod:`topostore.stores.overlap`), so one
tree gives both ways, alternated run by run.  A thread shows in wall time, not in CPU: the process CPU,
the main thread's own CPU (what is left on the critical path; on a machine with a free core the wall time
follows it) and the wall time are printed.
The map is the N-Triples file of :mod:`benchmarks.maps` (the one ``benchmarks.scale`` loads), written once
into ``--maps``.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

_CHILD = """
import json, sys, time, warnings
warnings.simplefilter("ignore")
from benchmarks.limits import lift_time_limit
from benchmarks.timing import peak_rss_mib
from topostore import Ontology
from topostore.reason import incremental

lift_time_limit()
phases = {}
close = incremental.close_full

def timed_close(*args, **kwargs):
    cpu, wall, main = time.process_time(), time.perf_counter(), time.thread_time()
    try:
        return close(*args, **kwargs)
    finally:
        phases["after the fixpoint"] = (time.process_time() - cpu, time.perf_counter() - wall, time.thread_time() - main)

incremental.close_full = timed_close
onto = Ontology()
cpu, wall, main = time.process_time(), time.perf_counter(), time.thread_time()
n = onto.load(sys.argv[1])
phases["LOAD"] = (time.process_time() - cpu, time.perf_counter() - wall, time.thread_time() - main)
cpu, wall, main = time.process_time(), time.perf_counter(), time.thread_time()
report = onto.reason()
phases["first REASON"] = (time.process_time() - cpu, time.perf_counter() - wall, time.thread_time() - main)
phases["rules (fixpoint)"] = tuple(a - b for a, b in zip(phases["first REASON"], phases["after the fixpoint"]))
print(json.dumps({"triples": n, "derived": report.stats.derived, "mode": report.stats.mode,
                  "consistent": report.consistent, "phases": phases, "peak_rss_mib": peak_rss_mib()}))
"""


def map_file(size: str, where: Path) -> Path:
    """The N-Triples chain map of ``size`` locations in ``where`` (written the first time it is asked for)."""
    from pyoxigraph import RdfFormat

    from benchmarks import maps

    path = where / f"map-{size}.nt"
    if not path.exists():
        where.mkdir(parents=True, exist_ok=True)
        maps.write(size, where, RdfFormat.N_TRIPLES)
    return path


def run_once(path: Path, way: str) -> dict:
    """One LOAD + first REASON in a fresh interpreter, ``way`` "overlap" or "sequential"."""
    env = {**os.environ, "TOPOSTORE_OVERLAP": "0" if way == "sequential" else "1"}
    out = subprocess.run([sys.executable, "-c", _CHILD, str(path)], check=True, capture_output=True, text=True,
                         env=env)
    return json.loads(out.stdout.strip().splitlines()[-1])


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("sizes", nargs="+", help="map sizes (locations), e.g. 10000 100000")
    parser.add_argument("--runs", type=int, default=3)
    parser.add_argument("--maps", type=Path, default=Path(tempfile.gettempdir()) / "topostore-maps-nt")
    parser.add_argument("--ways", nargs="+", default=["overlap", "sequential"], choices=["overlap", "sequential"])
    args = parser.parse_args(argv)
    for size in args.sizes:
        path = map_file(size, args.maps)
        rows: dict[str, list[dict]] = {way: [] for way in args.ways}
        for _ in range(args.runs):
            for way in args.ways:
                rows[way].append(run_once(path, way))
        for way, runs in rows.items():
            derived = {r["derived"] for r in runs}
            print(f"{size:>7} locations, {way:<10} ({len(runs)} runs; {runs[0]['triples']:,} triples, "
                  f"{'/'.join(map(str, sorted(derived)))} derived, peak RSS {max(r['peak_rss_mib'] for r in runs):,.0f} MiB)")
            for phase in runs[0]["phases"]:
                cpu, wall, main = (statistics.median(r["phases"][phase][k] for r in runs) for k in range(3))
                print(f"    {phase:<20} CPU {cpu:7.3f} s   main thread {main:7.3f} s   wall {wall:7.3f} s")
            total = [r["phases"]["LOAD"][1] + r["phases"]["first REASON"][1] for r in runs]
            print(f"    {'LOAD + first REASON':<20} wall {statistics.median(total):7.3f} s "
                  f"({', '.join(f'{t:.2f}' for t in total)})")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
