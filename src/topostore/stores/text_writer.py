"""Pieces of N-Triples text indexed by the store in a second thread while the next piece is made.

Why
---
pyoxigraph's ``Store.load`` of a ``bytes`` object parses and indexes without the GIL (a file-like object
makes it take the GIL back for every read), so one piece of a document can be indexed on the second core
while this thread parses the next and makes its text.  An earlier pipeline handed the worker lists of
Python quads (``extend``), which it read under the GIL: it cost more CPU and no wall time
(docs/benchmarks-history.md); text in ``bytes`` costs the worker no Python object at all.

A document of one piece is loaded in the calling thread (no thread started); the worker holds at most one
piece waiting, so the text held is bounded by two pieces beside the one being made.  Whatever the worker
raised is raised in the caller, at its next piece or at the end; the caller empties the graph on failure,
and :meth:`TextWriter.__exit__` has always joined the worker first, so nothing writes after it.
"""

from __future__ import annotations

import queue
import threading
from collections.abc import Callable
from types import TracebackType


class TextWriter:
    """A context manager taking pieces of text (:meth:`write`) for ``load``, a call that releases the GIL."""

    def __init__(self, load: Callable[[bytes], None]) -> None:
        self._load = load
        self._first: bytes | None = None  # the first piece, held until a second one says a thread pays
        self._pieces: queue.Queue[bytes | None] = queue.Queue(maxsize=1)  # None: no piece follows
        self._worker: threading.Thread | None = None
        self._failure: BaseException | None = None
        self._abandoned = False  # the caller failed: the pieces still queued are not loaded

    def write(self, text: bytes) -> None:
        """Hand over one piece (non-empty); raises what the worker raised on an earlier piece."""
        if not text:
            return
        if self._worker is None:
            if self._first is None:
                self._first = text
                return
            self._start()
        self._raise_failure()
        self._pieces.put(text)

    def _start(self) -> None:
        self._worker = threading.Thread(target=self._run, name="topostore-text-load", daemon=True)
        self._worker.start()
        first, self._first = self._first, None
        assert first is not None
        self._pieces.put(first)

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
        """Wait for the worker (always: the caller may empty the graph next); a lone first piece loaded
        here; the worker's failure raised unless the caller is failing already."""
        if self._worker is not None:
            self._abandoned = kind is not None
            self._pieces.put(None)
            self._worker.join()
            self._worker = None
        elif self._first is not None and kind is None:
            first, self._first = self._first, None
            self._load(first)
        if kind is None:
            self._raise_failure()


__all__ = ["TextWriter"]
