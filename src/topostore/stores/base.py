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
from collections.abc import Callable, Hashable, Iterable, Iterator, Mapping
from contextlib import contextmanager

from pyoxigraph import DefaultGraph, Literal, NamedNode, Quad, RdfFormat, Triple

from ..rdf.safeio import read_regular_file
from ..rdf.skolem import fresh_skolem, skolem, skolemize, unskolem, unskolemize
from ..rdf.syntax import FORMAT_NAMES, PROGRESS_EVERY, guess_format, parse_triples, serialize
from ..rdf.terms import Term, quad, triple, value_key
from ..rdf.vocab import FIRST, NIL, REST, SKOLEM_PREFIX, TYPE
from .batched import BatchedReads
from .facts import Fact, fact_of, fact_read
from .listings import Listings
from .literal_forms import FORMS, LiteralForms
from .meta import META, PersistedState

#: from this many quads on, :meth:`Store.add` asks whether the graph is empty (one look-up) and,
#: when it is, adds without looking each quad up
BULK_ADD = 1000


def key_census(facts: Iterable[Triple | Quad]) -> tuple[dict[str, int], dict[str, int]]:
    """Facts per predicate and per class (objects of rdf:type), keyed by SPARQL text: the read keys
    a set of facts changes, and how much (see :meth:`Store.census`)."""
    preds: dict[str, int] = {}
    classes: dict[str, int] = {}
    for f in facts:
        p = str(f.predicate)
        preds[p] = preds.get(p, 0) + 1
        if f.predicate == TYPE:
            c = str(f.object)
            classes[c] = classes.get(c, 0) + 1
    return preds, classes


def quad_data(quads: list[Quad]) -> str:
    """``GRAPH g { s p o . }`` blocks for INSERT/DELETE DATA, from pyoxigraph terms (escaped by pyoxigraph)."""
    by_graph: dict[str, list[str]] = {}
    for q in quads:
        by_graph.setdefault(str(q.graph_name), []).append(f"{q.subject} {q.predicate} {q.object} .")
    return " ".join(f"GRAPH {g} {{ {' '.join(lines)} }}" for g, lines in by_graph.items())


def data_update(adds: list[Quad], removes: list[Quad]) -> str:
    """One update request removing then adding quads (empty text when there is nothing to do)."""
    ops = []
    if removes:
        ops.append(f"DELETE DATA {{ {quad_data(removes)} }}")
    if adds:
        ops.append(f"INSERT DATA {{ {quad_data(adds)} }}")
    return " ;\n".join(ops)


class Store:
    """The store interface every other module talks to: quads in, SPARQL in, results out.

    This class holds what every implementation shares (parsing, transactions) and
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
        #: SPARQL extension functions by IRI (the rule compiler's, see :meth:`use_functions`)
        self.functions: dict[NamedNode, Callable[..., Term | None]] = {}
        #: values of (subject, predicate, graph) this process knows without asking (stores reached over HTTP)
        self.listings: Listings | None = Listings(self._key) if self.round_trips else None
        #: reads that cost one request where reads are round trips (see :mod:`.batched`)
        self.batched = BatchedReads(self)
        #: called with the writes a store that defers them could not apply, and whether that is certain
        #: (see :meth:`_writes_lost`)
        self.on_lost: list[Callable[[list[tuple[list[Quad], list[Quad]]], bool], None]] = []

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

    def original_literal(self, graph: NamedNode, s: Term, p: NamedNode, o: Literal) -> Literal:
        """The literal as the user asserted it (lexical form and datatype)."""
        return self.forms.original_literal(graph, s, p, o)

    def rewritten(self, graph: NamedNode, s: Term, p: NamedNode, o: Term) -> Literal | None:
        """The form the user wrote of ``o`` in ``graph`` where it differs from ``o``; None when ``o``
        is no literal or already that form (so a removal or an undo restores exactly what was written)."""
        if not isinstance(o, Literal):
            return None
        written = self.forms.original_literal(graph, s, p, o)
        return None if written == o else written

    def restore(self, term: Term) -> Term:
        """A literal as users wrote it, when that value was written in one form only."""
        return self.forms.restore(term)

    def stored_form(self, t: Triple) -> Triple:
        """The triple as this store holds it once added (Oxigraph canonicalises some literals)."""
        return self.forms.stored_form(t)

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

    # ------------------------------------------------------------ transactions
    def transaction(self) -> _Transaction:
        """Group writes into one atomic commit (nested calls join the outer one).

        On an exception nothing of the transaction is written.  A SPARQL query
        or update inside a transaction first commits what is pending, so that it
        sees it; manipulations only read through the quad methods, so they stay
        one commit.  (A plain context manager class: a robot step opens a dozen of them.)
        """
        return _Transaction(self)

    def _begin(self) -> None:
        """Enter a transaction (the outermost one starts with nothing pending)."""
        if self._depth == 0:
            self._pending = {}
            self.persisted.pending = {}
            self._known = {}
        self._depth += 1

    def _end(self, failed: bool) -> None:
        """Leave a transaction: the outermost one commits, or on failure forgets what is pending."""
        self._depth -= 1
        if self._depth:
            return
        if failed:
            self._pending, self._known = None, {}
            self.persisted.pending = {}
            return
        self._flush()
        self._pending, self._known = None, {}

    def _flush(self) -> None:
        """Commit the pending writes of the open transaction (also the persisted state)."""
        pending, self._pending = self._pending or {}, ({} if self._depth else None)
        meta = self.persisted.take_pending()
        keyed_adds = [(q, k) for k, (q, present) in pending.items() if present]
        keyed_removes = [(q, k) for k, (q, present) in pending.items() if not present]
        if not keyed_adds and not keyed_removes and not meta:
            return
        adds = [q for q, _ in keyed_adds]
        removes = [q for q, _ in keyed_removes]
        # undo: the literal forms as they were (the removed literals as their users wrote them)
        forms_add, forms_remove, undo = self.forms.record_keyed(keyed_adds, keyed_removes)
        meta_add, meta_remove = self.persisted.quads(meta) if meta else ([], [])
        try:
            self._write(adds + forms_add + meta_add, removes + forms_remove + meta_remove, undo)
        except BaseException:
            undo()
            raise
        self.persisted.committed(meta)

    def _key(self, quad: Quad) -> Hashable:
        """What identifies a quad: itself, or with a literal object its value (``1`` = ``"01"^^xsd:int``)."""
        o = quad.object
        if isinstance(o, Literal):
            return (quad.subject, quad.predicate, value_key(o), quad.graph_name)
        return quad

    def _present(self, quads: list[Quad], keys: list[tuple] | None = None) -> list[bool]:
        """Whether each quad is in the store as the open transaction sees it (``keys``: their :meth:`_key`)."""
        if self._pending is None and self.listings is None and not any(isinstance(q.object, Literal) for q in quads):
            return self._has_many(quads)  # no transaction, no value keys: each quad is its own key
        pending, known, listings = self._pending or {}, self._known, self.listings
        keys = keys if keys is not None else [self._key(q) for q in quads]
        answers: list[bool | None] = []
        unknown: list[int] = []  # positions neither the transaction nor the listings can answer
        for i, k in enumerate(keys):
            entry = pending.get(k)
            if entry is not None:
                answers.append(entry[1])
                continue
            present = known.get(k)
            if present is None and listings is not None:
                present = listings.presence(quads[i], k)
                if present is not None and self._pending is not None:
                    known[k] = present
            if present is None:
                unknown.append(i)
            answers.append(present)
        if len(unknown) == 1:  # a manipulation's one new triple
            i = unknown[0]
            answers[i] = self._has_many([quads[i]])[0]
            if self._pending is not None:
                known[keys[i]] = answers[i]
        elif unknown:  # one batch (one request on a remote store); a value asked twice takes the last answer
            found = dict(zip((keys[i] for i in unknown), self._has_many([quads[i] for i in unknown]), strict=True))
            if self._pending is not None:
                known.update(found)
            for i in unknown:
                answers[i] = found[keys[i]]
        return answers  # type: ignore[return-value] - every position is answered by now

    # ------------------------------------------------------------ quads
    def add(self, triples: Iterable[Triple], graph: NamedNode, distinct: bool = False) -> int:
        """Add triples to ``graph``; returns how many were new (``distinct``: the caller has
        removed repeated triples already, so a big load does not hash each one again)."""
        triples = triples if isinstance(triples, (list, tuple)) else list(triples)
        if self._depth == 0 and len(triples) >= BULK_ADD and self.is_empty(graph):
            return self._add_to_empty(triples, graph, distinct)
        return len(self.add_new(triples, graph))

    def add_new(self, triples: Iterable[Triple], graph: NamedNode) -> list[Triple]:
        """Add triples to ``graph``; returns those that were not there (deduplicated): what a caller
        recording the change needs, from the one presence look-up the addition makes anyway."""
        return self._toggle_each(triples, graph, True)

    def remove_present(self, triples: Iterable[Triple], graph: NamedNode) -> list[Triple]:
        """Remove triples from ``graph``; returns those that were there (deduplicated), as :meth:`add_new`."""
        return self._toggle_each(triples, graph, False)

    def _toggle_each(self, triples: Iterable[Triple], graph: NamedNode, add: bool) -> list[Triple]:
        """Record the pending addition (or removal) of each triple that is absent (present) in ``graph``,
        in one transaction; returns those triples."""
        triples = triples if isinstance(triples, (list, tuple)) else list(triples)
        if len(triples) == 1:  # a manipulation's usual change: nothing to deduplicate
            t = triples[0]
            quads, triples = [quad(t.subject, t.predicate, t.object, graph)], [t]
        else:  # deduplicated by quad
            made = {quad(t.subject, t.predicate, t.object, graph): t for t in triples}
            quads, triples = list(made), list(made.values())
        keys = [self._key(q) for q in quads]  # a literal's value key is the costly part of a load: once each
        if not self._depth:
            with self.transaction():
                return self._toggle_absent(quads, triples, keys, add)
        return self._toggle_absent(quads, triples, keys, add)  # inside the caller's transaction (a manipulation's)

    def _toggle_absent(self, quads: list[Quad], triples: list[Triple], keys: list[Hashable],
                       add: bool) -> list[Triple]:
        """:meth:`_toggle_each` inside an open transaction."""
        pending, changed = self._pending, []
        for q, t, k, present in zip(quads, triples, keys, self._present(quads, keys), strict=True):
            if present == add:
                continue
            entry = pending.get(k)  # as _toggle: pending True is absent from the committed store, False present
            if entry is None:
                pending[k] = (q, add)
            elif entry[1] != add:
                del pending[k]
            changed.append(t)
        return changed

    # ------------------------------------------------------------ facts: a change's triples with their keys made once
    def fact(self, t: Triple, graph: NamedNode, written: bool = True) -> Fact:
        """The :class:`~.facts.Fact` of a triple a caller adds (``written``: it is its own written form)
        or removes (its written form is asked of the literal forms when needed, see :meth:`written_fact`)."""
        return fact_of(t, graph, written)

    def read_facts(self, s: Term, p: NamedNode, graph: NamedNode) -> list[Fact]:
        """:meth:`triples` of (s, p, ?, graph) as facts, each quad keyed once (what a REPLACE reads, then
        removes some of): inside a transaction, their presence is remembered for the removal.  Their
        written forms are asked of the literal forms when they are removed (:meth:`written_fact`)."""
        pending = self._pending
        if pending is None or self.listings is not None:
            return [self.fact(t, graph, written=False) for t in self.triples(s, p, None, graph)]
        canonical, known, out = self.canonical_reads, self._known, []
        for q in list(self._match(s, p, None, graph)):
            f = fact_read(q, canonical)
            known[f.key] = True
            entry = pending.get(f.key)
            if entry is None or entry[1]:
                out.append(f)
        for q, present in list(pending.values()):
            if present and q.subject == s and q.predicate == p and q.graph_name == graph:
                out.append(self.fact(q.triple, graph, written=False))
        return out

    def written_fact(self, f: Fact) -> Triple:
        """The triple of ``f`` as its user wrote it (kept in ``f.written``): what a removal reports and
        an undo restores."""
        written = f.written
        if written is None:
            t = f.triple
            o = t.object
            lit = self.forms.written(f.quad.graph_name, t.subject, t.predicate, o, f.value)
            written = f.written = t if lit == o else triple(t.subject, t.predicate, lit)
        return written

    def toggle_facts(self, facts: list[Fact], add: bool) -> list[Fact]:
        """:meth:`add_new` (or :meth:`remove_present`) of facts, deduplicated by the caller: those whose
        presence changed."""
        if not self._depth:
            with self.transaction():
                return self.toggle_facts(facts, add)
        pending, changed = self._pending, []
        if len(facts) == 1:  # a manipulation's usual change: its presence asked without a batch
            f = facts[0]
            k = f.key
            entry = pending.get(k)
            if entry is not None:
                present = entry[1]
            else:
                present = self._known.get(k)
                if present is None and self.listings is None:
                    present = self._known[k] = self._has(f.quad)
                elif present is None:
                    present = self._present([f.quad], [k])[0]
            if present != add:
                if entry is None:
                    pending[k] = (f.quad if add else self._removal_quad(f), add)
                else:
                    del pending[k]
                changed.append(f)
            return changed
        keys = [f.key for f in facts]
        for f, k, present in zip(facts, keys, self._present([f.quad for f in facts], keys), strict=True):
            if present == add:
                continue
            entry = pending.get(k)
            if entry is None:
                pending[k] = (f.quad if add else self._removal_quad(f), add)
            elif entry[1] != add:
                del pending[k]
            changed.append(f)
        return changed

    def _removal_quad(self, f: Fact) -> Quad:
        """The quad a removal writes: the literal in the form its user wrote, as it was asserted (a store
        that keeps literals as written, a remote one, matches it exactly; the listings and the literal
        forms key it by value)."""
        written = self.written_fact(f)
        if written is f.triple:
            return f.quad
        return quad(written.subject, written.predicate, written.object, f.quad.graph_name)

    def _add_to_empty(self, triples: list[Triple] | tuple[Triple, ...], graph: NamedNode,
                      distinct: bool = False) -> int:
        """:meth:`add` into an empty graph with no transaction open: every triple is new, so none
        is looked up (a big load's look-ups cost as much as writing it), and quads are made only
        as the store takes them (one quad object is ≈ 440 bytes: a list of them for a map of
        100,000 locations was ≈ 800 MB).  As :meth:`add`, the first spelling of a value is
        written and every distinct triple counts as new."""
        unique = triples if distinct else tuple(dict.fromkeys(triples))
        spelled: dict[tuple, Literal] = {}  # (subject, predicate, value key) -> the literal kept
        recorded: list[bool] = []

        def quads() -> Iterator[Quad]:
            """The quads to write, each triple's terms taken once; then the literal forms' quads."""
            for t in unique:
                s, p, o = t.subject, t.predicate, t.object
                if isinstance(o, Literal):
                    key = (s, p, value_key(o))
                    if key in spelled:
                        continue
                    spelled[key] = o
                yield Quad(s, p, o, graph)
            forms_add = self.forms.record_loaded(graph, list(spelled.items()))  # each value key computed once
            recorded.append(True)
            yield from forms_add

        try:
            self._commit_stream(quads(), [])
        except BaseException:
            if recorded:
                self.forms.record([], [Quad(s, p, o, graph) for (s, p, _), o in spelled.items()], undo=True)
            raise
        return len(unique)

    def _commit_stream(self, quads: Iterator[Quad], extra: list[Quad]) -> None:
        """Add ``quads`` (made one by one) and ``extra`` in one commit; stores that can take a
        stream without a list override this."""
        self._commit([*quads, *extra], [])

    def _toggle(self, quad: Quad, add: bool, key: tuple | None = None) -> None:
        """Record a pending add (or removal) of ``quad``: it cancels a pending change the other way,
        and a second spelling of one value (``1`` and ``"01"^^xsd:int``) changes nothing more."""
        key = key if key is not None else self._key(quad)
        pending = self._pending.get(key)
        if pending is None:
            self._pending[key] = (quad, add)
        elif pending[1] != add:
            del self._pending[key]

    def add_scratch(self, triples: Iterable[Triple], graph: NamedNode) -> None:
        """Bulk-add to a reasoner's scratch graph (no literal forms recorded, no counting)."""
        self._write([Quad(t.subject, t.predicate, t.object, graph) for t in triples], [])

    def remove(self, triples: Iterable[Triple], graph: NamedNode) -> int:
        """Remove triples from ``graph``; returns how many were there."""
        return len(self.remove_present(triples, graph))

    def discard(self, triples: Iterable[Triple], graphs: Iterable[NamedNode]) -> None:
        """Remove triples from reasoner graphs, present or not (no literal forms are kept for those)."""
        graphs = tuple(graphs)
        quads = [Quad(t.subject, t.predicate, t.object, g) for t in triples for g in graphs]
        if quads:
            self._write([], quads)

    def contains(self, t: Triple, graph: NamedNode) -> bool:
        return self._present([Quad(t.subject, t.predicate, t.object, graph)])[0]

    def contains_each(self, triples: list[Triple], graph: NamedNode) -> list[bool]:
        """Whether each triple is in ``graph``: one look-up batch (one request on a remote store)."""
        return self._present([Quad(t.subject, t.predicate, t.object, graph) for t in triples])

    def contains_quads(self, quads: list[Quad]) -> list[bool]:
        """Whether each quad (triple and graph) is in the store: one look-up batch, as :meth:`contains_each`."""
        return self._present(quads)

    def triples(
        self, s: Term | None = None, p: NamedNode | None = None, o: Term | None = None, graph: NamedNode | None = None
    ) -> Iterator[Triple]:
        if self.listings is not None and s is not None and p is not None and o is None and graph is not None:
            yield from self.batched.listed(s, p, graph)
            return
        pending = self._pending
        if pending is None:
            for q in self._match(s, p, o, graph):
                yield q.triple
            return
        for q in list(self._match(s, p, o, graph)):
            key = self._key(q)
            self._known[key] = True
            entry = pending.get(key)
            if entry is None or entry[1]:
                yield q.triple
        for q, present in list(pending.values()):
            if present and _matches(q, s, p, o, graph):
                yield q.triple

    def _predicate_rows(self, p: NamedNode, graph: NamedNode, limit: int) -> list[tuple[Term, Term]]:
        """(subject, object) of up to ``limit`` facts of ``p`` in ``graph``."""
        text = f"SELECT ?s ?o WHERE {{ GRAPH {graph} {{ ?s {p} ?o }} }} LIMIT {limit}"
        return [(r["s"], r["o"]) for r in self._run_query(text, [graph])]

    def objects(self, s: Term, p: NamedNode, graph: NamedNode) -> list[Term]:
        if self._pending is None and self.listings is None:  # the index as it is: no triple made per value
            return [q.object for q in self._match(s, p, None, graph)]
        return [t.object for t in self.triples(s, p, None, graph)]

    def objects_many(self, pairs: list[tuple[Term, NamedNode]], graph: NamedNode) -> dict[tuple, list[Term]]:
        """:meth:`objects` of several (subject, predicate) pairs; one query where reads are round trips."""
        return self.batched.objects_many(pairs, graph)

    def subjects(self, p: NamedNode, o: Term, graph: NamedNode) -> list[Term]:
        return [t.subject for t in self.triples(None, p, o, graph)]

    def list_items(self, head: Term, graph: NamedNode) -> list[Term]:
        """Members of an RDF collection (rdf:first/rdf:rest), in order."""
        items: list[Term] = []
        seen = set()
        node = head
        while node != NIL and node not in seen:
            seen.add(node)
            firsts = self.objects(node, FIRST, graph)
            if not firsts:
                break
            items.append(firsts[0])
            rests = self.objects(node, REST, graph)
            if not rests:
                break
            node = rests[0]
        return items

    def census(self, graph: NamedNode) -> tuple[dict[str, int], dict[str, int]]:
        """Facts per predicate and per class (objects of rdf:type) in ``graph``, keyed by SPARQL text."""
        return self.census_many([graph])[graph]

    def census_many(self, graphs: list[NamedNode]) -> dict[NamedNode, tuple[dict[str, int], dict[str, int]]]:
        """:meth:`census` of several graphs, in one query.

        The reasoner reads the size of its scratch graphs after every round; on
        a store reached over HTTP each query is a round trip, so the graphs of
        one round are counted together (an empty graph counts nothing).
        """
        self._flush_open()
        found: dict[NamedNode, tuple[dict[str, int], dict[str, int]]] = {g: ({}, {}) for g in graphs}
        if not graphs:
            return found
        values = " ".join(str(g) for g in found)
        text = (f"SELECT ?g ?p ?c (COUNT(*) AS ?n) WHERE {{ VALUES ?g {{ {values} }} GRAPH ?g {{ ?s ?p ?o }} "
                f"BIND(IF(sameTerm(?p, {TYPE}), ?o, \"\") AS ?c) }} GROUP BY ?g ?p ?c")
        for r in self._run_query(text, None):
            preds, classes = found[self._graph_in(r["g"])]
            p, n = str(r["p"]), int(r["n"].value)
            preds[p] = preds.get(p, 0) + n
            if p == str(TYPE):
                classes[str(r["c"])] = classes.get(str(r["c"]), 0) + n
        return found

    def _graph_in(self, graph: NamedNode) -> NamedNode:
        """A graph name as a query answers it, in the engine's names (a remote store renames graphs)."""
        return graph

    def small_graph(self, graph: NamedNode, limit: int = 2000) -> list[Quad] | None:
        """Every quad of ``graph`` when there are at most ``limit`` and reading them is an index scan
        (in memory or on disk), else None: the caller reads by pattern or query instead."""
        return None

    def count(self, graph: NamedNode) -> int:
        result = self.query(f"SELECT (COUNT(*) AS ?n) WHERE {{ GRAPH {graph} {{ ?s ?p ?o }} }}")
        return int(next(iter(result))["n"].value)

    def is_empty(self, graph: NamedNode) -> bool:
        return not bool(self.query(f"ASK {{ GRAPH {graph} {{ ?s ?p ?o }} }}"))

    def clear(self, graph: NamedNode) -> None:
        self._flush_open()
        if self.listings is not None:
            self.listings.forget(graph)
        self._drop(graph)
        self.forms.forget(graph)

    # ------------------------------------------------------------ SPARQL
    def _flush_open(self) -> None:
        if self._pending:
            self._flush()
        self._known = {}

    def update(self, text: str, prefixes: dict[str, str] | None = None) -> None:
        self._flush_open()
        if self.listings is not None:
            self.listings.updated()
        self._run_update(text, prefixes)

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

    # ------------------------------------------------------------ output
    def dump(self, graphs: list[NamedNode], restore_literals_from: NamedNode | None = None) -> list[Triple]:
        """Triples of ``graphs`` (deduplicated), blank nodes and literal forms restored."""
        out: dict[Triple, None] = {}
        for g in graphs:
            for t in self.triples(graph=g):
                if isinstance(t.object, Literal):
                    form = self.forms.original_literal(restore_literals_from or g, t.subject, t.predicate, t.object)
                    t = Triple(t.subject, t.predicate, form)
                out[unskolemize(t)] = None
        return list(out)


class _Transaction:
    """The context manager :meth:`Store.transaction` returns."""

    __slots__ = ("store",)

    def __init__(self, store: Store) -> None:
        self.store = store

    def __enter__(self) -> Store:
        self.store._begin()
        return self.store

    def __exit__(self, kind, value, traceback) -> None:
        self.store._end(kind is not None)


def _matches(q: Quad, s, p, o, graph) -> bool:
    return ((s is None or q.subject == s) and (p is None or q.predicate == p)
            and (o is None or q.object == o) and (graph is None or q.graph_name == graph))


__all__ = [
    "Store", "guess_format", "skolemize", "unskolemize", "skolem", "unskolem", "fresh_skolem",
    "serialize", "DefaultGraph", "SKOLEM_PREFIX", "FORMS", "META", "FORMAT_NAMES", "PROGRESS_EVERY",
]
