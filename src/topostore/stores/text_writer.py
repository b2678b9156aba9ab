"""Pieces of N-Triples text indexed by the store in a second thread while the next piece is made.

Why
---
pyoxigraph's ``Store.load`` of a ``bytes`` object parses and indexes without the GIL (a file-like object
makes it take the GIL back for every read), so one piece of a document can be indexed on the second core
while this thread parses the next and makes its text.  An earlier pipeline handed the worker lists of
Python quads (``extend``), which it read under the GIL: it cost more CPU and no wall time
(docs/benchmarks-history.md); text in ``bytes`` costs the worker no Python object at all.

The worker still costs CPU (the GIL handed back and forth, two threads' caches: 8 % more at 10,000
locations), which pays only where a core is free for it.  So the pieces are loaded in the calling thread
until a core is known to be free (``second_core``: :class:`.cores.CoreWatch` by default, from the
machine's counters since the writer was made), and from then on by the worker; a document of one piece
never starts it.  ``TOPOSTORE_LOAD_THREAD=1`` (``=0``) in the environment takes the worker always (never).

The worker holds at most one piece waiting, so the text held is bounded by three pieces.  Whatever the
worker raised is raised in the caller, at its next piece or at the end; the caller empties the graph on
failure, and :meth:`TextWriter.__exit__` has always joined the worker first, so nothing writes after it.
"""

from __future__ import annotations

import os
import queue
import threading
from collections.abc import Callable
from types import TracebackType

from .cores import CoreWatch

#: ``TOPOSTORE_LOAD_THREAD``: unset or ``auto`` a worker once a core is free, ``1`` always, ``0`` never
_SETTING = os.environ.get("TOPOSTORE_LOAD_THREAD", "auto")


def second_core() -> Callable[[], bool | None]:
    """The default test of whether the worker pays: whether a core is free since now (None: not known
    yet), or the environment's setting."""
    if _SETTING == "1":
        return lambda: True
    if _SETTING == "0":
        return lambda: False
    return CoreWatch().free


class TextWriter:
    """A context manager taking pieces of text (:meth:`write`) for ``load``, a call that releases the GIL."""

    def __init__(self, load: Callable[[bytes], None], core: Callable[[], bool | None] | None = None) -> None:
        self._load = load
        self._core = core if core is not None else second_core()
        self._held: bytes | None = None  # the last piece, until the next says whether a worker takes it
        self._pieces: queue.Queue[bytes | None] = queue.Queue(maxsize=1)  # None: no piece follows
        self._worker: threading.Thread | None = None
        self._failure: BaseException | None = None
        self._abandoned = False  # the caller failed: the pieces still queued are not loaded

    def write(self, text: bytes) -> None:
        """Hand over one piece (empty: nothing); raises what the worker raised on an earlier piece."""
        if not text:
            return
        if self._worker is None and self._held is not None and self._core():
            self._start()
        if self._worker is not None:
            self._raise_failure()
            self._pieces.put(text)
            return
        if self._held is not None:
            held, self._held = self._held, None
            self._load(held)
        self._held = text

    def _start(self) -> None:
        """The worker started, the piece held its first."""
        self._worker = threading.Thread(target=self._run, name="topostore-text-load", daemon=True)
        self._worker.start()
        held, self._held = self._held, None
        self._pieces.put(held)

    def _run(self) -> None:
        """Load each piece until the end; after a failure, only drain (the caller learns of it)."""
        while True:
            text = self._pieces.get()
            if text is None:
                return
            if self._failure is None and not self._abandoned:
                try:
                    self._load(text)
                except BaseException as exc:  # handed to the caller's thread
                    self._failure = exc

    def _raise_failure(self) -> None:
        if self._failure is not None:
            failure, self._failure = self._failure, None
            raise failure

    def __enter__(self) -> TextWriter:
        return self

    def __exit__(self, kind: type[BaseException] | None, exc: BaseException | None,
                 tb: TracebackType | None) -> None:
        """Wait for the worker (always: the caller may empty the graph next); a piece still held loaded
        here; the worker's failure raised unless the caller is failing already."""
        if self._worker is not None:
            self._abandoned = kind is not None
            self._pieces.put(None)
            self._worker.join()
            self._worker = None
        elif self._held is not None and kind is None:
            held, self._held = self._held, None
            self._load(held)
        if kind is None:
            self._raise_failure()


__all__ = ["TextWriter", "second_core"]
