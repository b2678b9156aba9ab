"""A named reference: one ontology with its reasoner settings, buffer and mount owner.

aRMOR keeps these pieces in three places (AMOR's registry, the manipulator's
buffer and aRMOR's unsynchronised mount map); here they live together and are
guarded by one lock, so concurrent calls on a reference are serialised.
"""

from __future__ import annotations

import logging
import threading
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

from pyoxigraph import Triple

from ..compile.notices import answered, unsaid
from ..errors import TopostoreError
from ..ontology.facade import Ontology
from ..ontology.pellet_values import PelletDifferenceWarning
from ..stores.facts import Fact

#: Reasoner names accepted at LOAD (spec §5.2); all run topostore's reasoner.
REASONERS = frozenset({"", "PELLET", "HERMIT", "FACT", "SNOROCKET"})

logger = logging.getLogger(__name__)


@dataclass
class Delta:
    """The triples one manipulation adds and removes, computed against the current state (as triples, or
    as the store's facts a plan read them as: :meth:`Store.read_facts`)."""

    add: list[Triple | Fact] = field(default_factory=list)
    remove: list[Triple | Fact] = field(default_factory=list)
    warning: str = ""


@dataclass
class Change:
    """A validated manipulation waiting to be applied (now, or at APPLY/REASON when buffered).

    ``plan`` computes the delta when the change is applied, because what a
    REPLACE or REMOVE IND removes depends on the state at that moment.
    """

    description: str
    plan: Callable[[Ontology], Delta]
    #: the request (as a dict) that made this change, kept so a durable store can persist the buffer
    origin: dict | None = None


@dataclass
class Applied:
    """What applying a change really did (the ontology's change ledger is what undoes it)."""

    added: list[Triple]
    removed: list[Triple]
    warning: str


@dataclass
class Reference:
    """State of one reference; every access goes through :attr:`lock`."""

    name: str
    ontology: Ontology
    iri: str
    source: Path | None = None
    buffered_manipulation: bool = False
    reasoner: str = "PELLET"
    buffered_reasoner: bool = False
    owner: str | None = None  # mounted client, None when unmounted
    buffer: list[Change] = field(default_factory=list)
    lock: threading.RLock = field(default_factory=threading.RLock)
    #: writes the settings, owner and buffer to a durable store (None in memory); see armor/durable.py
    persist: Callable[[Reference], None] | None = None
    #: what the command lanes decided for this reference's shapes (:class:`~.lanes.Shapes`; None until asked)
    shapes: object | None = field(default=None, repr=False, compare=False)

    def __post_init__(self) -> None:
        # a buffered reasoner answers what it was last flushed with, asserted facts removed since included
        self.ontology.reads.answers_removed = self.buffered_reasoner

    def save_state(self) -> None:
        """Persist settings, owner and buffer (joins the store transaction in progress)."""
        if self.persist is not None:
            self.persist(self)

    @property
    def prefix(self) -> str:
        return self.ontology.prefix

    @property
    def is_consistent(self) -> bool:
        """Consistency as of the last reasoning (spec §2.6)."""
        return self.ontology.is_consistent

    def apply_change(self, change: Change) -> Applied:
        """Apply one change to the asserted graph; returns what it did (for undo)."""
        onto = self.ontology
        delta = change.plan(onto)
        # a removed literal is recorded in the form its user wrote (the ledger asks the literal forms), so
        # an undo restores it exactly
        added, removed, notes = onto.changes.change_noted(delta.add, delta.remove)
        return Applied(added, removed, "; ".join(filter(None, [delta.warning, *notes])) if notes else delta.warning)

    def submit(self, changes: list[Change]) -> list[str]:
        """Apply ``changes`` now, or queue them under manipulation buffering.

        All or nothing: if applying or re-reasoning fails the applied part is
        undone (by the ontology's change ledger), the reasoner is brought back
        to the old state, and the error propagates.  With a non-buffered reasoner the reference is left
        reasoned, as a Pellet reasoner listening to changes would be.
        """
        if self.buffered_manipulation:
            with self.ontology.store.transaction():
                self.buffer.extend(changes)
                try:
                    self.save_state()
                except BaseException:
                    del self.buffer[len(self.buffer) - len(changes):]
                    raise
            return []
        return [a.warning for a in self.applied(changes) if a.warning]  # run, without its call

    def run(self, changes: list[Change], reason: bool | None = None) -> list[str]:
        """Apply changes in order, all or nothing, then reason if ``reason`` (default: live reasoner); the
        changes' warnings (see :meth:`applied`)."""
        return [a.warning for a in self.applied(changes, reason) if a.warning]

    def applied(self, changes: list[Change], reason: bool | None = None) -> list[Applied]:
        """:meth:`run`, returning what each change really did (a value removed and added again in another
        spelling is neither: a reply counts from these, not from the plans).

        A live (non-buffered) reasoner sees every applied change, so the
        reference is re-reasoned after each applied manipulation.  The warnings its REASON gives (a
        :class:`~topostore.PelletDifferenceWarning`, said once the unit of work has ended well) are the last
        change's too: a command answers them, and never raises them, whatever the warnings filter.
        """
        if reason is None:
            reason = not self.buffered_reasoner and bool(changes)
        with answered(PelletDifferenceWarning) as heard:
            return self._applied(changes, reason, heard)

    def _applied(self, changes: list[Change], reason: bool, heard: list[str]) -> list[Applied]:
        """:meth:`applied` inside its block answering warnings, whose texts ``heard`` collects: they go into
        the last change's warning."""
        applied: list[Applied] = []
        onto = self.ontology
        try:
            with onto.ledger.undoable(onto):  # a failure below undoes the changes applied here
                with onto.store.transaction():  # the changes and the persisted buffer: one commit
                    for change in changes:
                        applied.append(self.apply_change(change))
                    if self.persist is not None:  # save_state (a memory reference has nothing to persist)
                        self.persist(self)
                if reason:
                    onto.reason()  # a failed REASON itself goes back to the last successful one
                else:
                    onto.rules  # noqa: B018 - compile now: a change no rules can be compiled from is refused
        except Exception:
            if reason:
                self._reason_quietly()
            raise
        if not heard:
            return applied
        said = unsaid(heard, (a.warning for a in applied))
        for text in said:  # on the service's log (LOG FILE / SCREEN) as well as the reasoner's
            logger.warning("reference %r: %s", self.name, text)
        if said and applied:
            last = applied[-1]
            last.warning = "; ".join(filter(None, [last.warning, *said]))
        return applied

    def manipulate(self, description: str, add: list[Triple],
                   remove: list[Triple]) -> tuple[list[Triple], list[Triple], list[str]]:
        """One all-or-nothing manipulation of the asserted graph, then reasoning (sparql.target.WritableOntology):
        what the store took (added, removed) and the warnings."""
        delta = Delta(list(add), list(remove))
        (done,) = self.applied([Change(description, lambda _onto: delta)])
        return done.added, done.removed, [done.warning] if done.warning else []

    def flush(self, reason: bool | None = None) -> list[str]:
        """Apply the manipulation buffer (APPLY/REASON); the buffer is emptied only on success."""
        if not self.buffer and reason is False:  # REASON with nothing buffered (every unbuffered robot step):
            self.ontology.rules  # noqa: B018 - what applying nothing checks, without a unit of work or a commit
            return []
        pending, self.buffer = self.buffer, []
        try:
            return self.run(pending, reason)
        except Exception:
            self.buffer = pending + self.buffer
            self.save_state()
            raise

    def discard_buffer(self) -> int:
        """Drop the buffered changes (a REASON failed with them: every later REASON would fail the same way)
        and persist the empty buffer; returns how many were dropped."""
        dropped, self.buffer = len(self.buffer), []
        if dropped:
            self.save_state()
        return dropped

    def _reason_quietly(self) -> None:
        """Bring the inferred graph back after an undo; a failure here is already being reported."""
        try:
            with answered():  # an undone command says nothing of a REASON (its warnings stay on the log)
                self.ontology.reason()
        except TopostoreError as exc:  # the original error is the one reported; this one is only logged
            logger.warning("reasoning again after undoing a failed manipulation failed too: %s", exc)


def consistent(ref: Reference) -> bool:
    """``ref``'s consistency (its lock held); false when a reasoner that cannot run (limits, store) says
    nothing about it."""
    try:
        return ref.ontology.is_consistent  # Reference.is_consistent, read without its forwarding call
    except TopostoreError:
        return False


__all__ = ["consistent", "Reference", "Change", "Delta", "Applied", "REASONERS"]
