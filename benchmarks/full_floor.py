"""The floor of a full REASON on the chain maps: ``python -m benchmarks.full_floor SIZE... [--reps N]``.

Before a target of topostore's full REASON is declared out of reach, the same work is measured done
the least way the store allows: the map file topostore loads (:func:`benchmarks.maps.write`) is read
into a bare pyoxigraph ``Store`` (``bulk_load`` and ``extend`` timed apart), then the same closure is
materialised by the hand-written updates of :mod:`benchmarks.full_floor_closure` to the fixpoint, and
once more as quads computed in Python and written with ``Store.extend`` (no SPARQL: the floor of
writing it; once more into a named graph, as topostore keeps its inferred graph apart).  Each form
runs in a process of its own (its peak RSS is its own), and so does
topostore's LOAD and ``reason(mode="full")`` on the same file.

Up to 10,000 locations (or with ``--check``) the new triples of both floors are held against
topostore's inferred graph as sets; any difference is printed and the exit status is 3.
The table gives CPU and wall seconds per rule, per form and for topostore, the machine (cores, load
average), the ratios topostore / floor and, with several sizes, the growth from the last but one to the last.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
import warnings
from collections.abc import Callable
from pathlib import Path
from typing import Any

from pyoxigraph import DefaultGraph, NamedNode, Quad, RdfFormat, Store, parse, serialize

from . import full_floor_closure as closure
from .timing import peak_rss_mib

#: above this size the sets are compared only when asked (``--check``): the dumps cost more than the run
CHECK_UP_TO = 10_000
#: the same closure written once more into a named graph, as topostore keeps its inferred graph apart
NAMED = NamedNode("urn:full-floor:inferred")


def timed(fn: Callable[[], Any]) -> tuple[Any, float, float]:
    """``fn()``'s result, CPU seconds and wall seconds."""
    cpu, wall = time.process_time(), time.perf_counter()
    out = fn()
    return out, time.process_time() - cpu, time.perf_counter() - wall


def _dump(triples: list, path: Path) -> None:
    path.write_bytes(serialize(triples, format=RdfFormat.N_TRIPLES) or b"")


def _median(runs: list[dict[str, float]]) -> dict[str, float]:
    return {k: statistics.median(r[k] for r in runs) for k in runs[0]}


def load_extend(path: Path) -> tuple[float, float]:
    """CPU and wall seconds of parsing the file and writing its quads with ``Store.extend``."""
    def go() -> Store:
        store = Store()
        store.extend(parse(path=str(path), format=RdfFormat.N_TRIPLES))
        return store
    _, cpu, wall = timed(go)
    return cpu, wall


def load_bulk(path: Path) -> tuple[Store, float, float]:
    """A store holding the file (``Store.bulk_load``), with the CPU and wall seconds it took."""
    store = Store()
    _, cpu, wall = timed(lambda: store.bulk_load(path=str(path), format=RdfFormat.N_TRIPLES))
    return store, cpu, wall


def sparql_once(path: Path, keep: bool) -> tuple[Store, dict[str, float], int, set | int]:
    """Load, then the hand-written rules to the fixpoint; seconds per step, the rounds it took, and
    the loaded triples (``keep``: for the comparison) or their count (not to hold them in memory)."""
    store, cpu, wall = load_bulk(path)
    times = {"load: bulk_load (cpu)": cpu, "load: bulk_load (wall)": wall}
    closure.refuse_outside(store)
    loaded = default_graph(store) if keep else count_default(store)  # not timed
    rounds = to_fixpoint(store, times)
    for name, ask in closure.CHECKS:
        found, c, w = timed(lambda ask=ask: store.query(closure.PREFIXES + ask))
        if found:
            raise closure.OutsideModel(f"the map is inconsistent ({name}): not a floor of a consistent REASON")
        times[f"check: {name} (cpu)"], times[f"check: {name} (wall)"] = c, w
    return store, times, rounds, loaded


def _update(store: Store, name: str, text: str, times: dict[str, float]) -> None:
    """Run one update and add its CPU and wall seconds to ``times`` under ``name``."""
    _, cpu, wall = timed(lambda: store.update(closure.PREFIXES + text))
    times[f"{name} (cpu)"] = times.get(f"{name} (cpu)", 0.0) + cpu
    times[f"{name} (wall)"] = times.get(f"{name} (wall)", 0.0) + wall


def to_fixpoint(store: Store, times: dict[str, float]) -> int:
    """The rules in order, then the closing update; again while the closing update adds a triple.
    Every rule runs after the rules that write what it reads, except for what the closing update writes:
    when that adds nothing, every rule has seen all of its input. Returns the rounds."""
    rounds = 0
    while True:
        rounds += 1
        for name, text in closure.RULES:
            _update(store, name, text, times)
        before = len(store)  # not timed
        _update(store, *closure.CLOSING, times)
        if len(store) == before:
            return rounds


def part_sparql(path: Path, reps: int, dump: Path | None) -> dict[str, Any]:
    """The SPARQL floor, ``reps`` times on a fresh store each; medians per step."""
    cpu, wall = load_extend(path)
    runs, rounds, store = [], 0, None
    for rep in range(reps):
        store = None  # one store at a time: the peak RSS is one run's
        store, times, rounds, loaded = sparql_once(path, dump is not None and rep == reps - 1)
        runs.append(times)
    assert store is not None
    return {"times": _median(runs), "load_extend_cpu": cpu, "load_extend_wall": wall, "rounds": rounds,
            "new_triples": _new(store, loaded, dump), "peak_rss_mib": peak_rss_mib()}


def _new(store: Store, loaded: set | int, dump: Path | None) -> int:
    """How many triples the floor added to the default graph; written to ``dump`` when the load was kept."""
    if isinstance(loaded, int):
        return count_default(store) - loaded
    new = new_triples(store, loaded)
    if dump is not None:
        _dump(new, dump)
    return len(new)


def default_graph(store: Store) -> set:
    """The default graph's triples (as the store gives them back: it writes ``xsd:long`` as ``xsd:integer``)."""
    return {q.triple for q in store.quads_for_pattern(None, None, None, DefaultGraph())}


def new_triples(store: Store, loaded: set) -> list:
    """The default graph's triples that were not there after the load: what the floor derived."""
    return list(default_graph(store) - loaded)


def count_default(store: Store) -> int:
    """The default graph's size (the helper graph left out)."""
    return int(next(iter(store.query("SELECT (COUNT(*) AS ?n) { ?s ?p ?o }")))["n"].value)


def python_once(path: Path, keep: bool) -> tuple[Store, dict[str, float], int, set | int]:
    """Load, read the facts back, compute the closure in Python, write it with ``Store.extend``."""
    store, cpu, wall = load_bulk(path)
    times = {"load: bulk_load (cpu)": cpu, "load: bulk_load (wall)": wall}
    closure.refuse_outside(store)
    loaded = default_graph(store) if keep else count_default(store)  # not timed
    facts, times["read the facts (cpu)"], times["read the facts (wall)"] = timed(lambda: closure.read_facts(store))
    quads, times["compute in Python (cpu)"], times["compute in Python (wall)"] = timed(
        lambda: closure.as_quads(closure.python_closure(facts)))
    _, times["write: Store.extend (cpu)"], times["write: Store.extend (wall)"] = timed(lambda: store.extend(quads))
    named = [Quad(q.subject, q.predicate, q.object, NAMED) for q in quads]
    _, cpu, wall = timed(lambda: store.extend(named))
    return store, times | {"named graph (cpu)": cpu, "named graph (wall)": wall}, len(quads), loaded


def part_python(path: Path, reps: int, dump: Path | None) -> dict[str, Any]:
    """The Python floor, ``reps`` times on a fresh store each; medians per step."""
    runs, store, written = [], None, 0
    for rep in range(reps):
        store = None  # one store at a time: the peak RSS is one run's
        store, times, written, loaded = python_once(path, dump is not None and rep == reps - 1)
        runs.append(times)
    assert store is not None
    return {"times": _median(runs), "written": written, "new_triples": _new(store, loaded, dump),
            "peak_rss_mib": peak_rss_mib()}


def part_topostore(path: Path, reps: int, dump: Path | None) -> dict[str, Any]:
    """topostore's LOAD, then ``reps`` full REASONs (the first reported apart); CPU and wall each."""
    from topostore import Ontology
    from topostore.rdf.vocab import INFERRED

    from .limits import lift_time_limit

    warnings.simplefilter("ignore")  # the map's notices are not what is measured
    lift_time_limit()
    onto = Ontology()
    _, load_cpu, load_wall = timed(lambda: onto.load(path))
    runs = []
    for _ in range(reps):
        report, cpu, wall = timed(lambda: onto.reason(mode="full"))
        if not report.consistent:
            raise RuntimeError("topostore found the map inconsistent")
        runs.append({"full (cpu)": cpu, "full (wall)": wall})
    inferred = list(onto.store.triples(None, None, None, INFERRED))
    if dump is not None:
        _dump(inferred, dump)
    return {"load_cpu": load_cpu, "load_wall": load_wall, "first": runs[0], "times": _median(runs),
            "inferred": len(inferred), "peak_rss_mib": peak_rss_mib()}


PARTS: dict[str, Callable[[Path, int, Path | None], dict[str, Any]]] = {
    "sparql": part_sparql, "python": part_python, "topostore": part_topostore}


def child(part: str, path: Path, reps: int, dump: Path | None) -> dict[str, Any]:
    """One part in a process of its own (its peak RSS is its own), its JSON row."""
    cmd = [sys.executable, "-m", "benchmarks.full_floor", "--part", part, "--file", str(path), "--reps", str(reps)]
    if dump is not None:
        cmd += ["--dump", str(dump)]
    out = subprocess.run(cmd, capture_output=True, text=True)
    if out.returncode != 0:
        raise RuntimeError(f"{part} on {path.name} failed:\n{out.stderr.strip()[-2000:]}")
    return json.loads(out.stdout)


def differences(ours: Path, theirs: Path) -> tuple[list[str], list[str]]:
    """Triples only in ``ours`` and only in ``theirs`` (N-Triples files), as sorted lines."""
    def read(p: Path) -> set[str]:
        return {str(q.triple) for q in parse(path=str(p), format=RdfFormat.N_TRIPLES)}
    a, b = read(ours), read(theirs)
    return sorted(a - b), sorted(b - a)


def measure(size: str, reps: int, check: bool, work: Path) -> dict[str, Any]:
    """Every part on the map of ``size`` locations, and the sets compared when ``check``."""
    from . import maps

    path, bench = maps.write(size, work, RdfFormat.N_TRIPLES)
    dumps = {p: (work / f"{p}-{size}.nt" if check else None) for p in PARTS}
    row: dict[str, Any] = {"size": size, "locations": bench.locations, "file_triples": bench.triples,
                           "load_average": os.getloadavg()[0], "mismatches": []}
    for part in PARTS:
        row[part] = child(part, path, reps, dumps[part])
    if check:
        for part in ("sparql", "python"):
            only_ours, only_topostore = differences(dumps[part], dumps["topostore"])
            for line in only_ours[:20]:
                row["mismatches"].append(f"{part} only: {line}")
            for line in only_topostore[:20]:
                row["mismatches"].append(f"topostore only ({part} lacks it): {line}")
            row[f"{part}_differences"] = len(only_ours) + len(only_topostore)
    return row


def _pair(times: dict[str, float], name: str) -> tuple[float, float]:
    return times[f"{name} (cpu)"], times[f"{name} (wall)"]


def _names(times: dict[str, float], skip: str = "load:") -> list[str]:
    return [k.removesuffix(" (cpu)") for k in times if k.endswith(" (cpu)") and not k.startswith(skip)]


def lines(row: dict[str, Any]) -> list[tuple[str, tuple[float, float] | float | str]]:
    """One size's figures as (label, (cpu, wall) or a number or text), in the table's order."""
    sp, py, ts = row["sparql"], row["python"], row["topostore"]
    rules = _names(sp["times"])
    sparql_total = tuple(sum(_pair(sp["times"], n)[i] for n in rules) for i in (0, 1))
    python_steps = [n for n in _names(py["times"]) if n != "named graph"]
    python_total = tuple(sum(_pair(py["times"], n)[i] for n in python_steps) for i in (0, 1))
    full = _pair(ts["times"], "full")
    write = _pair(py["times"], "write: Store.extend")
    out: list[tuple[str, Any]] = [
        ("file triples", float(row["file_triples"])),
        ("load: Store.bulk_load", _pair(sp["times"], "load: bulk_load")),
        ("load: parse + Store.extend", (sp["load_extend_cpu"], sp["load_extend_wall"])),
        (f"SPARQL floor ({sp['rounds']} round(s)), per update:", "")]
    out += [("  " + n, _pair(sp["times"], n)) for n in rules]
    closing = _pair(sp["times"], closure.CLOSING[0])
    out += [("  total (rules + checks)", sparql_total),
            ("  total without the closing (fixpoint shown by the bodies)",
             (sparql_total[0] - closing[0], sparql_total[1] - closing[1])),
            ("Python floor (no SPARQL):", "")]
    out += [("  " + n, _pair(py["times"], n)) for n in python_steps]
    out += [("  total", python_total),
            ("  the same quads again, into a named graph (not in the total)", _pair(py["times"], "named graph")),
            ("topostore:", ""),
            ("  LOAD", (ts["load_cpu"], ts["load_wall"])),
            ("  first full REASON", _pair(ts["first"], "full")),
            ("  full REASON (median)", full),
            ("  LOAD + full REASON", (ts["load_cpu"] + full[0], ts["load_wall"] + full[1])),
            ("peak RSS MiB: SPARQL floor", sp["peak_rss_mib"]), ("peak RSS MiB: Python floor", py["peak_rss_mib"]),
            ("peak RSS MiB: topostore", ts["peak_rss_mib"]),
            ("inferred: topostore", float(ts["inferred"])), ("new: SPARQL floor", float(sp["new_triples"])),
            ("new: Python floor", float(py["new_triples"])),
            ("differences (SPARQL, Python)", f"{row.get('sparql_differences', '-')}, "
                                              f"{row.get('python_differences', '-')}"),
            ("ratio full / SPARQL floor", (full[0] / sparql_total[0], full[1] / sparql_total[1])),
            ("ratio full / Store.extend", (full[0] / write[0], full[1] / write[1])),
            ("ratio SPARQL floor / Store.extend", (sparql_total[0] / write[0], sparql_total[1] / write[1])),
            ("load average at the start", row["load_average"])]
    return out


def _cell(value: Any) -> str:
    if isinstance(value, tuple):
        return f"{value[0]:.3f}/{value[1]:.3f}"
    if isinstance(value, float):
        return f"{value:,.0f}" if value >= 100 else f"{value:.2f}"
    return str(value)


def report(rows: list[dict[str, Any]]) -> str:
    """The rows as one table: one column per size (seconds as CPU/wall), and the growth to the last size
    from the one before it (10,000 -> 100,000 is the growth law of the issue)."""
    import pyoxigraph

    tables = [lines(r) for r in rows]
    head = (f"full REASON's floor, pyoxigraph {pyoxigraph.__version__}, os.cpu_count() = {os.cpu_count()}, "
            f"load average now {os.getloadavg()[0]:.2f}; seconds as CPU/wall")
    growth = len(rows) > 1
    out = [head, f"{'locations':<64}" + "".join(f"{r['locations']:>20,}" for r in rows)
           + (f"{'growth (CPU)':>14}" if growth else "")]
    if growth:
        out[0] += f"; growth = CPU of the last size / the one before ({rows[-2]['locations']:,} -> {rows[-1]['locations']:,})"
    for i, (label, _) in enumerate(tables[0]):
        cells = [t[i][1] for t in tables]
        line = f"{label:<64}" + "".join(f"{_cell(c):>20}" for c in cells)
        before = cells[-2] if growth else None
        if isinstance(before, tuple) and before[0] > 0 and not label.startswith("ratio"):
            line += f"{cells[-1][0] / before[0]:>13.1f}x"
        out.append(line)
    return "\n".join(out)


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("sizes", nargs="*", help="numbers of locations (even), each a chain map")
    parser.add_argument("--reps", type=int, default=3, help="runs of each part per size (medians; default 3)")
    parser.add_argument("--check", action="store_true", help=f"compare the sets above {CHECK_UP_TO:,} too")
    parser.add_argument("--json", action="store_true", help="print the rows as JSON instead of the table")
    parser.add_argument("--part", choices=list(PARTS), help=argparse.SUPPRESS)
    parser.add_argument("--file", type=Path, help=argparse.SUPPRESS)
    parser.add_argument("--dump", type=Path, help=argparse.SUPPRESS)
    args = parser.parse_args(argv)
    if args.reps < 1:
        parser.error("--reps must be at least 1")
    if args.part:
        print(json.dumps(PARTS[args.part](args.file, args.reps, args.dump)))
        return
    if not args.sizes:
        parser.error("give at least one size")
    from . import maps

    rows = []
    with tempfile.TemporaryDirectory(prefix="topostore-floor-") as tmp:
        for size in args.sizes:
            check = args.check or size == maps.EXAMPLE or int(size) <= CHECK_UP_TO
            rows.append(measure(size, args.reps, check, Path(tmp)))
    print(json.dumps(rows) if args.json else report(rows))
    bad = [m for r in rows for m in r["mismatches"]]
    for m in bad:
        print("MISMATCH", m, file=sys.stderr)
    sys.exit(3 if bad else 0)


if __name__ == "__main__":
    main()
