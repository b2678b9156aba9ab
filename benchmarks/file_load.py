"""LOAD of a generated map file: CPU, wall time and peak RSS of ``Ontology().load(path)`` alone.

    python -m benchmarks.file_load 10000 100000 [--runs 3] [--maps DIR] [--profile 25] [--ordinary]

Each size is written once (``benchmarks.maps``, kept in ``--maps`` so that runs of two trees
read the very same file) and loaded in a child process of its own, so that one size's peak
RSS is not another's.  No REASON: a first REASON is measured by ``benchmarks.scale`` and
``benchmarks.full``.  ``--profile N`` prints the N costliest functions (cProfile, by internal
time) of one extra load per size; its times are inflated by the profiler.  ``--ordinary`` loads through
the triple list, as every document but the first of an empty in-memory ontology is loaded, instead of
writing the document as it is parsed (``topostore.ontology.streamed``): the two ways in one tree.
``TOPOSTORE_LOAD_CHILD=1`` (or ``=0``) in the environment parses a big map in a child process (or never):
the CPU printed is the parent's and the child's together.  The main thread's CPU is printed beside it: the
store indexes the document's pieces in a second thread (``topostore.stores.text_writer``), so that on a quiet
machine the wall time follows the main thread's CPU, not the process's.
"""

from __future__ import annotations

import argparse
import json
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

_CHILD = """
import cProfile, json, pstats, resource, sys, time, warnings
warnings.simplefilter("ignore")
from topostore import Ontology
path, top, ordinary = sys.argv[1], int(sys.argv[2]), sys.argv[3] == "ordinary"
onto = Ontology()
if ordinary:
    onto.files._streaming_possible = lambda: False
profiler = cProfile.Profile() if top else None
cpu, wall, main = time.process_time(), time.perf_counter(), time.thread_time()
if profiler:
    profiler.enable()
n = onto.load(path)
if profiler:
    profiler.disable()
    pstats.Stats(profiler, stream=sys.stderr).sort_stats("tottime").print_stats(top)
child = resource.getrusage(resource.RUSAGE_CHILDREN)
print(json.dumps({"triples": n, "cpu": time.process_time() - cpu + child.ru_utime + child.ru_stime,
                  "main_cpu": time.thread_time() - main,
                  "child_cpu": child.ru_utime + child.ru_stime, "wall": time.perf_counter() - wall,
                  "peak_rss_mib": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024}))
"""


def map_file(size: str, where: Path) -> Path:
    """The map of ``size`` locations in ``where`` (written the first time it is asked for)."""
    from benchmarks import maps

    folder = where / size
    found = sorted(folder.glob("*.owl")) if folder.exists() else []
    if found:
        return found[0]
    folder.mkdir(parents=True, exist_ok=True)
    path, _ = maps.write(size, folder)
    return path


def load_once(path: Path, profile: int = 0, ordinary: bool = False) -> dict:
    """One load in a fresh interpreter: triples, cpu, wall, peak_rss_mib (``ordinary``: through the triple list)."""
    way = "ordinary" if ordinary else "streamed"
    out = subprocess.run([sys.executable, "-c", _CHILD, str(path), str(profile), way], check=True,
                         capture_output=True, text=True)
    if profile:
        print(out.stderr, file=sys.stderr)
    return json.loads(out.stdout.strip().splitlines()[-1])


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("sizes", nargs="+", help="map sizes (locations), e.g. 10000 100000")
    parser.add_argument("--runs", type=int, default=3)
    parser.add_argument("--maps", type=Path, default=Path(tempfile.gettempdir()) / "topostore-maps")
    parser.add_argument("--profile", type=int, default=0, metavar="N")
    parser.add_argument("--ordinary", action="store_true", help="load through the triple list")
    args = parser.parse_args(argv)
    for size in args.sizes:
        path = map_file(size, args.maps)
        runs = [load_once(path, ordinary=args.ordinary) for _ in range(args.runs)]
        cpu = statistics.median(r["cpu"] for r in runs)
        wall = statistics.median(r["wall"] for r in runs)
        main = statistics.median(r["main_cpu"] for r in runs)
        rss = max(r["peak_rss_mib"] for r in runs)
        print(f"{size:>7} locations  {runs[0]['triples']:>9,} triples  {path.stat().st_size / 1e6:6.1f} MB  "
              f"load CPU {cpu:6.2f} s (median of {len(runs)}; main thread {main:5.2f})  wall {wall:6.2f} s  "
              f"peak RSS {rss:5.0f} MiB")
        if args.profile:
            load_once(path, args.profile, args.ordinary)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
