"""Full REASON of one cardinality restriction of size n: ``python -m benchmarks.cardinality``.

The shape of the W3C OWL 2 test cases that used to exhaust the query engine: one
``owl:cardinality n`` (or min / max / qualified) restriction equivalent to a named class, and an
individual with ``fillers`` values, pairwise different through one ``owl:AllDifferent``.  Each n
runs in a child process of its own with a timeout, so a size that crashes the engine or hangs
is reported as such instead of ending the run.  ``--before DIR`` runs the same rows with the
sources of another checkout (``DIR/src`` first on the path), e.g. the main branch, and prints
both columns.

    python -m benchmarks.cardinality                       # n = 40, 80, 128, 600
    python -m benchmarks.cardinality --before ../main --timeout 60
    python -m benchmarks.cardinality --empty                  # the restriction alone, no values
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

SIZES = [40, 80, 128, 600]
KINDS = ("cardinality", "minCardinality", "maxCardinality")

PREFIXES = """@prefix : <http://example.org/card#> .
@prefix owl: <http://www.w3.org/2002/07/owl#> .
@prefix rdfs: <http://www.w3.org/2000/01/rdf-schema#> .
@prefix xsd: <http://www.w3.org/2001/XMLSchema#> .
<http://example.org/card> a owl:Ontology .
"""


def cardinality_ttl(kind: str, n: int, fillers: int, qualified: bool = False, data: bool = False) -> str:
    """Turtle: ``:C ≡ (kind n :p [:D | xsd:integer])`` and ``:x`` with ``fillers`` values of ``:p``.

    For an exact or maximum cardinality ``:x`` is asserted to be a ``:C`` (what is checked is
    the maximum); for a minimum, whether ``:x`` is a ``:C`` is what is inferred.
    Object values are individuals ``:y0 …`` of ``:D``, all in one ``owl:AllDifferent``; data
    values are the integers ``0 …``.
    """
    if kind not in KINDS:
        raise ValueError(f"kind must be one of {', '.join(KINDS)}")
    name = kind
    if qualified:
        name = "qualifiedCardinality" if kind == "cardinality" else kind[:-len("Cardinality")] + "QualifiedCardinality"
    filler = ("owl:onDataRange xsd:integer" if data else "owl:onClass :D") if qualified else ""
    lines = [PREFIXES,
             f":p a {'owl:DatatypeProperty' if data else 'owl:ObjectProperty'} .",
             ":C a owl:Class . :D a owl:Class .",
             f":C owl:equivalentClass [ a owl:Restriction ; owl:onProperty :p ; owl:{name} {n}"
             + (f" ; {filler}" if filler else "") + " ] ."]
    if kind != "minCardinality":
        lines.append(":x a :C .")
    if data:
        lines += [f":x :p {i} ." for i in range(fillers)]
    else:
        lines += [f":x :p :y{i} . :y{i} a :D ." for i in range(fillers)]
        if fillers:
            lines.append("[] a owl:AllDifferent ; owl:distinctMembers (" +
                         " ".join(f":y{i}" for i in range(fillers)) + ") .")
    return "\n".join(lines) + "\n"


def measure(kind: str, n: int, fillers: int, qualified: bool, data: bool) -> dict:
    """Load and reason one generated file in this process; the row as a dict."""
    from topostore import Ontology

    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "card.ttl"
        path.write_text(cardinality_ttl(kind, n, fillers, qualified, data))
        start = time.perf_counter()
        onto = Ontology.from_file(path)
        report = onto.reason()
        seconds = time.perf_counter() - start
        members = [onto.short(i) for i in onto.instances("C")]
    return {"seconds": round(seconds, 3), "consistent": report.consistent, "x_in_C": "x" in members,
            "rules": len(onto.rules.rules), "schema_rows": len(onto.rules.compiled_rules()) - len(onto.rules.rules)}


def run_child(src: Path | None, kind: str, n: int, fillers: int, qualified: bool, data: bool,
              timeout: float) -> dict:
    """One row in a child interpreter (``src`` first on its path); what happened, also a crash or a timeout."""
    env = dict(os.environ)
    if src is not None:
        env["PYTHONPATH"] = str(src) + os.pathsep + env.get("PYTHONPATH", "")
    args = [sys.executable, "-m", "benchmarks.cardinality", "--child", kind, str(n), str(fillers),
            str(int(qualified)), str(int(data))]
    try:
        done = subprocess.run(args, capture_output=True, text=True, timeout=timeout, env=env,
                              cwd=Path(__file__).resolve().parent.parent)
    except subprocess.TimeoutExpired:
        return {"outcome": f"> {timeout:g} s (killed)"}
    if done.returncode != 0:
        tail = (done.stderr.strip().splitlines() or [""])[-1]
        return {"outcome": f"died (exit {done.returncode}) {tail[:80]}"}
    row = json.loads(done.stdout.strip().splitlines()[-1])
    row["outcome"] = f"{row['seconds']:.2f} s"
    return row


def cases(sizes: list[int], empty: bool = False) -> list[tuple[str, int, int, bool, bool]]:
    """(kind, n, fillers, qualified, data) rows: each size as exact (n values: consistent), min (x is
    inferred a C) and max (n + 1 values: inconsistent); with ``empty``, no values at all (the rules
    alone: the shape of the W3C test cases)."""
    rows = []
    for n in sizes:
        rows.append(("cardinality", n, 0 if empty else n, False, False))
        rows.append(("minCardinality", n, 0 if empty else n, True, False))
        rows.append(("maxCardinality", n, 0 if empty else n + 1, True, False))
    rows.append(("minCardinality", max(sizes), 0 if empty else max(sizes), True, True))
    return rows


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(prog="python -m benchmarks.cardinality", description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--sizes", type=int, nargs="*", default=SIZES, help="values of n (default 40 80 128 600)")
    p.add_argument("--before", type=Path, help="another checkout to measure too (its src/ is put first on the path)")
    p.add_argument("--empty", action="store_true", help="no values: the restriction's rules alone")
    p.add_argument("--timeout", type=float, default=120.0, help="seconds per row and checkout (default 120)")
    p.add_argument("--child", nargs=5, help=argparse.SUPPRESS)
    args = p.parse_args(argv)
    if args.child:
        kind, n, fillers, qualified, data = args.child
        print(json.dumps(measure(kind, int(n), int(fillers), qualified == "1", data == "1")))
        return 0
    checkouts = [("before", args.before / "src")] if args.before else []
    checkouts.append(("after", None))
    print(f"{'restriction':<34} {'values':>6} " + " ".join(f"{name:>30}" for name, _ in checkouts) + "  answer")
    for kind, n, fillers, qualified, data in cases(args.sizes, args.empty):
        label = f"{'qualified ' if qualified else ''}{kind} {n}{' (data)' if data else ''}"
        rows = [run_child(src, kind, n, fillers, qualified, data, args.timeout) for _, src in checkouts]
        last = rows[-1]
        answer = ""
        if "consistent" in last:
            answer = "inconsistent" if not last["consistent"] else ("x in C" if last["x_in_C"] else "x not in C")
        print(f"{label:<34} {fillers:>6} " + " ".join(f"{r['outcome']:>30}" for r in rows) + f"  {answer}", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
