"""HTTP requests counted from the benchmark side: every request any ``httpx.Client`` sends.

The remote store is the library's business and its internals change; what a robot step costs on a
SPARQL server is the number of round trips it makes, and that is visible at the transport whatever
client sent them.  :func:`counting` wraps ``httpx.HTTPTransport.handle_request`` for the duration
of a ``with`` block (requests sent through a transport of its own, e.g. a mocked one, are not seen).
"""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field

import httpx


@dataclass
class RequestCounter:
    """Requests seen so far, in all and by (method, path)."""

    total: int = 0
    by_endpoint: dict[str, int] = field(default_factory=dict)

    def seen(self, request: httpx.Request) -> None:
        self.total += 1
        key = f"{request.method} {request.url.path}"
        self.by_endpoint[key] = self.by_endpoint.get(key, 0) + 1


@contextmanager
def counting() -> Iterator[RequestCounter]:
    """Count the HTTP requests sent inside the block (restores the transport on the way out)."""
    counter = RequestCounter()
    original = httpx.HTTPTransport.handle_request

    def handle_request(self: httpx.HTTPTransport, request: httpx.Request) -> httpx.Response:
        counter.seen(request)
        return original(self, request)

    httpx.HTTPTransport.handle_request = handle_request  # type: ignore[method-assign]
    try:
        yield counter
    finally:
        httpx.HTTPTransport.handle_request = original  # type: ignore[method-assign]
