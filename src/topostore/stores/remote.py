"""A remote SPARQL 1.1 Query + Update endpoint pair as a :class:`~topostore.stores.base.Store`.

Several references share one server: each keeps its graphs under its own
namespace (``urn:topostore:graph:asserted`` becomes
``urn:topostore:ref:<name>:graph:asserted`` on the wire), so the engine's
fixed graph names need no change.

Every request is a round trip, so writes wait: the data change of a manipulation
(``DELETE DATA``/``INSERT DATA``), the updates the reasoner sends while it runs
(until its next read, or its end) and its drop of its scratch graphs at the end of
a REASON are queued and go with the next request, joined
with ``;`` to the next update (one request, one transaction on the server), or sent
before the next read so that the read sees it.  A queued change the server then
refuses is undone in this process as well (literal forms, persisted state, what
the store knew, and through :attr:`~topostore.stores.base.Store.on_lost` the
ontology's change ledger) and reported as :class:`~topostore.errors.WritesLostError`;
an update refused on its own does not take the queued changes with it (they are
sent again alone).  The price: a change is on the server only once the next
request has gone, so a process killed in between loses the changes since its last
request (``defer_writes=False`` sends every write at once).

The server has none of Oxigraph's extensions, so ``supports_lateral`` and
``custom_functions`` are false: the engine then plans flat joins, and a rule
needing ``urn:topostore:fn:pow`` is refused at load
(:func:`topostore.stores.check_rules`).

Credentials come only from the environment: ``TOPOSTORE_STORE_TOKEN`` (a
bearer token) or ``TOPOSTORE_STORE_USER`` and ``TOPOSTORE_STORE_PASSWORD``
(HTTP basic), never from the command line where other users could read them.
"""

from __future__ import annotations

import atexit
import logging
import os
import re
import urllib.parse
import weakref
from collections.abc import Callable, Collection, Iterator
from dataclasses import dataclass
from functools import cached_property

import httpx
import pyoxigraph as ox
from pyoxigraph import NamedNode, Quad, QueryResultsFormat, RdfFormat

from ..errors import QueryError, StoreError, WritesLostError
from ..rdf.vocab import INTERNAL
from .base import Store
from .data_text import data_update
from .literal_forms import FORMS
from .meta import META

logger = logging.getLogger("topostore.store")
GRAPH_PREFIX = INTERNAL + "graph:"
#: an update that only drops graphs named by full IRIs (what a reasoner does with its scratch graphs)
_DROPS = re.compile(r"(?:\s*DROP\s+SILENT\s+GRAPH\s+<[^<>\s]+>\s*;?)+\s*", re.IGNORECASE)
_DROPPED = re.compile(r"GRAPH\s+<([^<>\s]+)>", re.IGNORECASE)
#: an update that declares its own prefixes or base (comments may come first)
_PROLOGUE = re.compile(r"(?:\s|#[^\n]*\n)*(?:PREFIX|BASE)\b", re.IGNORECASE)
_ACCEPT = "application/sparql-results+xml, application/n-triples;q=0.9, text/turtle;q=0.8"
_TIMEOUT = httpx.Timeout(300.0, connect=10.0)
#: Rows per presence check; keeps request bodies small.
_CHUNK = 500


def namespace_prefix(reference: str) -> str:
    """Graph-name prefix of one reference on a shared server (the name percent-encoded)."""
    return f"{INTERNAL}ref:{urllib.parse.quote(reference, safe='')}:graph:" if reference else GRAPH_PREFIX


def credentials() -> httpx.Auth | dict[str, str] | None:
    """HTTP credentials from the environment (token first), or None."""
    token = os.environ.get("TOPOSTORE_STORE_TOKEN")
    if token:
        return {"Authorization": f"Bearer {token}"}
    user = os.environ.get("TOPOSTORE_STORE_USER")
    if user:
        return httpx.BasicAuth(user, os.environ.get("TOPOSTORE_STORE_PASSWORD", ""))
    return None


@dataclass
class _Queued:
    """A data change accepted by the store and not yet sent: its update text (graph names on the wire),
    its quads, and how to undo what was recorded in memory for it."""

    text: str
    adds: list[Quad]
    removes: list[Quad]
    undo: Callable[[], None] | None
    #: graphs the change drops whole (a reasoner's scratch graphs)
    dropped: frozenset[NamedNode] = frozenset()
    #: a reasoner's update, whatever it reads and writes: every read sends it first
    opaque: bool = False
    #: the prefixes its text uses (declared once at the head of the request that carries it)
    prefixes: dict[str, str] | None = None

    @cached_property
    def _written(self) -> tuple[frozenset, frozenset]:
        """The graphs and the (subject, predicate, graph) and (None, predicate, graph) patterns it writes."""
        quads = (*self.adds, *self.removes)
        return (frozenset(q.graph_name for q in quads) | self.dropped,
                frozenset(k for q in quads for k in ((q.subject, q.predicate, q.graph_name),
                                                       (None, q.predicate, q.graph_name))))

    def touches(self, graphs: Collection[NamedNode] | None, patterns: Collection[tuple] | None) -> bool:
        """Whether a read of ``graphs`` (None: any) or of (subject, predicate, graph) ``patterns`` (subject
        None: any predicate's subject) sees it."""
        if self.opaque or (graphs is None and patterns is None):
            return True
        written, keys = self._written
        if patterns is None:
            return not written.isdisjoint(graphs)
        return not keys.isdisjoint(patterns) or any(p[2] in self.dropped for p in patterns)


class RemoteStore(Store):
    """Graphs of one reference on a SPARQL 1.1 server, reached over HTTP."""

    supports_lateral = False
    custom_functions = False
    durable = True
    round_trips = True

    def __init__(self, url: str, *, reference: str = "", query_url: str | None = None,
                 update_url: str | None = None, defer_writes: bool = True) -> None:
        super().__init__()
        #: data changes wait for the next request (see the module docstring)
        self.defer_writes = defer_writes
        self._queue: list[_Queued] = []
        _OPEN.add(self)  # a process that ends without closing its store still sends what it queued
        base = url.rstrip("/")
        single = base.endswith("/sparql")  # Virtuoso and others serve both on one path
        self.url = base
        self.query_url = query_url or (base if single else base + "/query")
        self.update_url = update_url or (base if single else base + "/update")
        self.reference = reference
        self._prefix = namespace_prefix(reference)
        auth = credentials()
        self._client = httpx.Client(timeout=_TIMEOUT, auth=auth if isinstance(auth, httpx.Auth) else None,
                                    headers=auth if isinstance(auth, dict) else None)
        #: HTTP requests sent (benchmarks report round trips per step)
        self.requests = 0
        self.forms.load()

    # ------------------------------------------------------------ wire
    def _out(self, text: str) -> str:
        """Graph names of this reference as the server knows them."""
        return text if self._prefix == GRAPH_PREFIX else text.replace("<" + GRAPH_PREFIX, "<" + self._prefix)

    def _graph_out(self, graph: NamedNode) -> NamedNode:
        return NamedNode(self._out(f"<{graph.value}>")[1:-1])

    def _graph_in(self, graph: NamedNode) -> NamedNode:
        v = graph.value
        return NamedNode(GRAPH_PREFIX + v[len(self._prefix):]) if v.startswith(self._prefix) else graph

    def _post(self, url: str, data: dict, accept: str | None = None) -> httpx.Response:
        self.requests += 1
        try:
            answer = self._client.post(url, data=data, headers={"Accept": accept} if accept else None)
        except httpx.HTTPError as exc:
            raise StoreError(f"the SPARQL server at {url} did not answer: {exc}") from None
        if answer.status_code >= 400:
            raise QueryError(f"the SPARQL server at {url} refused the request ({answer.status_code}): "
                             f"{answer.text[:500]}")
        if "virtuoso" in answer.headers.get("server", "").lower():
            # Virtuoso 7 answered a compiled step's long update request differently from the same
            # operations sent one by one (tests/test_store_equivalence.py): it gets the program key by key
            self.whole_programs = False
        return answer

    def _run_update(self, text: str, prefixes: dict[str, str] | None) -> None:
        if self._defer_drops(text) or self._defer_reasoning(text, prefixes):
            return
        if _PROLOGUE.match(text) or _clash(self._queue, prefixes):  # one prologue per request: queue first
            self.send_writes()
        self._send(self._out(text), prefixes)

    def _send(self, text: str = "", prefixes: dict[str, str] | None = None) -> None:
        """One update request: the queued changes, then ``text`` (either may be empty); the prefixes of
        all of them are declared once, first (the caller saw that they do not clash)."""
        queued, self._queue = self._queue, []
        body = " ;\n".join([q.text for q in queued] + ([text] if text else []))
        if not body:
            return
        declared: dict[str, str] = {}
        for q in queued:
            declared.update(q.prefixes or {})
        body = _with_prefixes(body, {**declared, **(prefixes or {})})
        try:
            self._post(self.update_url, {"update": body})
        except StoreError as exc:  # no answer: the queued changes may or may not be there
            if queued:
                self._lose(queued, f"the server did not answer, so whether it applied them is unknown: {exc}",
                           certain=False)
            raise
        except QueryError as exc:  # refused: nothing of the request was applied
            if not queued:
                raise
            self._refused(queued, bool(text), exc)

    def _refused(self, queued: list[_Queued], with_update: bool, exc: QueryError) -> None:
        """A request carrying queued changes was refused.  The manipulations' data changes are not to be
        lost for an update that went with them (the caller's, or the reasoner's queued ones): they are
        sent again alone; what still fails is undone here and said (WritesLostError).  Re-raises
        ``exc`` when the caller's update alone was at fault."""
        data = [q for q in queued if not (q.opaque or q.dropped)]
        reasoner = [q for q in queued if q.opaque or q.dropped]
        if not data or not (with_update or reasoner):
            self._lose(queued, f"the server refused them: {exc}")
        try:
            self._post(self.update_url, {"update": " ;\n".join(q.text for q in data)})
        except (QueryError, StoreError) as again:
            self._lose(queued, f"the server refused them: {exc}; sent alone: {again}",
                       certain=isinstance(again, QueryError))
        if reasoner:
            self._lose(reasoner, f"the server refused them: {exc}")
        raise exc

    def _defer_reasoning(self, text: str, prefixes: dict[str, str] | None) -> bool:
        """Queue an update sent while the reasoner runs (inside :meth:`~topostore.stores.base.Store.keeping`):
        it goes with the reasoner's next update, or before its next read (any read: what it changes is not
        known here); whatever is queued goes when the reasoner is done (:meth:`_settle`).  The server runs
        the same operations in the same order, in fewer requests."""
        if not self.defer_writes or self.listings is None or not self.listings.kept or _PROLOGUE.match(text):
            return False
        if _clash(self._queue, prefixes):
            self.send_writes()
        self._queue.append(_Queued(self._out(text), [], [], None, opaque=True, prefixes=prefixes))
        return True

    def _settle(self) -> None:
        """The reasoner is done: its queued updates go now (a REASON says it succeeded only once its
        writes are on the server); a drop of its scratch graphs alone may wait for the next request."""
        if any(q.opaque for q in self._queue):
            self._send()

    def _defer_drops(self, text: str) -> bool:
        """Queue an update that only drops graphs the caller declared its own (a reasoner clearing its
        scratch graphs, inside :meth:`~topostore.stores.base.Store.keeping`): it goes with the next
        request like a data change, and a read of one of those graphs sends it first."""
        if not self.defer_writes or self.listings is None or not self.listings.kept or not _DROPS.fullmatch(text):
            return False
        dropped = frozenset(NamedNode(iri) for iri in _DROPPED.findall(text))
        if dropped & (self.listings.kept | {META, FORMS}):
            return False
        self._queue.append(_Queued(self._out(text.strip().rstrip(";")), [], [], None, dropped))
        return True

    def send_writes(self, graphs: Collection[NamedNode] | None = None,
                    patterns: Collection[tuple] | None = None) -> None:
        """Send the queued data changes now: all of them, when one writes ``graphs`` or one of the
        (subject, predicate, graph) ``patterns`` (neither given: always).

        A read sends them first when it may see one (a query's dataset, a look-up's patterns; the
        persisted state no query reads waits for the next update); so does :meth:`close`.
        """
        if self._queue and any(q.touches(graphs, patterns) for q in self._queue):
            self._send()

    def _lose(self, queued: list[_Queued], why: str, certain: bool = True) -> None:
        """Undo queued changes that did not reach the server, in this process; raises WritesLostError."""
        for q in reversed(queued):
            if q.undo is not None:
                q.undo()
        # a lost drop or reasoner update leaves graphs' content unknown here: as an unanswered request does
        reasoner = sum(1 for q in queued if q.dropped or q.opaque)
        self._writes_lost([(q.adds, q.removes) for q in queued], certain and not reasoner)
        data = sum(1 for q in queued if any(x.graph_name != META for x in (*q.adds, *q.removes)))
        what = f"{data} change(s) of the data" + (f", {reasoner} update(s) of the reasoner" if reasoner else "")
        note = " (the next REASON is a full one)" if reasoner else ""
        raise WritesLostError(f"{what} ({len(queued) - data - reasoner} of the persisted state) accepted earlier and "
                              f"waiting to be written to the SPARQL server were not written, and were undone "
                              f"here{note}: {why}")

    def _run_query(self, text: str, graphs: list[NamedNode] | None, named: list[NamedNode] | None = None,
                   **kwargs):
        # the read sees every change accepted before it: with its dataset given, those of its graphs
        self.send_writes(None if graphs is None else {*graphs, *(graphs if named is None else named)})
        return self._query(text, graphs, named, **kwargs)

    def _query(self, text: str, graphs: list[NamedNode] | None, named: list[NamedNode] | None = None, **kwargs):
        """One query request (the caller has sent the queued changes the query may see)."""
        kwargs.pop("custom_functions", None)
        text = self._out(_with_prefixes(text, kwargs.pop("prefixes", None)))
        if kwargs:  # pyoxigraph-only options would otherwise be ignored silently
            raise QueryError(f"query options {', '.join(sorted(kwargs))} are not available on a remote SPARQL store")
        data: dict = {"query": text}
        if graphs is not None:
            data["default-graph-uri"] = [self._graph_out(g).value for g in graphs]
            data["named-graph-uri"] = [self._graph_out(g).value for g in (graphs if named is None else named)]
        answer = self._post(self.query_url, data, _ACCEPT)
        kind = answer.headers.get("content-type", "").split(";")[0].strip()
        if kind == "application/sparql-results+xml":
            return ox.parse_query_results(answer.content, format=QueryResultsFormat.XML)
        if kind in ("application/sparql-results+json", "application/json"):
            return ox.parse_query_results(answer.content, format=QueryResultsFormat.JSON)
        fmt = RdfFormat.TURTLE if "turtle" in kind else RdfFormat.N_TRIPLES
        return [q.triple for q in ox.parse(answer.content, format=fmt)]

    # ------------------------------------------------------------ primitives
    def _has(self, quad: Quad) -> bool:
        return self._has_many([quad])[0]

    def _has_many(self, quads: list[Quad]) -> list[bool]:
        found: set[tuple] = set()
        for i in range(0, len(quads), _CHUNK):
            chunk = quads[i:i + _CHUNK]
            rows = " ".join(f"({q.subject} {q.predicate} {q.object} {self._graph_out(q.graph_name)})" for q in chunk)
            text = f"SELECT ?s ?p ?o ?g WHERE {{ VALUES (?s ?p ?o ?g) {{ {rows} }} GRAPH ?g {{ ?s ?p ?o }} }}"
            self.send_writes(patterns={(q.subject, q.predicate, q.graph_name) for q in chunk})
            for r in self._query(text, None):
                found.add(self._key(Quad(r["s"], r["p"], r["o"], self._graph_in(r["g"]))))
        return [self._key(q) in found for q in quads]

    def _match(self, s, p, o, graph) -> Iterator[Quad]:
        terms = [t if t is not None else f"?{v}" for t, v in ((s, "s"), (p, "p"), (o, "o"))]
        pattern = f"{terms[0]} {terms[1]} {terms[2]}"
        if graph is not None:
            text = f"SELECT * WHERE {{ GRAPH {self._graph_out(graph)} {{ {pattern} }} }}"
        else:
            text = (f"SELECT * WHERE {{ GRAPH ?g {{ {pattern} }} "
                    f"FILTER(STRSTARTS(STR(?g), {ox.Literal(self._prefix)})) }}")
        if s is not None and p is not None and graph is not None:
            self.send_writes(patterns={(s, p, graph)})
        else:
            self.send_writes(None if graph is None else (graph,))
        for r in self._query(text, None):
            g = graph if graph is not None else self._graph_in(r["g"])
            yield Quad(s if s is not None else r["s"], p if p is not None else r["p"],
                       o if o is not None else r["o"], g)

    def _predicate_rows(self, p: NamedNode, graph: NamedNode, limit: int) -> list[tuple]:
        self.send_writes(patterns={(None, p, graph)})  # only writes of this predicate matter to the read
        text = f"SELECT ?s ?o WHERE {{ GRAPH {graph} {{ ?s {p} ?o }} }} LIMIT {limit}"
        return [(r["s"], r["o"]) for r in self._query(text, None)]

    def _data_text(self, adds: list[Quad], removes: list[Quad]) -> str:
        out = lambda qs: [Quad(q.subject, q.predicate, q.object, self._graph_out(q.graph_name)) for q in qs]  # noqa: E731
        return data_update(out(adds), out(removes))

    def _commit(self, adds: list[Quad], removes: list[Quad]) -> None:
        text = self._data_text(adds, removes)
        if text:
            self._send(text)

    def _write(self, adds: list[Quad], removes: list[Quad], undo: Callable[[], None] | None = None) -> None:
        """Queue the change for the next request (see the module docstring); at once without ``defer_writes``."""
        if not self.defer_writes:
            super()._write(adds, removes, undo)
            return
        text = self._data_text(adds, removes)
        if text:
            self._queue.append(_Queued(text, adds, removes, undo))
            self._written(adds, removes)

    def close(self) -> None:
        """Send the queued changes, then release the connection (a refusal is raised after it)."""
        try:
            self.send_writes()
        finally:
            _OPEN.discard(self)
            self._client.close()


#: remote stores not closed yet (see :func:`_send_at_exit`)
_OPEN: weakref.WeakSet[RemoteStore] = weakref.WeakSet()


@atexit.register
def _send_at_exit() -> None:
    """Send the changes stores still hold when the interpreter exits (a script that never closed them);
    a failure is logged, naming why (nothing can be raised to anyone any more)."""
    for store in list(_OPEN):
        try:
            store.send_writes()
        except Exception as exc:  # noqa: BLE001 - at exit the log is the only place left to say it
            logger.error("at exit, changes queued for %s were not written: %s", store.update_url, exc)


def _clash(queued: list[_Queued], prefixes: dict[str, str] | None) -> bool:
    """Whether ``prefixes`` declare a name the queued updates use for another IRI (one request then
    cannot declare both)."""
    return bool(prefixes) and any(q.prefixes and any(q.prefixes.get(k, v) != v for k, v in prefixes.items())
                                  for q in queued)


def _with_prefixes(text: str, prefixes: dict[str, str] | None) -> str:
    """PREFIX declarations for pyoxigraph's ``prefixes=`` argument, which servers do not have."""
    if not prefixes:
        return text
    return "".join(f"PREFIX {p}: <{iri}>\n" for p, iri in prefixes.items()) + text


def list_references(url: str, **kwargs) -> list[str]:
    """Names of the references a server holds (those with persisted settings)."""
    probe = RemoteStore(url, reference="", **kwargs)
    try:
        text = (f"SELECT DISTINCT ?g WHERE {{ GRAPH ?g {{ <{INTERNAL}meta> <{INTERNAL}meta:reference> ?j }} "
                f"FILTER(STRSTARTS(STR(?g), \"{INTERNAL}ref:\")) }}")
        names = []
        for r in probe._run_query(text, None):
            m = re.fullmatch(re.escape(INTERNAL) + r"ref:([^:]*):graph:meta", r["g"].value)
            if m:
                names.append(urllib.parse.unquote(m.group(1)))
        return sorted(names)
    finally:
        probe.close()


__all__ = ["RemoteStore", "list_references", "namespace_prefix", "credentials"]
