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
    free over that time (this process's own CPU time taken out), once :data:`WINDOW_S` have passed."""

    #: the shortest window read (the kernel counts in ticks of 10 ms)
    WINDOW_S = 0.05

    def __init__(self) -> None:
        self._first = cpu_times()
        self._since = time.monotonic()
        self._own = time.process_time()

    def free(self) -> bool | None:
        """True or False once the window is long enough, None before; False where nothing is known."""
        if self._first is None:
            return False
        elapsed = time.monotonic() - self._since
        if elapsed < self.WINDOW_S:
            return None
        second = cpu_times()
        if second is None:
            return False
        own = (time.process_time() - self._own) / elapsed
        return spare(busy_cores(self._first, second) - own)


__all__ = ["CoreWatch", "busy_cores", "cpu_times", "spare"]
