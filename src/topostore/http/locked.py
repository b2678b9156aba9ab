"""One reference's work as a JSON answer: under the reference's lock, off the event loop.

The live map and the inspector both answer from one reference at a time; the reference's lock
keeps a robot's commands and a page's reads apart, and the thread pool keeps the event loop free
while a proof or a map is built.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from starlette.concurrency import run_in_threadpool
from starlette.requests import Request
from starlette.responses import JSONResponse, Response

from ..armor.codes import CommandError
from ..armor.reference import Reference
from ..armor.service import ArmorService
from .security import error


async def reference_json(service: ArmorService, request: Request, work: Callable[[Reference], Any],
                         missing: tuple[type[Exception], ...] = (),
                         bad_input: tuple[type[Exception], ...] = ()) -> Response:
    """``work(reference)`` of the reference named in the path, as JSON.

    404 when there is no such reference or ``work`` raises one of ``missing``; 400 when it raises
    one of ``bad_input``; anything else propagates.
    """
    try:
        ref = service.reference(request.path_params["name"])
    except CommandError as exc:
        return error(404, exc.message)

    def locked() -> Any:
        with ref.lock:
            return work(ref)

    try:
        return JSONResponse(await run_in_threadpool(locked))
    except missing as exc:
        return error(404, str(exc))
    except bad_input as exc:
        return error(400, str(exc))


__all__ = ["reference_json"]
