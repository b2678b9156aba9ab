"""Peer reasoners on the same data, each run in a subprocess with a time limit.

* ``owlrl`` on rdflib: the OWL 2 RL closure (``DeductiveClosure(OWLRL_Semantics)``).
  owlrl does not execute SWRL rules, so it computes less than topostore (no
  connectedTo, canReach or URGENT) and its time is a lower bound for the
  same inferences.
* ``pellet``: Owlready2 (optional) running Pellet on Java, with property values
  inferred.  Skipped with a message when ``java`` or ``owlready2`` is missing.

``python -m benchmarks.peers NAME SIZE`` prints one JSON object: load and
reasoning seconds.
"""

from __future__ import annotations

import argparse
import importlib.util
import json
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from pyoxigraph import RdfFormat

from topostore.mapgen import generate
from topostore.resources import default_ontology, ontology_dir
from topostore.store import Store, serialize

PEERS = ("owlrl", "pellet")


def unavailable(name: str) -> str:
    """Why a peer cannot run here ("" when it can)."""
    if name == "pellet":
        if shutil.which("java") is None:
            return "java not found"
        if importlib.util.find_spec("owlready2") is None:
            return "owlready2 not installed (pip install -e '.[bench]')"
    return ""


def write_ntriples(size: str, folder: Path) -> Path:
    """TBox + map as one N-Triples file, the format every peer reads."""
    store = Store()
    triples = store.parse_file(default_ontology())
    if size == "seed":
        triples += store.parse_file(ontology_dir() / "topological_map_abox.ttl")
    else:
        triples += generate(int(size)).triples()
    path = folder / f"data-{size}.nt"
    path.write_bytes(serialize(triples, RdfFormat.N_TRIPLES))
    return path


def run_owlrl(path: Path) -> dict:
    import owlrl
    import rdflib

    start = time.perf_counter()
    graph = rdflib.Graph()
    graph.parse(path, format="nt")
    loaded = time.perf_counter()
    owlrl.DeductiveClosure(owlrl.OWLRL_Semantics).expand(graph)
    return {"load_s": loaded - start, "reason_s": time.perf_counter() - loaded, "triples": len(graph)}


def run_pellet(path: Path) -> dict:
    import owlready2

    start = time.perf_counter()
    world = owlready2.World()
    onto = world.get_ontology(path.as_uri()).load()
    loaded = time.perf_counter()
    with onto:
        owlready2.sync_reasoner_pellet(world, infer_property_values=True, infer_data_property_values=True, debug=0)
    return {"load_s": loaded - start, "reason_s": time.perf_counter() - loaded}


def measure(name: str, size: str, timeout: float) -> dict:
    """Run one peer on one size in a subprocess; {"status": "ok" | "timeout" | "skipped" | "error", ...}."""
    why = unavailable(name)
    if why:
        return {"status": "skipped", "why": why}
    cmd = [sys.executable, "-m", "benchmarks.peers", name, size]
    try:
        done = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return {"status": "timeout", "why": f"no result within {timeout:.0f} s"}
    if done.returncode != 0:
        last = (done.stderr.strip().splitlines() or ["no output"])[-1]
        return {"status": "error", "why": last[:200]}
    return {"status": "ok", **json.loads(done.stdout.strip().splitlines()[-1])}


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("peer", choices=PEERS)
    parser.add_argument("size")
    args = parser.parse_args(argv)
    with tempfile.TemporaryDirectory() as tmp:
        path = write_ntriples(args.size, Path(tmp))
        result = run_owlrl(path) if args.peer == "owlrl" else run_pellet(path)
    print(json.dumps(result))


if __name__ == "__main__":
    main()
