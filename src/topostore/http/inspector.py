"""The inspector: what Protégé shows of an ontology, live, with the why of every inference.

::

    GET /references/{name}/inspector                 the page (entity pages, SPARQL console, history)
    GET /references/{name}/entities/{entity}         one entity: facts asserted/inferred, proofs (JSON)
    GET /references/{name}/entities?q=R&limit=20     entities whose name contains ``q`` (the search box)
    GET /references/{name}/consistency[?brief=true]  the last REASON's violations: axiom, individuals, proof
    GET /references/{name}/history                   the change events recorded for the reference
    DELETE /references/{name}/history                stop recording them (the page starts it again)
    GET /references/{name}/queries                   the named queries (queries/*.rq), the console's examples

``{entity}`` is a short name (``R1``), a full IRI (``http://…%23R1``, its
``#`` percent-encoded, or ``<…>``) or ``owl:Thing``.  The routes sit behind the
service's protections like every other (loopback without a token, a bearer
token otherwise, no foreign origins); the page and its scripts (YASGUI,
vendored) come from the service itself and fetch nothing from elsewhere.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING, Any

from pyoxigraph import NamedNode, Triple
from starlette.convertors import Convertor, register_url_convertor
from starlette.requests import Request
from starlette.responses import FileResponse, JSONResponse, Response
from starlette.routing import Route

from ..armor.codes import CommandError
from ..errors import TopostoreError
from ..ontology.explain import constant
from ..ontology.named_queries import named_queries
from ..rdf.vocab import ASSERTED
from .entities import (
    DEFAULT_LIMIT,
    MAX_LIMIT,
    View,
    annotations,
    assertions,
    different_from,
    display_name,
    entity_kinds,
    individual_sections,
    is_mentioned,
    link_names,
    members,
    resolve_entity,
    search_entities,
)
from .history import Histories
from .locked import reference_json
from .schema import axioms_of, hierarchy, property_sections, read_tbox, rules_naming
from .security import error

if TYPE_CHECKING:  # pragma: no cover
    from ..armor.reference import Reference
    from ..ontology.facade import Ontology
    from ..reason.consistency import Violation
    from .app import Api

STATIC = Path(__file__).parent / "static"
_PROPERTY_KINDS = ("object property", "data property", "annotation property")
#: The page runs only the service's own scripts and talks only to the service: a name in the ontology
#: that reaches HTML unescaped (YASGUI's result table writes IRIs into links as they are) cannot run
#: script, and nothing can be fetched from elsewhere, whatever a script does.
CSP = ("default-src 'self'; script-src 'self'; style-src 'self' 'unsafe-inline'; img-src 'self' data:; "
       "connect-src 'self'; object-src 'none'; base-uri 'none'; form-action 'none'; frame-ancestors 'none'")


class AnyText(Convertor):
    """A path parameter that is any text, line breaks included (``path`` stops at a newline), so
    every entity name reaches the route and gets its own answer (400 for a name that cannot be an IRI)."""

    regex = "(?s:.*)"

    def convert(self, value: str) -> str:
        return value

    def to_string(self, value: str) -> str:
        return value


register_url_convertor("topostore_text", AnyText())


class NotFound(Exception):
    """The entity is named nowhere in the reference."""


def state(onto: Ontology, facts: bool = True) -> tuple[dict[str, Any], list[str]]:
    """Reasoning state every answer carries, and the warnings it calls for (``facts``: the answer lists facts)."""
    report = onto.report
    warnings = []
    if report is None:
        warnings.append("the reference was never reasoned: no inferred facts yet (send REASON)")
    elif not report.consistent and facts:
        warnings.append("the reference is inconsistent: like every query, this page shows the asserted facts only "
                        "(see the consistency report)")
    if onto.dirty and report is not None:
        warnings.append("the reference changed since its last REASON: inferred facts are those of that REASON")
    return {"consistent": None if report is None else report.consistent, "reasoned": report is not None,
            "changed_since_reasoning": onto.dirty}, warnings


def describe_entity(onto: Ontology, e: NamedNode, limit: int = DEFAULT_LIMIT) -> dict[str, Any]:
    """Everything the entity page shows of ``e`` (see the module docstring of :mod:`.entities`)."""
    if not is_mentioned(onto, e):
        raise NotFound(f"no entity {display_name(e, onto.prefix)!r} ({e.value}) in this reference")
    view = View(onto, limit)
    status, warnings = state(onto)
    view.warnings.extend(warnings)
    kinds = entity_kinds(onto, e, [ASSERTED, *onto.visible_graphs()])
    out: dict[str, Any] = {"iri": e.value, "name": display_name(e, onto.prefix),
                           "kind": kinds[0] if kinds else "entity", "kinds": kinds, **status,
                           "annotations": annotations(view, e), **individual_sections(view, e)}
    if "individual" in kinds:
        out["different_from"] = different_from(view, e)
    schema_kinds = [k for k in kinds if k == "class" or k in _PROPERTY_KINDS]
    tbox = read_tbox(view) if schema_kinds else None
    if "class" in kinds:
        out.update(hierarchy(view, e))
        out["members"] = members(view, e)
    if any(k in _PROPERTY_KINDS for k in kinds):
        out.update(property_sections(view, tbox, e))
        out["assertions"] = assertions(view, e)
    if tbox is not None:
        out["axioms"] = axioms_of(view, tbox, e)
    out["rules"] = rules_naming(view, e)
    out["links"] = link_names(view, proof_texts(out))
    out["warnings"], out["truncated"] = view.warnings, view.truncated
    return out


def proof_texts(value: Any) -> list[str]:
    """The texts of every proof node and axiom in an answer (for :func:`link_names`)."""
    found: list[str] = []

    def walk(v: Any) -> None:
        if isinstance(v, dict):
            for k, item in v.items():
                if k in ("triple", "text") and isinstance(item, str):
                    found.append(item)
                elif k in ("domain", "range") and isinstance(item, list):
                    found.extend(x for x in item if isinstance(x, str))
                else:
                    walk(item)
        elif isinstance(v, list):
            for item in v:
                walk(item)

    walk(value)
    return found


def violation_proof(view: View, v: Violation) -> dict[str, Any] | None:
    """Why a check matched: its rule's premises under the violation's individuals, each explained
    (the facts that clash, down to asserted ones), in the tree format of :mod:`topostore.ontology.explain`."""
    rule = next((r for r in view.onto.rules.checks if r.name == v.rule and r.origin == v.axiom), None)
    if rule is None:
        return None
    binding = {"?" + k: t for k, t in v.individuals.items() if isinstance(t, NamedNode)}
    premises = []
    for atom in rule.body:
        terms = [binding.get(x) if x.startswith("?") else constant(x) for x in (atom.s, atom.p, atom.o)]
        if any(t is None for t in terms):
            text = " ".join(view.explainer.render_term(t) if t is not None else x
                            for t, x in zip(terms, (atom.s, atom.p, atom.o)))
            premises.append({"triple": text, "status": "condition"})
            continue
        premises.append(view.explainer.explain(Triple(*terms)).to_dict())
    return {"triple": v.message, "status": "inferred", "rule": v.rule, "origin": v.axiom, "bindings": {},
            "premises": premises}


def consistency(onto: Ontology, brief: bool = False) -> dict[str, Any]:
    """The last REASON's consistency: each violation's rule, axiom, message and individuals (linked),
    and the proof of the clash; ``brief``: the state and the number of violations only (the page's badge)."""
    view = View(onto)
    status, warnings = state(onto, facts=False)
    if brief:
        return {**status, "violation_count": len(onto.violations)}
    violations = [{"rule": v.rule, "axiom": v.axiom, "message": v.message,
                   "individuals": [{"variable": k, **view.term(t)} for k, t in v.individuals.items()],
                   "why": violation_proof(view, v)}
                  for v in onto.violations]
    if status["consistent"] is False and not violations:
        warnings.append("the violations of a reference reopened from disk are not kept: send REASON to see them")
    return {**status, "violations": violations, "warnings": warnings,
            "links": link_names(view, proof_texts(violations) + [v["axiom"] for v in violations])}


def _limit(request: Request, default: int) -> int:
    text = request.query_params.get("limit")
    if text is None:
        return default
    if not text.isdigit() or not 1 <= int(text) <= MAX_LIMIT:
        raise ValueError(f"limit must be a whole number from 1 to {MAX_LIMIT}, got {text!r}")
    return int(text)


class InspectorRoutes:
    """The handlers, bound to the server's :class:`~topostore.http.app.Api` (its service)."""

    def __init__(self, api: Api) -> None:
        self.api = api
        self.histories = Histories()

    def _reference(self, request: Request) -> Reference:
        return self.api.service.reference(request.path_params["name"])

    async def _locked(self, request: Request, work: Callable[[Reference], Any]) -> Response:
        """``work(reference)`` as JSON (see :func:`.locked.reference_json`): 404 for an unknown reference or
        entity, 400 for bad input."""
        return await reference_json(self.api.service, request, work, missing=(NotFound,),
                                    bad_input=(TopostoreError, ValueError))

    async def page(self, request: Request) -> Response:
        try:
            self.histories.of(self._reference(request))  # recording starts when the page is first opened
        except CommandError as exc:
            return error(404, exc.message)
        return FileResponse(STATIC / "inspector.html", media_type="text/html", headers={"Content-Security-Policy": CSP})

    async def entity(self, request: Request) -> Response:
        def work(ref: Reference) -> dict[str, Any]:
            onto = ref.ontology
            return describe_entity(onto, resolve_entity(onto, request.path_params["entity"]),
                                   _limit(request, DEFAULT_LIMIT))

        return await self._locked(request, work)

    async def search(self, request: Request) -> Response:
        def work(ref: Reference) -> dict[str, Any]:
            text = request.query_params.get("q", "")
            found, total = search_entities(ref.ontology, text, _limit(request, 20))
            return {"q": text, "entities": found, "total": total}

        return await self._locked(request, work)

    async def consistency(self, request: Request) -> Response:
        brief = request.query_params.get("brief", "false")
        if brief not in ("true", "false"):
            return error(400, f"brief must be true or false, got {brief!r}")
        return await self._locked(request, lambda ref: consistency(ref.ontology, brief == "true"))

    async def history(self, request: Request) -> Response:
        def work(ref: Reference) -> dict[str, Any]:
            history = self.histories.of(ref)
            history.drain()
            return history.to_dict()

        return await self._locked(request, work)

    async def stop_history(self, request: Request) -> Response:
        """Stop recording (each REASON then takes no snapshots for it); opening the page starts again."""
        try:
            ref = self._reference(request)
        except CommandError as exc:
            return error(404, exc.message)
        return JSONResponse({"recording": False, "stopped": self.histories.stop(ref)})

    async def queries(self, request: Request) -> Response:
        try:
            self._reference(request)
        except CommandError as exc:
            return error(404, exc.message)
        return JSONResponse({"queries": [{"name": q.name, "description": q.description, "params": sorted(q.params),
                                          "text": q.text} for q in named_queries().values()]})


def inspector_routes(api: Api) -> list[Route]:
    """The routes to add to the service's application."""
    inspector = InspectorRoutes(api)
    return [
        Route("/references/{name}/inspector", inspector.page, methods=["GET"]),
        Route("/references/{name}/entities", inspector.search, methods=["GET"]),
        Route("/references/{name}/entities/{entity:topostore_text}", inspector.entity, methods=["GET"]),
        Route("/references/{name}/consistency", inspector.consistency, methods=["GET"]),
        Route("/references/{name}/history", inspector.history, methods=["GET"]),
        Route("/references/{name}/history", inspector.stop_history, methods=["DELETE"]),
        Route("/references/{name}/queries", inspector.queries, methods=["GET"]),
    ]


__all__ = ["inspector_routes", "describe_entity", "consistency", "InspectorRoutes", "NotFound"]
