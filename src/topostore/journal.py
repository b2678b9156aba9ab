"""All-or-nothing REASON: a failed reasoning restores the state before the change.

Reasoning can fail after asserted changes were applied: a rule that cannot be
compiled (``ADD IND CLASS [x, <…swrl#Imp>]`` makes ``x`` a SWRL rule without a
head), a rule with no finite closure stopped by :mod:`topostore.reason.limits`.
Leaving such a change in place would make *every* later REASON fail, and a
half-computed inferred graph would answer queries.  So the :class:`Journal`
records the net asserted changes since the last successful REASON, and
:func:`all_or_nothing` (the decorator on :meth:`Ontology.reason`) reverts them
and recomputes the previous closure when reasoning fails, then re-raises.

The journal holds references to the changed triples only until the next
successful REASON (LOAD reasons at once), so it stays as small as the change;
before the first successful REASON there is nothing to go back to, and a
failure leaves the asserted graph as it is.
"""

from __future__ import annotations

import functools
import logging
from collections.abc import Callable, Iterable
from typing import TYPE_CHECKING, Any, TypeVar

from pyoxigraph import Triple

from .errors import TopostoreError
from .reason import limits
from .vocab import ASSERTED, AUX, ENTAILED, INFERRED

if TYPE_CHECKING:  # pragma: no cover
    from .ontology import Ontology
    from .store import Store

logger = logging.getLogger("topostore.journal")
F = TypeVar("F", bound=Callable[..., Any])


class Journal:
    """Net asserted changes since the last successful REASON (adding then removing cancels out)."""

    def __init__(self) -> None:
        self.added: dict[Triple, None] = {}
        self.removed: dict[Triple, None] = {}
        #: recording starts at the first successful REASON: before it there is no state to go back to
        #: (and a large file loaded before reasoning is not copied)
        self.active = False

    def record(self, store: Store, triples: Iterable[Triple], added: bool) -> None:
        """Call before the store changes, with ``triples`` deduplicated."""
        if not self.active:
            return
        mine, other = (self.added, self.removed) if added else (self.removed, self.added)
        for t in triples:
            if store.contains(t, ASSERTED) == added:
                continue  # adding a present triple or removing an absent one changes nothing
            if t in other:
                del other[t]
            else:
                mine[t] = None

    def clear(self) -> None:
        self.added.clear()
        self.removed.clear()

    def start(self) -> None:
        """A REASON succeeded: its state is the one to return to from now on."""
        self.clear()
        self.active = True

    def revert(self, store: Store) -> int:
        """Undo the recorded changes on the asserted graph; returns how many triples changed."""
        n = store.remove(list(self.added), ASSERTED) + store.add(list(self.removed), ASSERTED)
        self.clear()
        return n


def all_or_nothing(reason: F) -> F:
    """Wrap ``Ontology.reason``: run it under the ontology's limits; on failure restore the last good state."""

    @functools.wraps(reason)
    def wrapper(self: Ontology, *args: Any, **kwargs: Any) -> Any:
        mode = kwargs.get("mode", args[1] if len(args) > 1 else "auto")
        if mode not in ("auto", "incremental", "full"):  # a wrong argument is not a failed REASON
            raise ValueError(f"unknown reasoning mode {mode!r}; use auto, incremental or full")
        try:
            with limits.budget(self.limits):
                report = reason(self, *args, **kwargs)
        except Exception:
            if self._journal.active:
                _restore(self, reason)
            raise
        self._journal.start()
        return report

    return wrapper  # type: ignore[return-value]


def _restore(onto: Ontology, reason: Callable[..., Any]) -> None:
    """Revert the asserted changes since the last good REASON and recompute its closure."""
    reverted = onto._journal.revert(onto.store)
    onto._rules = None
    onto._superclasses = None
    onto._reasoner = None
    onto._stop_tracking()
    onto.dirty = True
    logger.warning("reasoning failed; %d asserted change(s) since the last successful REASON were reverted", reverted)
    try:
        with limits.budget(onto.limits):
            reason(onto, mode="full")
        onto._journal.start()
    except TopostoreError:  # even the previous state cannot be reasoned (e.g. limits lowered): asserted facts only
        logger.exception("the state before the change could not be reasoned either; inferred facts cleared")
        onto.store.update(" ; ".join(f"DROP SILENT GRAPH {g}" for g in (INFERRED, AUX, ENTAILED)))
        onto._reasoner = None
        onto.dirty = True


__all__ = ["Journal", "all_or_nothing"]
