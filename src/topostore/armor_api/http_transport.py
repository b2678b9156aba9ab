"""``HttpTransport``: the armor_py_api client talking to ``topostore serve`` over HTTP.

``ArmorClient(..., url="http://127.0.0.1:8765")`` selects it, so the same
robot code runs against an in-process service or a remote server.  Standard
library only (urllib): a robot's client should not need extra packages.
"""

from __future__ import annotations

import json
import os
import urllib.error
import urllib.request
from collections.abc import Sequence
from typing import Any

from ..armor import ArmorRequest, ArmorResponse
from ..armor.types import ArmorResponseList
from .armor_exceptions import ArmorServiceCallError


class HttpTransport:
    """Sends requests to ``POST {url}/armor`` and ``POST {url}/armor/batch``.

    ``token`` defaults to the ``TOPOSTORE_TOKEN`` environment variable, so
    robot code written for armor_py_api needs no change to reach a server
    that requires one.

    Connection failures, timeouts and HTTP errors raise :class:`ArmorServiceCallError`
    with the server's one-line ``error`` message when there is one; aRMOR
    failures come back as normal responses with ``success=false``.
    """

    def __init__(self, url: str, timeout: float = 5, token: str | None = None) -> None:
        if not url.startswith(("http://", "https://")):
            raise ArmorServiceCallError(f"{url!r} is not an http(s) URL")
        self.url = url.rstrip("/")
        self.timeout = timeout
        self.token = token if token is not None else os.environ.get("TOPOSTORE_TOKEN") or None

    def call(self, request: ArmorRequest) -> ArmorResponse:
        return ArmorResponse.from_dict(self._post("/armor", ArmorRequest.from_dict(request).to_dict()))

    def call_many(self, requests: Sequence[ArmorRequest]) -> ArmorResponseList:
        body = [ArmorRequest.from_dict(r).to_dict() for r in requests]
        return ArmorResponseList.from_dict(self._post("/armor/batch", body))

    def _post(self, path: str, payload: Any) -> dict[str, Any]:
        headers = {"Content-Type": "application/json", "Accept": "application/json"}
        if self.token:
            headers["Authorization"] = f"Bearer {self.token}"
        req = urllib.request.Request(self.url + path, data=json.dumps(payload).encode(), headers=headers, method="POST")
        try:
            with urllib.request.urlopen(req, timeout=self.timeout) as answer:  # noqa: S310 - scheme checked above
                data = json.loads(answer.read())
        except urllib.error.HTTPError as exc:
            raise ArmorServiceCallError(f"{self.url}{path}: HTTP {exc.code}: {_error_text(exc)}") from None
        except (urllib.error.URLError, OSError) as exc:
            reason = getattr(exc, "reason", exc)
            raise ArmorServiceCallError(f"cannot reach {self.url}{path}: {reason}") from None
        except json.JSONDecodeError as exc:
            raise ArmorServiceCallError(f"{self.url}{path} did not answer JSON: {exc}") from None
        if not isinstance(data, dict):
            raise ArmorServiceCallError(f"{self.url}{path} answered {type(data).__name__}, not an object")
        return data


def _error_text(exc: urllib.error.HTTPError) -> str:
    try:
        return str(json.loads(exc.read()).get("error", exc.reason))
    except Exception:  # a non-JSON error page: the status line says enough
        return str(exc.reason)


__all__ = ["HttpTransport"]
