"""The network service: aRMOR commands as JSON over HTTP and a SPARQL 1.1 endpoint per reference.

Routes (all answers JSON unless a SPARQL result format is negotiated)::

    GET  /health                        liveness and version
    GET  /references                    each reference: triples, consistency, last reasoning
    POST /armor                         one aRMOR request  -> ArmorResponse fields
    POST /armor/batch                   a list of requests -> the serialized service's reply
    GET  /references/{name}/sparql      SPARQL 1.1 Protocol query (?query=...)
    GET  /references/{name}/explain     why a triple holds; /events (SSE), /map (live page): see live.py
    GET  /references/{name}/inspector   entity pages, SPARQL console, history: see http/inspector.py
    POST /references/{name}/sparql      query or update (form, application/sparql-query|update)

Secure by default: loopback only unless a bearer token is set, LOAD/SAVE
paths confined to the data directory, bounded request bodies, a time limit on
SPARQL, SPARQL updates off, and SERVICE/LOAD (which would make the service
fetch URLs) refused.  See docs/service.md for the reasons behind the stack.
"""

from __future__ import annotations

import asyncio
import concurrent.futures
import contextlib
import ipaddress
import json
import logging
import socket
import time
import urllib.parse
from collections.abc import AsyncIterator, Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from starlette.applications import Starlette
from starlette.concurrency import run_in_threadpool
from starlette.requests import Request
from starlette.responses import JSONResponse, Response
from starlette.routing import Route

from .. import __version__
from ..armor import ArmorService
from ..armor.codes import CommandError
from ..errors import QueryError, TopostoreError
from ..rdf.vocab import ASSERTED, INFERRED
from ..sparql.execute import (
    Job,
    ReferenceMounted,
    ResultTooLarge,
    SparqlTimeout,
    run_query,
    run_update,
    timeout_message,
)
from ..sparql.guard import UnsafeOperationError
from ..sparql.results import NotAcceptable
from .live import live_routes
from .security import error, security_middleware

logger = logging.getLogger("topostore.server")

DEFAULT_MAX_REQUEST_BYTES = 1024 * 1024
DEFAULT_SPARQL_TIMEOUT = 10.0
DEFAULT_SPARQL_WORKERS = 4
DEFAULT_SPARQL_MAX_ROWS = 500_000


class ConfigError(TopostoreError):
    """A server setting that would be unsafe or cannot work."""


@dataclass
class ServerConfig:
    """Everything ``topostore serve`` can set; the defaults are the safe choice."""

    host: str = "127.0.0.1"
    port: int = 8765
    data_dir: Path = Path("data")
    token: str | None = None
    allow_update: bool = False
    max_request_bytes: int = DEFAULT_MAX_REQUEST_BYTES
    sparql_timeout: float = DEFAULT_SPARQL_TIMEOUT
    sparql_workers: int = DEFAULT_SPARQL_WORKERS
    sparql_max_rows: int = DEFAULT_SPARQL_MAX_ROWS
    short_names: bool = False
    #: browser origins allowed to call the service (CORS), e.g. a YASGUI page; none by default
    cors_origins: tuple[str, ...] = ()
    #: where references live (None: memory; a directory; an http(s) SPARQL server), see topostore.stores
    store: str | None = None
    #: flush every acknowledged change to disk (directory stores)
    sync: bool = False
    store_query_url: str | None = None
    store_update_url: str | None = None
    #: LOAD refuses ontologies with axioms not reasoned completely (see topostore.compile.profile)
    strict: bool = False

    def check(self) -> None:
        """Refuse settings that would expose the service or cannot work, with the fix in the message."""
        if self.token is not None and not self.token.strip():
            raise ConfigError("the token is empty; give a real secret with --token")
        if not is_loopback(self.host) and not self.token:
            raise ConfigError(f"refusing to listen on {self.host!r} without a token: anyone on the network could "
                              "change the robot's map; add --token SECRET or bind 127.0.0.1")
        if self.max_request_bytes < 1:
            raise ConfigError("--max-request-bytes must be at least 1")
        if not self.sparql_timeout > 0:
            raise ConfigError("--sparql-timeout must be a positive number of seconds")
        if self.sparql_max_rows < 1:
            raise ConfigError("--sparql-max-rows must be at least 1")
        if self.sparql_workers < 1:
            raise ConfigError("the SPARQL worker count must be at least 1")


def is_loopback(host: str) -> bool:
    """True when every address ``host`` stands for is a loopback address ("" and 0.0.0.0 are not)."""
    name = host.strip().strip("[]")
    if not name:
        return False
    try:
        return ipaddress.ip_address(name).is_loopback
    except ValueError:
        pass
    try:
        infos = socket.getaddrinfo(name, None)
    except OSError:
        return False
    return bool(infos) and all(ipaddress.ip_address(info[4][0].split("%")[0]).is_loopback for info in infos)


# --------------------------------------------------------------------------- application

class Api:
    """Route handlers bound to one service and configuration."""

    def __init__(self, config: ServerConfig, service: ArmorService) -> None:
        self.config = config
        self.service = service
        self.pool = concurrent.futures.ThreadPoolExecutor(max_workers=config.sparql_workers,
                                                          thread_name_prefix="topostore-sparql")
        self.started = time.time()

    # ------------------------------------------------------------ simple routes
    async def health(self, request: Request) -> Response:
        return JSONResponse({"status": "ok", "version": __version__, "references": len(self.service.reference_names()),
                             "uptime_seconds": round(time.time() - self.started, 3)})

    async def references(self, request: Request) -> Response:
        infos = await run_in_threadpool(self._reference_infos)
        return JSONResponse({"references": infos})

    def _reference_infos(self) -> list[dict[str, Any]]:
        out = []
        for name in sorted(self.service.reference_names()):
            try:
                ref = self.service.reference(name)
            except CommandError:  # dropped meanwhile
                continue
            with ref.lock:
                onto = ref.ontology
                report = onto.report
                out.append({
                    "name": name,
                    "iri": ref.iri,
                    "triples_asserted": onto.store.count(ASSERTED),
                    "triples_inferred": onto.store.count(INFERRED),
                    "consistent": None if report is None else report.consistent,
                    "last_reasoning_seconds": None if report is None else round(report.stats.seconds, 6),
                    "changed_since_reasoning": onto.dirty,
                    "buffered_changes": len(ref.buffer),
                    "mounted_by": ref.owner,
                })
        return out

    # ------------------------------------------------------------ aRMOR
    async def armor(self, request: Request) -> Response:
        data = await _json_body(request)
        if isinstance(data, Response):
            return data
        if not isinstance(data, dict):
            return error(400, "POST /armor takes one request as a JSON object; use /armor/batch for a list")
        if "armor_request" in data and isinstance(data["armor_request"], dict):  # the ROS service's wrapper
            data = data["armor_request"]
        response = await run_in_threadpool(self.service.call, data)
        return JSONResponse(response.to_dict())

    async def armor_batch(self, request: Request) -> Response:
        data = await _json_body(request)
        if isinstance(data, Response):
            return data
        if isinstance(data, dict) and isinstance(data.get("armor_requests"), list):
            data = data["armor_requests"]
        if not isinstance(data, list):
            return error(400, "POST /armor/batch takes a JSON list of requests (or {\"armor_requests\": [...]})")
        result = await run_in_threadpool(self.service.call_many, data)
        return JSONResponse(result.to_dict())

    # ------------------------------------------------------------ SPARQL
    async def sparql(self, request: Request) -> Response:
        name = request.path_params["name"]
        try:
            ref = self.service.reference(name)
        except CommandError as exc:
            return error(404, exc.message)
        if request.method == "GET" and not {"query", "update"} & set(request.query_params):
            return await _described(request, ref, self.config.allow_update)  # SPARQL 1.1 Service Description
        parsed = await _sparql_operation(request)
        if isinstance(parsed, Response):
            return parsed
        kind, text = parsed
        params = request.query_params
        for dataset_param in ("default-graph-uri", "named-graph-uri", "using-graph-uri", "using-named-graph-uri"):
            if dataset_param in params:
                return error(400, f"{dataset_param} is not supported: the dataset of this endpoint is fixed to the "
                             f"asserted and inferred knowledge of reference {name!r}")
        if kind == "update" and not self.config.allow_update:
            return error(403, "SPARQL updates are disabled on this server (start it with --allow-update, "
                         "or change the ontology with aRMOR commands on /armor)")
        limit = self.config.sparql_timeout
        job = Job(deadline=time.monotonic() + limit)
        def work() -> Any:
            if kind == "query":
                return run_query(ref, text, request.headers.get("accept"), params.get("format"), job, limit,
                                 self.config.sparql_max_rows)
            return run_update(ref, text, job, limit)

        try:
            outcome = await self._run_limited(work, job, limit)
        except SparqlTimeout as exc:
            return error(503, str(exc))
        except NotAcceptable as exc:
            return error(406, str(exc))
        except ResultTooLarge as exc:
            return error(400, str(exc))
        except (UnsafeOperationError, ReferenceMounted) as exc:
            return error(403, str(exc))
        except QueryError as exc:
            return error(400, str(exc))
        except TopostoreError as exc:  # e.g. a rule in the update that cannot be compiled: nothing was changed
            return error(400, f"the update was not applied: {exc}")
        if kind == "update":
            return JSONResponse(outcome.to_dict())
        return Response(outcome.body, media_type=outcome.format.content_type,
                        headers={"Vary": "Accept"})

    async def _run_limited(self, work: Callable[[], Any], job: Job, limit: float) -> Any:
        """Run ``work`` on the SPARQL pool; give up at the deadline unless an update already committed."""
        loop = asyncio.get_running_loop()
        future = loop.run_in_executor(self.pool, work)
        future.add_done_callback(_consume_exception)
        remaining = max(0.0, job.deadline - time.monotonic())
        done, _ = await asyncio.wait({future}, timeout=remaining)
        if not done and job.expire():
            raise SparqlTimeout(timeout_message(limit))
        return await future

    def close(self) -> None:
        self.pool.shutdown(wait=False, cancel_futures=True)


async def _described(request: Request, ref: Any, allow_update: bool) -> Response:
    from . import describe_service

    try:
        return await describe_service(request, ref, allow_update)
    except NotAcceptable as exc:
        return error(406, str(exc))


def _consume_exception(future: asyncio.Future) -> None:
    """Abandoned (timed-out) futures still finish; read their exception so asyncio does not warn."""
    if not future.cancelled():
        future.exception()


async def _json_body(request: Request) -> Any:
    """The parsed JSON body; only ``application/json``, which browsers cannot send cross-site unasked."""
    media = request.headers.get("content-type", "").split(";")[0].strip().lower()
    if media != "application/json":
        return error(415, f"send aRMOR requests as application/json, not {media or 'no content type'!r}")
    body = await request.body()
    try:
        return json.loads(body)
    except (UnicodeDecodeError, json.JSONDecodeError) as exc:
        return error(400, f"the request body is not valid JSON: {exc}")
    except ValueError as exc:  # e.g. an integer of more than 4,300 digits
        return error(400, f"the request body has a value out of range: {exc}")
    except RecursionError:
        return error(400, "the request body nests JSON arrays or objects too deeply")


async def _sparql_operation(request: Request) -> tuple[str, str] | Response:
    """("query"|"update", text) from a SPARQL 1.1 Protocol request, or an error response."""
    if request.method == "GET":
        if "update" in request.query_params:
            return error(400, "SPARQL updates must be sent with POST")
        query = request.query_params.get("query")
        if not query:
            return error(400, "missing the 'query' parameter (GET /references/NAME/sparql?query=SELECT...)")
        return "query", query
    media = request.headers.get("content-type", "").split(";")[0].strip().lower()
    body = await request.body()
    try:
        text = body.decode("utf-8")
    except UnicodeDecodeError:
        return error(400, "the request body is not UTF-8 text")
    if media == "application/x-www-form-urlencoded":
        form = urllib.parse.parse_qs(text, keep_blank_values=True)
        queries, updates = form.get("query", []), form.get("update", [])
        if len(queries) + len(updates) != 1:
            return error(400, "send exactly one 'query' or one 'update' form field")
        return ("query", queries[0]) if queries else ("update", updates[0])
    if media == "application/sparql-query":
        return "query", text
    if media == "application/sparql-update":
        return "update", text
    return error(415, "POST a SPARQL operation as application/x-www-form-urlencoded (query= or update=), "
                 f"application/sparql-query or application/sparql-update, not {media or 'no content type'!r}")


def create_app(config: ServerConfig, service: ArmorService | None = None) -> Starlette:
    """The ASGI application serving one :class:`ArmorService` (created from ``config`` if not given)."""
    config.check()
    data_dir = Path(config.data_dir)
    data_dir.mkdir(parents=True, exist_ok=True)
    service = service or ArmorService(data_dir=data_dir, short_names=config.short_names, store=config.store,
                                      sync=config.sync, store_query_url=config.store_query_url,
                                      store_update_url=config.store_update_url, strict=config.strict)
    if service.data_dir is None:
        raise ConfigError("the served ArmorService must confine files to a data directory")
    api = Api(config, service)

    @contextlib.asynccontextmanager
    async def lifespan(app: Starlette) -> AsyncIterator[None]:
        yield
        api.close()
        service.close()

    routes = [
        Route("/health", api.health, methods=["GET"]),
        Route("/references", api.references, methods=["GET"]),
        Route("/armor", api.armor, methods=["POST"]),
        Route("/armor/batch", api.armor_batch, methods=["POST"]),
        Route("/references/{name}/sparql", api.sparql, methods=["GET", "POST"]),
    ]
    routes += live_routes(api)  # explanations, server-sent events, the live map page (live.py)
    from .inspector import inspector_routes  # entity pages, SPARQL console, history (http/inspector.py)

    routes += inspector_routes(api)
    from . import GraphStore  # SPARQL 1.1 Graph Store HTTP Protocol: /references/{name}/data

    routes += GraphStore(api).routes()
    protections = security_middleware(config.token, config.max_request_bytes, config.cors_origins, config.host)
    app = Starlette(routes=routes, lifespan=lifespan, middleware=protections)
    app.state.api = api
    return app


def serve(config: ServerConfig) -> None:
    """Check the configuration, then serve until interrupted (Ctrl-C)."""
    import uvicorn

    app = create_app(config)
    logger.info("serving on http://%s:%s (data directory %s)", config.host, config.port, Path(config.data_dir).resolve())
    uvicorn.run(app, host=config.host, port=config.port, log_level="info", server_header=False,
                timeout_graceful_shutdown=5)


__all__ = ["ServerConfig", "ConfigError", "create_app", "serve", "is_loopback", "error"]
