"""The store's native work overlapped with Python work: the one place topostore runs a second thread.

pyoxigraph 0.5 releases the GIL while it evaluates a query and while ``Store.extend`` inserts the quads
it has read (reading them from Python holds the GIL), and it runs one writer at a time: two updates in
two threads do not overlap, an update and a query do.  So, on a machine with a free core, two overlaps
pay and no other does:

* :func:`pipelined_extend`: a big write cut into chunks, each inserted by a worker thread while the
  caller's thread makes the next chunk (a document's parse and checks, see
  :mod:`topostore.ontology.streamed`);
* :class:`Beside`: a read-only evaluation (a query) in a worker thread while the caller's thread writes.

The contract, for both:

* **one worker thread**, started and joined inside the call (:class:`Beside`: inside its ``with``
  block): no thread outlives the call, even when either side raises;
* **errors propagated**: the worker's exception is raised in the caller's thread; when both sides fail,
  the caller's own error is the one raised;
* **the worker reads only what the caller's thread does not change meanwhile**: :func:`pipelined_extend`
  writes chunks in the caller's order, one at a time, into graphs nothing reads until it returns; a
  :class:`Beside` reader reads graphs the caller's writes leave alone (the caller says which, and
  keeps to it);
* **in memory only**: a remote or durable store is not asked to overlap (its callers stay sequential,
  see :attr:`topostore.stores.base.Store.overlaps`).

``TOPOSTORE_OVERLAP=0`` in the environment turns both off (:data:`ENABLED`): everything then runs in the
caller's thread, in the order a sequential caller takes (a machine without a free core gains nothing
from the second thread; the benchmarks compare the two ways in one tree).
"""

from __future__ import annotations

import os
from collections.abc import Callable, Iterable
from concurrent.futures import Future, ThreadPoolExecutor
from itertools import islice
from typing import Generic, TypeVar

T = TypeVar("T")
Q = TypeVar("Q")

#: quads per chunk of :func:`pipelined_extend`: big enough that a chunk's insertion outweighs a hand-over,
#: small enough that the first insertion starts early and two chunks in memory cost little
CHUNK = 65_536

#: whether the second thread is used at all (``TOPOSTORE_OVERLAP=0``: never)
ENABLED = os.environ.get("TOPOSTORE_OVERLAP", "1") != "0"


def pipelined_extend(write: Callable[[Iterable[Q]], object], quads: Iterable[Q], chunk: int = CHUNK) -> None:
    """``write`` every quad of ``quads``, in order, chunk by chunk: chunk *n* is written in a worker thread
    while the caller's thread makes chunk *n + 1* (at most one write at a time, at most two chunks held).

    A document of one chunk is written in the caller's thread (no thread for a small write).  Not atomic:
    an error in ``quads`` or in a write leaves the chunks written before it; the caller takes them out."""
    if not ENABLED:
        write(quads)
        return
    it = iter(quads)
    batch = list(islice(it, chunk))
    following = list(islice(it, chunk)) if len(batch) == chunk else []
    if not following:
        if batch:
            write(batch)
        return
    with ThreadPoolExecutor(max_workers=1, thread_name_prefix="topostore-write") as pool:
        pending: Future = pool.submit(write, batch)
        try:
            while following:
                batch, following = following, list(islice(it, chunk)) if len(following) == chunk else []
                pending.result()  # the previous chunk is in: hand over the next one
                pending = pool.submit(write, batch)
        finally:
            _settle(pending)
        pending.result()


def _settle(pending: Future) -> None:
    """Wait for ``pending`` to end, whatever the caller's thread is raising (the worker's error, if any,
    is raised by :meth:`Future.result` afterwards, unless the caller's thread raises its own)."""
    try:
        pending.exception()
    except BaseException:  # pragma: no cover - interrupted while waiting: the executor's exit still joins
        pass


class Beside(Generic[T]):
    """A read-only evaluation run in a worker thread while the caller's thread goes on writing::

        with Beside(lambda: check(store)) as checks:
            publish(store)             # writes graphs ``check`` does not read
        violations = checks.result()   # the worker is joined when the block ends

    The worker is started on entering the block and joined on leaving it, also when the block raises.
    With ``overlap=False`` the evaluation runs in the caller's thread on entering (the same order a
    sequential caller would take, for stores that must stay sequential)."""

    def __init__(self, read: Callable[[], T], overlap: bool = True) -> None:
        self._read = read
        self._overlap = overlap and ENABLED
        self._pool: ThreadPoolExecutor | None = None
        self._future: Future | None = None
        self._value: T | None = None

    def __enter__(self) -> Beside[T]:
        if self._overlap:
            self._pool = ThreadPoolExecutor(max_workers=1, thread_name_prefix="topostore-read")
            self._future = self._pool.submit(self._read)
        else:
            self._value = self._read()
        return self

    def __exit__(self, *exc_info: object) -> None:
        if self._pool is not None:
            _settle(self._future)
            self._pool.shutdown(wait=True)
            self._pool = None

    def result(self) -> T:
        """The evaluation's value (its error raised here); only after the block."""
        if self._pool is not None:
            raise RuntimeError("Beside.result() is read after its with block, once the worker is joined")
        if self._future is not None:
            return self._future.result()
        return self._value  # type: ignore[return-value]


__all__ = ["CHUNK", "Beside", "pipelined_extend"]
