"""When Python's cycle collector may leave an ontology's long-lived objects out of its walk.

A full collection of the cycle collector walks every tracked object.  A TBox-heavy ontology holds
hundreds of thousands of long-lived ones (its compiled rules, its step programs, the reasoner's
tables), so the full collections a robot step triggers cost more than the step's own work (400
classes: see docs/benchmarks-history.md).  Once such state is settled (after LOAD, after a full
REASON) it is moved out of the walk with :func:`gc.freeze`; before it is rebuilt it is moved back
(:func:`gc.unfreeze`), so that what the rebuild drops can be collected, and each settling collects
first, so that no garbage is frozen with it.

``TOPOSTORE_GC_FREEZE=0`` turns this off.  The collector's permanent generation is one per process:
an ontology's rebuild moves every frozen object back, the others' too, which only costs their next
steps the walk they had without freezing.
"""

from __future__ import annotations

import gc
import os

#: the environment variable that turns the policy off ("0")
ENV = "TOPOSTORE_GC_FREEZE"


def enabled() -> bool:
    """Whether the policy is on (``TOPOSTORE_GC_FREEZE`` unset or anything but "0")."""
    return os.environ.get(ENV, "1").strip() != "0"


class CollectorPolicy:
    """Freezes an ontology's settled state out of the cycle collector's walk, and thaws it before a rebuild."""

    def __init__(self, on: bool | None = None) -> None:
        #: read once per ontology (a process sets the variable before it opens its ontologies)
        self.on = enabled() if on is None else on

    def settled(self) -> None:
        """The long-lived state was just built (LOAD, full REASON): collect what its building dropped,
        then leave every surviving object out of later collections."""
        if self.on:
            gc.unfreeze()
            gc.collect()
            gc.freeze()

    def rebuilding(self) -> None:
        """The state is about to be dropped or rebuilt: let the collector reach it again."""
        if self.on and gc.get_freeze_count():
            gc.unfreeze()


__all__ = ["ENV", "CollectorPolicy", "enabled"]
