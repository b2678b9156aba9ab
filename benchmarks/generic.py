"""Full REASON with the schema tables' rules instantiated or generic: ``python -m benchmarks.generic INPUT``.

INPUT is ``tbox:N`` (the tutorial-style TBox of N classes, :mod:`benchmarks.tbox`), ``taxonomy:N``
(N classes and N properties in trees of fan-out 4, each property's domain and range its class, an
individual in each leaf class: a taxonomy, where the plain kinds of axiom are all there is) or
a number of locations (a chain map, :mod:`benchmarks.maps`).  The ontology is loaded once; then the
materialisation of a full REASON (:class:`topostore.reason.materialize.Materializer`, the part the
choice changes) runs ``--reps`` times per variant, the variants interleaved so that the machine's
load falls on each alike:

* ``instantiated``: one rule per axiom (every rule of :mod:`topostore.compile.schema` instantiated);
* ``default``: what a full REASON runs (generic above ``GENERIC_ROWS`` instantiations of a rule, or
  above its file's ``# generic-rows:``);
* ``generic``: every generic rule of ``rules/owl/`` run generically over its schema graph;
* ``generic-N``: generic above N instantiations (``--threshold N``, repeatable).

Each variant's closure (inferred and helper graphs) must equal the instantiated one: a difference
is printed and the exit status is 3.  Prints one JSON line per variant: rules evaluated, the
generic rules and their rows, rounds, evaluations, the median seconds and the median CPU seconds (the
materialisation and the dropping of the schema graphs; on a shared machine the CPU time is the steadier).
"""

from __future__ import annotations

import argparse
import json
import statistics
import sys
import tempfile
import time
import warnings
from pathlib import Path
from typing import Any

from pyoxigraph import RdfFormat

from topostore import Ontology
from topostore.compile.schema_program import full_program
from topostore.rdf.vocab import AUX, INFERRED
from topostore.reason.materialize import Materializer

from . import maps, tbox
from .limits import lift_time_limit


def taxonomy(classes: int) -> str:
    """Turtle: ``classes`` classes in a tree of fan-out 4 and as many properties in a tree alike (each
    property's domain and range its class), an individual per leaf class, each linked to the next
    by its leaf's property; the last property is symmetric and the root one transitive."""
    lines = [f"@prefix : <{tbox.NS}> .", "@prefix owl: <http://www.w3.org/2002/07/owl#> .",
             "@prefix rdfs: <http://www.w3.org/2000/01/rdf-schema#> ."]
    for i in range(1, classes):
        lines += [f":K{i} rdfs:subClassOf :K{(i - 1) // 4} .", f":r{i} rdfs:subPropertyOf :r{(i - 1) // 4} ."]
    lines += [f":r{i} rdfs:domain :K{i} ; rdfs:range :K{i} ." for i in range(classes)]
    leaves = [i for i in range(classes) if 4 * i + 1 >= classes]
    lines += [f":o{i} a :K{i} ." for i in leaves]
    lines += [f":o{a} :r{a} :o{b} ." for a, b in zip(leaves, leaves[1:])]
    lines += [f":r{classes - 1} a owl:SymmetricProperty .", ":r0 a owl:TransitiveProperty ."]
    return "\n".join(lines) + "\n"


def write_input(spec: str, folder: Path) -> Path:
    if spec.startswith("tbox:"):
        return tbox.write(int(spec.split(":", 1)[1]), folder)
    if spec.startswith("taxonomy:"):
        path = folder / "taxonomy.ttl"
        path.write_text(taxonomy(int(spec.split(":", 1)[1])))
        return path
    return maps.write(spec, folder, RdfFormat.N_TRIPLES)[0]


def closure(onto: Ontology) -> tuple[frozenset, frozenset]:
    """The inferred and helper graphs, as sets of triples."""
    return tuple(frozenset((t.subject, t.predicate, t.object) for t in onto.store.triples(None, None, None, g))
                 for g in (INFERRED, AUX))


def measure(onto: Ontology, variants: dict[str, int | None], reps: int) -> list[dict[str, Any]]:
    programs = {name: full_program(onto.rules, threshold) for name, threshold in variants.items()}
    seconds: dict[str, list[float]] = {name: [] for name in variants}
    cpu: dict[str, list[float]] = {name: [] for name in variants}
    rows: dict[str, dict[str, Any]] = {}
    for _ in range(reps):
        for name, program in programs.items():
            program.write(onto.store)
            start = time.process_time()
            try:
                stats = Materializer(onto.store, program.rules).run()
            finally:
                program.drop(onto.store)
            cpu[name].append(time.process_time() - start)
            seconds[name].append(stats.seconds)
            rows[name] = {"variant": name, "rules": len(program.rules.inference_rules),
                          "generic": {k: len(v) for k, v in program.rows.items()}, "rounds": stats.rounds,
                          "evaluations": stats.evaluations, "closure": closure(onto)}
    base = rows["instantiated"]["closure"]
    out = []
    for name, row in rows.items():
        same = row.pop("closure") == base
        out.append({**row, "same_closure": same, "median_s": round(statistics.median(seconds[name]), 4),
                    "all_s": [round(s, 4) for s in seconds[name]],
                    "median_cpu_s": round(statistics.median(cpu[name]), 4)})
    return out


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("input", help="tbox:N (N named classes) or a number of locations (a chain map)")
    parser.add_argument("--reps", type=int, default=5)
    parser.add_argument("--threshold", type=int, action="append", default=[],
                        help="also run generic above this many instantiations of a rule")
    args = parser.parse_args(argv)
    lift_time_limit()
    warnings.simplefilter("ignore")  # the TBox's notices (what is not reasoned completely) are not measured here
    variants: dict[str, int | None] = {"instantiated": sys.maxsize, "default": None, "generic": 0}
    variants.update({f"generic-{n}": n for n in args.threshold})
    with tempfile.TemporaryDirectory(prefix="topostore-bench-") as tmp:
        onto = Ontology()
        onto.load(write_input(args.input, Path(tmp)))
    rows = measure(onto, variants, args.reps)
    for row in rows:
        print(json.dumps({"input": args.input, **row}))
    sys.exit(0 if all(r["same_closure"] for r in rows) else 3)


if __name__ == "__main__":
    main()
