"""pyoxigraph as a :class:`~topostore.stores.base.Store`: in memory, or durable in a RocksDB directory.

On disk, every commit of a transaction is one SPARQL update, which Oxigraph
runs as one RocksDB transaction: a manipulation is written whole or not at
all, and once written it survives the process being killed (RocksDB's
write-ahead log is in the operating system's hands).  It survives an OS crash
or a power loss only once flushed to disk: ``sync=True`` flushes after every
commit (see docs/stores.md).
"""

from __future__ import annotations

import logging
import os
from collections.abc import Iterable, Iterator
from itertools import chain, islice

import pyoxigraph as ox
from pyoxigraph import Literal, NamedNode, Quad

from ..errors import QueryError, StoreError
from . import index_reads, reads
from .base import Store
from .compaction import compacted
from .data_text import data_update, quad_data  # noqa: F401 - quad_data: named here since the first release
from .held import HeldGraphs
from .literal_forms import stored_literal
from .reads import key_census
from .text_writer import TextWriter

logger = logging.getLogger(__name__)


class OxigraphStore(Store):
    """An Oxigraph store in memory (``path=None``) or in a RocksDB directory."""

    canonical_reads = True

    def __init__(self, path: str | os.PathLike[str] | None = None, sync: bool = False) -> None:
        super().__init__()
        self.path = path
        self.sync = sync
        self.durable = path is not None
        try:
            self._ox = ox.Store(str(path)) if path is not None else ox.Store()
        except OSError as exc:
            if "lock" in str(exc).lower():
                raise StoreError(f"the store {str(path)!r} is open in another process (RocksDB holds its lock); "
                                 "stop that topostore process or use another --store directory") from None
            raise StoreError(f"cannot open the store {str(path)!r}: {exc}") from None
        self._in_memory = path is None
        self._writes = 0  # write operations since the last compaction
        self._live_at_compaction = 0
        #: a reasoner's scratch graphs held in Python while only the quad API reads them (in memory only)
        self._held = HeldGraphs()
        if self.durable:
            self.forms.load()

    @property
    def overlaps(self) -> bool:  # type: ignore[override]
        """In memory, with no transaction open and nothing held in Python: a query in a second thread
        then reads the engine alone (the GIL released), never this wrapper's pending or held quads."""
        return self._in_memory and self._pending is None and not self._held.graphs

    # ------------------------------------------------------------ primitives
    def _has(self, quad: Quad) -> bool:
        held = self._held.graphs
        if held and quad.graph_name in held:
            return self._held.has(quad)
        return quad in self._ox

    def _match(self, s, p, o, graph) -> Iterator[Quad]:
        if type(s) is Literal:
            return iter(())  # a literal is no subject (:meth:`few_facts`)
        held = self._held.graphs
        if held:
            if graph is None:
                return chain(self._ox.quads_for_pattern(s, p, o, None), self._held.match(s, p, o, None))
            if graph in held:
                return self._held.match(s, p, o, graph)
        return iter(self._ox.quads_for_pattern(s, p, o, graph))

    # ------------------------------------------------------------ the look-ups' reads (see .index_reads)
    triples = index_reads.triples
    few_facts = index_reads.few_facts
    matches = index_reads.matches
    has_match = index_reads.has_match
    match_in = index_reads.match_in
    objects_by_graph = index_reads.objects_by_graph
    known_in = index_reads.known_in
    contains_each = index_reads.contains_each

    # ------------------------------------------------------------ reasoner scratch graphs held in Python
    def hold_scratch(self, graphs: Iterable[NamedNode]) -> None:
        """In memory, writes to ``graphs`` through :meth:`add_scratch` are held in Python until SPARQL
        text or a transactional write needs them in the store (see :mod:`.held`); the reasoner that
        names them drops them all at the end of every REASON (:meth:`drop_graphs`)."""
        if self._in_memory:
            self._held.eligible = self._held.eligible | frozenset(graphs)

    def _release_held(self, writes: bool = True) -> None:
        """Every held quad into the store: what follows may read any scratch graph there (``writes``:
        and write any, so none is held again until it is dropped)."""
        self._held.sparql()
        if self._held.graphs:
            self._ox.extend(self._held.take(writes))
        elif writes and self._held.eligible:
            self._held.take(writes)

    def _commit(self, adds: list[Quad], removes: list[Quad]) -> None:
        self._writes += 1
        eligible = self._held.eligible
        if eligible:
            for q in chain(adds, removes):  # a loop, not any() over a generator: a manipulation writes one or two
                if q.graph_name in eligible:
                    self._release_held()
                    break
        if self._in_memory:
            for q in removes:
                self._ox.remove(q)
            self._ox.extend(adds)
            return
        text = data_update(adds, removes)
        if text:
            self._ox.update(text)
            if self.sync:
                self._ox.flush()

    def _commit_stream(self, quads: Iterator[Quad], extra: list[Quad], count: bool = False) -> int | None:
        """In memory, the store takes the quads as they are made (one atomic ``extend``); asked to
        ``count``, it counts its quads before and after (0.08 s for 900,000 quads, where a SPARQL count
        of the graph takes 0.45 s).  Written in chunks, each inserted in a second thread while the next
        is parsed, the same load cost 10-14 % more CPU and no less wall time (docs/benchmarks-history.md)."""
        if not self._in_memory:
            return super()._commit_stream(quads, extra, count)
        self._release_held()  # a bulk write may name any graph: not scanned for scratch graphs
        self._writes += 1
        before = len(self._ox) if count else 0
        self._ox.extend(chain(quads, extra))
        return len(self._ox) - before if count else None

    def bulk_stream_possible(self) -> bool:
        """Whether :meth:`bulk_stream` may write here: in memory, with no transaction open."""
        return self._in_memory and self._pending is None

    def quad_total(self) -> int:
        """The quads of every graph (the engine counts them: 0.08 s for 900,000 in memory, so once per load,
        never per piece of one)."""
        return len(self._ox)

    def bulk_stream(self, source, graph: NamedNode) -> None:
        """N-Triples read from ``source`` (a binary reader, read as it fills) into ``graph``: the store parses
        and indexes without a Python object per triple and without the GIL, so that whoever writes ``source``
        runs beside it.  ``load``, not ``bulk_load``: in memory both cost the same CPU (2.1-2.2 s for 900,000
        triples), but ``bulk_load`` indexes only once the stream has ended, ``load`` as it reads.  The
        caller empties the graph on failure.  ``lenient``: the text is pyoxigraph's own serialisation of
        terms it built, so IRIs are valid."""
        self._release_held()  # a bulk write may name any graph: not scanned for scratch graphs
        self._writes += 1
        self._ox.load(input=source, format=ox.RdfFormat.N_TRIPLES, to_graph=graph, lenient=True)

    def add_ntriples(self, text: bytes, graph: NamedNode) -> None:
        """In memory, the engine parses and inserts ``text`` itself (``load`` of bytes: no Python object per
        triple, 0.5 s for the 100,000 AllDifferent keys); ``lenient``: the engine serialised these terms."""
        if not self._in_memory:
            super().add_ntriples(text, graph)
            return
        self._flush_open()
        self._release_held()
        self.add_ntriples_beside(text, graph)

    def add_ntriples_beside(self, text: bytes, graph: NamedNode) -> None:
        """:meth:`add_ntriples` from the worker thread of :mod:`.overlap`, started where :attr:`overlaps` held
        (nothing open or held here to release): the engine's load alone, which waits for the caller's update."""
        self._writes += 1
        self._ox.load(text, format=ox.RdfFormat.N_TRIPLES, to_graph=graph, lenient=True)

    def text_writer(self, graph: NamedNode) -> TextWriter:
        """A writer of N-Triples pieces (``bytes``) into ``graph``, each indexed in a second thread while the
        caller makes the next (:mod:`.text_writer`): ``Store.load`` of bytes holds no GIL.  ``lenient`` as in
        :meth:`bulk_stream`: the text is pyoxigraph's own serialisation of terms it built.  Only where
        :meth:`bulk_stream_possible`; the caller empties the graph on failure."""
        self._release_held()  # a bulk write may name any graph: not scanned for scratch graphs
        self._writes += 1
        load, nt = self._ox.load, ox.RdfFormat.N_TRIPLES
        return TextWriter(lambda text: load(text, format=nt, to_graph=graph, lenient=True))

    def add_scratch(self, triples, graph: NamedNode) -> None:
        """Bulk-add to a reasoner's scratch graph (one RocksDB transaction), or hold the triples in
        Python where the graph is held (see :meth:`hold_scratch`).  An empty list writes nothing (a
        recheck that kept no candidate): no write counted, no graph marked as written."""
        if type(triples) is list and not triples:
            return
        held = self._held
        # a graph held already (written in this REASON) is eligible and not in the store: no second test
        if graph in held.graphs or (graph in held.eligible and held.holds(graph)):
            taken = held.add(triples, graph)
            if taken is None:
                return
            self._writes += 1
            self._ox.extend(taken)
            return
        self._writes += 1
        self._ox.extend([Quad(t.subject, t.predicate, t.object, graph) for t in triples])

    def discard(self, triples, graphs: Iterable[NamedNode]) -> None:
        """In memory, a triple with a literal object is found by its subject and predicate and removed as
        the index holds it: making a quad of a literal costs pyoxigraph several times a look-up, and the
        reasoner's graphs seldom hold the asserted triples it discards (one write, as on disk)."""
        if not self._in_memory or self._pending is not None:
            super().discard(triples, graphs)
            return
        graphs = tuple(graphs)
        if self._held.graphs:
            triples = list(triples)
            for g in graphs:
                self._held.discard(triples, g)
        self._writes += 1
        ox = self._ox
        for t in triples:
            s, p, o = t.subject, t.predicate, t.object
            if isinstance(o, Literal):
                o = stored_literal(o)
                for q in [q for g in graphs for q in ox.quads_for_pattern(s, p, None, g) if q.object == o]:
                    ox.remove(q)
            else:
                for g in graphs:
                    ox.remove(Quad(s, p, o, g))

    def drop_graphs(self, graphs: Iterable[NamedNode]) -> None:
        """In memory each graph is removed from the index directly (a SPARQL DROP of a dozen graphs costs
        its parse, ≈ 10 µs); on disk, one update (one RocksDB transaction)."""
        if not self._in_memory:
            super().drop_graphs(graphs)
            return
        self._flush_open()
        dropped = self._held.drop(list(graphs))
        if not dropped:
            return
        self._writes += 1
        for g in dropped:
            self._ox.remove_graph(g)

    def _run_update(self, text: str, prefixes: dict[str, str] | None) -> None:
        self._release_held()
        self._writes += 1
        try:
            self._ox.update(text, custom_functions=self.functions, prefixes=prefixes)
        except SyntaxError as exc:
            raise QueryError(f"malformed SPARQL update: {exc}") from exc
        except (OSError, RuntimeError) as exc:
            raise QueryError(f"SPARQL update failed: {exc}") from exc

    def _run_query(self, text: str, graphs: list[NamedNode] | None, named: list[NamedNode] | None = None,
                   **kwargs):
        kwargs.setdefault("custom_functions", self.functions)
        self._release_held(writes=False)
        try:
            if graphs is not None:
                named = graphs if named is None else named
                return self._ox.query(text, default_graph=list(graphs), named_graphs=list(named), **kwargs)
            return self._ox.query(text, **kwargs)
        except SyntaxError as exc:
            raise QueryError(f"malformed SPARQL query: {exc}") from exc
        except (OSError, RuntimeError) as exc:  # evaluation errors reported by Oxigraph
            raise QueryError(f"SPARQL evaluation failed: {exc}") from exc

    # ------------------------------------------------------------ reasoner scratch graphs
    def small_graph(self, graph: NamedNode, limit: int = 2000) -> list[Quad] | None:
        self._flush_open()
        held = self._held.graphs.get(graph)
        if held is not None:
            return self._held.quads(graph) if len(held) <= limit else None
        quads = list(islice(self._ox.quads_for_pattern(None, None, None, graph), limit + 1))
        return quads if len(quads) <= limit else None

    def small_terms(self, graph: NamedNode, limit: int = 2000) -> list[tuple] | None:
        """:func:`.reads.small_terms`; a held graph's facts as they are held (no quad made)."""
        self._flush_open()
        held = self._held.graphs.get(graph)
        if held is not None:
            return list(held) if len(held) <= limit else None
        return reads.small_terms(self, graph, limit)

    def census(self, graph: NamedNode, small: int = 2000) -> tuple[dict[str, int], dict[str, int]]:
        """Facts per predicate and per class in ``graph``, counted from the index up to ``small`` quads.

        Reasoning asks this of its small scratch graphs many times per REASON;
        reading the index costs microseconds where a GROUP BY query costs a
        parse and a plan.  Larger graphs are counted by a query.
        """
        quads = self.small_graph(graph, small)
        return key_census(quads) if quads is not None else super().census_many([graph])[graph]

    def census_many(self, graphs: list[NamedNode]) -> dict[NamedNode, tuple[dict[str, int], dict[str, int]]]:
        """Each graph counted from the index (see :meth:`census`): no query to batch in memory."""
        return {g: self.census(g) for g in graphs}

    def is_empty(self, graph: NamedNode) -> bool:
        self._flush_open()
        if graph in self._held.graphs:
            return False  # a held graph is never empty
        return next(iter(self._ox.quads_for_pattern(None, None, None, graph)), None) is None

    def close(self) -> None:
        if self.durable:
            self._ox.flush()
        del self._ox

    # ------------------------------------------------------------ housekeeping
    def maybe_compact(self) -> bool:
        """Rebuild the in-memory store once enough writes have piled up (:mod:`.compaction`)."""
        if not self._in_memory:
            return False
        try:
            fresh, self._live_at_compaction = compacted(self._ox, self._writes, self._live_at_compaction)
        except Exception as exc:  # noqa: BLE001 - an optimisation: the store stays as it is (the copy did not fit,
            # or the engine refused it), and a command that asked for it after its change was committed succeeds
            logger.warning("the in-memory store could not be compacted (%s); it stays as it is",
                           type(exc).__name__ if isinstance(exc, MemoryError) else exc)
            self._writes = 0
            return False
        if fresh is None:
            return False
        self._ox = fresh
        self._writes = 0
        return True


__all__ = ["OxigraphStore", "data_update", "quad_data"]
