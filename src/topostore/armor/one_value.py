"""The short lane of REPLACE: one asserted value of a property replaced by one other, as a robot does every step.

Why: the general path (a :class:`~.reference.Change` whose plan runs inside :meth:`Reference.applied`) serves
every manipulation, buffered or not, live reasoner or not, durable or not, and each of its layers costs a few
microseconds a robot pays three times a step.  The plain case takes none of them: it reads the values once,
and where it is the plain case hands the same facts to the same store-level change
(:meth:`AssertedChanges.change_noted`) inside the same unit of work and transaction, so the asserted graph,
the literal forms, the ledger (what an incremental REASON and an undo read) and the reply are the general
path's.  Anything else, or any doubt, returns None before anything changed, and the general path runs.

The plain case: the reference applies manipulations at once (unbuffered), its reasoner is buffered (no REASON
follows the change), nothing persists its state (a memory reference), no unit of work or transaction is open,
the rules compile, exactly one asserted value is the old one, the new value is not held and is another value,
and the value gives no note (a data value to an object property, an individual to a data property: see
:func:`~.manipulation._note_for`).
"""

from __future__ import annotations

from collections.abc import Callable

from pyoxigraph import NamedNode

from ..errors import TopostoreError
from ..ontology.facade import Ontology
from ..rdf import terms
from ..rdf.vocab import ASSERTED
from ..stores.facts import Fact
from . import codes
from .codes import CommandError
from .reference import Reference

#: whether REPLACE takes the short lane where it can (off: every REPLACE takes the general path)
ENABLED = True

#: the note a value given to a property of the other kind earns ("" for none): (ontology, property, description) → text
Note = Callable[[Ontology, NamedNode, str], str]


def replace(ref: Reference, ind: NamedNode, prop: NamedNode, new, old, description: str,
            note: Note) -> list[str] | None:
    """The warnings of the REPLACE of ``old`` by ``new`` as ``prop`` of ``ind`` done in the short lane, or None
    (nothing changed) where it is not the plain case; a failure of the store is the general path's 209."""
    if not ENABLED or not _plain_reference(ref):
        return None
    onto = ref.ontology
    if note(onto, prop, description):  # a value of the other kind: the general path says it
        return None
    try:
        with onto.ledger.undoable(onto):  # as Reference.applied: a failure below undoes the change
            with onto.store.transaction():
                old_fact = _one_old(onto, ind, prop, new, old)
                if old_fact is None:  # not the plain case: nothing was written, the transaction commits nothing
                    return None
                added = onto.store.unread_fact(ind, prop, new, ASSERTED)
                _, _, notes = onto.changes.change_noted([added], [old_fact])
            onto.rules  # noqa: B018 - as Reference.applied: compiled (a cached read where the TBox is unchanged)
    except (TopostoreError, OSError) as exc:  # as Context.submit says it
        raise CommandError(codes.REASONER_OR_QUERY_FAILURE,
                           f"the change was undone because reasoning failed: {exc}") from exc
    return ["; ".join(notes)] if notes else []


def _plain_reference(ref: Reference) -> bool:
    """Whether the reference applies a change at once and nothing else: no buffer, no REASON after it, no
    state to persist, no unit of work or transaction open around it."""
    if ref.buffered_manipulation or ref.buffer or not ref.buffered_reasoner or ref.persist is not None:
        return False
    onto = ref.ontology  # compiled rules: the note and the check after the change read them, never compile
    return not onto.store._depth and onto.ledger.unit_step is None and onto._rules is not None


def _one_old(onto: Ontology, ind: NamedNode, prop: NamedNode, new, old) -> Fact | None:
    """The one asserted fact holding ``old`` where the new value is another and not held, else None."""
    old_key, new_key = terms.value_key(old), terms.value_key(new)
    if old_key == new_key:
        return None
    olds, held = values(onto.store.read_facts(ind, prop, ASSERTED), old, old_key, new, new_key)
    return olds[0] if len(olds) == 1 and not held else None


def values(facts: list[Fact], old, old_key: tuple, new, new_key: tuple) -> tuple[list[Fact], bool]:
    """The facts whose object is the same data value as ``old`` (``old_key``: its value key) or the same
    individual, and whether one is the same as ``new``: one pass, each fact's object read once."""
    olds, held = [], False
    for f in facts:
        value = f.value
        if value is not None:  # a literal: compared by value (an individual's key is never a literal's)
            if value == old_key:
                olds.append(f)
            if value == new_key:
                held = True
        else:
            o = f.triple.object
            if o == old:
                olds.append(f)
            if o == new:
                held = True
    return olds, held


__all__ = ["replace", "values", "ENABLED"]
