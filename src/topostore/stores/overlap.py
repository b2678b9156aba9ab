"""A read-only query beside a write: the one place topostore runs a second thread.

pyoxigraph 0.5 releases the GIL while it evaluates a query, and it runs one writer at a time: two updates
in two threads do not overlap, an update and a query do.  So, on a machine with a free core, a read-only
evaluation in a worker thread while the caller's thread writes (:class:`Beside`, or :class:`Reader` for a
series of them) can take the read off the wall time; its users are a full REASON's reads
(:mod:`topostore.reason.closing`, :mod:`topostore.reason.early_reads`).  (A big write cut
into chunks, each inserted in a worker thread while the next is parsed, was measured and not kept: the
insertion releases the GIL too, but the load cost 10-14 % more CPU and no less wall time.)

The contract:

* **one worker thread** per :class:`Beside` or :class:`Reader`, started and joined inside its ``with``
  block: no thread outlives it, even when either side raises;
* **errors propagated**: the worker's exception is raised in the caller's thread by
  :meth:`Beside.result`; when both sides fail, the caller's own error is the one raised;
* **the worker reads only what the caller's thread does not change meanwhile**: the caller's writes
  leave the graphs the reader reads alone (the caller says which, and keeps to it); the engine gives
  each query a consistent snapshot;
* **a write by the worker waits its turn**: the engine runs one writer at a time, so a load the worker
  sends (:meth:`topostore.stores.base.Store.add_ntriples_beside`: a full run's evaluations found early,
  :mod:`topostore.reason.early_rules`) and the caller's updates follow one another, each whole; the
  caller reads those facts only after it has waited for that read;
* **a shared read may run in the caller's thread**: a read queued with ``shared`` needs none of the reads
  queued before it to have run; the caller about to wait for the worker runs those not started yet itself
  (:meth:`Reader.help`), each once, so that they are not left behind a long read while the caller idles;
* **in memory only**: a remote or durable store, or one with a transaction open, is not asked to
  overlap (its callers stay sequential, see :attr:`topostore.stores.base.Store.overlaps`).

``TOPOSTORE_OVERLAP=0`` in the environment turns it off (:data:`ENABLED`): everything then runs in the
caller's thread, in the order a sequential caller takes (a machine without a free core gains nothing
from the second thread; the benchmarks compare the two ways in one tree).
"""

from __future__ import annotations

import os
import threading
from collections.abc import Callable
from concurrent.futures import Future, ThreadPoolExecutor
from typing import Generic, TypeVar

T = TypeVar("T")

#: whether the second thread is used at all (``TOPOSTORE_OVERLAP=0``: never)
ENABLED = os.environ.get("TOPOSTORE_OVERLAP", "1") != "0"


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


class Reader:
    """One worker thread running read-only evaluations one after the other, in the order given, while the
    caller's thread writes; for reads started at several points of a long run (:mod:`topostore.reason.early_reads`)::

        with Reader() as reader:
            answer = reader.submit(lambda: ask(store))   # a Future
            ...                                          # writes the ask does not read
            if answer.result(): ...                      # waits for it
            answer.cancel()                              # or drops it, if not started yet

    The thread starts with the first read and is joined when the block ends, also when it raises (reads
    not started then are dropped).  Only used where the store overlaps and :data:`ENABLED` holds."""

    def __init__(self) -> None:
        self._pool: ThreadPoolExecutor | None = None
        #: the reads queued with ``shared`` that neither thread has taken yet (or has, not yet dropped)
        self._shared: list[_Shared] = []

    def __enter__(self) -> Reader:
        return self

    def submit(self, read: Callable[[], T], shared: bool = False) -> Future:
        """Queue ``read`` after the reads queued before it; its Future gives its value or raises its error.
        ``shared``: a read that does not need the reads queued before it to have run (it reads nothing they
        write), which the caller's thread may take on instead of waiting (:meth:`help`)."""
        if self._pool is None:
            self._pool = ThreadPoolExecutor(max_workers=1, thread_name_prefix="topostore-read")
        if not shared:
            return self._pool.submit(read)
        task = _Shared(read)
        self._shared.append(task)
        self._pool.submit(task.run)
        return task.future

    def help(self) -> None:
        """The caller's thread, about to wait for the worker, runs the shared reads the worker has not
        started, in their order: what would have queued behind the awaited read is done meanwhile (at
        100,000 locations the checks reading the asserted visit times, 0.26 s, waited behind the
        AllDifferent keys and the minimum's count while the caller's thread waited for the keys)."""
        while self._shared:
            self._shared.pop(0).run()

    def __exit__(self, *exc_info: object) -> None:
        if self._pool is not None:
            self._pool.shutdown(wait=True, cancel_futures=True)
            self._pool = None
        for task in self._shared:  # not started by either thread: dropped as the pool drops its own
            task.future.cancel()
        self._shared.clear()


class _Shared:
    """A read that whichever thread takes it first runs, once (:meth:`Reader.help`); a cancelled one, none."""

    def __init__(self, read: Callable[[], object]) -> None:
        self._read = read
        self._lock = threading.Lock()
        self._taken = False
        self.future: Future = Future()

    def run(self) -> None:
        with self._lock:
            if self._taken:
                return
            self._taken = True
        if not self.future.set_running_or_notify_cancel():
            return
        try:
            self.future.set_result(self._read())
        except Exception as error:  # noqa: BLE001 - raised to whoever reads the Future, as the pool does
            self.future.set_exception(error)
        except BaseException as error:  # an interrupt or exit: the reader learns it, and so does this thread now
            self.future.set_exception(error)
            raise


def early_result(started: tuple[object, Future[T]] | None, made_for: object) -> T | None:
    """The result of a read started early, where it was started for what the caller asks now
    (``made_for``: its text, or the graphs it read); else the read is cancelled and None returned, and
    the caller runs it again itself.  A read that failed in the worker gives None too: run again in the
    caller's thread, its error is raised where the caller handles it."""
    if started is None:
        return None
    expected, pending = started
    if expected != made_for:
        pending.cancel()
        return None
    try:
        return pending.result()
    except Exception:  # noqa: BLE001 - run again by the caller, where its error is raised
        return None


__all__ = ["ENABLED", "Beside", "Reader", "early_result"]
