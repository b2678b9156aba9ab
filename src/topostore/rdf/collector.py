"""Python's cycle collector paused while many long-lived objects are made at once.

Why
---
The collector runs whenever allocations outnumber frees by a threshold, and each older-generation
run walks every object that survived so far.  A LOAD, or a robot's first step on a large TBox that
indexes a rule per pair of disjoint classes (tens of thousands of rules, their atoms and index
lists), makes such objects by the hundred thousand and no cycle that must be freed meanwhile: the
collector then walks them again and again (half of building the rules per pair of 400 classes).
"""

from __future__ import annotations

import gc
from collections.abc import Iterator
from contextlib import contextmanager


@contextmanager
def collector_paused() -> Iterator[None]:
    """The cycle collector off for the block, as it was after.

    Whatever cycles the block (or another thread meanwhile) leaves are collected as usual once it is
    on again, which for those reaching old objects means at the next full collection: rare once
    millions of objects live, so what a block must free soon (the rule compiler after a LOAD) makes no
    cycle (tests/test_compile_cycles.py).  A collector found off is left off (blocks nest)."""
    enabled = gc.isenabled()
    gc.disable()
    try:
        yield
    finally:
        if enabled:
            gc.enable()


__all__ = ["collector_paused"]
