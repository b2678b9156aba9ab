"""Which of the read keys the rules need have facts: one query, whatever the size of the data.

Maintenance skips evaluations that cannot match (:meth:`.triggers.Triggers.feasible`) from the keys
with facts after a full run.  Only the keys some rule or check body reads are ever asked about, so
those are the ones looked up: one existence test each, instead of listing every distinct predicate
and class of the graphs (two scans of every quad: 0.13 s at 10,000 locations, 1.5 s at 100,000).
One query rather than a look-up per key, so that a store reached over HTTP pays one round trip.
"""

from __future__ import annotations

from collections.abc import Iterable

from pyoxigraph import NamedNode

from ..compile.rule import ReadKey
from ..rdf.vocab import TYPE
from ..stores.base import Store
from .triggers import Present


def keys_with_facts(store: Store, keys: Iterable[ReadKey], graphs: list[NamedNode]) -> Present:
    """The predicates (``("p", …)``) and classes (``("t", …)``) among ``keys`` with at least one fact
    in the union of ``graphs`` (a superset: a key that is no IRI counts as having facts); other kinds
    of key (``("*",)``) are not asked about."""
    keys = set(keys)
    preds = sorted(k[1] for k in keys if k[0] == "p" and k[1].startswith("<"))
    classes = sorted(k[1] for k in keys if k[0] == "t" and k[1].startswith("<"))
    # a key that is no IRI cannot be a VALUES term: counted as having facts (the result is a superset)
    found: Present = ({k[1] for k in keys if k[0] == "p" and not k[1].startswith("<")},
                      {k[1] for k in keys if k[0] == "t" and not k[1].startswith("<")})
    branches = []
    if preds:
        branches.append(f"{{ VALUES ?p {{ {' '.join(preds)} }} FILTER EXISTS {{ ?s ?p ?o }} }}")
    if classes:
        branches.append(f"{{ VALUES ?c {{ {' '.join(classes)} }} FILTER EXISTS {{ ?s {TYPE} ?c }} }}")
    if not branches:
        return found
    for row in store.query("SELECT ?p ?c WHERE { " + " UNION ".join(branches) + " }", graphs=graphs):
        if row["p"] is not None:
            found[0].add(str(row["p"]))
        if row["c"] is not None:
            found[1].add(str(row["c"]))
    return found


__all__ = ["keys_with_facts"]
