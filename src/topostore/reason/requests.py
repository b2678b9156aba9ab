"""How incremental maintenance sends its SPARQL: evaluations queued and joined into one request.

The evaluations of one phase write graphs the others of that phase do not read
(or only benefit from reading), so one update request per phase gives the same
result as one per evaluation and saves the per-request cost (~0.1 ms each).
Texts are made once per (phase, rule, atom, plan) and cached.  With
``profile``, each evaluation runs and is timed on its own.
"""

from __future__ import annotations

import time
from collections.abc import Collection, Iterable

from pyoxigraph import NamedNode, Quad, Triple

from ..compile.generic import PREFIXES
from ..compile.rule import Rule
from ..stores.base import Store, data_update
from .plan import KeyCounts, is_small, key_counts
from .scratch import rule_start
from .stats import ReasonStats


class RequestQueue:
    """The update queue and SPARQL text cache that the phases of one incremental REASON share.

    :class:`~.incremental.IncrementalReasoner` owns one; its deletion phases
    (:class:`~.dred.Deletion`) and its flips (:class:`~.flips.Flips`) queue
    evaluations here, so that one request carries a whole phase.
    """

    def __init__(self, store: Store, rules: list[Rule]) -> None:
        self.store = store
        self.rules = rules
        #: time each evaluation on its own (set per REASON)
        self.profile = False
        #: SPARQL texts by (phase, rule, atom, plan): made once, sent many times
        self.texts: dict[tuple, str] = {}
        self.queue: list[str] = []
        #: is the graph the next evaluation starts from small (per-solution plans)?
        self.lateral = store.supports_lateral
        #: read keys of the graph evaluations start from, with counts
        self.counts: KeyCounts = ({}, {})

    def run(self, key: tuple, make, i: int, j: int | None, stats: ReasonStats) -> None:
        """Queue one evaluation; :meth:`flush` sends the queue as one update request.

        The evaluations of one phase write graphs the others of that phase do
        not read (or only benefit from reading, as PROVEN), so one request
        gives the same result and saves the per-request cost (~0.1 ms each).
        When profiling, each runs on its own to be timed.
        """
        self.lateral = is_small(self.counts, rule_start(self.rules[i], j, key[0])) and self.store.supports_lateral
        key = (*key, self.lateral)
        text = self.texts.get(key)
        if text is None:
            text = self.texts[key] = make(i, j)
        stats.evaluations += 1
        if self.profile:
            self.update(text, stats, f"{key[0]}:{self.rules[i].name}")
        else:
            self.queue.append(text)

    def start(self, graph: NamedNode) -> KeyCounts:
        """The evaluations that follow start from ``graph``: its read keys, and their sizes for the plans."""
        self.counts = self.keys(graph)
        return self.counts

    def defer(self, text: str) -> None:
        """Queue a bookkeeping update to go with the next request (they run in queue order)."""
        self.queue.append(text)

    def flush(self) -> None:
        """Send what is queued as one update request."""
        if self.queue:
            text = " ;\n".join(self.queue)
            self.queue.clear()
            self.store.update(text, prefixes=PREFIXES)

    def update(self, text: str, stats: ReasonStats, label: str) -> None:
        """Send ``text`` now (after the queue), timed under ``label`` when profiling."""
        self.flush()
        if not self.profile:
            self.store.update(text, prefixes=PREFIXES)
            return
        start = time.perf_counter()
        self.store.update(text, prefixes=PREFIXES)
        stats.per_rule[label] = stats.per_rule.get(label, 0.0) + time.perf_counter() - start

    def keys(self, graph: NamedNode) -> KeyCounts:
        """Predicates and classes (of rdf:type facts) in ``graph``, with counts: the read keys it changes."""
        return key_counts(self.store, graph)

    def scratch(self, triples: Iterable[Triple], graph: NamedNode) -> None:
        """Copy triples into a scratch graph as they are.

        Not through :meth:`Store.add`, which would record the literals' written
        forms for a graph that is dropped with SPARQL and never shown.  Where
        every write is a round trip, the copy waits in the request queue and
        goes with the next update.
        """
        if not self.store.round_trips:
            self.store.add_scratch(triples, graph)
        elif quads := [Quad(t.subject, t.predicate, t.object, graph) for t in triples]:
            self.defer(data_update(quads, []))

    def discard(self, triples: Collection[Triple], graphs: tuple[NamedNode, ...]) -> None:
        """Remove triples from reasoner graphs, present or not (queued where writes are round trips)."""
        if not self.store.round_trips:
            self.store.discard(triples, graphs)
        elif quads := [Quad(t.subject, t.predicate, t.object, g) for t in triples for g in graphs]:
            self.defer(data_update([], quads))

    def drop(self, graphs: Iterable[NamedNode]) -> None:
        """Drop scratch graphs after what is queued: with the queue's next request where every request
        is a round trip, else at once (:meth:`Store.drop_graphs`)."""
        graphs = list(graphs)
        if self.store.round_trips:
            self.defer(" ; ".join(f"DROP SILENT GRAPH {g}" for g in graphs))
            return
        self.flush()
        self.store.drop_graphs(graphs)

    def clear(self) -> None:
        """Forget what is queued (after a failed REASON)."""
        self.queue.clear()


class LaterCopies:
    """Scratch copies written once, when first called: a REASON's asserted changes go to ADDED and
    REMOVED only where SPARQL text reads them (the general phases, a compiled operation sent as text);
    a compiled step run by look-ups alone writes the changes where it reads them and needs no copy."""

    __slots__ = ("copies", "done", "requests")

    def __init__(self, requests: RequestQueue, copies: tuple[tuple[Collection[Triple], NamedNode], ...]) -> None:
        self.requests = requests
        #: (triples, scratch graph) pairs
        self.copies = copies
        self.done = False

    def __call__(self) -> None:
        if not self.done:
            self.done = True
            for triples, graph in self.copies:
                self.requests.scratch(triples, graph)


__all__ = ["LaterCopies", "RequestQueue"]
