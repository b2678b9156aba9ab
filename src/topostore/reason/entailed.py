"""Publishing the conclusions drawn with entailed-only difference.

A SWRL rule whose DifferentIndividuals atom holds only by entailment (the two
individuals are not declared different, but equating them would be
inconsistent) still has an entailed conclusion, which Pellet reports; Pellet
finds it by refutation and never uses it to fire other rules.  The compiler
derives such conclusions in the helper graph under an internal predicate (so no
rule reads them); this step copies them, under their real predicate, into the
ENTAILED graph that queries see, leaving out those already asserted or inferred.

After a full run the graph is rebuilt: one indexed scan per such predicate.
After incremental maintenance only the triples the maintenance touched can
have changed their standing, so only those are looked at: a triple is in
ENTAILED exactly when its internal twin is in the helper graph and the triple
is neither asserted nor inferred, and each of those three facts changes only
for triples in the graphs of facts new in the closure or deleted from it.
"""

from __future__ import annotations

from collections.abc import Sequence

from pyoxigraph import NamedNode

from ..compile.rule import RuleSet
from ..store import Store
from ..vocab import ASSERTED, AUX, ENTAILED, ENTAILED_PREFIX, INFERRED


def publish_entailed(store: Store, rules: RuleSet) -> None:
    """Rebuild the ENTAILED graph from the helper graph (after a full run)."""
    store.update(entailed_update(rules))


def entailed_update(rules: RuleSet, changed: Sequence[NamedNode] | None = None) -> str:
    """The update that brings ENTAILED up to date.

    ``changed``: graphs holding every triple whose presence in the asserted,
    inferred or helper graph changed since ENTAILED was last right (both forms,
    real and internal predicate); None rebuilds the whole graph.
    """
    predicates = sorted(rules.entailed_predicates, key=lambda t: t.value)
    if changed is None:
        return " ; ".join([f"DROP SILENT GRAPH {ENTAILED}", *(_insert(p, "") for p in predicates)])
    ops = []
    for p in predicates:
        touched = _touched(p, changed)
        ops.append(f"DELETE {{ GRAPH {ENTAILED} {{ ?s {p} ?o }} }} WHERE {{ {touched} GRAPH {ENTAILED} {{ ?s {p} ?o }} }}")
        ops.append(_insert(p, touched))
    return " ; ".join(ops)


def _internal(p: NamedNode) -> NamedNode:
    return NamedNode(ENTAILED_PREFIX + p.value)


def _insert(p: NamedNode, restriction: str) -> str:
    """Insert the conclusions of ``p`` that only entailment gives, among those ``restriction`` binds."""
    return (f"INSERT {{ GRAPH {ENTAILED} {{ ?s {p} ?o }} }} WHERE {{ {restriction} GRAPH {AUX} {{ ?s {_internal(p)} ?o }} "
            f"FILTER NOT EXISTS {{ GRAPH {INFERRED} {{ ?s {p} ?o }} }} "
            f"FILTER NOT EXISTS {{ GRAPH {ASSERTED} {{ ?s {p} ?o }} }} }}")


def _touched(p: NamedNode, changed: Sequence[NamedNode]) -> str:
    """Pattern binding ?s ?o of the ``p`` triples (real or internal) in the ``changed`` graphs."""
    graphs = " ".join(str(g) for g in changed)
    return (f"{{ SELECT DISTINCT ?s ?o WHERE {{ VALUES ?g {{ {graphs} }} VALUES ?q {{ {p} {_internal(p)} }} "
            f"GRAPH ?g {{ ?s ?q ?o }} }} }}")
