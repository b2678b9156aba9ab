"""SPARQL 1.1 Graph Store HTTP Protocol for each reference: ``/references/{name}/data``.

Graphs of a reference, addressed as the protocol says (``?default`` or
``?graph=IRI``, indirect identification):

* the **asserted graph** — what was loaded and manipulated — is the graph
  store's default graph, and also answers to its name: the reference's IRI
  (as given at LOAD) or ``urn:topostore:graph:asserted``.  GET, PUT (replace),
  POST (merge) and DELETE (empty it) work on it; every write is one
  all-or-nothing manipulation followed by reasoning, like an aRMOR command;
* the **inferred graph** ``urn:topostore:graph:inferred`` is read-only (GET):
  inferences change only through reasoning on what is asserted.

Uploading an ontology file is a PUT (or POST) of its bytes with their media
type; a PUT to a reference that does not exist creates it (201), with the IRI
from ``?iri=`` or the document's ``owl:Ontology``.  Writes need the server's
``--allow-update`` (as SPARQL updates do) and are refused on a reference
mounted by an aRMOR client.  Parsing is pyoxigraph's: no URL is fetched, no
XML entity is expanded beyond the document.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from pyoxigraph import Literal, NamedNode, RdfFormat, Triple
from starlette.concurrency import run_in_threadpool
from starlette.requests import Request
from starlette.responses import JSONResponse, Response
from starlette.routing import Route

from ..armor.codes import CommandError
from ..armor.reference import Change, Delta, Reference
from ..errors import TopostoreError
from ..ontology.facade import Ontology
from ..rdf.terms import value_key
from ..rdf.vocab import ASSERTED, ENTAILED, INFERRED, OWL, RDF, RDFS, TYPE, XSD
from ..sparql.results import GRAPH_FORMATS, NotAcceptable, choose_format, render_graph
from ..stores.language_tags import literal_tags
from .security import error

if TYPE_CHECKING:  # pragma: no cover
    from .app import Api

#: Media types accepted in PUT and POST bodies.
UPLOAD_FORMATS = {
    "text/turtle": RdfFormat.TURTLE,
    "application/x-turtle": RdfFormat.TURTLE,
    "text/n3": RdfFormat.N3,
    "application/n-triples": RdfFormat.N_TRIPLES,
    "application/rdf+xml": RdfFormat.RDF_XML,
    "application/owl+xml": None,  # OWL/XML: named so the refusal can say what to send instead
    "application/ld+json": RdfFormat.JSON_LD,
}


class GraphStoreError(TopostoreError):
    """A request the graph store refuses; carries the HTTP status."""

    def __init__(self, status: int, message: str) -> None:
        super().__init__(message)
        self.status = status


def target_graph(request: Request, ref: Reference | None) -> str:
    """``"asserted"`` or ``"inferred"`` from ``?default`` / ``?graph=``; GraphStoreError otherwise."""
    params = request.query_params
    has_default, graph = "default" in params, params.get("graph")
    if has_default == (graph is not None):
        raise GraphStoreError(400, "name exactly one graph: ?default (the asserted graph) or ?graph=IRI")
    if has_default:
        return "asserted"
    assert graph is not None
    names = {ASSERTED.value: "asserted", INFERRED.value: "inferred"}
    if ref is not None:
        names.setdefault(ref.iri, "asserted")
    if graph in names:
        return names[graph]
    known = ", ".join(f"<{n}>" for n in sorted(names))
    raise GraphStoreError(404, f"graph <{graph}> does not exist in this reference; its graphs are {known}")


def graph_triples(ref: Reference, which: str) -> list[Triple]:
    """The asserted triples, or the inferred ones (empty while the ontology is inconsistent)."""
    onto = ref.ontology
    with ref.lock:
        if which == "asserted":
            return onto.triples(inferred=False)
        visible = [g for g in onto.visible_graphs() if g in (INFERRED, ENTAILED)]
        return onto.store.dump(visible, restore_literals_from=ASSERTED)


def parse_upload(request: Request, body: bytes, base_iri: str | None) -> list[Triple]:
    """The triples of a PUT/POST body in a supported RDF syntax (GraphStoreError 415/400 otherwise)."""
    media = request.headers.get("content-type", "").split(";")[0].strip().lower()
    if media not in UPLOAD_FORMATS or UPLOAD_FORMATS[media] is None:
        raise GraphStoreError(415, f"send the graph as one of {', '.join(m for m, f in UPLOAD_FORMATS.items() if f)}, "
                              f"not {media or 'no content type'!r} (OWL files from Protégé: application/rdf+xml)")
    try:
        return Ontology().store.parse_bytes(body, UPLOAD_FORMATS[media], base_iri, source="the request body")
    except TopostoreError as exc:
        raise GraphStoreError(400, f"the graph was not stored: {exc}") from None


def ontology_iri(triples: list[Triple]) -> str | None:
    """The IRI of the document's owl:Ontology, if it declares exactly one."""
    iris = {t.subject.value for t in triples
            if t.predicate == TYPE and t.object == NamedNode(OWL + "Ontology") and isinstance(t.subject, NamedNode)}
    return iris.pop() if len(iris) == 1 else None


class GraphStore:
    """The protocol's handlers over one :class:`~topostore.http.app.Api` (service and configuration)."""

    def __init__(self, api: Api) -> None:
        self.api = api

    def routes(self) -> list[Route]:
        return [Route("/references/{name}/data", self.handle, methods=["GET", "PUT", "POST", "DELETE"])]

    async def handle(self, request: Request) -> Response:
        try:
            if request.method in ("GET", "HEAD"):
                return await self.get(request)
            return await self.write(request)
        except GraphStoreError as exc:
            return error(exc.status, str(exc))
        except NotAcceptable as exc:
            return error(406, str(exc))

    def _reference(self, name: str) -> Reference | None:
        try:
            return self.api.service.reference(name)
        except CommandError:
            return None

    async def get(self, request: Request) -> Response:
        name = request.path_params["name"]
        ref = self._reference(name)
        if ref is None:
            raise GraphStoreError(404, f"reference {name!r} is not loaded")
        which = target_graph(request, ref)
        fmt = choose_format(request.headers.get("accept"), graph=True, explicit=request.query_params.get("format"))
        triples = await run_in_threadpool(graph_triples, ref, which)
        prefixes = {"owl": OWL, "rdf": RDF, "rdfs": RDFS, "xsd": XSD, "": ref.prefix}
        body = await run_in_threadpool(render_graph, triples, fmt, prefixes)
        if isinstance(fmt.ox_format, RdfFormat):  # pyoxigraph lowers language tags: spelled as first written
            body = await run_in_threadpool(ref.ontology.store.forms.tags.respell, body, fmt.ox_format)
        return Response(body, media_type=fmt.content_type, headers={"Vary": "Accept"})

    async def write(self, request: Request) -> Response:
        if not self.api.config.allow_update:
            raise GraphStoreError(403, "graph store writes are disabled on this server (start it with --allow-update, "
                                  "or change the ontology with aRMOR commands on /armor)")
        name = request.path_params["name"]
        ref = self._reference(name)
        if ref is None:
            if request.method != "PUT":
                raise GraphStoreError(404, f"reference {name!r} is not loaded; PUT a graph to create it")
            return await self.create(request, name)
        which = target_graph(request, ref)
        if which != "asserted":
            raise GraphStoreError(405, "the inferred graph is read-only: change what is asserted and the reasoner "
                                  "updates it")
        triples: list[Triple] = []
        written = None
        if request.method != "DELETE":
            body = await request.body()
            triples = await run_in_threadpool(parse_upload, request, body, ref.iri or None)
            written = (body, UPLOAD_FORMATS[request.headers.get("content-type", "").split(";")[0].strip().lower()])
        plan = _plan(request.method, triples)
        outcome = await run_in_threadpool(_apply, ref, plan, request.method, written)
        return JSONResponse(outcome)

    async def create(self, request: Request, name: str) -> Response:
        """PUT to a new reference: load the uploaded ontology as LOAD FILE would."""
        if "default" not in request.query_params:
            raise GraphStoreError(404, f"reference {name!r} is not loaded; create it with PUT ...?default")
        body = await request.body()
        triples = await run_in_threadpool(parse_upload, request, body, request.query_params.get("iri"))
        iri = request.query_params.get("iri") or ontology_iri(triples)
        if not iri:
            raise GraphStoreError(400, "cannot tell the ontology IRI: the document declares no single owl:Ontology; "
                                  "add ?iri=http://... (names are resolved against IRI#)")
        media = request.headers.get("content-type", "").split(";")[0].strip().lower()
        ref = await run_in_threadpool(_new_reference, self.api, name, iri, body, UPLOAD_FORMATS[media])
        with ref.lock:
            counts = {"reference": name, "iri": iri, "added": len(triples), "removed": 0,
                      "is_consistent": ref.is_consistent}
        return JSONResponse(counts, status_code=201, headers={"Location": f"/references/{name}/data?default"})


def _plan(method: str, uploaded: list[Triple]) -> Callable[[Ontology], Delta]:
    """What PUT (replace), POST (merge) or DELETE (empty) does, computed against the state when applied."""

    def plan(onto: Ontology) -> Delta:
        # as written (the store keeps a canonical form of some literals): a document that spells a stored
        # value otherwise then reaches the change as a respelling, which is said (SpellingKeptWarning), not
        # taken for the value already there
        store = onto.store
        current = {Triple(t.subject, t.predicate, store.original_literal(ASSERTED, t.subject, t.predicate, t.object))
                   if isinstance(t.object, Literal) else t for t in store.triples(graph=ASSERTED)}
        new = set(_one_spelling(uploaded))
        if method == "POST":
            return Delta(add=sorted(new - current, key=str))
        if method == "PUT":
            return Delta(add=sorted(new - current, key=str), remove=sorted(current - new, key=str))
        return Delta(remove=sorted(current, key=str))

    return plan


def _one_spelling(triples: list[Triple]) -> list[Triple]:
    """``triples`` with one spelling per value (the first written): the store keeps one value once, so a
    document writing ``"7"^^xsd:long`` and ``"07"^^xsd:long`` asserts one fact, counted and said once."""
    seen: set = set()
    kept = []
    for t in triples:
        o = t.object
        key = (t.subject, t.predicate, value_key(o)) if isinstance(o, Literal) else t
        if key not in seen:
            seen.add(key)
            kept.append(t)
    return kept


def _apply(ref: Reference, plan: Callable[[Ontology], Delta], method: str,
           written: tuple[bytes, RdfFormat | None] | None = None) -> dict[str, Any]:
    """One all-or-nothing manipulation of the asserted graph, reasoned as aRMOR manipulations are;
    ``written``: the uploaded document and its format, whose spellings of the added literals' language
    tags are kept (pyoxigraph lowers them)."""
    with ref.lock:
        if ref.owner is not None:
            raise GraphStoreError(403, f"reference {ref.name!r} is mounted by client {ref.owner!r}; only that client "
                                  "may change it")
        delta = plan(ref.ontology)
        try:
            done = ref.applied([Change(f"Graph Store {method}", lambda _onto: delta)])
        except TopostoreError as exc:
            raise GraphStoreError(400, f"the graph was not stored: {exc}") from None
        added = [t for a in done for t in a.added]
        if written is not None:
            ref.ontology.values.learned(*written, only=literal_tags(added))
        return {"added": len(added), "removed": sum(len(a.removed) for a in done), "is_consistent": ref.is_consistent,
                "warnings": [a.warning for a in done if a.warning]}


def _new_reference(api: Api, name: str, iri: str, body: bytes, fmt: RdfFormat | None) -> Reference:
    onto = Ontology(prefix=iri + "#")
    try:
        onto.load_data(body, fmt, base_iri=iri)  # compiles the rules first: all or nothing
        onto.reason()
    except TopostoreError as exc:
        raise GraphStoreError(400, f"the ontology was not loaded: {exc}") from None
    ref, created = api.service.add_reference(Reference(name, onto, iri))
    if not created:
        raise GraphStoreError(409, f"reference {name!r} was created by another request meanwhile; PUT again to "
                              "replace its graph")
    return ref


__all__ = ["GraphStore", "GraphStoreError", "UPLOAD_FORMATS", "target_graph", "ontology_iri", "GRAPH_FORMATS"]
