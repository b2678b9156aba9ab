"""Summaries of step times: the first steps warm caches (and the JVM's JIT) and are left out."""

from __future__ import annotations

import resource
import statistics

#: steps 1-3 are warm-up; medians are over steps 4 to the last
WARMUP = 3


def counted(times: list[float]) -> list[float]:
    """The steps that count: from the 4th on, or all of them when there are no more than 3."""
    return times[WARMUP:] if len(times) > WARMUP else list(times)


def median(times: list[float]) -> float | None:
    kept = counted(times)
    return statistics.median(kept) if kept else None


def p95(times: list[float]) -> float | None:
    """Nearest-rank 95th percentile of the counted steps."""
    kept = sorted(counted(times))
    if not kept:
        return None
    rank = -(-95 * len(kept) // 100)  # ceil(0.95 n)
    return kept[rank - 1]


def peak_rss_mib() -> float:
    """Peak resident set size of this process so far (Linux reports KiB); Oxigraph's memory is Rust's,
    which tracemalloc would not see."""
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
