"""The manipulation path: every change of the asserted graph, recorded in the change ledger.

A manipulation validates its values before anything changes, changes the asserted graph and records
the net change in the ledger in one transaction (what incremental REASON, rollback and a unit of
work's undo read), and marks the ontology changed since its last reasoning; a schema triple makes
the rules be compiled again.  A named part of one :class:`~topostore.ontology.facade.Ontology`
(``onto.changes``); the ontology's ``add``, ``remove``, ``change`` and ``replace`` are these.
"""

from __future__ import annotations

import logging
import warnings
from collections.abc import Iterable, Sequence
from typing import TYPE_CHECKING

from pyoxigraph import Literal, NamedNode, Triple

from ..rdf.terms import check_literal, triple, value_key
from ..rdf.vocab import ASSERTED
from ..stores.facts import Fact
from . import state as durable_state
from .files import changes_schema
from .nary import all_different, individual_triples
from .spellings import HELD, SpellingKeptWarning, one_spelling, spelling_kept

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

    def add(self, *triples: Triple, said: bool = False) -> int:
        """Assert triples; returns how many were new (``said``: warn of each value held already in another
        spelling, as :meth:`add_new` does; a load says it in its own notes, an undo has nothing to say)."""
        triples = tuple(dict.fromkeys(triples))
        for t in triples:
            o = t.object  # each term taken from a triple is a new object: once here (a big load has millions)
            if isinstance(o, Literal):
                _validate_literal(o)
        self.touch(triples)
        if not self.ledger.tracking:  # nothing to record: a big first load takes the store's bulk path
            added = self.store.add(triples, ASSERTED, distinct=True)
            if said and added < len(triples):  # some were there already: in another spelling, said
                _warn(_held_before(self.store, triples), stacklevel=4)
            return added
        return len(self._change(triples, added=True, said=said))

    def remove(self, *triples: Triple) -> int:
        """Retract asserted triples (inferred ones cannot be removed, only their premises)."""
        triples = tuple(dict.fromkeys(triples))
        self.touch(triples)
        return len(self._change(triples, added=False))

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
        _warn(notes, stacklevel=4)
        return added, removed

    def change_noted(self, add: Sequence[Triple | Fact],
                     remove: Sequence[Triple | Fact]) -> tuple[list[Triple], list[Triple], list[str]]:
        """:meth:`change`, with a note (not a warning) for each value removed and added in another spelling.

        Why: the store keys a literal by its value, so removing ``"3"^^xsd:integer`` and adding
        ``"3.0"^^xsd:decimal`` in one transaction nets out and the asserted graph keeps ``"3"``.  The
        ledger keys by the spelling as stored, so it would record both, and an incremental REASON would
        derive from a triple the asserted graph does not hold.  Such a pair is neither recorded nor
        reported as added or removed: the ledger and the report say exactly what the graph gained and lost."""
        store = self.store
        adds = []
        for t in _distinct(add):  # every value is validated before anything changes
            if type(t) is Fact:
                if t.value is not None:
                    _validate_literal(t.triple.object)
            else:
                _validate(t)
                t = store.fact(t, ASSERTED)
            adds.append(t)
        removes = [t if type(t) is Fact else store.fact(t, ASSERTED, written=False) for t in _distinct(remove)]
        ledger, limit = self.ledger, self._change_limit
        with store.transaction():
            removed = store.toggle_facts(removes, False) if removes else []
            added = store.toggle_facts(adds, True) if adds else []
            notes = _held(store, adds, added)
            added, removed, respelled = _respelled(store, added, removed)
            notes += respelled
            if removed or added:  # one record of the change: the ledger's unit-of-work step undoes both
                ledger.record_change(store, added, removed, limit)
        added_triples, removed_triples = [f.triple for f in added], [f.triple for f in removed]
        self.touch(removed_triples + added_triples)
        return added_triples, removed_triples, notes

    def _change(self, triples: tuple[Triple, ...], added: bool, said: bool = False) -> list[Triple]:
        """Add or remove in the asserted graph and record what changed in the ledger: one presence look-up
        per triple (the store's), in one transaction with the change (``said``: warn of each value not
        added because the graph held it in another spelling)."""
        store = self.store
        facts = [store.fact(t, ASSERTED, written=added) for t in triples]
        with store.transaction():
            changed = store.toggle_facts(facts, added)
            self.ledger.record(store, changed, added=added, limit=self._change_limit)
            notes = _held(store, facts, changed) if said else []
        _warn(notes, stacklevel=5)  # the caller of Ontology.add
        return [f.triple for f in changed]

    def touch(self, triples: Iterable[Triple]) -> None:
        """Note that the asserted graph changed; a schema triple among ``triples`` makes the rules, the
        classification and the namespace be read again."""
        self.onto.dirty = True
        if self.store.durable:
            durable_state.note_changed(self.store)
        if changes_schema(self.store, triples if type(triples) is list or isinstance(triples, Sequence)
                          else list(triples)):
            self.onto.schema_changed()

    def _change_limit(self) -> float:
        """Net changes above which an incremental REASON no longer pays off (a share of the asserted graph):
        past it the ledger keeps the change for rollback only, and the next REASON is a full one."""
        reasoner = self.onto._reasoner
        return self.onto.max_change_share * (reasoner.state.asserted_size if reasoner else 0)

    def replace(self, subject: str, prop: str, new: object, old: object | None = None) -> int:
        """Replace ``old`` by ``new`` (every current value when ``old`` is None); atomic.

        Values are matched by data value, so ``7`` replaces a stored ``"7"^^xsd:long``.
        Returns how many old facts were removed.
        """
        new_t = self.onto.fact(subject, prop, new)
        s, p = new_t.subject, new_t.predicate
        with self.store.transaction():  # one commit: a durable store never holds half a REPLACE
            if old is None:
                olds = list(self.store.triples(s, p, None, ASSERTED))
            else:
                old_t = self.onto.fact(subject, prop, old)
                key = value_key(old_t.object)
                olds = [t for t in self.store.triples(s, p, None, ASSERTED) if value_key(t.object) == key]
            self.remove(*olds)
            self.add(new_t)
        return len(olds)

    def add_all_different(self, names: Sequence[str | NamedNode]) -> NamedNode:
        """One owl:AllDifferent over ``names`` (deduplicated): linear in size, never n² pairs."""
        triples = all_different(list(dict.fromkeys(self.onto.iri(n) for n in names)))
        self.add(*triples)
        return triples[0].subject

    def remove_individual(self, name: str | NamedNode) -> int:
        """Remove every asserted triple mentioning the individual, and whole AllDifferent axioms containing it."""
        return self.remove(*individual_triples(self.store, self.onto.iri(name)))


def _validate_literal(lit: Literal) -> None:
    """Raise InvalidValueError when ``lit`` is not a valid value of its XSD type (kept as written otherwise)."""
    check_literal(lit)


def _distinct(items: Sequence[Triple | Fact]) -> Sequence[Triple | Fact]:
    """``items`` without repeats (one triple, a manipulation's usual change, is not hashed for it)."""
    return items if len(items) < 2 else list(dict.fromkeys(items))


def _validate(t: Triple) -> None:
    if isinstance(t.object, Literal):
        _validate_literal(t.object)


def _warn(notes: list[str], stacklevel: int = 4) -> None:
    """Log and warn (:class:`SpellingKeptWarning`) of each spelling a change wrote and did not store."""
    for note in notes:
        logger.warning("%s", note)
        warnings.warn(note, SpellingKeptWarning, stacklevel=stacklevel)


def _held(store: Store, adds: list[Fact], added: list[Fact]) -> list[str]:
    """A note for each added literal not stored because the graph held its value in another spelling (the
    spelling kept is the committed one's, so a value written twice in this change is not named here)."""
    if len(added) == len(adds):  # every fact new: the usual change, nothing looked up
        return []
    taken = {id(f) for f in added}
    notes = (_held_note(store, f.quad.graph_name, f.triple, f.value) for f in adds
             if id(f) not in taken and f.value is not None)
    return [note for note in notes if note is not None]


def _held_before(store: Store, triples: Sequence[Triple]) -> list[str]:
    """:func:`_held` of triples added without facts (already committed): a value's first spelling in
    ``triples`` not kept as written was held before in the spelling kept (a later one is the call's own)."""
    firsts, _ = one_spelling(t for t in triples if isinstance(t.object, Literal))
    notes = (_held_note(store, ASSERTED, t, value_key(t.object)) for t in firsts)
    return [note for note in notes if note is not None]


def _held_note(store: Store, graph: NamedNode, t: Triple, value: tuple) -> str | None:
    """The HELD note of ``t`` where ``graph`` keeps its value in another spelling (the literal forms), else None."""
    kept = store.forms.recorded(graph, t.subject, t.predicate, value)
    if kept is None or kept == t.object:
        return None
    return spelling_kept(triple(t.subject, t.predicate, kept), t, HELD)


def _respelled(store: Store, added: list[Fact], removed: list[Fact]) -> tuple[list[Fact], list[Fact], list[str]]:
    """``added`` and ``removed`` without the pairs of one value in two spellings, which the store netted out
    (its pending write is keyed by value), with a note naming the spelling kept and the one not written.
    A pair of one spelling stays: the ledger cancels it itself (it keys by the stored form)."""
    if not added or not removed:
        return added, removed, []
    if len(added) == 1 and len(removed) == 1 and added[0].key != removed[0].key:
        return added, removed, []  # a REPLACE of one value by another: no pair, nothing built to find one
    gone = {f.key: f for f in removed}
    pairs = [(gone[f.key], f) for f in added if f.key in gone and _spelled_apart(store, gone[f.key], f)]
    if not pairs:
        return added, removed, []
    kept = {id(f) for pair in pairs for f in pair}
    notes = [spelling_kept(store.written_fact(old), new.triple, "removed and added in one change (to change only "
                           "the spelling, remove it in one change and add the new one in the next)")
             for old, new in pairs]
    return [f for f in added if id(f) not in kept], [f for f in removed if id(f) not in kept], notes


def _spelled_apart(store: Store, old: Fact, new: Fact) -> bool:
    """Whether ``new`` writes the value of ``old`` in another spelling: other stored forms (the store nets
    them out) or one stored form written otherwise (``"0100"`` and ``"100"`` as xsd:long: the ledger
    cancels them and the spelling written first stays)."""
    if store.stored_form(old.triple) != store.stored_form(new.triple):
        return True
    return store.written_fact(old).object != new.triple.object
