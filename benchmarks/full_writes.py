"""What the first REASON after LOAD writes, evaluation by evaluation, and what a write costs by store size.

    python -m benchmarks.full_writes 10000 100000 [--maps DIR] [--engine 90000 900000 1800000]

For each chain map (:mod:`benchmarks.maps`, the N-Triples file of :mod:`benchmarks.full_first`), in a
process of its own: LOAD, then the first REASON with the second thread off (``TOPOSTORE_OVERLAP=0``, so
every write is the main thread's and timed where it is made) and profiled (each evaluation its own
request).  Each request is listed with the quads it added to the store, its CPU, its CPU per quad added
and the store's quads after it; the engine's count (``len``) is taken between requests, outside the
timed part.  With two sizes the CPU of each evaluation is compared (10× the locations should cost
10× the time: what is above is the part that grows faster than the store).

``--engine`` measures pyoxigraph alone: one ``INSERT ... WHERE`` copying 20,000 quads of terms already
held, and one load of 20,000 quads of new IRIs, into a store of N quads (five times each, the minimum
and median per quad).  The same write costs more in a bigger store: that is the floor of the growth
of a REASON whose time is its writes.
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

from .full_first import map_file

_CHILD = """
import json, sys, time, warnings
warnings.simplefilter("ignore")
from benchmarks.limits import lift_time_limit
from topostore import Ontology
from topostore.reason import materialize
from topostore.stores import oxigraph

lift_time_limit()
rows, naming = [], {"name": None}
update, load = oxigraph.OxigraphStore._run_update, oxigraph.OxigraphStore.add_ntriples_beside

def counted(kind, fn):
    def wrapper(self, text, *args):
        before, start = len(self._ox), time.process_time()
        fn(self, text, *args)
        cpu = time.process_time() - start
        name = naming["name"] or kind
        rows.append({"name": name, "added": len(self._ox) - before, "cpu": cpu, "quads": len(self._ox)})
    return wrapper

def named(timed):
    def wrapper(self, text, name, stats):
        naming["name"] = name
        try:
            return timed(self, text, name, stats)
        finally:
            naming["name"] = None
    return wrapper

def profiled(init):
    def wrapper(self, *args, **kwargs):
        init(self, *args, **{**kwargs, "profile": True})
    return wrapper

oxigraph.OxigraphStore._run_update = counted("other update", update)
oxigraph.OxigraphStore.add_ntriples_beside = counted("N-Triples load", load)
materialize.Materializer._timed = named(materialize.Materializer._timed)
materialize.Materializer.__init__ = profiled(materialize.Materializer.__init__)
onto = Ontology()
onto.load(sys.argv[1])
loaded = len(onto.store._ox)
rows.clear()
start = time.process_time()
report = onto.reason()
print(json.dumps({"loaded": loaded, "derived": report.stats.derived, "cpu": time.process_time() - start,
                  "rows": rows}))
"""

_ENGINE = """
import json, sys, time
import pyoxigraph as ox
n, k = int(sys.argv[1]), 20000
kind = "<http://www.w3.org/1999/02/22-rdf-syntax-ns#type>"
store = ox.Store()
store.load("".join(f"<urn:s{i}> <urn:p> <urn:o{i}> .\\n" for i in range(n)).encode(), format=ox.RdfFormat.N_TRIPLES,
           to_graph=ox.NamedNode("urn:g:a"))
store.load("".join(f"<urn:s{i}> {kind} <urn:C> .\\n" for i in range(k)).encode(), format=ox.RdfFormat.N_TRIPLES,
           to_graph=ox.NamedNode("urn:g:c"))
copy, fresh = [], []
for r in range(5):
    start = time.process_time()
    store.update(f"INSERT {{ GRAPH <urn:g:u{r}> {{ ?s a <urn:D{r}> }} }} WHERE {{ GRAPH <urn:g:c> {{ ?s a <urn:C> }} }}")
    copy.append((time.process_time() - start) / k * 1e6)
    store.update(f"DROP GRAPH <urn:g:u{r}>")
    text = "".join(f"<urn:key:{r}:{i:032x}> <urn:keyOf> <urn:s{i}> .\\n" for i in range(k)).encode()
    start = time.process_time()
    store.load(text, format=ox.RdfFormat.N_TRIPLES, to_graph=ox.NamedNode(f"urn:g:l{r}"), lenient=True)
    fresh.append((time.process_time() - start) / k * 1e6)
    store.update(f"DROP GRAPH <urn:g:l{r}>")
print(json.dumps({"copy": copy, "fresh": fresh}))
"""


def child(code: str, *args: str, env: dict[str, str] | None = None) -> dict:
    """Run ``code`` in a fresh interpreter (its memory its own) and read its last line as JSON."""
    out = subprocess.run([sys.executable, "-c", code, *args], check=True, capture_output=True, text=True,
                         env={**os.environ, **(env or {})})
    return json.loads(out.stdout.strip().splitlines()[-1])


def by_name(rows: list[dict]) -> dict[str, tuple[int, float]]:
    """Quads added and CPU per evaluation name, summed over its requests."""
    out: dict[str, tuple[int, float]] = {}
    for r in rows:
        added, cpu = out.get(r["name"], (0, 0.0))
        out[r["name"]] = (added + r["added"], cpu + r["cpu"])
    return out


def census(size: str, run: dict) -> list[str]:
    """One map's requests that added 100 quads or more or took 10 ms or more, in the order they ran."""
    lines = [f"{size} locations: {run['loaded']:,} quads after LOAD, {run['derived']:,} derived, "
             f"first REASON CPU {run['cpu']:.2f} s (profiled, sequential)",
             f"  {'evaluation':<28} {'quads added':>11} {'CPU (s)':>8} {'µs/quad':>8} {'store after':>12}"]
    for r in run["rows"]:
        if abs(r["added"]) >= 100 or r["cpu"] >= 0.01:
            per = f"{r['cpu'] / r['added'] * 1e6:8.1f}" if r["added"] > 0 else f"{'':>8}"
            lines.append(f"  {r['name'][:28]:<28} {r['added']:>11,} {r['cpu']:8.3f} {per} {r['quads']:>12,}")
    return lines


def growth(small: str, large: str, runs: dict[str, dict]) -> list[str]:
    """The CPU of each evaluation at ``large`` over its CPU at ``small``."""
    a, b = by_name(runs[small]["rows"]), by_name(runs[large]["rows"])
    lines = [f"growth {small} -> {large} (CPU, by evaluation):"]
    for name, (_, cpu) in sorted(b.items(), key=lambda kv: -kv[1][1]):
        if name in a and a[name][1] > 0 and cpu >= 0.01:
            lines.append(f"  {name[:28]:<28} {a[name][1]:7.3f} -> {cpu:7.3f} s  ×{cpu / a[name][1]:5.1f}")
    total = [sum(r["cpu"] for r in runs[s]["rows"]) for s in (small, large)]
    lines.append(f"  {'all requests':<28} {total[0]:7.3f} -> {total[1]:7.3f} s  ×{total[1] / total[0]:5.1f}")
    return lines


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("sizes", nargs="*", help="map sizes (locations), e.g. 10000 100000")
    parser.add_argument("--maps", type=Path, default=Path(tempfile.gettempdir()) / "topostore-maps-nt")
    parser.add_argument("--engine", nargs="*", default=[], help="store sizes (quads) for the engine alone")
    args = parser.parse_args(argv)
    runs = {size: child(_CHILD, str(map_file(size, args.maps)), env={"TOPOSTORE_OVERLAP": "0"})
            for size in args.sizes}
    for size, run in runs.items():
        print("\n".join(census(size, run)))
    for small, large in zip(args.sizes, args.sizes[1:]):
        print("\n".join(growth(small, large, runs)))
    for n in args.engine:
        found = child(_ENGINE, n)
        print(f"engine alone, store of {int(n):,} quads: µs per quad (min / median of 5): copy "
              f"{min(found['copy']):.2f} / {statistics.median(found['copy']):.2f}, new IRIs loaded "
              f"{min(found['fresh']):.2f} / {statistics.median(found['fresh']):.2f}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
