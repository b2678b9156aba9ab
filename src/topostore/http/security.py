"""The HTTP service's protections, run before any route: origins, CORS, Host, token, request size.

Without a token the service trusts whoever can reach the loopback interface,
so two browser attacks are stopped here: requests from web pages of other
origins (refused unless allowed with ``--cors-origin``) and DNS rebinding (the
Host header must name this machine literally).  With a token, every request
must carry it instead.  Bodies are read here up to the limit and replayed to
the route, so an oversized upload is refused (413) without being held in memory.

Where Starlette has the middleware, it is used as is: :class:`CORSMiddleware`
adds the CORS headers and answers preflights of allowed origins;
:class:`TrustedHostMiddleware` checks the Host header (answering
``400 Invalid host header``; it parses the header by RFC 9112, so
``localhost:80@evil.com`` is refused).  What Starlette does not do is a small
middleware of its own here: CORSMiddleware only withholds its headers from
other origins, so :class:`RefuseForeignOrigins` refuses their requests (a
cross-site form POST would otherwise still change the map); :class:`RequireToken`
checks the bearer token; :class:`LimitRequestSize` bounds query strings and bodies.
"""

from __future__ import annotations

import hmac
import ipaddress
from collections.abc import Sequence

from starlette.datastructures import Headers
from starlette.middleware import Middleware
from starlette.middleware.cors import CORSMiddleware
from starlette.middleware.trustedhost import TrustedHostMiddleware
from starlette.responses import JSONResponse
from starlette.types import ASGIApp, Message, Receive, Scope, Send

#: Host names that always name this machine (``*.localhost`` resolves to loopback by RFC 6761)
LOOPBACK_HOSTS = ("localhost", "*.localhost", "127.0.0.1", "[::1]")
#: what a browser may ask of an allowed origin in a preflight
CORS_METHODS = ("GET", "POST")
CORS_HEADERS = ("Authorization", "Content-Type", "Accept")


def error(status: int, message: str, headers: dict[str, str] | None = None) -> JSONResponse:
    """Every error answer of topostore's own has the same shape: ``{"error": "..."}`` and a fitting status."""
    return JSONResponse({"error": message}, status_code=status, headers=headers)


class RefuseForeignOrigins:
    """403 for any request carrying an ``Origin`` that is not allowed: a web page of another site.

    CORSMiddleware only decides which responses a page may *read*; the request
    itself (a form POST of a SPARQL update, a costly query) would still run.
    """

    def __init__(self, app: ASGIApp, allowed: Sequence[str]) -> None:
        self.app = app
        self.allowed = frozenset(allowed)

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        origin = Headers(scope=scope).get("origin") if scope["type"] == "http" else None
        if origin is not None and origin not in self.allowed:
            response = error(403, f"requests from web pages of origin {origin!r} are refused; "
                             "allow it with --cors-origin")
            await response(scope, receive, send)
            return
        await self.app(scope, receive, send)


class RequireToken:
    """401 unless the request carries ``Authorization: Bearer <token>`` (compared in constant time)."""

    def __init__(self, app: ASGIApp, token: str) -> None:
        self.app = app
        self.token = token.encode()

    def authorized(self, header: str) -> bool:
        scheme, _, value = header.encode("latin-1").partition(b" ")
        return scheme.lower() == b"bearer" and hmac.compare_digest(value.strip(), self.token)

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] == "http" and not self.authorized(Headers(scope=scope).get("authorization", "")):
            response = error(401, "missing or wrong bearer token (send 'Authorization: Bearer <token>')",
                             {"WWW-Authenticate": 'Bearer realm="topostore"'})
            await response(scope, receive, send)
            return
        await self.app(scope, receive, send)


class BodyTooLarge(Exception):
    """The request body grew past the limit while it was read."""


class ClientGone(Exception):
    """The client disconnected before sending its whole body."""


async def read_body(receive: Receive, max_bytes: int) -> bytes:
    """The whole request body, read chunk by chunk and never more than ``max_bytes`` of it."""
    chunks: list[bytes] = []
    size = 0
    while True:
        message = await receive()
        if message["type"] == "http.disconnect":
            raise ClientGone
        chunk = message.get("body", b"")
        size += len(chunk)
        if size > max_bytes:
            raise BodyTooLarge
        chunks.append(chunk)
        if not message.get("more_body", False):
            return b"".join(chunks)


def replaying(body: bytes, receive: Receive) -> Receive:
    """A ``receive`` that hands the already-read ``body`` to the route once, then waits as the original."""
    replayed = False

    async def replay() -> Message:
        nonlocal replayed
        if not replayed:
            replayed = True
            return {"type": "http.request", "body": body, "more_body": False}
        return await receive()

    return replay


class LimitRequestSize:
    """414 for a query string, 413 for a body (declared or sent) longer than ``max_bytes``."""

    def __init__(self, app: ASGIApp, max_bytes: int) -> None:
        self.app = app
        self.max_bytes = max_bytes

    def too_large(self) -> JSONResponse:
        return error(413, f"the request body is larger than the limit of {self.max_bytes} bytes "
                     "(server option --max-request-bytes)")

    def declared_too_large(self, scope: Scope) -> bool:
        declared = Headers(scope=scope).get("content-length")
        return declared is not None and declared.isdigit() and int(declared) > self.max_bytes

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] != "http":
            await self.app(scope, receive, send)
            return
        if len(scope.get("query_string", b"")) > self.max_bytes:
            await error(414, f"the query string is longer than the limit of {self.max_bytes} bytes; "
                        "send the query with POST")(scope, receive, send)
            return
        if self.declared_too_large(scope):
            await self.too_large()(scope, receive, send)
            return
        try:
            body = await read_body(receive, self.max_bytes)
        except BodyTooLarge:
            await self.too_large()(scope, receive, send)
            return
        except ClientGone:
            return
        await self.app(scope, replaying(body, receive), send)


def allowed_hosts(bind_host: str) -> list[str]:
    """The Host names a request may use without a token: loopback names, and the address bound if it is one."""
    hosts = list(LOOPBACK_HOSTS)
    name = bind_host.strip().strip("[]")
    try:
        address = ipaddress.ip_address(name)
    except ValueError:
        return hosts
    literal = f"[{address}]" if address.version == 6 else str(address)
    if address.is_loopback and literal not in hosts:
        hosts.append(literal)
    return hosts


def security_middleware(token: str | None, max_request_bytes: int, cors_origins: Sequence[str] = (),
                        bind_host: str = "127.0.0.1") -> list[Middleware]:
    """The protections in the order they run (outermost first), for ``Starlette(middleware=...)``."""
    origins = tuple(dict.fromkeys(o.rstrip("/") for o in cors_origins))
    stack = [Middleware(RefuseForeignOrigins, allowed=origins)]
    if origins:
        stack.append(Middleware(CORSMiddleware, allow_origins=origins, allow_methods=CORS_METHODS,
                                allow_headers=CORS_HEADERS, expose_headers=("Content-Type",), max_age=600))
    if token is None:
        stack.append(Middleware(TrustedHostMiddleware, allowed_hosts=allowed_hosts(bind_host), www_redirect=False))
    else:
        stack.append(Middleware(RequireToken, token=token))
    stack.append(Middleware(LimitRequestSize, max_bytes=max_request_bytes))
    return stack


__all__ = ["security_middleware", "error", "allowed_hosts", "RefuseForeignOrigins", "RequireToken",
           "LimitRequestSize", "read_body", "LOOPBACK_HOSTS"]
