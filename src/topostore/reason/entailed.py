"""Publishing the conclusions drawn with entailed-only difference.

A SWRL rule whose DifferentIndividuals atom holds only by entailment (the two
individuals are not declared different, but equating them would be
inconsistent) still has an entailed conclusion, which Pellet reports; Pellet
finds it by refutation and never uses it to fire other rules.  The compiler
derives such conclusions in the helper graph under an internal predicate (so no
rule reads them); this step copies them, under their real predicate, into the
ENTAILED graph that queries see.  It runs after every REASON and costs one
indexed scan per such predicate.
"""

from __future__ import annotations

from pyoxigraph import NamedNode

from ..compile.rule import RuleSet
from ..store import Store
from ..vocab import ASSERTED, AUX, ENTAILED, ENTAILED_PREFIX, INFERRED


def publish_entailed(store: Store, rules: RuleSet) -> None:
    ops = [f"DROP SILENT GRAPH {ENTAILED}"]
    for p in sorted(rules.entailed_predicates, key=lambda t: t.value):
        internal = NamedNode(ENTAILED_PREFIX + p.value)
        ops.append(
            f"INSERT {{ GRAPH {ENTAILED} {{ ?s {p} ?o }} }} WHERE {{ GRAPH {AUX} {{ ?s {internal} ?o }} "
            f"FILTER NOT EXISTS {{ GRAPH {INFERRED} {{ ?s {p} ?o }} }} FILTER NOT EXISTS {{ GRAPH {ASSERTED} {{ ?s {p} ?o }} }} }}"
        )
    store.update(" ; ".join(ops))
