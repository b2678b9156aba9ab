"""Full materialisation, one engine on one input: ``python -m benchmarks.full ENGINE INPUT`` prints JSON.

INPUT is a chain map of N locations (``1000``; the compared maps' TBox with its SWRL rules plus the
ABox, as :mod:`benchmarks.maps` writes it) or ``tbox:N``, the tutorial-style TBox of N classes
(:mod:`benchmarks.tbox`).  Every engine reads the very same N-Triples file, in a process of its own
so that its peak RSS is its own (Pellet's JVM is a child: the larger of the two is reported):

* ``topostore``: ``Ontology.load`` then ``reason(mode="full")``, its time limit lifted
  when run as a program (:mod:`benchmarks.limits`);
* ``reasonable`` (Rust, OWL 2 RL; no SWRL, so on the maps it does the OWL part only);
* ``owlrl`` (pure Python, OWL 2 RL, over rdflib);
* ``pellet``: Pellet 2.3.1 through Owlready2's ``sync_reasoner_pellet`` (its JVM start and file
  round trip are in its REASON time, as Owlready2 runs it).

On a map the robot's canReach is checked; on a TBox the named classes of every individual are
listed (``types``) so that the caller can hold each engine's answers against Pellet's.
"""

from __future__ import annotations

import argparse
import json
import resource
import sys
import tempfile
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

from pyoxigraph import NamedNode, RdfFormat, parse

from . import maps, tbox
from .limits import lift_time_limit
from .timing import peak_rss_mib

ENGINES = ["topostore", "reasonable", "owlrl", "pellet"]
TYPE = "http://www.w3.org/1999/02/22-rdf-syntax-ns#type"
NAMED_INDIVIDUAL = "http://www.w3.org/2002/07/owl#NamedIndividual"


def write_input(spec: str, work: Path) -> tuple[Path, dict[str, Any]]:
    """The N-Triples file of ``spec`` and what is known of it (its kind, size, the robot's neighbours)."""
    if spec.startswith("tbox:"):
        classes = int(spec.removeprefix("tbox:"))
        label = f"tutorial-style TBox ({classes} classes)"
        return tbox.write(classes, work), {"input_kind": "tbox", "classes": classes, "label": label}
    path, bench = maps.write(spec, work, RdfFormat.N_TRIPLES)
    return path, {"input_kind": "map", "locations": bench.locations, "label": bench.label,
                  "expected_can_reach": bench.neighbours[bench.start]}


def individuals(path: Path, ns: str) -> list[str]:
    """The named individuals a file declares in ``ns``, as local names."""
    found = {q.subject.value for q in parse(path=str(path), format=RdfFormat.N_TRIPLES)
             if q.predicate.value == TYPE and isinstance(q.object, NamedNode) and q.object.value == NAMED_INDIVIDUAL}
    return sorted(s.removeprefix(ns) for s in found if s.startswith(ns))


def types_from_triples(triples: Any, ns: str, names: list[str]) -> dict[str, list[str]]:
    """Named classes in ``ns`` of each individual, from (s, p, o) triples of strings or rdflib terms."""
    wanted = {ns + n: n for n in names}
    out: dict[str, set[str]] = {n: set() for n in names}
    for s, p, o in triples:
        if str(p) == TYPE and str(s) in wanted and str(o).startswith(ns):
            out[wanted[str(s)]].add(str(o).removeprefix(ns))
    return {n: sorted(v) for n, v in out.items()}


def run_topostore(path: Path, ns: str, names: list[str]) -> tuple[float, float, dict[str, Any]]:
    from topostore import Ontology

    start = time.perf_counter()
    onto = Ontology()
    onto.load(path)
    loaded = time.perf_counter()
    report = onto.reason(mode="full")
    done = time.perf_counter()
    extra: dict[str, Any] = {"consistent": report.consistent}
    if names:
        extra["types"] = {n: sorted(t.value.removeprefix(ns) for t in onto.types(NamedNode(ns + n))
                                    if t.value.startswith(ns)) for n in names}
    else:
        ns = maps.PREFIXES[""]
        reach = onto.object_values(NamedNode(ns + "canReach"), NamedNode(ns + maps.ROBOT), names=False)
        extra["can_reach"] = sorted(maps.local(r) for r in reach)
    return loaded - start, done - loaded, extra


def run_reasonable(path: Path, ns: str, names: list[str]) -> tuple[float, float, dict[str, Any]]:
    import reasonable

    turtle = path.with_suffix(".ttl")  # N-Triples is Turtle; reasonable picks its parser by the file name
    turtle.symlink_to(path.name)
    start = time.perf_counter()
    engine = reasonable.PyReasoner()
    engine.load_file(str(turtle))
    loaded = time.perf_counter()
    triples = engine.reason()
    done = time.perf_counter()
    extra: dict[str, Any] = {"triples_out": len(triples)}
    if names:
        extra["types"] = types_from_triples(triples, ns, names)
    return loaded - start, done - loaded, extra


def run_owlrl(path: Path, ns: str, names: list[str]) -> tuple[float, float, dict[str, Any]]:
    import owlrl
    import rdflib

    start = time.perf_counter()
    graph = rdflib.Graph()
    graph.parse(str(path), format="nt")
    loaded = time.perf_counter()
    owlrl.DeductiveClosure(owlrl.OWLRL_Semantics).expand(graph)
    done = time.perf_counter()
    extra: dict[str, Any] = {"triples_out": len(graph)}
    if names:
        extra["types"] = types_from_triples(graph, ns, names)
    return loaded - start, done - loaded, extra


def run_pellet(path: Path, ns: str, names: list[str]) -> tuple[float, float, dict[str, Any]]:
    import owlready2

    start = time.perf_counter()
    world = owlready2.World()
    onto = world.get_ontology(path.as_uri()).load(format="ntriples")
    loaded = time.perf_counter()
    with onto:
        owlready2.sync_reasoner_pellet(world, infer_property_values=False, debug=0)
    done = time.perf_counter()
    extra: dict[str, Any] = {}
    if names:
        found: dict[str, list[str]] = {}
        for n in names:
            ind = world[ns + n]
            classes = [c for c in ind.INDIRECT_is_a if isinstance(c, owlready2.ThingClass)] if ind is not None else []
            found[n] = sorted(c.iri.removeprefix(ns) for c in classes if c.iri.startswith(ns))
        extra["types"] = found
    return loaded - start, done - loaded, extra


RUNNERS: dict[str, Callable[[Path, str, list[str]], tuple[float, float, dict[str, Any]]]] = {
    "topostore": run_topostore, "reasonable": run_reasonable, "owlrl": run_owlrl, "pellet": run_pellet}


def run(engine: str, spec: str, work: Path) -> dict[str, Any]:
    """One engine on one input: load and REASON seconds, peak RSS, and what it answered."""
    work.mkdir(parents=True, exist_ok=True)
    path, info = write_input(spec, work)
    names = individuals(path, tbox.NS) if info["input_kind"] == "tbox" else []
    row: dict[str, Any] = {"kind": "full", "engine": engine, "size": spec, **info, "mismatches": []}
    try:
        load_s, reason_s, extra = RUNNERS[engine](path, tbox.NS, names)
    except Exception as exc:  # noqa: BLE001 - a peer that fails (inconsistent, not installed) is a row saying so
        row["error"] = f"{type(exc).__name__}: {str(exc).strip()[-400:]}"
        return row
    children = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024
    row.update(load_s=load_s, reason_s=reason_s, peak_rss_mib=max(peak_rss_mib(), children), **extra)
    want = info.get("expected_can_reach")
    if want is not None and "can_reach" in extra and extra["can_reach"] != want:
        row["mismatches"].append(f"canReach of the robot: {extra['can_reach']} != expected {want}")
    return row


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("engine", choices=ENGINES)
    parser.add_argument("input", help="a number of locations (a chain map) or tbox:N (N named classes)")
    args = parser.parse_args(argv)
    lift_time_limit()  # topostore's full REASON is measured, not refused: the suite's timeout bounds the run
    with tempfile.TemporaryDirectory(prefix="topostore-bench-") as tmp:
        row = run(args.engine, args.input, Path(tmp))
    print(json.dumps(row))
    sys.exit(3 if row["mismatches"] else 0)


if __name__ == "__main__":
    main()
