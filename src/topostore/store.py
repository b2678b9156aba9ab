"""The one store interface every other module talks to.

All reasoning goes through :meth:`Store.query` and :meth:`Store.update` with
graphs named explicitly, so the same rules can later run against an on-disk
Oxigraph store or a remote SPARQL 1.1 server.  Today's implementation is
pyoxigraph, in memory or on disk.

Two details of the store are handled here so that nobody else has to know them:

* Blank nodes are *skolemised* on load (``urn:topostore:bnode:…``): the rule
  compiler must name class expressions and SWRL atoms inside SPARQL text, which
  is impossible for blank nodes.  They become blank nodes again on save.
* Oxigraph keeps numbers in canonical form (``"7"^^xsd:long`` is stored as
  ``"7"^^xsd:integer``).  The asserted lexical form and datatype of every
  literal is remembered so that answers and saved files show what the user wrote.
"""

from __future__ import annotations

import json
import os
import threading
import uuid
from collections.abc import Callable, Iterable, Iterator
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path

import pyoxigraph as ox
from pyoxigraph import BlankNode, DefaultGraph, Literal, NamedNode, Quad, RdfFormat, Triple

from .errors import LoadError, QueryError
from .safeio import check_xml_entities, read_regular_file
from .terms import Term, value_key
from .vocab import AUX, ASSERTED, INFERRED, INTERNAL, NIL, FIRST, REST, TYPE

SKOLEM_PREFIX = INTERNAL + "bnode:"

#: a scratch store that shows how a literal is stored (see Store.stored_form)
_PROBE = ox.Store()
_PROBE_LOCK = threading.Lock()
_PROBE_GRAPH = NamedNode(INTERNAL + "graph:probe")
_XSD = "http://www.w3.org/2001/XMLSchema#"


#: largest integer result swrlb:pow computes (bits); beyond it the built-in gives no value
_POW_MAX_BITS = 4096


def _pow(base: Term, exponent: Term) -> Literal | None:
    """swrlb:pow for a non-constant exponent (SPARQL 1.1 has no power function).

    Integers with a non-negative integer exponent stay integers; anything else
    is computed as a double.  Non-numbers give no value (the rule does not fire).
    """
    if not isinstance(base, Literal) or not isinstance(exponent, Literal):
        return None
    try:
        if base.datatype.value.startswith(_XSD) and "." not in base.value and "e" not in base.value.lower() \
                and exponent.value.lstrip("+").isdigit():
            b, e = int(base.value), int(exponent.value)
            if abs(b) > 1 and e * abs(b).bit_length() > _POW_MAX_BITS:
                return None  # a number this large is not a measurement; computing it would freeze the service
            return Literal(str(b ** e), datatype=NamedNode(_XSD + "integer"))
        return Literal(repr(float(base.value) ** float(exponent.value)), datatype=NamedNode(_XSD + "double"))
    except (ValueError, OverflowError, ZeroDivisionError):
        return None


#: Extension functions the compiled rules may call (see compile/builtins.py).
CUSTOM_FUNCTIONS = {NamedNode(INTERNAL + "fn:pow"): _pow}

#: How often (in triples) parsing reports progress.
PROGRESS_EVERY = 5000

_FORMATS = {
    ".owl": RdfFormat.RDF_XML,
    ".rdf": RdfFormat.RDF_XML,
    ".xml": RdfFormat.RDF_XML,
    ".ttl": RdfFormat.TURTLE,
    ".turtle": RdfFormat.TURTLE,
    ".nt": RdfFormat.N_TRIPLES,
    ".ntriples": RdfFormat.N_TRIPLES,
    ".n3": RdfFormat.N3,
    ".jsonld": RdfFormat.JSON_LD,
}
FORMAT_NAMES = {
    "rdfxml": RdfFormat.RDF_XML,
    "rdf/xml": RdfFormat.RDF_XML,
    "xml": RdfFormat.RDF_XML,
    "owl": RdfFormat.RDF_XML,
    "turtle": RdfFormat.TURTLE,
    "ttl": RdfFormat.TURTLE,
    "ntriples": RdfFormat.N_TRIPLES,
    "nt": RdfFormat.N_TRIPLES,
    "n-triples": RdfFormat.N_TRIPLES,
}


def guess_format(path: str | os.PathLike[str], explicit: str | RdfFormat | None = None) -> RdfFormat:
    """The RDF format of a file, from an explicit name or its extension (RDF/XML by default)."""
    if isinstance(explicit, RdfFormat):
        return explicit
    if explicit:
        try:
            return FORMAT_NAMES[explicit.lower()]
        except KeyError:
            raise LoadError(f"unknown RDF format {explicit!r}; use one of {', '.join(FORMAT_NAMES)}") from None
    return _FORMATS.get(Path(path).suffix.lower(), RdfFormat.RDF_XML)


def _syntax_error_message(source: str, exc: SyntaxError, data: bytes, fmt: RdfFormat) -> str:
    """'file:line: cause', finding the line with rdflib when Oxigraph gives none (RDF/XML)."""
    cause = str(exc.msg if hasattr(exc, "msg") and exc.msg else exc)
    line = exc.lineno
    if line is None and fmt == RdfFormat.RDF_XML:
        line = _xml_error_line(data)
    where = f"{source}:{line}" if line else f"{source}:?"
    return f"{where}: not valid {fmt.name}: {cause}"


def _xml_error_line(data: bytes) -> int | None:
    import xml.sax

    class _Handler(xml.sax.handler.ContentHandler):
        pass

    try:
        xml.sax.parseString(data, _Handler())
    except xml.sax.SAXParseException as exc:
        return exc.getLineNumber()
    except Exception:  # pragma: no cover - only used to locate an error
        return None
    return None


@dataclass(frozen=True)
class Graphs:
    """The names of the graphs of one reference (several references may share a store)."""

    asserted: NamedNode = ASSERTED
    inferred: NamedNode = INFERRED
    aux: NamedNode = AUX

    @classmethod
    def for_prefix(cls, prefix: str) -> "Graphs":
        return cls(NamedNode(prefix + "asserted"), NamedNode(prefix + "inferred"), NamedNode(prefix + "aux"))


class Store:
    """The store interface every other module talks to: quads in, SPARQL in, results out.

    This class holds what every implementation shares (parsing, the literal
    forms users wrote, transactions, the small persisted state of a reference)
    on top of a few primitives each implementation provides: ``_has``,
    ``_match``, ``_commit``, ``_run_update``, ``_run_query`` and ``_drop``.
    Implementations: :class:`topostore.stores.oxigraph.OxigraphStore` (memory
    or RocksDB on disk) and :class:`topostore.stores.remote.RemoteStore` (a
    SPARQL 1.1 Query + Update endpoint pair); :func:`topostore.stores.open_store`
    picks one from a ``store`` setting.  ``Store()`` itself gives an in-memory store.

    Writes (``add``/``remove``/``meta_set``) are grouped by :meth:`transaction`
    into one atomic commit; reads inside a transaction see its pending writes.
    """

    #: Can the compiled rules use Oxigraph's LATERAL joins on this store?
    supports_lateral = True
    #: Does this store run topostore's extension functions (``urn:topostore:fn:pow``)?
    custom_functions = True
    #: Does this store outlive the process (disk, remote server)?
    durable = False

    def __new__(cls, *args, **kwargs):
        if cls is Store:  # Store() keeps meaning "a fresh in-memory store"
            from .stores.oxigraph import OxigraphStore
            cls = OxigraphStore
        return super().__new__(cls)

    def __init__(self) -> None:
        # (graph, subject, predicate, value key) -> literal as the user wrote it
        self._literal_forms: dict[tuple, Literal] = {}
        # value key -> {literal as written: number of asserted triples using it}
        self._value_forms: dict[tuple, dict[Literal, int]] = {}
        # quad key -> (quad, present after commit) while a transaction is open
        self._pending: dict[tuple, tuple[Quad, bool]] | None = None
        # quad key -> present in the committed store, learnt during the open transaction (saves round trips)
        self._known: dict[tuple, bool] = {}
        self._depth = 0
        self._meta: dict[str, object] | None = None
        self._meta_pending: dict[str, object] = {}

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

    def _run_update(self, text: str, prefixes: dict[str, str] | None) -> None:
        raise NotImplementedError

    def _run_query(self, text: str, graphs: list[NamedNode] | None, **kwargs):
        raise NotImplementedError

    def _drop(self, graph: NamedNode) -> None:
        self._run_update(f"DROP SILENT GRAPH {graph}", None)

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
        if isinstance(data, str):
            data = data.encode("utf-8", errors="surrogatepass")
        if fmt == RdfFormat.RDF_XML:
            check_xml_entities(data, source)
        try:
            quads = []
            for quad in ox.parse(data, format=fmt, base_iri=base_iri, rename_blank_nodes=True):
                quads.append(quad)
                if progress is not None and len(quads) % PROGRESS_EVERY == 0:
                    progress(len(quads))
        except SyntaxError as exc:
            raise LoadError(_syntax_error_message(source, exc, data, fmt)) from exc
        except ValueError as exc:
            raise LoadError(f"{source}: {exc}") from exc
        return [skolemize(Triple(q.subject, q.predicate, q.object)) for q in quads]

    # ------------------------------------------------------------ transactions
    @contextmanager
    def transaction(self) -> Iterator["Store"]:
        """Group writes into one atomic commit (nested calls join the outer one).

        On an exception nothing of the transaction is written.  A SPARQL query
        or update inside a transaction first commits what is pending, so that it
        sees it; manipulations only read through the quad methods, so they stay
        one commit.
        """
        if self._depth == 0:
            self._pending = {}
            self._meta_pending = {}
            self._known = {}
        self._depth += 1
        try:
            yield self
        except BaseException:
            self._depth -= 1
            if self._depth == 0:
                self._pending, self._meta_pending, self._known = None, {}, {}
            raise
        self._depth -= 1
        if self._depth == 0:
            self._flush()
            self._pending, self._known = None, {}

    def _flush(self) -> None:
        """Commit the pending writes of the open transaction (also the persisted state)."""
        pending, self._pending = self._pending or {}, ({} if self._depth else None)
        meta, self._meta_pending = self._meta_pending, {}
        adds = [q for q, present in pending.values() if present]
        removes = [q for q, present in pending.values() if not present]
        if not adds and not removes and not meta:
            return
        forms_add, forms_remove = self._record_forms(adds, removes)
        meta_add, meta_remove = self._meta_quads(meta)
        try:
            self._commit(adds + forms_add + meta_add, removes + forms_remove + meta_remove)
        except BaseException:
            self._record_forms(removes, adds, undo=True)
            raise
        if meta:
            self._meta = {**(self._meta or {}), **meta}

    def _key(self, quad: Quad) -> tuple:
        o = quad.object
        return (quad.subject, quad.predicate, value_key(o) if isinstance(o, Literal) else o, quad.graph_name)

    def _present(self, quads: list[Quad]) -> list[bool]:
        pending, known = self._pending or {}, self._known
        unknown = [q for q in quads if self._key(q) not in pending and self._key(q) not in known]
        found = dict(zip(map(self._key, unknown), self._has_many(unknown))) if unknown else {}
        if self._pending is not None:
            known.update(found)
        return [pending[k][1] if k in pending else known[k] if k in known else found[k] for k in map(self._key, quads)]

    # ------------------------------------------------------------ quads
    def add(self, triples: Iterable[Triple], graph: NamedNode) -> int:
        """Add triples to ``graph``; returns how many were new."""
        quads = list(dict.fromkeys(Quad(t.subject, t.predicate, t.object, graph) for t in triples))
        with self.transaction():
            new = [q for q, present in zip(quads, self._present(quads)) if not present]
            for q in new:  # pending True: absent from the committed store; False: present there
                key = self._key(q)
                if self._pending.pop(key, None) is None:
                    self._pending[key] = (q, True)
        return len(new)

    def add_scratch(self, triples: Iterable[Triple], graph: NamedNode) -> None:
        """Bulk-add to a reasoner's scratch graph (no literal forms recorded, no counting)."""
        self._commit([Quad(t.subject, t.predicate, t.object, graph) for t in triples], [])

    def remove(self, triples: Iterable[Triple], graph: NamedNode) -> int:
        quads = list(dict.fromkeys(Quad(t.subject, t.predicate, t.object, graph) for t in triples))
        with self.transaction():
            gone = [q for q, present in zip(quads, self._present(quads)) if present]
            for q in gone:
                key = self._key(q)
                if self._pending.pop(key, None) is None:
                    self._pending[key] = (q, False)
        return len(gone)

    def stored_form(self, t: Triple) -> Triple:
        """The triple as this store holds it once added (Oxigraph canonicalises some literals,
        e.g. ``"7"^^xsd:long`` becomes ``"7"^^xsd:integer``)."""
        if not isinstance(t.object, Literal):
            return t
        with _PROBE_LOCK:
            _PROBE.add(Quad(t.subject, t.predicate, t.object, _PROBE_GRAPH))
            stored = next(iter(_PROBE.quads_for_pattern(t.subject, t.predicate, None, _PROBE_GRAPH)))
            _PROBE.remove(stored)
        return Triple(t.subject, t.predicate, stored.object)

    def discard(self, triples: Iterable[Triple], graphs: Iterable[NamedNode]) -> None:
        """Remove triples from reasoner graphs, present or not (no literal forms are kept for those)."""
        graphs = tuple(graphs)
        quads = [Quad(t.subject, t.predicate, t.object, g) for t in triples for g in graphs]
        if quads:
            self._commit([], quads)

    def contains(self, t: Triple, graph: NamedNode) -> bool:
        return self._present([Quad(t.subject, t.predicate, t.object, graph)])[0]

    def triples(
        self, s: Term | None = None, p: NamedNode | None = None, o: Term | None = None, graph: NamedNode | None = None
    ) -> Iterator[Triple]:
        pending = self._pending
        if pending is None:
            for q in self._match(s, p, o, graph):
                yield Triple(q.subject, q.predicate, q.object)
            return
        for q in list(self._match(s, p, o, graph)):
            self._known[self._key(q)] = True
            entry = pending.get(self._key(q))
            if entry is None or entry[1]:
                yield Triple(q.subject, q.predicate, q.object)
        for q, present in list(pending.values()):
            if present and _matches(q, s, p, o, graph):
                yield Triple(q.subject, q.predicate, q.object)

    def objects(self, s: Term, p: NamedNode, graph: NamedNode) -> list[Term]:
        return [t.object for t in self.triples(s, p, None, graph)]

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
        self._flush_open()
        preds = {str(r["p"]): int(r["n"].value) for r in self._run_query(
            f"SELECT ?p (COUNT(*) AS ?n) WHERE {{ GRAPH {graph} {{ ?s ?p ?o }} }} GROUP BY ?p", None)}
        classes: dict[str, int] = {}
        if str(TYPE) in preds:
            classes = {str(r["c"]): int(r["n"].value) for r in self._run_query(
                f"SELECT ?c (COUNT(*) AS ?n) WHERE {{ GRAPH {graph} {{ ?s {TYPE} ?c }} }} GROUP BY ?c", None)}
        return preds, classes

    def count(self, graph: NamedNode) -> int:
        result = self.query(f"SELECT (COUNT(*) AS ?n) WHERE {{ GRAPH {graph} {{ ?s ?p ?o }} }}")
        return int(next(iter(result))["n"].value)

    def is_empty(self, graph: NamedNode) -> bool:
        return not bool(self.query(f"ASK {{ GRAPH {graph} {{ ?s ?p ?o }} }}"))

    def clear(self, graph: NamedNode) -> None:
        self._flush_open()
        self._drop(graph)
        gone = [(k, v) for k, v in self._literal_forms.items() if k[0] == graph.value]
        if self.durable and gone:
            self._commit([], [_form_quad(k[0], k[1], k[2], lit) for k, lit in gone])
        self._literal_forms = {k: v for k, v in self._literal_forms.items() if k[0] != graph.value}
        self._rebuild_value_forms()

    # ------------------------------------------------------------ literal forms
    def _record_forms(self, adds: list[Quad], removes: list[Quad], undo: bool = False) -> tuple[list[Quad], list[Quad]]:
        """Remember (or forget) how committed literals were written; the quads persisting that on a durable store."""
        forms_add: list[Quad] = []
        forms_remove: list[Quad] = []
        for q in removes:
            if isinstance(q.object, Literal) and not _is_scratch(q.graph_name):
                key = value_key(q.object)
                original = self._literal_forms.pop((q.graph_name.value, q.subject, q.predicate, key), q.object)
                self._count_form(key, original, -1)
                if self.durable and not undo:
                    forms_remove.append(_form_quad(q.graph_name.value, q.subject, q.predicate, original))
        for q in adds:
            if isinstance(q.object, Literal) and not _is_scratch(q.graph_name):
                key = value_key(q.object)
                self._literal_forms[(q.graph_name.value, q.subject, q.predicate, key)] = q.object
                self._count_form(key, q.object, +1)
                if self.durable and not undo:
                    forms_add.append(_form_quad(q.graph_name.value, q.subject, q.predicate, q.object))
        return forms_add, forms_remove

    def _count_form(self, key: tuple, lit: Literal, delta: int) -> None:
        forms = self._value_forms.setdefault(key, {})
        forms[lit] = forms.get(lit, 0) + delta
        if forms[lit] <= 0:
            del forms[lit]

    def _rebuild_value_forms(self) -> None:
        self._value_forms = {}
        for (_, _, _, key), lit in self._literal_forms.items():
            self._count_form(key, lit, +1)

    def load_forms(self) -> None:
        """Read the persisted literal forms back (a durable store opened again)."""
        self._literal_forms = {}
        for q in self._match(None, None, None, FORMS):
            graph, _, text = q.object.value.partition(" ")
            lit = _parse_literal(text)
            if lit is not None:
                self._literal_forms[(graph, q.subject, q.predicate, value_key(lit))] = lit
        self._rebuild_value_forms()

    def original_literal(self, graph: NamedNode, s: Term, p: NamedNode, o: Literal) -> Literal:
        """The literal as the user asserted it (lexical form and datatype)."""
        found = self._literal_forms.get((graph.value, s, p, value_key(o)))
        return found if found is not None else self.restore(o)

    def restore(self, term: Term) -> Term:
        """A literal as users wrote it, when that value was written in one form only."""
        if not isinstance(term, Literal):
            return term
        forms = self._value_forms.get(value_key(term))
        if forms and len(forms) == 1:
            return next(iter(forms))
        return term

    # ------------------------------------------------------------ persisted state
    @property
    def meta(self) -> dict[str, object]:
        """The small JSON state a durable store keeps beside the data (settings, flags)."""
        if self._meta is None:
            self._meta = {}
            for q in self._match(META_SUBJECT, None, None, META):
                try:
                    self._meta[q.predicate.value[len(META_KEY):]] = json.loads(q.object.value)
                except ValueError:
                    continue
        return {**self._meta, **self._meta_pending}

    def meta_set(self, key: str, value: object) -> None:
        """Persist ``key`` (JSON value) with the current transaction; no-op on a memory store."""
        if not self.durable or self.meta.get(key, _MISSING) == value:
            return
        with self.transaction():
            self._meta_pending[key] = value

    def _meta_quads(self, meta: dict[str, object]) -> tuple[list[Quad], list[Quad]]:
        adds, removes = [], []
        self.meta  # noqa: B018 - loads the persisted values once; they name the quads to replace
        for key, value in meta.items():
            pred = NamedNode(META_KEY + key)
            if key in self._meta:
                removes.append(Quad(META_SUBJECT, pred, Literal(json.dumps(self._meta[key], sort_keys=True)), META))
            adds.append(Quad(META_SUBJECT, pred, Literal(json.dumps(value, sort_keys=True)), META))
        return adds, removes

    # ------------------------------------------------------------ SPARQL
    def _flush_open(self) -> None:
        if self._pending:
            self._flush()
        self._known = {}

    def update(self, text: str, prefixes: dict[str, str] | None = None) -> None:
        self._flush_open()
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
                    t = Triple(t.subject, t.predicate, self.original_literal(restore_literals_from or g, t.subject, t.predicate, t.object))
                out[unskolemize(t)] = None
        return list(out)


#: Graph of the persisted literal forms, and of the persisted state of a reference.
FORMS = NamedNode(INTERNAL + "graph:forms")
META = NamedNode(INTERNAL + "graph:meta")
META_SUBJECT = NamedNode(INTERNAL + "meta")
META_KEY = INTERNAL + "meta:"
_MISSING = object()


def _is_scratch(graph) -> bool:
    """Reasoner scratch graphs and the persisted state need no literal forms."""
    return not isinstance(graph, NamedNode) or graph == FORMS or graph == META


def _form_quad(graph: str, s: Term, p: NamedNode, lit: Literal) -> Quad:
    return Quad(s, p, Literal(f"{graph} {lit}"), FORMS)


def _parse_literal(text: str) -> Literal | None:
    try:
        quads = list(ox.parse(f"<urn:x:s> <urn:x:p> {text} .", format=RdfFormat.N_TRIPLES))
    except (SyntaxError, ValueError):
        return None
    return quads[0].object if quads and isinstance(quads[0].object, Literal) else None


def _matches(q: Quad, s, p, o, graph) -> bool:
    return ((s is None or q.subject == s) and (p is None or q.predicate == p)
            and (o is None or q.object == o) and (graph is None or q.graph_name == graph))


def skolem(term: Term) -> Term:
    if isinstance(term, BlankNode):
        return NamedNode(SKOLEM_PREFIX + term.value)
    return term


def skolemize(t: Triple) -> Triple:
    return Triple(skolem(t.subject), t.predicate, skolem(t.object))


def unskolem(term: Term) -> Term:
    if isinstance(term, NamedNode) and term.value.startswith(SKOLEM_PREFIX):
        return BlankNode(term.value[len(SKOLEM_PREFIX):])
    return term


def unskolemize(t: Triple) -> Triple:
    return Triple(unskolem(t.subject), t.predicate, unskolem(t.object))


def fresh_skolem() -> NamedNode:
    """A new skolem IRI, standing for a fresh blank node (e.g. a new AllDifferent axiom)."""
    return NamedNode(SKOLEM_PREFIX + "n" + uuid.uuid4().hex)


def serialize(triples: Iterable[Triple], fmt: RdfFormat, prefixes: dict[str, str] | None = None) -> bytes:
    return ox.serialize(list(triples), format=fmt, prefixes=prefixes or None)


__all__ = [
    "Store", "Graphs", "guess_format", "skolemize", "unskolemize", "skolem", "unskolem", "fresh_skolem",
    "serialize", "DefaultGraph", "SKOLEM_PREFIX", "CUSTOM_FUNCTIONS", "FORMS", "META",
]
