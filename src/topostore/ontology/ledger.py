"""The change ledger: the one record of asserted changes since the last successful REASON, and their undo.

Every assertion and retraction of an :class:`~topostore.ontology.facade.Ontology` is
recorded here before the store changes (:meth:`ChangeLedger.record`), as a net change
(adding then removing a triple cancels out).  Three readers share that record:

* **incremental REASON** reads the net added and removed triples (:meth:`ChangeLedger.net_changes`)
  while they are few enough for incremental maintenance to pay off;
* **rollback**: reasoning can fail after asserted changes were applied (a rule that cannot be
  compiled, a rule with no finite closure stopped by :mod:`topostore.reason.limits`).  Leaving
  such a change in place would make *every* later REASON fail, and a half-computed inferred
  graph would answer queries, so :func:`all_or_nothing` (the decorator on
  :meth:`Ontology.reason`) undoes the recorded changes and recomputes the previous closure,
  then re-raises;
* **a caller's unit of work** (an aRMOR manipulation, :meth:`ChangeLedger.undoable`): the changes
  made inside it are undone, newest first, when it fails.

The record starts at the first successful REASON (before it there is no state to go back to, and
a large file loaded before reasoning is not copied) and is emptied by each successful REASON, so
it stays as small as the change.  Triples are keyed as the store holds them (Oxigraph
canonicalises numbers), and a removed literal is kept in the form the user asserted, so an undo
restores it exactly; where an addition in another spelling cancelled a removal, the spelling held at the
last REASON is kept aside (``ChangeLedger.held``) for a revert.
"""

from __future__ import annotations

import functools
import logging
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from typing import TYPE_CHECKING, Any, TypeVar

from pyoxigraph import Triple

from ..errors import TopostoreError
from ..rdf.vocab import ASSERTED, AUX, ENTAILED, INFERRED
from ..reason import limits
from ..reason.incremental import check_mode
from .pellet_values import missed_by_pellet, warn_pellet_differences

if TYPE_CHECKING:  # pragma: no cover
    from ..stores.base import Store
    from ..stores.facts import Fact
    from .facade import Ontology

logger = logging.getLogger("topostore.journal")  # the log keeps its name from the module this one replaced
F = TypeVar("F", bound=Callable[..., Any])

#: Below this many net changes incremental REASON is always worth trying, whatever the share.
MIN_TRACKED = 1000


class ChangeLedger:
    """Net asserted changes since the last successful REASON, and the steps of open units of work."""

    def __init__(self) -> None:
        #: stored form → triple as written, for triples added / removed since the last successful REASON
        self.added: dict[Triple, Triple] = {}
        self.removed: dict[Triple, Triple] = {}
        #: stored form → triple as written at the last successful REASON, for a value whose removal an
        #: addition in another spelling cancelled (the net record keeps no side of it, a revert gives it back)
        self.held: dict[Triple, Triple] = {}
        #: recording starts at the first successful REASON
        self.recording = False
        #: whether the record may drive an incremental REASON (false after a schema change or a large change)
        self.incremental = False
        #: (added, removed) triples of each change applied since the outermost open unit of work began
        self._steps: list[tuple[list[Triple], list[Triple]]] = []
        self._open = 0
        #: what REASONs inside an open unit of work found to say, said when the outermost unit ends well
        self._unsaid: list[str] = []
        #: how the last failed REASON left the ontology: "undone" (back at its last good state, reasoned
        #: again) or "cleared" (the asserted facts kept, the inferred graphs dropped); None before any
        self.last_failure: str | None = None

    # ------------------------------------------------------------ recording
    @property
    def tracking(self) -> bool:
        """Whether changes are being recorded (since the first successful REASON, or in a unit of work)."""
        return self.recording or bool(self._open)

    @property
    def unit_open(self) -> bool:
        """Whether a caller's unit of work is open (its changes can still be undone)."""
        return bool(self._open)

    @property
    def unit_step(self) -> int | None:
        """Within an open unit of work, the number of its steps so far (what an undo back to a unit's start
        drops is at or past that start); None outside one."""
        return len(self._steps) if self._open else None

    def record(self, store: Store, changed: list[Fact], added: bool, limit: Callable[[], float] | None = None) -> None:
        """Record ``changed``, all added or all removed: :meth:`record_change` of one side."""
        if added:
            self.record_change(store, changed, [], limit)
        else:
            self.record_change(store, [], changed, limit)

    def record_change(self, store: Store, added: list[Fact], removed: list[Fact],
                      limit: Callable[[], float] | None = None) -> None:
        """Record one change: facts (:class:`~topostore.stores.facts.Fact`) whose presence in the asserted
        graph the caller's change flips (``removed`` while present, then ``added`` while absent), as
        :meth:`Store.toggle_facts` returns them.  One call and one unit-of-work step per manipulation (a
        REPLACE's removal and addition together), so that undoing it undoes both.  Call inside the
        transaction making the change, so that a removed literal is still known in the form the user
        asserted.  Each fact's stored form (the key both sides share, so an addition and a removal cancel)
        and written form (what an undo restores) are read from it, not made again.

        ``limit``: gives the number of net changes above which an incremental REASON no longer pays off
        (at least :data:`MIN_TRACKED`; asked only past that); past it the record only serves rollback.
        """
        if not self.recording and not self._open:
            return
        # a REPLACE's one fact each side without a comprehension's call
        gone = [store.written_fact(removed[0])] if len(removed) == 1 else [store.written_fact(f) for f in removed]
        made = [added[0].triple] if len(added) == 1 else [f.triple for f in added]
        if self._open:
            self._steps.append((made, gone))
        if not self.recording:
            return
        if removed:
            _net(store, removed, gone, self.removed, self.added)
        if added:
            _net(store, added, made, self.added, self.removed, self.held)
        if self.incremental:
            self._check_size(limit)

    def record_replaced(self, store: Store, added: Fact, removed: Fact, gone: Triple,
                        limit: Callable[[], float] | None = None) -> None:
        """:meth:`record_change` of one removed fact (``gone``: as written, read before the change) and one
        added fact of another value, the change written already (``AssertedChanges.replace_fact``: the
        stored form of either is no read of the store): no list made for either side."""
        if self._open:
            self._steps.append(([added.triple], [gone]))
        if not self.recording:
            return
        _net_one(store, removed, gone, self.removed, self.added, None)
        _net_one(store, added, added.triple, self.added, self.removed, self.held)
        if self.incremental:
            self._check_size(limit)

    def _check_size(self, limit: Callable[[], float] | None) -> None:
        """Past :data:`MIN_TRACKED` net changes and ``limit``, the record serves rollback only."""
        size = len(self.added) + len(self.removed)
        if size > MIN_TRACKED and (limit is None or size > limit()):
            self.incremental = False

    def lost(self, store: Store, changes: list[tuple[list[Triple], list[Triple]]]) -> None:
        """Recorded changes (added, removed; oldest first) that never reached the store: a store that
        defers writes had them refused.  The record is set back as if each had been undone, newest
        first, without reading the store (it may be the store that is unreachable)."""
        if not self.recording:
            return
        for added, removed in reversed(changes):
            for triples, was_added in ((added, True), (removed, False)):
                mine, other = (self.added, self.removed) if was_added else (self.removed, self.added)
                for t in triples:
                    key = store.stored_form(t)
                    if key in mine:  # changed since the last REASON: back to as it was then
                        del mine[key]
                    else:  # it cancelled an earlier change the store has: that one stands alone again
                        other[key] = t

    def net_changes(self) -> tuple[list[Triple], list[Triple]]:
        """The net added and removed triples (as stored) for an incremental REASON; empty when not usable."""
        if not self.incremental:
            return [], []
        return list(self.added), list(self.removed)

    def stop_incremental(self) -> None:
        """The next REASON cannot be incremental (the schema changed); rollback still has the record."""
        self.incremental = False

    def succeeded(self, incremental_ready: bool) -> None:
        """A REASON succeeded: its state is the one to return to from now on."""
        self.added.clear()
        self.removed.clear()
        self.held.clear()
        self.recording = True
        self.incremental = incremental_ready

    # ------------------------------------------------------------ undo
    def revert(self, store: Store) -> int:
        """Undo every recorded change since the last successful REASON on the asserted graph (the caller
        forgets its reasoning state); returns how many triples changed.  Open units of work have nothing
        left to undo afterwards."""
        removed, respelled = self._held_at_reason(store)
        added = list(self.added.values()) + respelled  # a respelled value goes, then comes back as held
        self.added.clear()
        self.removed.clear()
        self.held.clear()
        self._steps.clear()
        self.incremental = False
        with store.transaction():  # each removed triple back in the spelling it was held in
            return store.remove(added, ASSERTED) + len(store.restore_facts([store.fact(t, ASSERTED) for t in removed]))

    def _held_at_reason(self, store: Store) -> tuple[list[Triple], list[Triple]]:
        """What a revert gives back: each removed triple as it was held at the last successful REASON, and
        the spellings the graph holds of those it still holds otherwise (to remove first, as written: one
        transaction's removal and addition of a value in two spellings is a respelling the store writes).

        Why: the record is keyed by stored form, so an addition of a removed value in another spelling
        (``"1.5E0"^^xsd:double`` after ``"1.5"`` went) cancels the removal, and a later removal records the
        spelling then held; :attr:`held` kept the first one."""
        if not self.held:
            return list(self.removed.values()), []
        back = [self.held.get(key, t) for key, t in self.removed.items()]
        respelled = []
        for key, t in self.held.items():
            if key not in self.removed:
                now = store.written_fact(store.fact(t, ASSERTED, written=False))
                if now != t:
                    back.append(t)
                    respelled.append(now)
        return back, respelled

    def say(self, texts: list[str]) -> None:
        """Warn of what a REASON found that Pellet would answer otherwise (:func:`missed_by_pellet`): now, or
        where a unit of work is open, when the outermost one ends without an error (an undone command says
        nothing)."""
        if self._open:
            self._unsaid.extend(texts)
        else:
            warn_pellet_differences(texts)

    def undoable(self, onto: Ontology) -> _UnitOfWork:
        """A unit of work: the asserted changes made inside are undone (newest first) if it raises.
        (A plain context manager class: every manipulation opens one.)"""
        return _UnitOfWork(self, onto)

    def _undo_since(self, onto: Ontology, start: int) -> None:
        """Undo the steps recorded since ``start`` (newest first) and forget them.  A step a failed store
        transaction never wrote was taken out of the record when it rolled back (:meth:`lost`, told by
        ``Store.on_rolled_back``):
        undoing it here flips nothing and records nothing."""
        steps = self._steps[start:]
        with self._paused(), onto.store.transaction():
            for added, removed in reversed(steps):  # a change removed, then added: undone the other way
                if added:
                    onto.changes.remove(*added)
                if removed:  # in the spelling it was held in, where the undone steps left another
                    onto.changes.restore(*removed)
        del self._steps[start:]

    @contextmanager
    def _paused(self) -> Iterator[None]:
        """Undo steps are recorded in the net record but are no steps of a unit of work themselves."""
        steps = self._steps
        self._steps = []
        try:
            yield
        finally:
            self._steps = steps


def _net(store: Store, facts: list[Fact], written: list[Triple], mine: dict[Triple, Triple],
         other: dict[Triple, Triple], held: dict[Triple, Triple] | None = None) -> None:
    """Note ``facts`` (as ``written``) on their side ``mine`` of the net record, or cancel them on ``other``;
    an addition cancelling a removal written otherwise keeps the removed spelling in ``held`` (the first one:
    the spelling at the last REASON)."""
    for f, as_written in zip(facts, written, strict=True):
        _net_one(store, f, as_written, mine, other, held)


def _net_one(store: Store, f: Fact, as_written: Triple, mine: dict[Triple, Triple], other: dict[Triple, Triple],
             held: dict[Triple, Triple] | None) -> None:
    """:func:`_net` of one fact."""
    key = f.stored
    if key is None:  # both sides hold triples as the store does, so they cancel (a removal named in
        # another spelling: the one the store held; the probe takes the fact's quad, made for its write
        # already, where the triple is the one written)
        key = f.stored = store.stored_form(as_written, f.quad if as_written is f.triple else None)
    if key in other:
        was = other.pop(key)
        if held is not None and was is not as_written and was != as_written:  # a respelling: rare
            held.setdefault(key, was)
    else:
        mine[key] = as_written


class _UnitOfWork:
    """The context manager :meth:`ChangeLedger.undoable` returns."""

    __slots__ = ("ledger", "onto", "start")

    def __init__(self, ledger: ChangeLedger, onto: Ontology) -> None:
        self.ledger = ledger
        self.onto = onto
        self.start = 0

    def __enter__(self) -> None:
        self.start = len(self.ledger._steps)
        self.ledger._open += 1

    def __exit__(self, kind, value, traceback) -> None:
        ledger = self.ledger
        unsaid: list[str] = []
        try:
            if kind is not None:
                ledger._undo_since(self.onto, self.start)
                self.onto.values.undone(self.start)
        finally:
            ledger._open -= 1
            if not ledger._open:
                ledger._steps.clear()
                self.onto.values.settled()
                unsaid, ledger._unsaid = ledger._unsaid, []
        if kind is None and not ledger._open and not self.onto.store.writes_pending:
            self.onto.store.maybe_compact()  # the unit's changes are final: see AssertedChanges._settled
        if kind is None and unsaid:
            warn_pellet_differences(unsaid)


def all_or_nothing(reason: F) -> F:
    """Wrap ``Ontology.reason``: check the mode, run it under the ontology's limits; on failure
    restore the last good state."""

    @functools.wraps(reason)
    def wrapper(self: Ontology, *args: Any, **kwargs: Any) -> Any:
        check_mode(kwargs.get("mode", args[1] if len(args) > 1 else "auto"))
        try:
            with limits.budget(self.limits):
                report = reason(self, *args, **kwargs)
        except Exception as exc:
            if self.ledger.recording and _restore(self, reason):
                self.ledger.last_failure = "undone"
            else:  # no good state to return to, or it cannot be reasoned: never a half-written closure
                if not self.ledger.recording:
                    _clear_inferred(self)
                self.ledger.last_failure = "cleared"
            if isinstance(exc, limits.ReasonLimitExceeded):
                exc.outcome = self.ledger.last_failure  # its text says what was left, now that it is known
            raise
        self.ledger.succeeded(self.incremental_ready())
        self.values.reasoned()
        # said once the REASON has completed, and inside a command's unit of work once that ends: a warning
        # turned into an error must not undo a good REASON or the command that ran it
        if report.violations:
            self.ledger.say(missed_by_pellet(self.store, report.violations))
        return report

    return wrapper  # type: ignore[return-value]


def _restore(onto: Ontology, reason: Callable[..., Any]) -> bool:
    """Revert the asserted changes since the last good REASON and recompute its closure; False where
    that closure cannot be computed either (its inferred graphs are then cleared)."""
    reverted = onto.ledger.revert(onto.store)
    onto.values.reverted()  # the spellings that came with the reverted literals go with them
    onto.forget_reasoning()
    logger.warning("reasoning failed; %d asserted change(s) since the last successful REASON were reverted", reverted)
    try:
        with limits.budget(onto.limits):
            reason(onto, mode="full")
        onto.ledger.succeeded(onto.incremental_ready())
        onto.values.reasoned()
        return True
    except TopostoreError:  # even the previous state cannot be reasoned (e.g. limits lowered): asserted facts only
        logger.exception("the state before the change could not be reasoned either; inferred facts cleared")
        _clear_inferred(onto)
        return False


def _clear_inferred(onto: Ontology) -> None:
    """Leave the asserted facts alone: the reasoner's graphs dropped and its state forgotten (a durable
    store's mark stays "building", so reopening it reasons again)."""
    onto.store.update(" ; ".join(f"DROP SILENT GRAPH {g}" for g in (INFERRED, AUX, ENTAILED)))
    onto.forget_reasoning()


__all__ = ["ChangeLedger", "all_or_nothing", "check_mode"]
