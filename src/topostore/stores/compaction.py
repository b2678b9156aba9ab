"""When an in-memory Oxigraph store is rebuilt, and how.

Oxigraph's in-memory store keeps removed quads around (for its transactions), so a long-running
reasoner that derives and drops the same facts step after step gets slower and bigger.  Copying the
live quads into a fresh store resets that; it is done when the writes since the last compaction
outnumber a fiftieth of the live quads (at least :data:`MIN_WRITES`), which keeps its amortised cost
small.  The live quads are counted when first needed, so that a store loaded with a big map is not
rebuilt after its first 200 writes (0.8 s at 10,000 locations).  It is asked after every REASON and after
every committed change (a command's unit of work, a Python API change), so a client that writes often and
reasons rarely is compacted too (``python -m benchmarks.rewrites``).  On-disk stores compact themselves.
"""

from __future__ import annotations

import pyoxigraph as ox

#: writes below which a store is never rebuilt (nor its live quads counted)
MIN_WRITES = 200


def compacted(store: ox.Store, writes: int, live: int) -> tuple[ox.Store | None, int]:
    """A fresh copy of ``store`` when ``writes`` since the last compaction call for one (None if not),
    and the live quads to compare the next writes with (``live``: those counted at the last compaction,
    0 when never counted)."""
    if writes < MIN_WRITES:
        return None, live
    if not live:
        live = len(store)
    if writes < max(MIN_WRITES, live // 50):
        return None, live
    fresh = ox.Store()
    fresh.extend(store)
    return fresh, len(fresh)


__all__ = ["MIN_WRITES", "compacted"]
