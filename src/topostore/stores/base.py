"""The one store interface every other module talks to.

All reasoning goes through :meth:`Store.query` and :meth:`Store.update` with
graphs named explicitly, so the same rules run against Oxigraph in memory or on
disk (:mod:`.oxigraph`) and against a remote SPARQL 1.1 server (:mod:`.remote`).

Two details of the store are handled here so that nobody else has to know them:

* Blank nodes are *skolemised* on load (``urn:topostore:bnode:…``): the rule
  compiler must name class expressions and SWRL atoms inside SPARQL text, which
  is impossible for blank nodes.  They become blank nodes again on save.
* Oxigraph keeps numbers in canonical form (``"7"^^xsd:long`` is stored as
  ``"7"^^xsd:integer``).  The asserted lexical form and datatype of every
  literal is remembered so that answers and saved files show what the user wrote.
"""

from __future__ import annotations

import logging
import os
from collections.abc import Callable, Iterable, Iterator, Mapping
from contextlib import contextmanager

from pyoxigraph import DefaultGraph, Literal, NamedNode, Quad, RdfFormat, Triple

from ..rdf.safeio import read_regular_file
from ..rdf.skolem import fresh_skolem, skolem, skolemize, unskolem, unskolemize
from ..rdf.syntax import FORMAT_NAMES, PROGRESS_EVERY, guess_format, parse_triples, serialize
from ..rdf.terms import Term, value_key
from ..rdf.vocab import SKOLEM_PREFIX
from . import presence, reads, respelling, work
from .batched import BatchedReads
from .data_text import data_update, quad_data
from .listings import Listings
from .literal_forms import FORMS, LiteralForms
from .meta import META, PersistedState
from .reads import key_census
from .work import BULK_ADD


class Store:
    """The store interface every other module talks to: quads in, SPARQL in, results out.

    This class holds what every implementation shares: the unit of work (transactions, pending writes,
    presence: the functions of :mod:`.work`) and the reads (:mod:`.reads`), both bound as its methods, and
    named parts: the literal forms users wrote (``forms``, :class:`.literal_forms.LiteralForms`),
    the small persisted state of a reference (``persisted``, :class:`.meta.PersistedState`), what a
    store reached over HTTP knows without asking (``listings``, :class:`.listings.Listings`) and the
    reads batched for it (``batched``, :class:`.batched.BatchedReads`),
    on top of a few primitives each implementation provides: ``_has``,
    ``_match``, ``_commit``, ``_run_update``, ``_run_query`` and ``_drop``.
    Implementations: :class:`topostore.stores.oxigraph.OxigraphStore` (memory
    or RocksDB on disk) and :class:`topostore.stores.remote.RemoteStore` (a
    SPARQL 1.1 Query + Update endpoint pair); :func:`topostore.stores.open_store`
    picks one from a ``store`` setting and :func:`topostore.stores.memory_store` gives a fresh in-memory one
    (this base never builds a subclass itself).

    Writes (``add``/``remove``/``meta_set``) are grouped by :meth:`transaction`
    into one atomic commit; reads inside a transaction see its pending writes.
    """

    #: Can the compiled rules use Oxigraph's LATERAL joins on this store?
    supports_lateral = True
    #: Can this store run extension functions handed to it (:meth:`use_functions`)?
    custom_functions = True
    #: Does this store outlive the process (disk, remote server)?
    durable = False
    #: every read and write is a network round trip: callers batch them into few requests
    round_trips = False
    #: whether a long multi-operation update request gives what its operations give sent one by one
    #: (where a request is a round trip, the compiled step sends its whole program as one request)
    whole_programs = True
    #: whether a literal read from this store is in the form Oxigraph stores it (its own stored form)
    canonical_reads = False
    #: whether a read-only query may run in a second thread while this thread writes (in memory: the
    #: store's own engine, which releases the GIL; :mod:`.overlap` holds the contract)
    overlaps = False

    def __init__(self) -> None:
        #: how each committed literal was written (Oxigraph canonicalises numbers)
        self.forms = LiteralForms(self)
        #: the small JSON state kept beside the data (``meta``/``meta_set``)
        self.persisted = PersistedState(self)
        # quad key -> (quad, present after commit) while a transaction is open
        self._pending: dict[tuple, tuple[Quad, bool]] | None = None
        # quad key -> present in the committed store, learnt during the open transaction (saves round trips)
        self._known: dict[tuple, bool] = {}
        self._depth = 0
        #: write operations that may have changed a graph of data (every one but a reasoner's writes to its own
        #: graphs: :meth:`add_scratch`, :meth:`discard`, :meth:`drop_graphs`, :meth:`add_ntriples`); never goes
        #: back, so that what was read of the asserted graph at one count holds while the count is the same
        #: (:class:`~.one_fact.KeptFacts`)
        self.data_writes = 0
        #: SPARQL extension functions by IRI (the rule compiler's, see :meth:`use_functions`)
        self.functions: dict[NamedNode, Callable[..., Term | None]] = {}
        #: values of (subject, predicate, graph) this process knows without asking (stores reached over HTTP)
        self.listings: Listings | None = Listings(self._key) if self.round_trips else None
        #: reads that cost one request where reads are round trips (see :mod:`.batched`)
        self.batched = BatchedReads(self)
        #: called with the writes a store that defers them could not apply, and whether that is certain
        #: (see :meth:`_writes_lost`)
        self.on_lost: list[Callable[[list[tuple[list[Quad], list[Quad]]], bool], None]] = []
        #: called with the writes (adds, removes) an outermost transaction held pending when it failed:
        #: never written, they are undone by whoever recorded them as made (the ontology's ledger)
        self.on_rolled_back: list[Callable[[list[Quad], list[Quad]], None]] = []

    def use_functions(self, functions: Mapping[NamedNode, Callable[..., Term | None]]) -> None:
        """Let SPARQL run on this store call ``functions`` (IRI -> Python function of RDF terms).

        The compiled rules need one (swrlb:pow, :data:`topostore.compile.builtins.FUNCTIONS`);
        the engine hands them over, so the store knows nothing of rules.  A store that cannot
        run them (``custom_functions`` false) keeps them unused; such rules are refused at load
        (:func:`topostore.stores.check_rules`).
        """
        self.functions.update(functions)

    # ------------------------------------------------------------ the parts, as every caller reads them
    @property
    def meta(self) -> dict[str, object]:
        """The small JSON state a durable store keeps beside the data (settings, flags)."""
        return self.persisted.values

    def meta_set(self, key: str, value: object) -> None:
        """Persist ``key`` (JSON value) with the current transaction; no-op on a memory store."""
        self.persisted.set(key, value)

    @property
    def writes_pending(self) -> bool:
        """Whether the open transaction holds writes not committed yet: a SPARQL query would commit them
        first (so that it sees them), which a reader that must leave the transaction undoable avoids."""
        return bool(self._pending)

    def original_literal(self, graph: NamedNode, s: Term, p: NamedNode, o: Literal) -> Literal:
        """The literal as the user asserted it (lexical form and datatype); inside a transaction, as its pending
        write adds it (read-your-writes: the literal forms learn it at the commit)."""
        if not self._pending:
            return self.forms.original_literal(graph, s, p, o)
        value = value_key(o)
        pending = work.pending_literal(self, graph, s, p, value)
        return pending if pending is not None else self.forms.written(graph, s, p, o, value)

    def kept_literal(self, graph: NamedNode, s: Term, p: NamedNode, value: tuple | None) -> Literal | None:
        """The spelling kept for this one fact (``value``: its value key): the open transaction's pending
        addition of it, else the form kept at the last commit; None when neither is."""
        pending = work.pending_literal(self, graph, s, p, value) if self._pending else None
        return pending if pending is not None else self.forms.recorded(graph, s, p, value)

    def restore(self, term: Term) -> Term:
        """A literal as users wrote it, when that value was written in one form only."""
        return self.forms.restore(term)

    def stored_form(self, t: Triple, written: Quad | None = None) -> Triple:
        """The triple as this store holds it once added (Oxigraph canonicalises some literals); ``written``:
        a quad of it made already (see :meth:`LiteralForms.stored_form`)."""
        return self.forms.stored_form(t, written)

    # ------------------------------------------------------------ the unit of work (see .work), bound as methods
    transaction = work.transaction
    _begin = work.begin
    _end = work.end
    _flush = work.flush
    _flush_open = work.flush_open
    _key = presence.key
    _present = presence.present
    add = work.add
    add_new = work.add_new
    remove_present = work.remove_present
    remove = work.remove
    _toggle_each = work.toggle_each
    _toggle_absent = work.toggle_absent
    _add_to_empty = work.add_to_empty
    fact = work.fact
    read_facts = work.read_facts
    unread_fact = work.unread_fact
    written_fact = work.written_fact
    pending_add = work.pending_add
    toggle_facts = work.toggle_facts
    restore_facts = respelling.restore_facts
    _removal_quad = work.removal_quad

    # ------------------------------------------------------------ the reads (see .reads), bound as methods
    triples = reads.triples
    few_facts = reads.few_facts
    objects = reads.objects
    objects_many = reads.objects_many
    subjects = reads.subjects
    list_items = reads.list_items
    list_read = reads.list_read
    contains = reads.contains
    contains_each = reads.contains_each
    contains_quads = reads.contains_quads
    known_in = reads.known_in
    contains_terms = reads.contains_terms
    census = reads.census
    census_many = reads.census_many
    small_graph = reads.small_graph
    small_terms = reads.small_terms
    count = reads.count
    is_empty = reads.is_empty
    dump = reads.dump

    def objects_by_graph(self, s: Term, p: NamedNode, graphs: list[NamedNode]) -> dict[NamedNode, list[Term]]:
        """:meth:`objects` of one (subject, predicate) in each of ``graphs`` (a store reading its own
        index may read them all at once)."""
        return {g: self.objects(s, p, g) for g in graphs}

    def matches(self, s, p, o, graph: NamedNode, limit: int) -> list | None:
        """:meth:`few_facts` of one graph for a caller that reads only each fact's subject, predicate and
        object (a look-up join): a store reading its own index may give its quads as they come."""
        return self.few_facts(s, p, o, (graph,), limit)

    def has_match(self, s, p, o, graph: NamedNode) -> bool:
        """Whether ``graph`` holds a fact of the pattern (None: any)."""
        return next(iter(self.triples(s, p, o, graph)), None) is not None

    # ------------------------------------------------------------ primitives (implementations)
    def _has(self, quad: Quad) -> bool:
        raise NotImplementedError

    def _has_many(self, quads: list[Quad]) -> list[bool]:
        """Presence of several quads (one round trip where that matters)."""
        return [self._has(q) for q in quads]

    def _match(self, s, p, o, graph) -> Iterator[Quad]:
        raise NotImplementedError

    def _commit(self, adds: list[Quad], removes: list[Quad]) -> None:
        """Apply removals then additions, all or nothing."""
        raise NotImplementedError

    def _write(self, adds: list[Quad], removes: list[Quad], undo: Callable[[], None] | None = None) -> None:
        """Apply a data change (removals then additions) through :meth:`_commit`.

        A store that defers writes (:class:`~topostore.stores.remote.RemoteStore`) queues it instead and
        calls ``undo`` (what the caller recorded in memory for it) should the server refuse it later.
        """
        self.data_writes += 1  # counted first: a write that fails half-way counts too
        self._commit(adds, removes)
        self._written(adds, removes)

    def _written(self, adds: list[Quad], removes: list[Quad]) -> None:
        """A change is committed as far as this process is concerned: the listings follow it."""
        if self.listings is not None:
            self.listings.committed(adds, removes, self._stored_quad)

    def _stored_quad(self, q: Quad) -> Quad:
        if not isinstance(q.object, Literal):
            return q
        t = self.forms.stored_form(q.triple)
        return Quad(t.subject, t.predicate, t.object, q.graph_name)

    def _writes_lost(self, lost: list[tuple[list[Quad], list[Quad]]], certain: bool = True) -> None:
        """Deferred writes (oldest first) the server did not apply (``certain`` false: it did not answer, so
        it may have, or a lost write dropped graphs whose content is then unknown here): forget what this
        process believed of the committed state, and tell the owners (the ontology's ledger) so that they
        undo them too."""
        if self.listings is not None:
            self.listings.forget()
        self._known = {}
        self.persisted.forget()
        for listener in list(self.on_lost):
            listener(lost, certain)

    @contextmanager
    def keeping(self, graphs: Iterable[NamedNode]) -> Iterator[None]:
        """SPARQL updates sent inside the block leave ``graphs`` unchanged (what this process knows of
        them stays valid; see :mod:`.listings`).  The reasoner writes only its own graphs."""
        if self.listings is None:
            yield
            return
        with self.listings.keeping(graphs):
            try:
                yield
            except BaseException:
                self._settle_quietly()
                raise
        self._settle()

    def _settle(self) -> None:
        """The block of :meth:`keeping` is over: a store that deferred its updates sends them."""

    def _settle_quietly(self) -> None:
        """:meth:`_settle` while the block's own error propagates: a failure here is logged, not raised."""
        try:
            self._settle()
        except Exception as exc:  # noqa: BLE001 - the block's error is the one reported
            logging.getLogger("topostore.store").warning("sending the deferred updates failed too: %s", exc)

    def _run_update(self, text: str, prefixes: dict[str, str] | None) -> None:
        raise NotImplementedError

    def _run_query(self, text: str, graphs: list[NamedNode] | None, **kwargs):
        raise NotImplementedError

    def _drop(self, graph: NamedNode) -> None:
        self._run_update(f"DROP SILENT GRAPH {graph}", None)

    def drop_graphs(self, graphs: Iterable[NamedNode]) -> None:
        """Drop a reasoner's scratch graphs (no literal forms are kept for them): one update."""
        self.update(" ; ".join(f"DROP SILENT GRAPH {g}" for g in graphs))

    def close(self) -> None:
        """Release the store (files, connections, locks)."""

    # ------------------------------------------------------------ parsing
    def parse_file(
        self, path: str | os.PathLike[str], fmt: str | RdfFormat | None = None, base_iri: str | None = None,
        progress: Callable[[int], None] | None = None,
    ) -> list[Triple]:
        """Parse a document into skolemised triples without touching the store."""
        data = read_regular_file(path)  # regular files only, size-limited (LoadError otherwise)
        return self.parse_bytes(data, guess_format(path, fmt), base_iri, source=str(path), progress=progress)

    def parse_bytes(
        self, data: bytes | str, fmt: RdfFormat, base_iri: str | None = None, source: str = "<input>",
        progress: Callable[[int], None] | None = None,
    ) -> list[Triple]:
        """``progress(n)`` is called every ``PROGRESS_EVERY`` triples parsed (for progress displays)."""
        return parse_triples(data, fmt, base_iri, source, progress)

    # ------------------------------------------------------------ writes and reads an implementation specialises
    def _commit_stream(self, quads: Iterator[Quad], extra: list[Quad], count: bool = False) -> int | None:
        """Add ``quads`` (made one by one) and ``extra`` in one commit; stores that can take a
        stream without a list override this.  Asked to ``count``: how many quads the store gained,
        where it can tell that without a query (None otherwise, and here)."""
        self.data_writes += 1
        self._commit([*quads, *extra], [])
        return None

    def add_scratch(self, triples: Iterable[Triple], graph: NamedNode) -> None:
        """Bulk-add to a reasoner's scratch graph (no literal forms recorded, no counting)."""
        self._write([Quad(t.subject, t.predicate, t.object, graph) for t in triples], [])

    def hold_scratch(self, graphs: Iterable[NamedNode]) -> None:
        """``graphs`` are a reasoner's scratch graphs, read only by it and dropped by it at the end of every
        REASON: a store may hold what :meth:`add_scratch` writes to them outside its index until SPARQL
        needs them (the in-memory store does, see :mod:`.held`); here they are written at once."""

    def discard(self, triples: Iterable[Triple], graphs: Iterable[NamedNode]) -> None:
        """Remove triples from reasoner graphs, present or not (no literal forms are kept for those)."""
        graphs = tuple(graphs)
        quads = [Quad(t.subject, t.predicate, t.object, g) for t in triples for g in graphs]
        if quads:
            self._write([], quads)

    def _predicate_rows(self, p: NamedNode, graph: NamedNode, limit: int) -> list[tuple[Term, Term]]:
        """(subject, object) of up to ``limit`` facts of ``p`` in ``graph``."""
        text = f"SELECT ?s ?o WHERE {{ GRAPH {graph} {{ ?s {p} ?o }} }} LIMIT {limit}"
        return [(r["s"], r["o"]) for r in self._run_query(text, [graph])]

    def _graph_in(self, graph: NamedNode) -> NamedNode:
        """A graph name as a query answers it, in the engine's names (a remote store renames graphs)."""
        return graph

    def clear(self, graph: NamedNode) -> None:
        self._flush_open()
        self.data_writes += 1
        if self.listings is not None:
            self.listings.forget(graph)
        self._drop(graph)
        self.forms.forget(graph)

    # ------------------------------------------------------------ SPARQL
    def update(self, text: str, prefixes: dict[str, str] | None = None) -> None:
        self._flush_open()
        self.data_writes += 1  # SPARQL text may name any graph
        if self.listings is not None:
            self.listings.updated()
        self._run_update(text, prefixes)

    def add_ntriples(self, text: bytes, graph: NamedNode) -> None:
        """Add the triples of ``text`` (N-Triples this engine serialised: a query's answer) to ``graph``, as a
        SPARQL update inserting them would (no literal forms recorded: a reasoner's graph)."""
        self.update(f"INSERT DATA {{ GRAPH {graph} {{\n{text.decode()}\n}} }}")

    def add_ntriples_beside(self, text: bytes, graph: NamedNode) -> None:
        """:meth:`add_ntriples` from a second thread (:mod:`.overlap`), only where :attr:`overlaps` held."""
        self.add_ntriples(text, graph)

    def query(self, text: str, graphs: list[NamedNode] | None = None, named: list[NamedNode] | None = None,
              **kwargs):
        """Run a query whose default graph is the union of ``graphs`` (the named graphs: ``named``,
        by default ``graphs`` too)."""
        self._flush_open()
        return self._run_query(text, graphs, named=named, **kwargs)

    # ------------------------------------------------------------ housekeeping
    def maybe_compact(self) -> bool:
        """Reclaim space left by removed quads where the implementation needs it (see OxigraphStore)."""
        return False


__all__ = [
    "Store", "guess_format", "skolemize", "unskolemize", "skolem", "unskolem", "fresh_skolem",
    "serialize", "DefaultGraph", "SKOLEM_PREFIX", "FORMS", "META", "FORMAT_NAMES", "PROGRESS_EVERY",
    # at home in .work, .reads and .data_text; named here too, where their callers import them
    "BULK_ADD", "key_census", "data_update", "quad_data",
]
