"""Where a full REASON spends its time: ``python -m benchmarks.full_profile 10000 [100000]``.

:mod:`benchmarks.full` times a full REASON as a whole; this module splits it, so that a change is aimed
at what costs.  For each chain map (:mod:`benchmarks.maps`), in a process of its own (its peak RSS is
its own), after LOAD and its first REASON:

* the phases of ``reason(mode="full")`` run one by one on the same store, CPU seconds: the rules to
  their fixpoint (:class:`~topostore.reason.materialize.Materializer`), the census of which graphs
  hold the keys the rules and checks read (maintenance starts from it, the checks read a key of one
  graph there), the consistency checks, the publication of entailed-only conclusions, and the counts;
  "rules" is the only phase that grows with the rule set's work, the others are what a full REASON
  does after it;
* the quads each graph holds afterwards (a quad of a named graph is six index entries);
* the rules' CPU per rule name (the profiled run: each evaluation its own request, so its total is a
  little above the unprofiled "rules" phase).

With two sizes it prints the growth of each phase and rule from the first to the second (10× the
locations should cost at most 10× the time; a rule above that is the superlinear part).
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import time
import warnings
from collections.abc import Callable
from typing import Any

from .limits import lift_time_limit
from .timing import peak_rss_mib


def _cpu(fn: Callable[[], object]) -> float:
    start = time.process_time()
    fn()
    return time.process_time() - start


def profile(size: str) -> dict[str, Any]:
    """The phases, graph sizes and per-rule CPU of a full REASON of the chain map of ``size`` locations."""
    from topostore.rdf.vocab import ASSERTED, INFERRED
    from topostore.reason.consistency import check_consistency
    from topostore.reason.entailed import publish_entailed
    from topostore.reason.materialize import Materializer

    from . import maps

    warnings.simplefilter("ignore")  # the map's notices are not what is measured
    lift_time_limit()
    onto, load = maps.loaded(size)
    first = _cpu(onto.reason)
    whole = _cpu(lambda: onto.reason(mode="full"))
    store, rules = onto.store, onto.rules
    reasoner = onto._reasoner  # the census maintenance starts from is the reasoner's own
    keys: dict = {}  # filled by the census, read by the checks, as in a full REASON
    phases = {
        "rules": _cpu(lambda: Materializer(store, rules).run()),
        "keys with facts": _cpu(lambda: keys.update(reasoner.key_graphs())),
        "consistency checks": _cpu(lambda: check_consistency(store, rules, keys)),
        "publish entailed": _cpu(lambda: publish_entailed(store, rules)),
        "counts": _cpu(lambda: (store.count(ASSERTED), store.count(INFERRED))),
    }
    graphs = {str(r["g"].value): int(r["n"].value) for r in store.query(
        "SELECT ?g (COUNT(*) AS ?n) WHERE { GRAPH ?g { ?s ?p ?o } } GROUP BY ?g")}
    profiled = Materializer(store, rules, profile=True)
    stats = profiled.run()
    per_rule = dict(sorted(stats.per_rule.items(), key=lambda kv: -kv[1]))
    return {"size": size, "load_cpu_s": load, "first_reason_cpu_s": first, "full_cpu_s": whole,
            "rounds": stats.rounds, "evaluations": stats.evaluations, "phases": phases, "graphs": graphs,
            "per_rule": per_rule, "peak_rss_mib": peak_rss_mib()}


def _child(size: str) -> dict[str, Any]:
    out = subprocess.run([sys.executable, "-m", "benchmarks.full_profile", "--one", size],
                         capture_output=True, text=True, check=True)
    return json.loads(out.stdout)


def report(rows: list[dict[str, Any]]) -> str:
    """The rows as text: one column per size, and the growth from the first size to the last."""
    def line(label: str, values: list[float], unit: str = "s") -> str:
        cells = "".join(f"{v:>12.3f}" for v in values)
        growth = f"{values[-1] / values[0]:>9.1f}x" if len(values) > 1 and values[0] > 0 else ""
        return f"{label:<34}{cells} {unit}{growth}"

    sizes = "".join(f"{r['size']:>12}" for r in rows)
    out = [f"{'locations':<34}{sizes}"]
    for key in ("load_cpu_s", "first_reason_cpu_s", "full_cpu_s"):
        out.append(line(key.removesuffix("_cpu_s").replace("_", " ") + " (CPU)", [r[key] for r in rows]))
    out.append(line("peak RSS", [r["peak_rss_mib"] for r in rows], "MiB"))
    out.append("phases of the full REASON (CPU):")
    for phase in rows[0]["phases"]:
        out.append(line("  " + phase, [r["phases"][phase] for r in rows]))
    out.append("quads per graph:")
    for graph in rows[-1]["graphs"]:
        out.append(line("  " + graph, [float(r["graphs"].get(graph, 0)) for r in rows], "quads"))
    out.append(f"rules, profiled (CPU; rounds {', '.join(str(r['rounds']) for r in rows)}):")
    for name in list(rows[-1]["per_rule"])[:20]:
        out.append(line("  " + name, [r["per_rule"].get(name, 0.0) for r in rows]))
    return "\n".join(out)


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("sizes", nargs="+", help="numbers of locations (even), each profiled in its own process")
    parser.add_argument("--one", action="store_true", help="profile the one size here and print JSON")
    parser.add_argument("--json", action="store_true", help="print the rows as JSON instead of the table")
    args = parser.parse_args(argv)
    if args.one:
        print(json.dumps(profile(args.sizes[0])))
        return
    rows = [_child(size) for size in args.sizes]
    print(json.dumps(rows) if args.json else report(rows))


if __name__ == "__main__":
    main()
