"""HTTP routes that make reasoning visible: explanations, server-sent events, the live map page.

::

    GET /references/{name}/explain?s=R1&p=rdf:type&o=URGENT   the derivation tree (JSON)
    GET /references/{name}/events[?pattern=rdf:type+URGENT]   one server-sent event per REASON
    GET /references/{name}/map                               the live map page (HTML)
    GET /references/{name}/map.json                          the map as the page draws it
    GET /static/...                                          the page's script and Cytoscape.js (vendored)

Events are JSON objects (:func:`topostore.ontology.events.event_json`, also the ROS events topic's) sent as
``event: reason``; a comment line keeps the connection alive every
``keepalive`` seconds (default 15).  A subscriber that reads too slowly loses
the oldest events of its bounded queue (``queue``, default 100) and the next
event it gets says how many (``missed``); reasoning never waits for it.
"""

from __future__ import annotations

import asyncio
from collections.abc import AsyncIterator, Callable
from pathlib import Path
from typing import TYPE_CHECKING, Any

from pyoxigraph import Literal, NamedNode
from starlette.requests import Request
from starlette.responses import FileResponse, Response, StreamingResponse
from starlette.routing import Mount, Route
from starlette.staticfiles import StaticFiles

from ..armor.codes import CommandError
from ..errors import TopostoreError
from ..ontology.events import event_json, term_text
from ..ontology.explain import resolve_triple
from ..rdf.vocab import is_internal
from .locked import reference_json
from .security import error

if TYPE_CHECKING:  # pragma: no cover
    from ..ontology.facade import Ontology
    from .app import Api

STATIC = Path(__file__).parent / "static"
DEFAULT_KEEPALIVE = 15.0


def _number(request: Request, name: str, default: float, low: float, high: float) -> float:
    text = request.query_params.get(name)
    if text is None:
        return default
    try:
        value = float(text)
    except ValueError:
        raise ValueError(f"{name} must be a number, got {text!r}") from None
    if not low <= value <= high:
        raise ValueError(f"{name} must be between {low} and {high}, got {value}")
    return value


class LiveRoutes:
    """The handlers, bound to the server's :class:`~topostore.http.app.Api` (service and pool)."""

    def __init__(self, api: Api) -> None:
        self.api = api

    def _reference(self, request: Request):
        return self.api.service.reference(request.path_params["name"])

    async def _with_ontology(self, request: Request, work: Callable[[Ontology], dict]) -> Response:
        """``work(ontology)`` of the named reference as JSON (see :func:`.http.locked.reference_json`)."""
        return await reference_json(self.api.service, request, lambda ref: work(ref.ontology))

    # ------------------------------------------------------------ explanations
    async def explain(self, request: Request) -> Response:
        params = request.query_params
        missing = [k for k in ("s", "p", "o") if not params.get(k)]
        if missing:
            return error(400, f"missing parameter(s) {', '.join(missing)}: GET .../explain?s=R1&p=rdf:type&o=URGENT")
        def work(onto: Ontology) -> dict:
            s, p, o = resolve_triple(onto, params["s"], params["p"], params["o"])
            return onto.explain(s, p, o).to_dict()

        try:
            return await self._with_ontology(request, work)
        except (TopostoreError, ValueError) as exc:
            return error(400, str(exc))

    # ------------------------------------------------------------ events
    async def events(self, request: Request) -> Response:
        try:
            ref = self._reference(request)
            keepalive = _number(request, "keepalive", DEFAULT_KEEPALIVE, 0.05, 300)
            size = int(_number(request, "queue", 100, 1, 10_000))
            loop = asyncio.get_running_loop()
            wake = asyncio.Event()
            onto, name = ref.ontology, ref.name
            sub = onto.events.open(request.query_params.get("pattern"), size, every_reason=True,
                                   notify=lambda: loop.call_soon_threadsafe(wake.set))
        except CommandError as exc:
            return error(404, exc.message)
        except (TopostoreError, ValueError) as exc:
            return error(400, str(exc))

        async def stream() -> AsyncIterator[str]:
            try:
                yield "retry: 2000\n: connected\n\n"
                while True:
                    try:
                        await asyncio.wait_for(wake.wait(), keepalive)
                    except TimeoutError:
                        yield ": keep-alive\n\n"
                        continue
                    wake.clear()
                    while (event := sub.get(timeout=0)) is not None:
                        data = event_json(event, onto.prefix, name)
                        yield f"id: {event.seq}\nevent: reason\ndata: {data}\n\n"
            finally:
                sub.close()

        return StreamingResponse(stream(), media_type="text/event-stream",
                                 headers={"Cache-Control": "no-cache", "X-Accel-Buffering": "no"})

    # ------------------------------------------------------------ the map page
    async def map_page(self, request: Request) -> Response:
        try:
            self._reference(request)
        except CommandError as exc:
            return error(404, exc.message)
        return FileResponse(STATIC / "map.html", media_type="text/html")

    async def map_data(self, request: Request) -> Response:
        return await self._with_ontology(request, map_data)


def map_data(onto: Ontology) -> dict[str, Any]:
    """Locations (with their classes), doors, robots and links as the page draws them.

    Uses the topological map's vocabulary (LOCATION, ROOM, CORRIDOR, URGENT,
    DOOR, ROBOT, hasDoor, isIn) in the ontology's namespace, asserted ∪ inferred.
    """
    prefix = onto.prefix

    def name(t) -> str:
        return term_text(t, prefix)

    def members(cls: str) -> list[NamedNode]:
        return sorted((i for i in onto.instances(cls) if isinstance(i, NamedNode) and not is_internal(i)),
                      key=lambda i: i.value)

    urgent = {i.value for i in members("URGENT")}
    corridors = {i.value for i in members("CORRIDOR")}
    rooms = {i.value for i in members("ROOM")}
    locations = []
    links = []
    for loc in members("LOCATION"):
        kind = "CORRIDOR" if loc.value in corridors else ("ROOM" if loc.value in rooms else "LOCATION")
        visited = [v.value for v in onto.data_values("visitedAt", loc) if isinstance(v, Literal)]
        locations.append({"id": name(loc), "kind": kind, "urgent": loc.value in urgent,
                          "visitedAt": visited[0] if visited else None})
        links += [{"source": name(loc), "target": name(d), "kind": "hasDoor"}
                  for d in onto.object_values("hasDoor", loc, names=False)]
    robots = []
    for robot in members("ROBOT"):
        where = onto.object_values("isIn", robot, names=False)
        now = [v.value for v in onto.data_values("now", robot)]
        robots.append({"id": name(robot), "isIn": name(where[0]) if where else None, "now": now[0] if now else None})
        links += [{"source": name(robot), "target": name(w), "kind": "isIn"} for w in where]
    report = onto.report
    return {"locations": locations, "doors": [{"id": name(d)} for d in members("DOOR")], "robots": robots,
            "links": links, "urgent": sorted(name(NamedNode(u)) for u in urgent),
            "consistent": None if report is None else report.consistent}


def live_routes(api: Api) -> list:
    """The routes to add to the service's application."""
    live = LiveRoutes(api)
    return [
        Route("/references/{name}/explain", live.explain, methods=["GET"]),
        Route("/references/{name}/events", live.events, methods=["GET"]),
        Route("/references/{name}/map", live.map_page, methods=["GET"]),
        Route("/references/{name}/map.json", live.map_data, methods=["GET"]),
        Mount("/static", StaticFiles(directory=STATIC), name="static"),
    ]


__all__ = ["live_routes", "map_data", "LiveRoutes"]
