"""The manipulation path: every change of the asserted graph, recorded in the change ledger.

A manipulation validates its values before anything changes, changes the asserted graph and records
the net change in the ledger in one transaction (what incremental REASON, rollback and a unit of
work's undo read), and marks the ontology changed since its last reasoning; a schema triple makes
the rules be compiled again.  A named part of one :class:`~topostore.ontology.facade.Ontology`
(``onto.changes``); the ontology's ``add``, ``remove``, ``change`` and ``replace`` are these.
"""

from __future__ import annotations

import logging
import sys
from collections.abc import Iterable, Sequence
from typing import TYPE_CHECKING

from pyoxigraph import Literal, NamedNode, Triple

from ..compile.key_form import touches_groups
from ..compile.notices import warn
from ..rdf.terms import Term, check_literal, triple, value_key
from ..rdf.vocab import ASSERTED
from ..stores import one_fact
from ..stores.facts import Fact
from . import state as durable_state
from .files import changes_schema, schema_predicate
from .nary import all_different, individual_triples
from .spellings import (
    AGAIN_IN_CHANGE,
    EARLIER_IN_TRANSACTION,
    HELD,
    REMOVED_AND_ADDED,
    REMOVED_AND_ADDED_IN_TRANSACTION,
    SpellingKeptWarning,
    one_spelling,
    spelling_kept,
)

if TYPE_CHECKING:
    from ..stores.base import Store
    from .facade import Ontology

logger = logging.getLogger("topostore.changes")


class AssertedChanges:
    """Adds and removes asserted triples for one ontology, recording each net change in its ledger."""

    def __init__(self, onto: Ontology) -> None:
        self.onto = onto
        self.store = onto.store
        self.ledger = onto.ledger
        #: the facts :meth:`replace_fact` left, while the store counts no other write (a robot's next REPLACE
        #: of the same value reads them here, not from the index)
        self.kept = one_fact.KeptFacts()

    def add(self, *triples: Triple, said: bool = False) -> int:
        """Assert triples; returns how many were new (``said``: warn of each value held already in another
        spelling, or written again here in another, as :meth:`add_new` does; a load says it in its own
        notes, an undo has nothing to say)."""
        triples = tuple(dict.fromkeys(triples))
        for t in triples:
            o = t.object  # each term taken from a triple is a new object: once here (a big load has millions)
            if isinstance(o, Literal):
                check_literal(o)
        self.touch(triples)
        if not self.ledger.tracking:  # nothing to record: a big first load takes the store's bulk path
            added = self.store.add(triples, ASSERTED, distinct=True)
            if said and added < len(triples):  # held already, or written twice here: a spelling said
                _warn(_held_before(self.store, triples))
            return added
        return len(self._change(triples, added=True, said=said))

    def remove(self, *triples: Triple) -> int:
        """Retract asserted triples (inferred ones cannot be removed, only their premises)."""
        triples = tuple(dict.fromkeys(triples))
        self.touch(triples)
        return len(self._change(triples, added=False))

    def restore(self, *triples: Triple) -> int:
        """Assert triples an undo gives back, each in the spelling it was held in; returns how many changed
        the graph.  Unlike :meth:`add`, a value this transaction removed in another spelling is respelled
        (:meth:`Store.restore_facts`), not kept as the undone changes left it; recorded as :meth:`add` is."""
        triples = tuple(dict.fromkeys(triples))
        store = self.store
        facts = [store.fact(t, ASSERTED) for t in triples]
        with store.transaction():
            changed = store.restore_facts(facts)
            self.ledger.record(store, changed, added=True, limit=self._change_limit)
        self.touch([f.triple for f in changed])
        return len(changed)

    def add_new(self, *triples: Triple) -> list[Triple]:
        """Assert triples; returns those that were new (what a manipulation reports it did).  Unlike
        :meth:`add`, only the new triples count as touched (a schema triple already there recompiles nothing)."""
        triples = tuple(dict.fromkeys(triples))
        for t in triples:
            _validate(t)
        new = self._change(triples, added=True, said=True)
        self.touch(new)
        return new

    def remove_present(self, *triples: Triple) -> list[Triple]:
        """Retract asserted triples; returns those that were asserted, as :meth:`add_new`."""
        gone = self._change(tuple(dict.fromkeys(triples)), added=False)
        self.touch(gone)
        return gone

    def change(self, add: Sequence[Triple | Fact], remove: Sequence[Triple | Fact]) -> tuple[list[Triple], list[Triple]]:
        """Retract ``remove``, then assert ``add``, in one transaction: (added, removed), those that were new
        and those that were asserted, as :meth:`add_new` and :meth:`remove_present` return them.  One
        manipulation's delta (an aRMOR REPLACE) is one call: one transaction, one change limit, one touch.
        A value removed and added again in another spelling changes nothing (see :meth:`change_noted`); a
        :class:`SpellingKeptWarning` says which spelling stays.

        The triples may come as facts (:class:`~topostore.stores.facts.Fact`, e.g. read by
        :meth:`Store.read_facts`): their keys and forms, made once, serve the store, the ledger and the
        literal forms alike."""
        added, removed, notes = self.change_noted(add, remove)
        _warn(notes)
        return added, removed

    def change_noted(self, add: Sequence[Triple | Fact],
                     remove: Sequence[Triple | Fact]) -> tuple[list[Triple], list[Triple], list[str]]:
        """:meth:`change`, with a note (not a warning) for each value removed and added in another spelling.

        Why: the store keys a literal by its value, so removing ``"3"^^xsd:integer`` and adding
        ``"3.0"^^xsd:decimal`` in one transaction nets out and the asserted graph keeps ``"3"``.  The
        ledger keys by the spelling as stored, so it would record both, and an incremental REASON would
        derive from a triple the asserted graph does not hold.  Such a pair is neither recorded nor
        reported as added or removed, nor is one removed and added again in one spelling: the ledger and
        the report say exactly what the graph gained and lost, and each spelling written and not stored
        (held already, or written again in this change) is said."""
        store = self.store
        adds = []
        for t in _distinct(add):  # every value is validated before anything changes
            if type(t) is Fact:
                if t.value is not None:
                    check_literal(t.triple.object)  # InvalidValueError: not a value of its type
            else:
                _validate(t)
                t = store.fact(t, ASSERTED)
            adds.append(t)
        removes = remove if len(remove) < 2 and (not remove or type(remove[0]) is Fact) else \
            [t if type(t) is Fact else store.fact(t, ASSERTED, written=False) for t in _distinct(remove)]
        ledger, limit = self.ledger, self._change_limit
        with store.transaction():
            removed = store.toggle_facts(removes, False) if removes else []
            added = store.toggle_facts(adds, True) if adds else []
            if len(adds) == 1 and len(added) == 1 and len(removed) == 1 and added[0].key != removed[0].key \
                    and added[0].written is added[0].triple:
                notes = []  # one value replaced by another, written as given: no pair, no spelling to say
            else:
                added, removed, notes = _netted(store, adds, added, removed)
            if removed or added:  # one record of the change: the ledger's unit-of-work step undoes both
                ledger.record_change(store, added, removed, limit)
        self._settled()
        # a REPLACE's one fact each side without a comprehension's call
        added_triples = [added[0].triple] if len(added) == 1 else [f.triple for f in added]
        removed_triples = [removed[0].triple] if len(removed) == 1 else [f.triple for f in removed]
        self.touch(removed_triples + added_triples)
        return added_triples, removed_triples, notes

    def replace_fact(self, s: Term, p: NamedNode, o: Term, old: Fact, new: Fact, alone: bool, before: int) -> None:
        """:meth:`change_noted` of one fact for another, written straight (:mod:`~..stores.one_fact`): ``old``
        read from the committed store by :func:`one_fact.read`, ``new`` (of (s, p, o): the terms as the caller
        holds them) of another value that read did not find, of a property :func:`fact_property` accepts, on a
        store :func:`one_fact.direct` accepts, with no unit of work open (the caller checks all of that);
        ``alone``: ``old`` is the one fact that read found (see :func:`one_fact.replace`), ``before`` the
        store's count of data writes at that read (read through :attr:`kept`).  One write, the literal forms,
        the ledger's record and the ontology marked changed, as :meth:`change_noted` leaves them for that
        change (which says no spelling for it: one value replaced by another, written as given)."""
        store = self.store
        if new.value is not None:
            check_literal(o)  # type: ignore[arg-type] - InvalidValueError: not a value of its type, nothing changed
        gone = store.written_fact(old)  # as written: read before the write takes its form
        one_fact.replace(store, s, p, o, ASSERTED, old, new, alone, self.kept, before)
        self.ledger.record_replaced(store, new, old, gone, self._change_limit)
        self.onto.dirty = True  # touch: a fact property names no schema triple, a memory store no durable state
        store.maybe_compact()  # :meth:`_settled`, whose conditions the caller checked (no unit, nothing pending)

    def _settled(self) -> None:
        """A change committed outside any caller's unit of work: the in-memory store may be rebuilt now
        (:meth:`Store.maybe_compact`). A client that changes facts and never REASONs (a buffered reasoner, a
        clock written many times between REASONs) would otherwise pile up removed quads, and every look-up
        of a rewritten pair walks all of them (``benchmarks.rewrites``: a REPLACE 82 -> 500 µs over 10,000). Inside a
        unit of work the unit's end does it (:class:`.ledger._UnitOfWork`), once the change can no longer
        be undone."""
        if not self.ledger.unit_open and not self.store.writes_pending:
            self.store.maybe_compact()

    def _change(self, triples: tuple[Triple, ...], added: bool, said: bool = False) -> list[Triple]:
        """Add or remove in the asserted graph and record what changed in the ledger: one presence look-up
        per triple (the store's), in one transaction with the change (``said``: warn of each value not
        added because the graph held it in another spelling)."""
        store = self.store
        facts = [store.fact(t, ASSERTED, written=added) for t in triples]
        with store.transaction():
            changed = store.toggle_facts(facts, added)
            self.ledger.record(store, changed, added=added, limit=self._change_limit)
            notes = _held(store, facts, changed, {}) if said else []
        self._settled()
        _warn(notes)
        return [f.triple for f in changed]

    def touch(self, triples: Iterable[Triple]) -> None:
        """Note that the asserted graph changed; a schema triple among ``triples`` makes the rules, the
        classification and the namespace be read again."""
        self.onto.dirty = True
        if self.store.durable:
            durable_state.note_changed(self.store)
        triples = triples if type(triples) is list or isinstance(triples, Sequence) else list(triples)
        if touches_groups(triples):
            self.onto.groups_touched = True
        if changes_schema(self.store, triples):
            self.onto.schema_changed()

    def _change_limit(self) -> float:
        """Net changes above which an incremental REASON no longer pays off (a share of the asserted graph):
        past it the ledger keeps the change for rollback only, and the next REASON is a full one."""
        reasoner = self.onto._reasoner
        return self.onto.max_change_share * (reasoner.state.asserted_size if reasoner else 0)

    def replace(self, subject: str, prop: str, new: object, old: object | None = None) -> int:
        """Replace ``old`` by ``new`` (every current value when ``old`` is None); atomic: one :meth:`change`.

        Values are matched by data value, so ``7`` replaces a stored ``"7"^^xsd:long``.
        Returns how many old facts were removed: a value replaced by itself (in any spelling) is not
        (the graph keeps it as held, and a spelling it did not take is said).
        """
        new_t = self.onto.fact(subject, prop, new)
        s, p = new_t.subject, new_t.predicate
        with self.store.transaction():  # one commit: a durable store never holds half a REPLACE
            olds = list(self.store.triples(s, p, None, ASSERTED))
            if old is not None:
                key = value_key(self.onto.fact(subject, prop, old).object)
                olds = [t for t in olds if value_key(t.object) == key]
            _, removed = self.change([new_t], olds)
        self._settled()
        return len(removed)

    def add_all_different(self, names: Sequence[str | NamedNode]) -> NamedNode:
        """One owl:AllDifferent over ``names`` (deduplicated): linear in size, never n² pairs."""
        triples = all_different(list(dict.fromkeys(self.onto.iri(n) for n in names)))
        self.add(*triples)
        return triples[0].subject

    def remove_individual(self, name: str | NamedNode) -> int:
        """Remove every asserted triple mentioning the individual, and whole AllDifferent axioms containing it."""
        return self.remove(*individual_triples(self.store, self.onto.iri(name)))


def fact_property(p: NamedNode) -> bool:
    """Whether every triple of ``p`` is a fact: a property outside the RDF, RDFS, OWL and SWRL vocabularies
    and XSD's facets, whose triples :func:`~.files.changes_schema` never takes for a schema triple or a list
    cell the TBox reads (each of those is named by a property of these vocabularies), told by the property alone."""
    return not schema_predicate(p)


def _distinct(items: Sequence[Triple | Fact]) -> Sequence[Triple | Fact]:
    """``items`` without repeats (one triple, a manipulation's usual change, is not hashed for it)."""
    return items if len(items) < 2 else list(dict.fromkeys(items))


def _validate(t: Triple) -> None:
    if isinstance(t.object, Literal):
        check_literal(t.object)


def _warn(notes: list[str]) -> None:
    """Log and warn (:class:`SpellingKeptWarning`) of each spelling a change wrote and did not store, the
    warning pointing at the first caller outside topostore (whichever public method it came through)."""
    if not notes:
        return
    level, frame = 1, sys._getframe(0)
    while frame is not None and frame.f_code.co_filename.startswith(_PACKAGE):
        frame, level = frame.f_back, level + 1
    for note in notes:
        logger.warning("%s", note)
        warn(note, SpellingKeptWarning, stacklevel=level)


#: the source folder of topostore: the frames a warning does not point at
_PACKAGE = __file__[: -len("ontology/changes.py")]


def _held(store: Store, adds: list[Fact], added: list[Fact], netted: dict) -> list[str]:
    """A note for each added literal not stored: written again in this change in another spelling of its
    value (the spelling kept: the graph's, where ``netted`` (key → fact removed) says this change removed
    and added it again; else the one this change took), or held by the graph in another spelling."""
    notes = _restored(added, netted)
    if len(added) == len(adds):  # every fact new: the usual change, nothing looked up
        return notes
    taken = {id(f) for f in added}
    here = {f.key: f.triple if f.written is None else f.written for f in added}
    for f in adds:
        if id(f) in taken or f.value is None:
            continue
        gone = netted.get(f.key)
        kept = store.written_fact(gone) if gone is not None else here.get(f.key)
        if kept is not None:
            note = spelling_kept(kept, f.triple, AGAIN_IN_CHANGE) if kept.object != f.triple.object else None
        elif (kept := store.pending_add(f.key)) is not None:
            note = spelling_kept(kept, f.triple, EARLIER_IN_TRANSACTION) if kept.object != f.triple.object else None
        else:
            note = _held_note(store, f.quad.graph_name, f.triple, f.value)
        if note is not None:
            notes.append(note)
    return notes


def _restored(added: list[Fact], netted: dict) -> list[str]:
    """A note for each added literal that took back a removal of its value earlier in the transaction
    (:meth:`Store.toggle_facts` gives it the spelling the store keeps as its written form) in another
    spelling; one this change removed itself (``netted``) is said by :func:`_netted`."""
    notes = []
    for f in added:
        kept = f.written
        if kept is not None and kept is not f.triple and kept.object != f.triple.object and f.key not in netted:
            notes.append(spelling_kept(kept, f.triple, REMOVED_AND_ADDED_IN_TRANSACTION))
    return notes


def _held_before(store: Store, triples: Sequence[Triple]) -> list[str]:
    """:func:`_held` of triples added without facts (already committed): a value's first spelling in
    ``triples`` not kept as written was held before in the spelling kept; a later one is said beside the
    spelling the graph keeps."""
    firsts, again = one_spelling(t for t in triples if isinstance(t.object, Literal))
    notes = (_held_note(store, ASSERTED, t, value_key(t.object)) for t in firsts)
    kept = ((triple(first.subject, first.predicate, store.original_literal(ASSERTED, first.subject, first.predicate,
                                                                          first.object)), later)
            for first, later in again)
    return [note for note in notes if note is not None] + [spelling_kept(k, later, AGAIN_IN_CHANGE)
                                                           for k, later in kept if k.object != later.object]


def _held_note(store: Store, graph: NamedNode, t: Triple, value: tuple) -> str | None:
    """The HELD note of ``t`` where ``graph`` keeps its value in another spelling (the literal forms), else None."""
    kept = store.kept_literal(graph, t.subject, t.predicate, value)
    if kept is None or kept == t.object:
        return None
    return spelling_kept(triple(t.subject, t.predicate, kept), t, HELD)


def _netted(store: Store, adds: list[Fact], added: list[Fact],
            removed: list[Fact]) -> tuple[list[Fact], list[Fact], list[str]]:
    """``added`` and ``removed`` without the values this change removed and added again and the store
    holds as it did (its pending write is keyed by value: the second toggle took back the first), and the
    notes of the spellings written and not stored.  A value removed and added in another spelling keeps
    the spelling held (said); in one spelling, nothing is said.  Where the transaction had written the
    value before this change, the store writes the added spelling: in another spelling than that write's,
    that pair is a change and stays."""
    if not added or not removed:
        return added, removed, _held(store, adds, added, {})
    if len(added) == 1 and len(removed) == 1 and added[0].key != removed[0].key:
        return added, removed, _held(store, adds, added, {})  # a REPLACE of one value by another: no pair
    gone = {f.key: f for f in removed}
    pairs = [(old, f) for f in added if (old := gone.get(f.key)) is not None
             and (store.pending_add(f.key) is None or store.written_fact(old).object == f.triple.object)]
    if not pairs:
        return added, removed, _held(store, adds, added, {})
    netted = {new.key: old for old, new in pairs}
    notes = [spelling_kept(kept, new.triple, REMOVED_AND_ADDED) for old, new in pairs
             if (kept := store.written_fact(old)).object != new.triple.object]
    notes += _held(store, adds, added, netted)
    out = {id(f) for pair in pairs for f in pair}
    return [f for f in added if id(f) not in out], [f for f in removed if id(f) not in out], notes
