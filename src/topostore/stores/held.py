"""A reasoner's scratch graphs held in Python until SPARQL text needs them in the store.

Why this exists
---------------
A compiled robot step on a small map runs as index look-ups (:mod:`topostore.reason.staged`): it
writes a few facts at a time to a dozen scratch graphs (the step's changes, candidates, kept and
flipped facts), reads them back by pattern, and drops every scratch graph at the end of the REASON.
In Oxigraph's in-memory store each of those writes is a bulk ``extend`` (a few microseconds for one
quad), each drop a ``remove_graph``, and every removed quad stays in the index until the store is
compacted, slowing the reads that follow.  Held here, a write is a dictionary insert, a read of one to
three facts a short scan, and a drop forgets the dictionary.

The store stays the one source of truth for everything else: a graph is held only while nothing but
the quad API has touched it since it was last dropped.  The first SPARQL request (which may read or
write any graph), a transactional write, or a graph growing past :data:`HELD_MAX` quads moves the
held facts into the store (:meth:`HeldGraphs.take`), and the graph stays there until it is dropped.
A literal is held in the form the store would give back (:func:`.literal_forms.stored_literal`), and
asked for in that form, so presence and pattern reads answer as the store's index would.
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator

from pyoxigraph import Literal, NamedNode, Quad, Triple

from .literal_forms import stored_literal

#: a held graph past this many quads goes to the store (a held read is a scan)
HELD_MAX = 64


def _stored(o):
    return stored_literal(o) if isinstance(o, Literal) else o


class HeldGraphs:
    """The scratch graphs of one store held in Python (see the module's docstring)."""

    __slots__ = ("_last", "active", "eligible", "graphs", "in_store", "needed", "reasoning")

    def __init__(self) -> None:
        #: graphs that may be held: a reasoner's scratch graphs, which only it reads and which it drops
        self.eligible: frozenset[NamedNode] = frozenset()
        #: held graph -> {(subject, predicate, stored object): the triple as read back, or None until
        #: first read}; a graph is absent once empty or in the store
        self.graphs: dict[NamedNode, dict[tuple, Triple | None]] = {}
        #: eligible graphs whose facts may be in the store (moved there, or open to SPARQL) until dropped
        self.in_store: set[NamedNode] = set()
        #: whether writes are held in this REASON: not after a REASON whose SPARQL needed the scratch
        #: graphs in the store (a map whose steps run SPARQL would only pay the move)
        self.active = True
        #: a scratch graph was written since the last drop of them all (a REASON is under way)
        self.reasoning = False
        #: SPARQL ran in the REASON under way
        self.needed = False
        #: (the eligible graphs, the graphs last dropped, what :meth:`_dropping` found of them)
        self._last: tuple | None = None

    def holds(self, graph) -> bool:
        """Whether writes to ``graph`` are held here (eligible, and nothing of it is in the store);
        an eligible graph written to the store instead is remembered as there."""
        if graph not in self.eligible:
            return False
        self.reasoning = True
        if self.active and graph not in self.in_store:
            return True
        self.in_store.add(graph)
        return False

    def sparql(self) -> None:
        """SPARQL is about to run: where a REASON is under way, the next one writes to the store."""
        if self.reasoning:
            self.needed = True

    def settle(self) -> None:
        """Every scratch graph was dropped (a REASON ended): the next REASON holds its writes unless
        this one ran SPARQL."""
        self.active = not self.needed
        self.reasoning = self.needed = False

    def add(self, triples: Iterable[Triple], graph: NamedNode) -> list[Quad] | None:
        """Hold ``triples`` in ``graph``; returns the quads the store must take instead when the graph
        grew past :data:`HELD_MAX` (every quad of it, the graph then in the store), else None.

        Held by their terms, not as quads: pyoxigraph makes a quad or a triple of a literal ten times
        slower than of IRIs (≈ 1.5 µs), and most held facts are never read back as one."""
        held = self.graphs.get(graph)
        if held is None:
            held = self.graphs[graph] = {}
        for t in triples:
            o = t.object
            if isinstance(o, Literal):
                stored = stored_literal(o)
                if stored != o:
                    held[(t.subject, t.predicate, stored)] = None  # its triple made when read
                    continue
            held[(t.subject, t.predicate, o)] = t
        if not held:
            del self.graphs[graph]
            return None
        if len(held) <= HELD_MAX:
            return None
        del self.graphs[graph]
        self.in_store.add(graph)
        return [Quad(s, p, o, graph) for s, p, o in held]

    def match(self, s, p, o, graph) -> Iterator[Quad]:
        """The held quads of ``graph`` (None: of every held graph) matching the pattern (None: any)."""
        if o is not None:
            o = _stored(o)
        graphs = self.graphs.items() if graph is None else ((graph, self.graphs.get(graph, {})),)
        return iter([Quad(qs, qp, qo, g) for g, held in graphs for qs, qp, qo in held
                     if (s is None or qs == s) and (p is None or qp == p) and (o is None or qo == o)])

    def triples(self, s, p, o, held: dict) -> list[Triple]:
        """The triples of one held graph's facts ``held`` matching the pattern (None: any), as
        :meth:`match` finds them but without a quad made per read (a triple made once per fact)."""
        if o is not None:
            o = _stored(o)
        out = []
        for key, t in held.items():
            qs, qp, qo = key
            if (s is None or qs == s) and (p is None or qp == p) and (o is None or qo == o):
                if t is None:
                    t = held[key] = Triple(qs, qp, qo)
                out.append(t)
        return out

    def any_match(self, s, p, o, held: dict) -> bool:
        """Whether one of a held graph's facts ``held`` matches the pattern (:meth:`triples`' first)."""
        if o is not None:
            o = _stored(o)
        for qs, qp, qo in held:
            if (s is None or qs == s) and (p is None or qp == p) and (o is None or qo == o):
                return True
        return False

    def quads(self, graph: NamedNode) -> list[Quad] | None:
        """Every held quad of ``graph`` (None where it is not held)."""
        held = self.graphs.get(graph)
        return None if held is None else [Quad(s, p, o, graph) for s, p, o in held]

    def has(self, quad: Quad) -> bool:
        """Whether a quad of a held graph is there (its literal compared as the store would)."""
        held = self.graphs.get(quad.graph_name)
        if held is None:
            return False
        return (quad.subject, quad.predicate, _stored(quad.object)) in held

    def discard(self, triples: Iterable[Triple], graph: NamedNode) -> None:
        """Remove ``triples`` from a held graph, present or not."""
        held = self.graphs.get(graph)
        if held is None:
            return
        for t in triples:
            held.pop((t.subject, t.predicate, _stored(t.object)), None)
        if not held:
            del self.graphs[graph]

    def take(self, writes: bool) -> list[Quad]:
        """Every held quad, for the store to take: SPARQL is about to run, which may read any scratch
        graph, so they are in the store from now until they are dropped; with ``writes`` (an update or
        a transactional write, which may write any scratch graph) every eligible graph is."""
        quads = [Quad(s, p, o, g) for g, held in self.graphs.items() for s, p, o in held]
        self.in_store.update(self.eligible if writes else self.graphs)
        self.graphs.clear()
        return quads

    def drop(self, graphs: list[NamedNode]) -> list[NamedNode]:
        """Forget ``graphs``; those the store may hold facts of (the store drops them too).  Dropping
        every eligible graph ends a REASON (:meth:`settle`)."""
        members, outside, covers = self._dropping(graphs)
        in_store = self.in_store
        if covers:  # every held graph and every graph in the store is eligible: forgotten without a hash each
            dropped = [*outside, *in_store]
            self.graphs.clear()
            in_store.clear()
            self.settle()
            return dropped
        dropped = list(dict.fromkeys([*outside, *(g for g in in_store if g in members)])) if in_store else list(outside)
        held = self.graphs
        if held:
            for g in [g for g in held if g in members]:
                del held[g]
        if in_store:
            in_store.difference_update(members)
        return dropped

    def _dropping(self, graphs: list[NamedNode]) -> tuple[frozenset[NamedNode], list[NamedNode], bool]:
        """``graphs`` as a set, those of them not eligible, and whether they are every eligible graph;
        kept for the last list asked about while the eligible graphs stay the same (a reasoner drops the
        same two dozen graphs after every REASON, and hashing a term costs pyoxigraph a call each)."""
        graphs = tuple(graphs)
        last = self._last
        if last is not None and last[0] is self.eligible and last[1] == graphs:
            return last[2]
        members = frozenset(graphs)
        eligible = self.eligible
        found = (members, [g for g in graphs if g not in eligible], bool(eligible) and eligible <= members)
        self._last = (eligible, graphs, found)
        return found


__all__ = ["HELD_MAX", "HeldGraphs"]
