"""A remote SPARQL 1.1 Query + Update endpoint pair as a :class:`~topostore.stores.base.Store`.

Several references share one server: each keeps its graphs under its own
namespace (``urn:topostore:graph:asserted`` becomes
``urn:topostore:ref:<name>:graph:asserted`` on the wire), so the engine's
fixed graph names need no change.

Every request is a round trip, so writes wait (:mod:`.write_queue`): the data change
of a manipulation (``DELETE DATA``/``INSERT DATA``), the updates the reasoner sends
while it runs (until its next read, or its end) and its drop of its scratch graphs at
the end of a REASON are queued and go with the next request, joined
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

import httpx
import pyoxigraph as ox
from pyoxigraph import NamedNode, Quad, QueryResultsFormat, RdfFormat

from ..errors import QueryError, StoreError
from ..rdf.vocab import INTERNAL
from .base import Store
from .data_text import data_update
from .write_queue import PROLOGUE, Queued, WriteQueue, with_prefixes

logger = logging.getLogger("topostore.store")
GRAPH_PREFIX = INTERNAL + "graph:"
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
        self._queue = WriteQueue(lambda body: self._post(self.update_url, {"update": body}), self._writes_lost)
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
        if PROLOGUE.match(text) or self._queue.clashes(prefixes):  # one prologue per request: queue first
            self.send_writes()
        self._queue.send(self._out(text), prefixes)

    def _defer_reasoning(self, text: str, prefixes: dict[str, str] | None) -> bool:
        """Queue an update sent while the reasoner runs (inside :meth:`~topostore.stores.base.Store.keeping`):
        it goes with the reasoner's next update, or before its next read (any read: what it changes is not
        known here); whatever is queued goes when the reasoner is done (:meth:`_settle`).  The server runs
        the same operations in the same order, in fewer requests."""
        if not self.defer_writes or self.listings is None or not self.listings.kept or PROLOGUE.match(text):
            return False
        self._queue.defer_reasoning(self._out(text), prefixes)
        return True

    def _settle(self) -> None:
        """The reasoner is done: its queued updates go now (a REASON says it succeeded only once its
        writes are on the server); a drop of its scratch graphs alone may wait for the next request."""
        if self._queue.holds_reasoning():
            self._queue.send()

    def _defer_drops(self, text: str) -> bool:
        """Queue an update that only drops graphs the caller declared its own (a reasoner clearing its
        scratch graphs, inside :meth:`~topostore.stores.base.Store.keeping`): it goes with the next
        request like a data change, and a read of one of those graphs sends it first."""
        if not self.defer_writes or self.listings is None or not self.listings.kept:
            return False
        return self._queue.defer_drops(text, self._out, self.listings.kept)

    def send_writes(self, graphs: Collection[NamedNode] | None = None,
                    patterns: Collection[tuple] | None = None) -> None:
        """Send the queued data changes now: all of them, when one writes ``graphs`` or one of the
        (subject, predicate, graph) ``patterns`` (neither given: always).

        A read sends them first when it may see one (a query's dataset, a look-up's patterns; the
        persisted state no query reads waits for the next update); so does :meth:`close`.
        """
        if self._queue and self._queue.touched(graphs, patterns):
            self._queue.send()

    def _run_query(self, text: str, graphs: list[NamedNode] | None, named: list[NamedNode] | None = None,
                   **kwargs):
        # the read sees every change accepted before it: with its dataset given, those of its graphs
        self.send_writes(None if graphs is None else {*graphs, *(graphs if named is None else named)})
        return self._query(text, graphs, named, **kwargs)

    def _query(self, text: str, graphs: list[NamedNode] | None, named: list[NamedNode] | None = None, **kwargs):
        """One query request (the caller has sent the queued changes the query may see)."""
        kwargs.pop("custom_functions", None)
        text = self._out(with_prefixes(text, kwargs.pop("prefixes", None)))
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
            self._queue.send(text)

    def _write(self, adds: list[Quad], removes: list[Quad], undo: Callable[[], None] | None = None) -> None:
        """Queue the change for the next request (see the module docstring); at once without ``defer_writes``."""
        if not self.defer_writes:
            super()._write(adds, removes, undo)
            return
        text = self._data_text(adds, removes)
        if text:
            self._queue.append(Queued(text, adds, removes, undo))
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
