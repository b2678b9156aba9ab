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
step after step, so :class:`.kinds.Decisions` keeps what was decided for each (until the next full run).
"""

from __future__ import annotations

from collections.abc import Callable, Iterable

from pyoxigraph import NamedNode, Triple

from ..rdf.terms import Term
from ..rdf.vocab import TYPE
from ..stores.base import Store
from . import after
from .entailed import ENTAILED_TYPE
from .plan import LATERAL_MAX, KeyCounts
from .scratch import NEW_FACTS, OVERDELETED
from .triggers import Present

_TYPE_KEY, _ENTAILED_TYPE_KEY = str(TYPE), str(ENTAILED_TYPE)

#: quads of a scratch graph read into memory at most; a larger graph is read by pattern or counted by query
SMALL = 2000


class ChangedGraphs:
    """The scratch graphs of one REASON, each read at most once (:meth:`forget` when they are dropped).

    A graph read into memory is gone through once (:meth:`_scan`) for all four readers: its facts per
    read key, its type facts (real or entailed-only) and its facts of the watched predicates (those
    whose entailed-only conclusions are published, in real or internal form; :mod:`.entailed`)."""

    def __init__(self, store: Store, flush: Callable[[], None],
                 watched: dict[NamedNode, NamedNode] | None = None) -> None:
        """``flush`` sends what the reasoner still queues (before a graph is read); ``watched``: each
        form (real or internal) of a predicate whose touched triples :meth:`touched_watched` tells →
        the real predicate."""
        self.store = store
        self._flush = flush
        self.watched = watched or {}
        #: the watched forms' texts (what :meth:`_scan` compares)
        self._watched_keys = frozenset(str(form) for form in self.watched)
        self._quads: dict[NamedNode, list[tuple] | None] = {}
        self._keys: dict[NamedNode, KeyCounts] = {}
        #: per graph scanned: its (individual, class) type facts, and its watched facts (subject, form, object)
        self._types: dict[NamedNode, list[tuple[Term, NamedNode]]] = {}
        self._watched: dict[NamedNode, list[tuple[Term, NamedNode, Term]]] = {}

    def quads(self, graph: NamedNode) -> list[tuple] | None:
        """Every fact of ``graph`` as its (subject, predicate, object) (:meth:`.Store.small_terms`); None
        when it is large or the store is reached over HTTP (the caller then reads by pattern or query)."""
        if graph not in self._quads:
            self._flush()
            self._quads[graph] = self.store.small_terms(graph, SMALL)
        return self._quads[graph]

    def _scan(self, graph: NamedNode) -> bool:
        """Go through the quads of ``graph`` once (False when it is not read into memory)."""
        if graph in self._keys:
            return graph in self._types
        quads = self.quads(graph)
        if quads is None:
            return False
        preds: dict[str, int] = {}
        classes: dict[str, int] = {}
        types: list[tuple[Term, NamedNode]] = []
        watched, seen = self._watched_keys, []
        for s, p, o in quads:  # compared by their text: a pyoxigraph term's equality or hash is a call
            key = str(p)
            preds[key] = preds.get(key, 0) + 1
            if key == _TYPE_KEY or key == _ENTAILED_TYPE_KEY:
                if key == _TYPE_KEY:
                    c = str(o)
                    classes[c] = classes.get(c, 0) + 1
                if isinstance(o, NamedNode):
                    types.append((s, o))
            if watched and key in watched:
                seen.append((s, p, o))
        self._keys[graph] = (preds, classes)
        self._types[graph] = types
        self._watched[graph] = seen
        return True

    def keys(self, *graphs: NamedNode) -> list[KeyCounts]:
        """Facts per predicate and per class in each of ``graphs`` (their read keys): counted from the
        quads read, else those not counted yet by one census (one query where reads are round trips)."""
        for graph in graphs:
            self._scan(graph)
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
            if graph in self._types:  # gone through for the other reads already
                touched.update(dict.fromkeys(self._types[graph]))
                continue
            quads = self.quads(graph)
            if quads is not None:  # its type facts only: no key counted, no text made per fact
                for s, p, o in quads:
                    if (p == TYPE or p == ENTAILED_TYPE) and isinstance(o, NamedNode):
                        touched[(s, o)] = None
                continue
            for predicate in (TYPE, ENTAILED_TYPE):
                for t in self.store.triples(None, predicate, None, graph):
                    if isinstance(t.object, NamedNode):
                        touched[(t.subject, t.object)] = None
        return list(touched)

    def touched_watched(self, graphs: Iterable[NamedNode]) -> tuple[list[Triple], set[Triple]] | None:
        """The triples of the watched predicates in ``graphs`` (as the real triple, without duplicates),
        and those of them found in internal form; None when a graph is not read into memory."""
        found: dict[Triple, None] = {}
        internal: set[Triple] = set()
        watched = self.watched
        for graph in graphs:
            if not self._scan(graph):
                return None
            for s, form, o in self._watched[graph]:
                real = watched[form]
                t = Triple(s, real, o)
                found[t] = None
                if form != real:
                    internal.add(t)
        return list(found), internal

    def forget(self) -> None:
        """The graphs were dropped (or are about to be written again)."""
        self._quads.clear()
        self._keys.clear()
        self._types.clear()
        self._watched.clear()


def shape(counts: list[KeyCounts], clean: frozenset, present: Present) -> tuple:
    """What a read after maintenance decides from: the changed keys of each graph (each with whether it
    is small, :func:`.plan.is_small`), the cleanly replaced predicates and the keys with facts (a set that only
    grows until the next full run, so its size tells it)."""
    small = tuple(sum(preds.values()) <= LATERAL_MAX for preds, _ in counts)
    # in a small graph every key is small (a class's type facts are among its facts): the keys alone tell it
    keys = tuple((frozenset(preds), frozenset(classes)) if few else
                 frozenset((kind, key, n <= LATERAL_MAX) for kind, found in (("p", preds), ("t", classes))
                           for key, n in found.items())
                 for (preds, classes), few in zip(counts, small, strict=True))
    return keys, small, clean, len(present[0]), len(present[1])


__all__ = ["ChangedGraphs", "SMALL", "shape"]
