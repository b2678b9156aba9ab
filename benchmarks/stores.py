"""Robot-step latency and full REASON per store: in memory, on disk (RocksDB), on a SPARQL server.

    python -m benchmarks.stores                      # example map and 100 locations, memory/disk/oxigraph
    python -m benchmarks.stores --sizes seed,100,1000 --steps 30 --virtuoso

Self-contained (it starts its own ``oxigraph serve`` on a free loopback port, and Virtuoso
with ``--virtuoso`` when installed), so ``make bench`` can call it as one more suite.  A robot
step is the Python API doing what a patrolling robot does: REPLACE isIn, REPLACE now,
REPLACE visitedAt, REASON, then the canReach values and the URGENT instances.  For remote
stores it also counts the HTTP requests (round trips) of a step.  Writes
``out/bench/stores.csv`` and ``out/bench/stores.md``.
"""

from __future__ import annotations

import argparse
import csv
import random
import shutil
import signal
import socket
import statistics
import subprocess
import sys
import tempfile
import time
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import asdict, dataclass
from pathlib import Path

import httpx
from pyoxigraph import NamedNode, RdfFormat

from topostore import Ontology
from topostore.demo.mapgen import MAP_NS, generate
from topostore.resources import default_ontology, ontology_dir
from topostore.stores import open_store
from topostore.stores.base import serialize

ROBOT = NamedNode(MAP_NS + "Robot1")


def N(name: str) -> NamedNode:
    return NamedNode(MAP_NS + name)


@dataclass
class Row:
    """One map size on one store."""

    size: str
    store: str
    load_s: float
    full_reason_s: float
    step_median_ms: float
    step_p95_ms: float
    steps: int
    requests_per_step: float | None  # HTTP round trips (remote stores)
    requests_full_reason: int | None


# --------------------------------------------------------------------------- servers

def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def _wait(url: str, proc: subprocess.Popen, seconds: float) -> None:
    deadline = time.monotonic() + seconds
    while time.monotonic() < deadline:
        if proc.poll() is not None:
            raise RuntimeError(f"the server for {url} exited with {proc.returncode}")
        try:
            httpx.get(url, params={"query": "ASK {}"}, timeout=2)
            return
        except httpx.HTTPError:
            time.sleep(0.2)
    raise RuntimeError(f"{url} did not answer within {seconds} s")


@contextmanager
def oxigraph_server() -> Iterator[str]:
    exe = shutil.which("oxigraph") or str(Path(sys.executable).with_name("oxigraph"))
    with tempfile.TemporaryDirectory(prefix="bench-oxigraph-") as tmp:
        port = _free_port()
        proc = subprocess.Popen([exe, "serve", "-l", tmp + "/db", "-b", f"127.0.0.1:{port}"],
                                stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        try:
            _wait(f"http://127.0.0.1:{port}/query", proc, 30)
            yield f"http://127.0.0.1:{port}"
        finally:
            proc.send_signal(signal.SIGTERM)
            proc.wait(10)


@contextmanager
def virtuoso_server() -> Iterator[str]:
    """Virtuoso as the tests start it (tests/servers.py), when installed."""
    sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))
    from servers import virtuoso_server as start  # type: ignore[import-not-found]

    with start() as url:
        yield url


# --------------------------------------------------------------------------- workload

def map_file(size: str, folder: Path) -> tuple[Path, dict[str, list[str]]]:
    if size == "seed":
        return ontology_dir() / "topological_map_abox.ttl", {"C1": ["R1", "R2"], "R1": ["C1"], "R2": ["C1"]}
    m = generate(int(size))
    path = folder / f"map-{size}.nt"
    path.write_bytes(serialize(m.triples(), RdfFormat.N_TRIPLES))
    return path, {loc: sorted(m.neighbours(loc)) for loc in m.locations}


def requests(onto: Ontology) -> int | None:
    return getattr(onto.store, "requests", None)


def measure(size: str, store_name: str, spec, steps: int, folder: Path) -> Row:
    path, neighbours = map_file(size, folder)
    store = open_store(spec, reference=f"bench-{size}-{time.time_ns()}", sync=store_name.endswith("--sync"))
    try:
        start = time.perf_counter()
        onto = Ontology(store=store)
        onto.load(default_ontology())
        onto.load(path)
        load_s = time.perf_counter() - start
        before = requests(onto)
        start = time.perf_counter()
        onto.reason(mode="full")
        full_s = time.perf_counter() - start
        full_requests = None if before is None else requests(onto) - before
        rng = random.Random(7)
        where = onto.object_values("isIn", ROBOT)[0]
        now = int(onto.data_values("now", ROBOT)[0].value)
        latencies: list[float] = []
        before = requests(onto)
        for i in range(steps + 1):  # the first step compiles the incremental texts: not counted
            where = rng.choice(neighbours[where] or [where])
            now += rng.randint(1, 5)
            if i == 1:
                before = requests(onto)
            t = time.perf_counter()
            onto.replace(ROBOT, N("isIn"), N(where))
            onto.replace(ROBOT, N("now"), onto.value(now, "long"))
            onto.replace(N(where), N("visitedAt"), onto.value(now, "long"))
            report = onto.reason()
            onto.object_values("canReach", ROBOT)
            onto.instances("URGENT")
            if i:
                latencies.append(time.perf_counter() - t)
            if not report.consistent:
                raise AssertionError(f"inconsistent after a step on {store_name}: {report.explain()}")
        per_step = None if before is None else (requests(onto) - before) / steps
        return Row(size, store_name, round(load_s, 3), round(full_s, 3), round(statistics.median(latencies) * 1000, 1),
                   round(sorted(latencies)[int(0.95 * (len(latencies) - 1))] * 1000, 1), steps,
                   None if per_step is None else round(per_step, 1), full_requests)
    finally:
        store.close()


def table(rows: list[Row]) -> str:
    lines = ["| map | store | load | full REASON | step median / p95 | HTTP requests per step | per full REASON |",
             "|---|---|---|---|---|---|---|"]
    for r in rows:
        lines.append(f"| {r.size} | {r.store} | {r.load_s:.2f} s | {r.full_reason_s:.2f} s | "
                     f"{r.step_median_ms:.1f} / {r.step_p95_ms:.1f} ms ({r.steps}) | "
                     f"{'-' if r.requests_per_step is None else r.requests_per_step} | "
                     f"{'-' if r.requests_full_reason is None else r.requests_full_reason} |")
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--sizes", default="seed,100", help="comma-separated: seed or a number of locations")
    parser.add_argument("--steps", type=int, default=20, help="robot steps per size and store")
    parser.add_argument("--virtuoso", action="store_true", help="also run on Virtuoso (when installed)")
    parser.add_argument("--out", default="out/bench", help="folder for stores.csv and stores.md")
    args = parser.parse_args(argv)
    rows: list[Row] = []
    with tempfile.TemporaryDirectory(prefix="bench-stores-") as tmp, oxigraph_server() as oxigraph:
        stores: list[tuple[str, object]] = [("memory", None), ("disk", Path(tmp) / "disk"),
                                            ("disk --sync", Path(tmp) / "sync"), ("oxigraph serve", oxigraph)]
        virtuoso = virtuoso_server() if args.virtuoso and shutil.which("virtuoso-t") else None
        url = virtuoso.__enter__() if virtuoso else None
        if url:
            stores.append(("virtuoso", url))
        try:
            for size in args.sizes.split(","):
                for name, spec in stores:
                    row = measure(size, name, spec, args.steps, Path(tmp))
                    rows.append(row)
                    print(table([row]).splitlines()[-1], flush=True)
        finally:
            if virtuoso:
                virtuoso.__exit__(None, None, None)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    with (out / "stores.csv").open("w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(asdict(rows[0])))
        writer.writeheader()
        writer.writerows(asdict(r) for r in rows)
    (out / "stores.md").write_text(table(rows) + "\n")
    print(table(rows))
    return 0


if __name__ == "__main__":
    sys.exit(main())
