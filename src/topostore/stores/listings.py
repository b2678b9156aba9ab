"""What this process knows of a remote store without asking: the values of (subject, predicate, graph).

Why
---
On a store reached over HTTP every read is a round trip.  A robot step replaces the same few values
every step (``isIn``, ``now``, ``visitedAt`` of the place it reaches): a REPLACE reads the values of
its (individual, property) to match the old one, and the reasoner reads them again to find what a
replaced value flipped.  Those reads are the ones this process answered itself a moment ago: it read
the values once and every change since was its own write.

A :class:`Listings` keeps, for each (subject, predicate, graph) read completely, the committed quads
keyed by :meth:`~topostore.stores.base.Store._key` (a literal by its value), and applies the store's
own writes to them.  It is sound because one process writes a reference: the store's writer lock
(:mod:`topostore.stores.lock`) refuses a second one.  A write this process cannot follow (a SPARQL
update, a dropped graph) forgets the graphs it may have changed; the caller of an update that
leaves some graphs alone says so with :meth:`keeping` (the reasoner writes only its own graphs).

On a large map the robot reaches a place it has not replaced a value of before at almost every
step; reading that place's values would be a round trip per step.  So the second time a
(predicate, graph) is missed, the store reads the whole predicate at once (when it has at most
:data:`MAX_WHOLE` facts) and knows it *whole*: a subject without a listing then has no value.
"""

from __future__ import annotations

from collections.abc import Callable, Hashable, Iterable, Iterator
from contextlib import contextmanager

from pyoxigraph import NamedNode, Quad

from ..rdf.terms import Term

#: at most this many (subject, predicate, graph) listings are kept (the oldest learnt go first)
MAX_LISTINGS = 50_000
#: a predicate with at most this many facts in a graph is read whole on its second miss
MAX_WHOLE = 20_000

_Pattern = tuple[Term, NamedNode, NamedNode]


class Listings:
    """Complete committed values of (subject, predicate, graph) patterns, kept up to date by own writes."""

    def __init__(self, key: Callable[[Quad], Hashable]) -> None:
        self._key = key
        self._lists: dict[_Pattern, dict[Hashable, Quad]] = {}
        #: graphs the updates being sent now leave unchanged (see :meth:`keeping`)
        self._kept: frozenset[NamedNode] = frozenset()
        #: (predicate, graph) known whole: a subject without a listing has no value there
        self._whole: dict[tuple[NamedNode, NamedNode], None] = {}
        #: listings missed per (predicate, graph), to read a predicate whole on its second miss
        self._misses: dict[tuple[NamedNode, NamedNode], int] = {}

    def __len__(self) -> int:
        return len(self._lists)

    @property
    def kept(self) -> frozenset[NamedNode]:
        """The graphs the updates being sent now leave unchanged (declared with :meth:`keeping`)."""
        return self._kept

    def get(self, s: Term, p: NamedNode, graph: NamedNode) -> list[Quad] | None:
        """The committed quads of the pattern, or None when not known."""
        found = self._lists.get((s, p, graph))
        if found is None:
            return [] if (p, graph) in self._whole else None
        return list(found.values())

    def learn(self, s: Term, p: NamedNode, graph: NamedNode, quads: Iterable[Quad]) -> None:
        """A complete read of the pattern (committed state, nothing pending in between)."""
        if (s, p, graph) not in self._lists:
            self._make_room(1)
        self._lists[(s, p, graph)] = {self._key(q): q for q in quads}

    def missed(self, p: NamedNode, graph: NamedNode) -> bool:
        """Count a listing of ``p`` in ``graph`` read from the store; True on the second (read it whole)."""
        n = self._misses[(p, graph)] = self._misses.get((p, graph), 0) + 1
        return n == 2

    def learn_whole(self, p: NamedNode, graph: NamedNode, quads: Iterable[Quad]) -> None:
        """A complete read of every (subject, ``p``) in ``graph``: the predicate is known whole."""
        by_subject: dict[Term, dict[Hashable, Quad]] = {}
        for q in quads:
            by_subject.setdefault(q.subject, {})[self._key(q)] = q
        if len(by_subject) > MAX_LISTINGS // 2:
            return
        self._make_room(len(by_subject))
        for subject, found in by_subject.items():
            self._lists[(subject, p, graph)] = found
        self._whole[(p, graph)] = None

    def _make_room(self, n: int) -> None:
        """Evict the oldest listings until ``n`` more fit; a predicate that loses one is no longer whole."""
        while self._lists and len(self._lists) + n > MAX_LISTINGS:
            s, p, g = next(iter(self._lists))
            del self._lists[(s, p, g)]
            self._whole.pop((p, g), None)

    def presence(self, quad: Quad, key: Hashable) -> bool | None:
        """Whether the quad is committed (by its key), or None when its pattern is not known."""
        found = self._lists.get((quad.subject, quad.predicate, quad.graph_name))
        if found is None:
            return False if (quad.predicate, quad.graph_name) in self._whole else None
        return key in found

    def committed(self, adds: Iterable[Quad], removes: Iterable[Quad], stored: Callable[[Quad], Quad]) -> None:
        """Own writes, removals first (as :meth:`~topostore.stores.base.Store._commit` applies them);
        ``stored`` gives an added quad as the store will hold it (numbers canonicalised), so a listing
        answers what a read would."""
        if not self._lists:
            return
        for q in removes:
            found = self._lists.get((q.subject, q.predicate, q.graph_name))
            if found is not None:
                found.pop(self._key(q), None)
        for q in adds:
            found = self._lists.get((q.subject, q.predicate, q.graph_name))
            if found is None and (q.predicate, q.graph_name) in self._whole:
                self._make_room(1)
                found = self._lists[(q.subject, q.predicate, q.graph_name)] = {}
            if found is not None:
                found.setdefault(self._key(q), stored(q))

    def updated(self) -> None:
        """A SPARQL update was sent: forget every graph it may have changed."""
        if self._lists or self._whole:
            self._lists = {k: v for k, v in self._lists.items() if k[2] in self._kept}
            self._whole = {k: v for k, v in self._whole.items() if k[1] in self._kept}

    def forget(self, graph: NamedNode | None = None) -> None:
        """Forget one graph (dropped), or everything (None: writes were lost, the server is the truth)."""
        self._lists = {} if graph is None else {k: v for k, v in self._lists.items() if k[2] != graph}
        self._whole = {} if graph is None else {k: v for k, v in self._whole.items() if k[1] != graph}

    @contextmanager
    def keeping(self, graphs: Iterable[NamedNode]) -> Iterator[None]:
        """Updates sent inside the block leave ``graphs`` unchanged (their listings stay)."""
        before = self._kept
        self._kept = before | frozenset(graphs)
        try:
            yield
        finally:
            self._kept = before


__all__ = ["Listings", "MAX_LISTINGS", "MAX_WHOLE"]
