"""Reads that cost one request where every read is a round trip: a part of every store (``store.batched``).

Why
---
On a store reached over HTTP (:class:`~topostore.stores.remote.RemoteStore`) the robot's questions
would each be a query per graph: the values of a property in the asserted, inferred and entailed
graphs, the membership of the individuals a REASON touched, the values a REPLACE replaces.  This part
answers them from what the store knows without asking (:mod:`.listings`) and asks the rest in one
query: several (subject, predicate) pairs, one pair in several graphs, or one pair's values together
with the presence of a few quads (two questions of one robot step, one request).  In memory and on
disk, where reads cost microseconds, every method reads the store's indexes as it always did.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from pyoxigraph import NamedNode, Quad, Triple

from ..rdf.terms import Term
from .listings import MAX_WHOLE

if TYPE_CHECKING:
    from .base import Store


class BatchedReads:
    """The batched and listed reads of one :class:`~topostore.stores.base.Store`."""

    def __init__(self, store: Store) -> None:
        self._store = store

    def listed(self, s: Term, p: NamedNode, graph: NamedNode) -> list[Triple]:
        """:meth:`Store.triples` of (s, p, ?, graph) from its listing (read once, then kept by own writes;
        the second predicate missed is read whole), with the open transaction's changes on top."""
        store, listings = self._store, self._store.listings
        quads = listings.get(s, p, graph)
        if quads is None and listings.missed(p, graph) and self._learn_whole(p, graph):
            quads = listings.get(s, p, graph)
        if quads is None:
            quads = list(store._match(s, p, None, graph))
            listings.learn(s, p, graph, quads)
        pending = store._pending
        if pending is None:
            return [q.triple for q in quads]
        out = []
        for q in quads:
            key = store._key(q)
            store._known[key] = True
            entry = pending.get(key)
            if entry is None:  # a pending write of its value stands for it (adding a held value: a respelling)
                out.append(q.triple)
        out += [q.triple for q, present in list(pending.values())
                if present and q.subject == s and q.predicate == p and q.graph_name == graph]
        return out

    def _learn_whole(self, p: NamedNode, graph: NamedNode) -> bool:
        """Read every fact of ``p`` in ``graph`` into the listings when there are few enough (one query)."""
        rows = self._store._predicate_rows(p, graph, MAX_WHOLE + 1)
        if len(rows) > MAX_WHOLE:
            return False
        self._store.listings.learn_whole(p, graph, (Quad(s, p, o, graph) for s, o in rows))
        return True

    def objects_many(self, pairs: list[tuple[Term, NamedNode]], graph: NamedNode) -> dict[tuple, list[Term]]:
        """:meth:`Store.objects` of several (subject, predicate) pairs; one query where reads are round trips."""
        store = self._store
        found: dict[tuple, list[Term]] = {pair: [] for pair in pairs}
        if not store.round_trips or not pairs:
            return {pair: store.objects(*pair, graph) for pair in found}
        store._flush_open()
        listings = store.listings
        missing = [pair for pair in found if listings is None or listings.get(*pair, graph) is None]
        if missing:
            rows = " ".join(f"({s} {p})" for s, p in missing)
            for r in store._run_query(f"SELECT ?s ?p ?o WHERE {{ VALUES (?s ?p) {{ {rows} }} ?s ?p ?o }}", [graph]):
                found[(r["s"], r["p"])].append(r["o"])
        for pair in found:
            if pair in missing:
                if listings is not None:
                    listings.learn(*pair, graph, (Quad(*pair, o, graph) for o in found[pair]))
            else:
                found[pair] = [q.object for q in listings.get(*pair, graph)]
        return found

    def objects_in(self, s: Term, p: NamedNode, graphs: list[NamedNode]) -> dict[NamedNode, list[Term]]:
        """:meth:`Store.objects` of one (subject, predicate) in each of ``graphs``: where reads are round
        trips, from the listings and one query for the graphs not known (then kept)."""
        store, listings = self._store, self._store.listings
        if listings is None or store._pending is not None:
            return store.objects_by_graph(s, p, graphs)
        found: dict[NamedNode, list[Term]] = {}
        for g in graphs:
            quads = listings.get(s, p, g)
            if quads is not None:
                found[g] = [q.object for q in quads]
        missing = [g for g in graphs if g not in found]
        if len(missing) == 1:
            found[missing[0]] = store.objects(s, p, missing[0])
        elif missing:
            rows: dict[NamedNode, list[Quad]] = {g: [] for g in missing}
            for r in store.query(f"SELECT ?g ?o WHERE {{ GRAPH ?g {{ {s} {p} ?o }} }}", graphs=missing):
                g = store._graph_in(r["g"])
                rows[g].append(Quad(s, p, r["o"], g))
            for g, quads in rows.items():
                listings.learn(s, p, g, quads)
                found[g] = [q.object for q in quads]
        return {g: found[g] for g in graphs}

    def objects_and_presence(self, s: Term, p: NamedNode, graphs: list[NamedNode],
                             quads: list[Quad]) -> tuple[dict[NamedNode, list[Term]], list[bool]]:
        """:meth:`objects_in` and :meth:`Store.contains_quads` together: one query where reads are round
        trips and neither is known already."""
        store, listings = self._store, self._store.listings
        if listings is None or store._pending is not None or not quads:
            return self.objects_in(s, p, graphs), store.contains_quads(quads)
        missing = [g for g in graphs if listings.get(s, p, g) is None]
        keys = [store._key(q) for q in quads]
        unknown = [q for q, k in zip(quads, keys, strict=True) if listings.presence(q, k) is None]
        if not missing or not unknown:
            return self.objects_in(s, p, graphs), store.contains_quads(quads)
        rows = " ".join(f"({q.subject} {q.predicate} {q.object} {q.graph_name})" for q in unknown)
        text = (f"SELECT ?g ?o ?qs ?qp ?qo WHERE {{ {{ VALUES ?g {{ {' '.join(map(str, missing))} }} "
                f"GRAPH ?g {{ {s} {p} ?o }} }} UNION {{ VALUES (?qs ?qp ?qo ?g) {{ {rows} }} GRAPH ?g {{ ?qs ?qp ?qo }} }} }}")
        dataset = list(dict.fromkeys([*missing, *(q.graph_name for q in unknown)]))
        values: dict[NamedNode, list[Quad]] = {g: [] for g in missing}
        found: set = set()
        for r in store.query(text, graphs=dataset):
            g = store._graph_in(r["g"])
            if r["o"] is not None:
                values[g].append(Quad(s, p, r["o"], g))
            else:
                found.add(store._key(Quad(r["qs"], r["qp"], r["qo"], g)))
        for g, learnt in values.items():
            listings.learn(s, p, g, learnt)
        objects = {g: [q.object for q in listings.get(s, p, g) or values.get(g, [])] for g in graphs}
        presence = [listings.presence(q, k) for q, k in zip(quads, keys, strict=True)]
        return objects, [k in found if known is None else known for k, known in zip(keys, presence, strict=True)]

    def subjects_in(self, p: NamedNode, o: Term, graphs: list[NamedNode]) -> list[Term]:
        """:meth:`Store.subjects` in any of ``graphs``, each once: one query where reads are round trips."""
        store = self._store
        if not store.round_trips or store._pending is not None:
            return list(dict.fromkeys(s for g in graphs for s in store.subjects(p, o, g)))
        return [r["s"] for r in store.query(f"SELECT DISTINCT ?s WHERE {{ ?s {p} {o} }}", graphs=graphs)]


__all__ = ["BatchedReads"]
