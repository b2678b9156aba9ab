"""How the client reaches a service: any object with ``call`` and ``call_many``.

``ArmorService`` itself satisfies :class:`Transport`, so the default transport
is an in-process service shared by every client of the process (several
clients on one reference see each other's changes, as with one aRMOR node).
A network transport only has to translate the same request/response objects.
"""

from __future__ import annotations

import threading
from collections.abc import Sequence
from typing import Protocol, runtime_checkable

from ..armor import ArmorRequest, ArmorResponse, ArmorService
from ..armor.types import ArmorResponseList


@runtime_checkable
class Transport(Protocol):
    """Carries requests to an aRMOR-compatible service."""

    def call(self, request: ArmorRequest) -> ArmorResponse:
        """One request; raises ``OSError`` (e.g. ``ConnectionError``) or ``ArmorServiceCallError`` when the
        service cannot be reached."""
        ...

    def call_many(self, requests: Sequence[ArmorRequest]) -> ArmorResponseList:
        """The serialized service: requests executed in order."""
        ...


_default_service: ArmorService | None = None
_default_lock = threading.Lock()


def default_service() -> ArmorService:
    """The process-wide in-process service used when a client is given no transport."""
    global _default_service
    with _default_lock:
        if _default_service is None:
            _default_service = ArmorService()
        return _default_service


def set_default_service(service: ArmorService | None) -> None:
    """Replace the shared service (``None``: a fresh one is created on next use); for tests and embedding."""
    global _default_service
    with _default_lock:
        _default_service = service


__all__ = ["Transport", "default_service", "set_default_service"]
