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
from ..compile.notices import answered, unsaid
from ..errors import TopostoreError
from ..ontology.facade import Ontology
from ..ontology.pellet_values import PelletDifferenceWarning
from ..ontology.spellings import (
    HELD,
    again_notes,
    holding,
    joined,
    one_spelling,
    spelling_kept,
    tag_notes,
    value_of,
)
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
    return _parsed(body, UPLOAD_FORMATS[media], base_iri)


def _parsed(body: bytes, fmt: RdfFormat | None, base_iri: str | None) -> list[Triple]:
    try:
        return Ontology().store.parse_bytes(body, fmt, base_iri, source="the request body")
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
        outcome = await run_in_threadpool(_apply, ref, plan, request.method, triples, written)
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
        ref, heard = await run_in_threadpool(_new_reference, self.api, name, iri, body, UPLOAD_FORMATS[media])
        counts = await run_in_threadpool(_created, ref, heard)
        return JSONResponse(counts, status_code=201, headers={"Location": f"/references/{name}/data?default"})


def _plan(method: str, uploaded: list[Triple]) -> Callable[[Ontology], Delta]:
    """What PUT (replace), POST (merge) or DELETE (empty) does, computed against the state when applied;
    the delta's warning names each spelling written but not taken, and the one that stays instead."""

    def plan(onto: Ontology) -> Delta:
        current = _as_written(onto)
        if method == "DELETE":
            return Delta(remove=sorted(current, key=str))
        held = {value_of(t): t for t in current if isinstance(t.object, Literal)}
        new, again = one_spelling(uploaded)
        notes = again_notes(again, lambda first: held.get(value_of(first), first))
        added = [t for t in new if t not in current]
        if method == "PUT":  # a stored value respelled is removed and added in one change: the change says it
            gone = current.difference(new)
            return Delta(add=sorted(added, key=str), remove=sorted(gone, key=str), warning=joined(notes))
        taken = []  # POST: the store keeps one value once, in the spelling it holds
        for t in added:
            old = held.get(value_of(t)) if isinstance(t.object, Literal) else None
            if old is None:
                taken.append(t)
            else:
                notes.append(spelling_kept(old, t, HELD))
        return Delta(add=sorted(taken, key=str), warning=joined(notes))

    return plan


def _as_written(onto: Ontology) -> set[Triple]:
    """The asserted graph with each literal as written (the store keeps a canonical form of some): a
    document that spells a stored value otherwise is then seen as a respelling, not as the value there."""
    store = onto.store
    return {Triple(t.subject, t.predicate, store.original_literal(ASSERTED, t.subject, t.predicate, t.object))
            if isinstance(t.object, Literal) else t for t in store.triples(graph=ASSERTED)}


def _apply(ref: Reference, plan: Callable[[Ontology], Delta], method: str, uploaded: list[Triple],
           written: tuple[bytes, RdfFormat | None] | None = None) -> dict[str, Any]:
    """One all-or-nothing manipulation of the asserted graph, reasoned as aRMOR manipulations are;
    ``written``: the uploaded document and its format, whose spellings of the added literals' language
    tags are kept (pyoxigraph lowers them), and whose ``uploaded`` triples' other spellings are said."""
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
        notes = []
        if written is not None:
            ref.ontology.values.learned(*written, only=literal_tags(added))
            notes = _tag_notes(ref, uploaded, written, set(added))
        return {"added": len(added), "removed": sum(len(a.removed) for a in done), "is_consistent": ref.is_consistent,
                "warnings": [*(a.warning for a in done if a.warning), *filter(None, [joined(notes)])]}


def _tag_notes(ref: Reference, uploaded: list[Triple], written: tuple[bytes, RdfFormat | None],
               added: set[Triple]) -> list[str]:
    """The notes of the uploaded literals whose language tag the graph spells otherwise: the same value
    where the graph held it before (not among the triples ``added``), else a new value spelled as stored."""
    return tag_notes(ref.ontology.store.forms.tags, written, lambda keys: holding(uploaded, keys),
                     lambda t: t not in added, literal_tags(uploaded))


def _created(ref: Reference, heard: list[str]) -> dict[str, Any]:
    """The reply to a PUT that made ``ref``: the facts its graph holds (a document may write one fact twice,
    or one value in two spellings) and what its load says, as a LOAD's reply (each spelling written but not
    taken among it, with the one the graph keeps), and what else its load and REASON warned of (``heard``)."""
    with ref.lock:
        onto = ref.ontology
        lines = onto.notice_lines()
        return {"reference": ref.name, "iri": ref.iri, "added": onto.store.count(ASSERTED), "removed": 0,
                "is_consistent": ref.is_consistent, "warnings": [*lines, *unsaid(heard, lines)]}


def _new_reference(api: Api, name: str, iri: str, body: bytes, fmt: RdfFormat | None) -> tuple[Reference, list[str]]:
    """The reference a PUT creates from the document ``body`` (its rules compiled first: all or nothing), and
    the warnings its load and REASON gave (answered, whatever the warnings filter)."""
    onto = Ontology(prefix=iri + "#")
    try:
        assert fmt is not None  # parse_upload refused the formats it cannot read
        with answered(PelletDifferenceWarning) as heard:
            onto.load_data(body, fmt, base_iri=iri)
            onto.reason()
    except TopostoreError as exc:
        raise GraphStoreError(400, f"the ontology was not loaded: {exc}") from None
    ref, created = api.service.add_reference(Reference(name, onto, iri))
    if not created:
        raise GraphStoreError(409, f"reference {name!r} was created by another request meanwhile; PUT again to "
                              "replace its graph")
    return ref, heard


__all__ = ["GraphStore", "GraphStoreError", "UPLOAD_FORMATS", "target_graph", "ontology_iri", "GRAPH_FORMATS"]
