"""Whether this machine has a core free beside this process, read from the kernel's CPU counters.

Why
---
Work handed to a second thread or a child pays only where a core is free for it: on busy cores it costs
its own overhead and shortens nothing (docs/benchmarks-history.md: LOAD in a child, LOAD's pieces indexed
by a second thread).  The load average counts this very process and lags by a minute; the counters of
``/proc/stat`` over a short window, less this process's own CPU time over it, say what the others use now.
"""

from __future__ import annotations

import os
import time
from collections.abc import Callable


def cpu_times() -> list[int] | None:
    """The machine's CPU time counters (the first line of ``/proc/stat``), or None where there are none."""
    try:
        with open("/proc/stat", "rb") as stat:
            fields = stat.readline().split()
    except OSError:
        return None
    if not fields or fields[0] != b"cpu" or len(fields) < 6:
        return None
    return [int(v) for v in fields[1:]]


def busy_cores(first: list[int], second: list[int]) -> float:
    """How many cores the machine kept busy between two readings of :func:`cpu_times`."""
    total = sum(second) - sum(first)
    idle = (second[3] + second[4]) - (first[3] + first[4])  # idle and iowait
    return (os.cpu_count() or 1) * (total - idle) / total if total > 0 else 0.0


def spare(others: float) -> bool:
    """Whether cores busy with ``others`` leave one free beside this process (less than the cores less one
    and a half: on two cores, the others under half a core)."""
    return others < (os.cpu_count() or 1) - 1.5


class CoreWatch:
    """Watches the machine from its creation: :meth:`free` says whether the other processes left a core
    free over the last window (this process's own CPU time taken out), once :data:`WINDOW_S` have passed.

    Each answer "busy" starts the next window where it was read: a busy spell (another process's short
    burst, the kernel writing back a file just written) says no for its own window only, where a window
    from the creation on kept it in every later answer (a 100,000-location LOAD once took no worker at
    all).  On cores busy throughout, every window says busy, as one long window did."""

    #: the shortest window read (the kernel counts in ticks of 10 ms)
    WINDOW_S = 0.05

    def __init__(self, counters: Callable[[], list[int] | None] = cpu_times,
                 clock: Callable[[], float] = time.monotonic,
                 own_cpu: Callable[[], float] = time.process_time) -> None:
        """``counters``, ``clock`` and ``own_cpu``: the machine's counters, the time and this process's CPU
        time (the kernel's, by default)."""
        self._counters, self._clock, self._own_cpu = counters, clock, own_cpu
        self._first = counters()
        self._since = clock()
        self._own = own_cpu()

    def free(self) -> bool | None:
        """True or False once the window is long enough, None before; False where nothing is known."""
        if self._first is None:
            return False
        now = self._clock()
        elapsed = now - self._since
        if elapsed < self.WINDOW_S:
            return None
        second = self._counters()
        if second is None:
            return False
        own_now = self._own_cpu()
        answer = spare(busy_cores(self._first, second) - (own_now - self._own) / elapsed)
        if not answer:  # the next answer reads the machine from here on
            self._first, self._since, self._own = second, now, own_now
        return answer


__all__ = ["CoreWatch", "busy_cores", "cpu_times", "spare"]
