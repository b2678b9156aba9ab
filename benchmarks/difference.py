"""Where the difference helper facts cost in a full REASON: ``python -m benchmarks.difference N`` prints JSON.

A SWRL rule with a DifferentIndividuals atom and every OWL rule that needs two values told apart
(minimum cardinality, functional properties) ask for *candidate* pairs; the generic rules in
``rules/`` and the compiled ``different-*`` rules turn a candidate into a declared difference
(AllDifferent group keys, owl:differentFrom, disjoint classes) or an entailed one (two values of a
property allowing one), and every declared difference is copied into ``ts:different``.  On a chain
map of N locations (:mod:`benchmarks.maps`) this prints:

* ``reason_cpu_s``: the full REASON's CPU time; ``helper_facts``: the helper graph per predicate;
* ``per_rule_s``: wall time per rule name of a profiled run (``stats.per_rule``), the difference
  rules (``different*``, ``all-different``) summed in ``difference_rules_s``;
* ``inline``: for each SWRL rule reading a declared difference, the CPU time of its body as a
  ``SELECT`` over the reasoned store in three shapes: the body alone, with the materialised
  declared-difference atom (as the rule runs), and with the declared difference tested inline
  (``FILTER(EXISTS …)`` over the AllDifferent keys, owl:differentFrom both ways and the disjoint
  class pairs) instead of materialised candidate and difference facts.  Since
  :mod:`topostore.compile.inline_difference` a rule with one difference atom (and an OWL minimum of
  two fillers) joins the declared-difference rules into its body, so only rules that still read the
  materialised relation are listed (two or more difference atoms); the list was how the join was
  chosen (docs/benchmarks-history.md).  ``ts:valueCandidate`` in ``helper_facts`` are the pairs asked of
  the value rules alone (an entailed-only SWRL conclusion's).
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

from pyoxigraph import RdfFormat

from topostore import Ontology
from topostore.compile.generic import PREFIXES
from topostore.compile.rule import Rule
from topostore.rdf.vocab import ASSERTED, AUX, DECLARED_DIFFERENT, INFERRED, INTERNAL, OWL, TYPE

from . import maps
from .limits import lift_time_limit

DIFFERENCE_NAMES = ("different", "different-candidate", "different-disjoint", "different-values", "all-different")
DATASET = f"FROM {ASSERTED} FROM {INFERRED} FROM {AUX} FROM NAMED {AUX}"
PROLOGUE = "".join(f"PREFIX {p}: <{iri}>\n" for p, iri in PREFIXES.items())
KEY_OF = f"<{INTERNAL}differentKeyOf>"


def group_test(a: str, b: str) -> str:
    """EXISTS: ``a`` and ``b`` hold two different keys of one AllDifferent group (rules/different-by-group.rq)."""
    group = 'STRBEFORE(STRAFTER(STR({k}), "urn:topostore:key:"), ":")'
    return (f"EXISTS {{ GRAPH {AUX} {{ ?k1_ {KEY_OF} {a} . ?k2_ {KEY_OF} {b} }} "
            f"FILTER(!sameTerm(?k1_, ?k2_) && {group.format(k='?k1_')} = {group.format(k='?k2_')}) }}")


def disjoint_pairs(rules: list[Rule]) -> list[tuple[str, str]]:
    """The ordered (class, class) pairs of the compiled ``different-disjoint`` rules."""
    pairs = []
    for r in rules:
        if r.name == "different-disjoint":
            types = {a.s: a.o for a in r.body if a.p == str(TYPE)}
            pairs.append((types["?a"], types["?b"]))
    return pairs


def inline_test(a: str, b: str, pairs: list[tuple[str, str]]) -> str:
    """A FILTER testing declared difference of ``a`` and ``b`` without candidate or difference facts."""
    tests = [group_test(a, b), f"EXISTS {{ {a} <{OWL}differentFrom> {b} }}",
             f"EXISTS {{ {b} <{OWL}differentFrom> {a} }}"]
    if pairs:
        values = " ".join(f"({c1} {c2})" for c1, c2 in pairs)
        tests.append(f"EXISTS {{ {a} {TYPE} ?c1_ . VALUES (?c1_ ?c2_) {{ {values} }} {b} {TYPE} ?c2_ }}")
    return f"FILTER({' || '.join(tests)})"


def timed_count(onto: Ontology, where: str, repeats: int = 2) -> tuple[float, int]:
    """The best CPU time of ``SELECT (COUNT(*))`` over ``where``, and the count."""
    best, count = float("inf"), 0
    for _ in range(repeats):
        start = time.process_time()
        rows = list(onto.store.query(f"{PROLOGUE}SELECT (COUNT(*) AS ?n) {DATASET} WHERE {{ {where} }}"))
        best = min(best, time.process_time() - start)
        count = int(rows[0]["n"].value)
    return best, count


def inline_rows(onto: Ontology) -> list[dict[str, Any]]:
    """The three shapes of every SWRL rule reading a declared difference (see the module docstring)."""
    rules = onto.rules.inference_rules
    pairs = disjoint_pairs(rules)
    out = []
    for rule in rules:
        declared = [a for a in rule.body if a.p == str(DECLARED_DIFFERENT)]
        if not declared or not rule.name.startswith("swrl:"):
            continue
        rest = dataclasses.replace(rule, body=tuple(a for a in rule.body if a not in declared))
        tests = " ".join(inline_test(a.s, a.o, pairs) for a in declared)
        shapes = {"body": rest.where(), "materialised": rule.where(), "inline": f"{rest.where()}\n  {tests}"}
        row: dict[str, Any] = {"rule": rule.origin}
        for shape, where in shapes.items():
            seconds, count = timed_count(onto, where)
            row[shape] = {"cpu_s": round(seconds, 4), "rows": count}
        out.append(row)
    return out


def run(locations: str, work: Path) -> dict[str, Any]:
    path, _ = maps.write(locations, work, RdfFormat.N_TRIPLES)
    onto = Ontology()
    onto.load(path)
    start = time.process_time()
    onto.reason(mode="full")
    reason_cpu = time.process_time() - start
    helper = {str(r["p"].value): int(r["n"].value) for r in onto.store.query(
        f"SELECT ?p (COUNT(*) AS ?n) WHERE {{ GRAPH {AUX} {{ ?s ?p ?o }} }} GROUP BY ?p")}
    profiled = Ontology()
    profiled.load(path)
    per_rule = profiled.reason(mode="full", profile=True).stats.per_rule
    return {"locations": int(locations), "reason_cpu_s": round(reason_cpu, 3), "helper_facts": helper,
            "per_rule_s": {k: round(v, 4) for k, v in sorted(per_rule.items(), key=lambda kv: -kv[1])},
            "difference_rules_s": round(sum(v for k, v in per_rule.items() if k in DIFFERENCE_NAMES), 3),
            "inline": inline_rows(onto)}


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("locations", help="a number of locations (a chain map)")
    args = parser.parse_args(argv)
    lift_time_limit()
    with tempfile.TemporaryDirectory(prefix="topostore-bench-") as tmp:
        print(json.dumps(run(args.locations, Path(tmp)), indent=1))
    sys.exit(0)


if __name__ == "__main__":
    main()
