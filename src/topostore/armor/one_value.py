"""The short lane of REPLACE: one asserted value of a property replaced by one other, as a robot does every step.

Why: the general path (a :class:`~.reference.Change` whose plan runs inside :meth:`Reference.applied`) serves
every manipulation, buffered or not, live reasoner or not, durable or not, and each of its layers costs a few
microseconds a robot pays three times a step: and below it the store-level change
(:meth:`AssertedChanges.change_noted`) inside a unit of work and a store transaction, which serve any
change too.  The plain case takes none of them: it reads the committed values once and hands the one old
fact and the new one to :meth:`AssertedChanges.replace_fact`, which writes the two quads, the literal forms
and the ledger's record straight (:mod:`~..stores.one_fact`), so the asserted graph, the literal forms, the
ledger (what an incremental REASON and an undo read) and the reply are the general path's.  Anything else,
or any doubt, returns None before anything changed, and the general path runs.

The plain case: the reference applies manipulations at once (unbuffered), its reasoner is buffered (no REASON
follows the change), nothing persists its state (a memory reference), no unit of work or transaction is open,
the store writes straight (:func:`~..stores.one_fact.direct`: in memory, no listings, nothing pending), the
rules are compiled, the property names facts only (:func:`~..ontology.changes.fact_property`: no triple of it
changes the rules), exactly one asserted value is the old one, the new value is not held and is another
value, and the value gives no note (a data value to an object property, an individual to a data property: see
:func:`~.manipulation.note_for_kind`).  No unit of work is needed around it: every check is made before the one
write, and what follows the write (the forms, the ledger's dictionaries) cannot fail.
"""

from __future__ import annotations

from collections.abc import Callable

from pyoxigraph import Literal, NamedNode

from ..errors import TopostoreError
from ..ontology.changes import fact_property
from ..ontology.facade import Ontology
from ..rdf import terms
from ..rdf.vocab import ASSERTED
from ..stores import one_fact
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
    if not ENABLED or not plain_reference(ref):
        return None
    if not fact_property(prop) or note(ref.ontology, prop, description):
        return None  # a schema property, a value of the other kind
    return replace_plain(ref, ind, prop, new, old)


def replace_plain(ref: Reference, ind: NamedNode, prop: NamedNode, new, old) -> list[str] | None:
    """:func:`replace` where the reference (:func:`plain_reference`) and the property (a fact property, no note
    for the value's kind) are known plain: the store's check, its one read and its one write; None (nothing
    changed) where the store or the values held are not the plain case."""
    onto = ref.ontology
    store = onto.store
    if not one_fact.direct(store):
        return None  # a store change the unit of work must hold
    changes = onto.changes
    before = store.data_writes
    facts = changes.kept.read(store, ind, prop, ASSERTED)
    old_fact = _one_old(facts, new, old)
    if old_fact is None:
        return None
    try:
        changes.replace_fact(ind, prop, new, old_fact, one_fact.new_fact(ind, prop, new, ASSERTED), len(facts) == 1,
                             before)
    except (TopostoreError, OSError) as exc:  # as Context.submit says it (nothing was changed)
        raise CommandError(codes.REASONER_OR_QUERY_FAILURE,
                           f"the change was undone because reasoning failed: {exc}") from exc
    return []


def plain_reference(ref: Reference) -> bool:
    """Whether the reference applies a change at once and nothing else: no buffer, no REASON after it, no
    state to persist, no unit of work or transaction open around it."""
    if ref.buffered_manipulation or ref.buffer or not ref.buffered_reasoner or ref.persist is not None:
        return False
    onto = ref.ontology  # compiled rules: the note reads them, never compiles (and a fact changes none)
    return onto.ledger.unit_step is None and onto._rules is not None


def _one_old(facts: list[Fact], new, old) -> Fact | None:
    """The one fact of ``facts`` holding ``old`` where the new value is another and not held, else None.  An
    individual's value key is never a literal's: two individuals are compared as they are."""
    if type(old) is Literal or type(new) is Literal:
        old_key, new_key = terms.value_key(old), terms.value_key(new)
        if old_key == new_key:
            return None
    elif old == new:
        return None
    else:
        old_key = new_key = None
    olds, held = values(facts, old, old_key, new, new_key)
    return olds[0] if len(olds) == 1 and not held else None


def values(facts: list[Fact], old, old_key: tuple | None, new, new_key: tuple | None) -> tuple[list[Fact], bool]:
    """The facts whose object is the same data value as ``old`` (``old_key``: its value key; None for an
    individual, which only a fact of that individual holds) or the same individual, and whether one is the same
    as ``new``: one pass, each fact's object read once."""
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


__all__ = ["replace", "replace_plain", "plain_reference", "values", "ENABLED"]
