"""What one incremental REASON changed, as the reads after maintenance see it.

After maintenance the scratch graphs NEW_FACTS and OVERDELETED hold every triple whose presence in
the asserted, inferred or helper graph changed (a superset, in real or internal form).  Four reads
follow in memory: whether a rule with a negated premise may now match, which consistency checks may,
the entailed-only refresh (:mod:`.entailed`) and the type facts the class views re-decide.  Each
graph is small after a robot step but full of removed quads (Oxigraph keeps them until the store is
compacted), so :class:`ChangedGraphs` reads each one once from the index and shares the quads and
their read keys among the four.

What the first two reads decide depends only on the *shape* of the change (:func:`shape`): the
changed keys, the cleanly replaced predicates, the keys with facts.  A robot repeats a few shapes
step after step, so :class:`Decisions` keeps what was decided for each (until the next full run).
"""

from __future__ import annotations

from collections.abc import Callable

from pyoxigraph import NamedNode, Quad

from ..rdf.terms import Term
from ..rdf.vocab import TYPE
from ..stores.base import Store, key_census
from . import after
from .entailed import ENTAILED_TYPE
from .plan import LATERAL_MAX, KeyCounts
from .scratch import NEW_FACTS, OVERDELETED
from .triggers import Present

#: quads of a scratch graph read into memory at most; a larger graph is read by pattern or counted by query
SMALL = 2000


class ChangedGraphs:
    """The scratch graphs of one REASON, each read at most once (:meth:`forget` when they are dropped)."""

    def __init__(self, store: Store, flush: Callable[[], None]) -> None:
        """``flush`` sends what the reasoner still queues (before a graph is read)."""
        self.store = store
        self._flush = flush
        self._quads: dict[NamedNode, list[Quad] | None] = {}
        self._keys: dict[NamedNode, KeyCounts] = {}

    def quads(self, graph: NamedNode) -> list[Quad] | None:
        """Every quad of ``graph``; None when it is large or the store is reached over HTTP (the caller
        then reads by pattern or query)."""
        if graph not in self._quads:
            self._flush()
            self._quads[graph] = self.store.small_graph(graph, SMALL)
        return self._quads[graph]

    def keys(self, *graphs: NamedNode) -> list[KeyCounts]:
        """Facts per predicate and per class in each of ``graphs`` (their read keys): counted from the
        quads read, else those not counted yet by one census (one query where reads are round trips)."""
        for graph in graphs:
            if graph not in self._keys and (quads := self.quads(graph)) is not None:
                self._keys[graph] = key_census(quads)
        if missing := [g for g in graphs if g not in self._keys]:
            self._keys.update(self.store.census_many(missing))
        return [self._keys[g] for g in graphs]

    def touched_types(self) -> list[tuple[Term, NamedNode]]:
        """(individual, class) of every type fact, real or entailed-only, whose presence the maintenance
        may have changed (what the class views re-decide)."""
        if self.store.round_trips:  # one query instead of four pattern reads
            text = f"SELECT DISTINCT ?s ?c WHERE {{ {after.touched_types('?s', '?c')} }}"
            return [(r["s"], r["c"]) for r in self.store.query(text)]
        touched: dict[tuple[Term, NamedNode], None] = {}
        for graph in (NEW_FACTS, OVERDELETED):
            quads = self.quads(graph)
            found = (q for q in quads if q.predicate in (TYPE, ENTAILED_TYPE)) if quads is not None else \
                (t for predicate in (TYPE, ENTAILED_TYPE) for t in self.store.triples(None, predicate, None, graph))
            for t in found:
                if isinstance(t.object, NamedNode):
                    touched[(t.subject, t.object)] = None
        return list(touched)

    def forget(self) -> None:
        """The graphs were dropped (or are about to be written again)."""
        self._quads.clear()
        self._keys.clear()


def shape(counts: list[KeyCounts], clean: frozenset, present: Present) -> tuple:
    """What a read after maintenance decides from: the changed keys (each with whether it is small,
    :func:`.plan.is_small`), the cleanly replaced predicates and the keys with facts (a set that only
    grows until the next full run, so its size tells it)."""
    keys = frozenset((kind, key, n <= LATERAL_MAX) for preds, classes in counts
                     for kind, found in (("p", preds), ("t", classes)) for key, n in found.items())
    small = all(sum(preds.values()) <= LATERAL_MAX for preds, _ in counts)
    return keys, small, clean, len(present[0]), len(present[1])


class Decisions:
    """What the reads after maintenance decided, by what and :func:`shape` (at most ``limit`` kept)."""

    def __init__(self, limit: int) -> None:
        self.limit = limit
        self._decided: dict[tuple, object] = {}

    def get(self, key: tuple, decide: Callable[[], object]) -> object:
        """The decision kept for ``key``, or ``decide()`` kept from now on."""
        if key in self._decided:
            return self._decided[key]
        if len(self._decided) >= self.limit:
            self._decided.clear()
        value = self._decided[key] = decide()
        return value

    def clear(self) -> None:
        """A full run recounted the keys with facts: decide afresh."""
        self._decided.clear()


__all__ = ["ChangedGraphs", "Decisions", "SMALL", "shape"]
