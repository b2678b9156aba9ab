"""How incremental maintenance sends its SPARQL: evaluations queued and joined into one request.

The evaluations of one phase write graphs the others of that phase do not read
(or only benefit from reading), so one update request per phase gives the same
result as one per evaluation and saves the per-request cost (~0.1 ms each).
Texts are made once per (phase, rule, atom, plan) and cached.  With
``profile``, each evaluation runs and is timed on its own.
"""

from __future__ import annotations

import time

from pyoxigraph import NamedNode

from ..compile.generic import PREFIXES
from ..compile.rule import Rule
from ..stores.base import Store
from .materialize import ReasonStats
from .plan import KeyCounts, is_small, key_counts
from .scratch import rule_start


class Requests:
    """The request queue and text cache of :class:`~.incremental.IncrementalReasoner` (set up by it)."""

    store: Store
    rules: list[Rule]
    profile: bool
    _texts: dict[tuple, str]
    _queue: list[str]
    #: is the graph the next evaluation starts from small (per-solution plans)?
    _lateral: bool
    #: read keys of the graph evaluations start from, with counts
    _counts: KeyCounts

    def _run(self, key: tuple, make, i: int, j: int | None, stats: ReasonStats) -> None:
        """Queue one evaluation; :meth:`_flush` sends the queue as one update request.

        The evaluations of one phase write graphs the others of that phase do
        not read (or only benefit from reading, as PROVEN), so one request
        gives the same result and saves the per-request cost (~0.1 ms each).
        When profiling, each runs on its own to be timed.
        """
        self._lateral = is_small(self._counts, rule_start(self.rules[i], j, key[0])) and self.store.supports_lateral
        key = (*key, self._lateral)
        text = self._texts.get(key)
        if text is None:
            text = self._texts[key] = make(i, j)
        stats.evaluations += 1
        if self._profiling(stats):
            self._update(text, stats, f"{key[0]}:{self.rules[i].name}")
        else:
            self._queue.append(text)

    def _start(self, graph: NamedNode) -> KeyCounts:
        """The evaluations that follow start from ``graph``: its read keys, and their sizes for the plans."""
        self._counts = self._keys(graph)
        return self._counts

    def _defer(self, text: str) -> None:
        """Queue a bookkeeping update to go with the next request (they run in queue order)."""
        self._queue.append(text)

    def _flush(self) -> None:
        if self._queue:
            text = " ;\n".join(self._queue)
            self._queue.clear()
            self.store.update(text, prefixes=PREFIXES)

    def _update(self, text: str, stats: ReasonStats, label: str) -> None:
        self._flush()
        if not self._profiling(stats):
            self.store.update(text, prefixes=PREFIXES)
            return
        start = time.perf_counter()
        self.store.update(text, prefixes=PREFIXES)
        stats.per_rule[label] = stats.per_rule.get(label, 0.0) + time.perf_counter() - start

    def _profiling(self, stats: ReasonStats) -> bool:
        """Whether to time each update (and count what the phases did): only with ``profile``."""
        return self.profile

    def _keys(self, graph: NamedNode) -> KeyCounts:
        """Predicates and classes (of rdf:type facts) in ``graph``, with counts: the read keys it changes."""
        return key_counts(self.store, graph)


__all__ = ["Requests"]
