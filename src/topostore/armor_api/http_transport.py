"""``HttpTransport``: the armor_py_api client talking to ``topostore serve`` over HTTP.

``ArmorClient(..., url="http://127.0.0.1:8765")`` selects it (or the
``TOPOSTORE_URL`` environment variable, so unchanged robot code can reach a
server), and the same robot code runs against an in-process service or a
remote server.  Standard library only (:mod:`http.client`): a robot's client
should not need extra packages.

``timeout`` has armor_py_api's meaning: how long to *wait for the service*
(rospy.wait_for_service), not a cap on the call.  The transport retries
connecting until the service answers or ``timeout`` has passed; once
connected, the request may take as long as the command needs (a LOAD of a
map of thousands of locations takes longer than the default 5 s).
"""

from __future__ import annotations

import http.client
import json
import os
import time
import urllib.parse
from collections.abc import Sequence
from typing import Any

from ..armor import ArmorRequest, ArmorResponse
from ..armor.types import ArmorResponseList
from .armor_exceptions import ArmorServiceCallError

#: Environment variables read when the client is not told explicitly.
TOKEN_ENV = "TOPOSTORE_TOKEN"
URL_ENV = "TOPOSTORE_URL"
_RETRY_SECONDS = 0.1


class HttpTransport:
    """Sends requests to ``POST {url}/armor`` and ``POST {url}/armor/batch``.

    ``token`` defaults to the ``TOPOSTORE_TOKEN`` environment variable, so
    robot code written for armor_py_api needs no change to reach a server
    that requires one.  ``call_timeout`` caps a whole call (``None``: no cap,
    as with a ROS service call).

    Connection failures, an unreachable service after ``timeout`` and HTTP
    errors raise :class:`ArmorServiceCallError` with the server's one-line
    ``error`` message when there is one; aRMOR failures come back as normal
    responses with ``success=false``.
    """

    def __init__(self, url: str, timeout: float = 5, token: str | None = None,
                 call_timeout: float | None = None) -> None:
        parts = urllib.parse.urlsplit(url)
        if parts.scheme not in ("http", "https") or not parts.hostname:
            raise ArmorServiceCallError(f"{url!r} is not an http(s) URL")
        self.url = url.rstrip("/")
        self._parts = parts
        self.timeout = timeout
        self.call_timeout = call_timeout
        self.token = token if token is not None else os.environ.get(TOKEN_ENV) or None

    def call(self, request: ArmorRequest) -> ArmorResponse:
        return ArmorResponse.from_dict(self._post("/armor", ArmorRequest.from_dict(request).to_dict()))

    def call_many(self, requests: Sequence[ArmorRequest]) -> ArmorResponseList:
        body = [ArmorRequest.from_dict(r).to_dict() for r in requests]
        return ArmorResponseList.from_dict(self._post("/armor/batch", body))

    def _connect(self) -> http.client.HTTPConnection:
        """A connection to the service, retried until it answers or ``timeout`` has passed."""
        kind = http.client.HTTPSConnection if self._parts.scheme == "https" else http.client.HTTPConnection
        deadline = time.monotonic() + max(0.0, float(self.timeout))
        while True:
            remaining = deadline - time.monotonic()
            conn = kind(self._parts.hostname, self._parts.port, timeout=max(remaining, _RETRY_SECONDS))
            try:
                conn.connect()
                return conn
            except OSError as exc:
                conn.close()
                if time.monotonic() + _RETRY_SECONDS >= deadline:
                    raise ArmorServiceCallError(f"cannot reach {self.url} within {self.timeout} s "
                                                f"(is topostore serve running?): {exc}") from None
                time.sleep(_RETRY_SECONDS)

    def _post(self, path: str, payload: Any) -> dict[str, Any]:
        headers = {"Content-Type": "application/json", "Accept": "application/json"}
        if self.token:
            headers["Authorization"] = f"Bearer {self.token}"
        target = self._parts.path.rstrip("/") + path
        conn = self._connect()
        try:
            assert conn.sock is not None
            conn.sock.settimeout(self.call_timeout)  # connected: the command may take as long as it needs
            conn.request("POST", target, body=json.dumps(payload).encode(), headers=headers)
            answer = conn.getresponse()
            raw = answer.read()
        except OSError as exc:
            raise ArmorServiceCallError(f"{self.url}{path}: the connection failed: {exc}") from None
        finally:
            conn.close()
        if answer.status >= 400:
            raise ArmorServiceCallError(f"{self.url}{path}: HTTP {answer.status}: {_error_text(raw, answer.reason)}")
        try:
            data = json.loads(raw)
        except (UnicodeDecodeError, json.JSONDecodeError) as exc:
            raise ArmorServiceCallError(f"{self.url}{path} did not answer JSON: {exc}") from None
        if not isinstance(data, dict):
            raise ArmorServiceCallError(f"{self.url}{path} answered {type(data).__name__}, not an object")
        return data


def _error_text(raw: bytes, reason: str) -> str:
    try:
        return str(json.loads(raw).get("error", reason))
    except (ValueError, AttributeError):  # not JSON, or JSON but not an object: the status line says enough
        return reason


__all__ = ["HttpTransport", "TOKEN_ENV", "URL_ENV"]
