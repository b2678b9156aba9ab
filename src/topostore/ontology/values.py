"""Values and facts made from Python values and names, with the language tags' spellings users gave.

A named part of one :class:`~topostore.ontology.facade.Ontology` (``onto.values``); the ontology's
``value`` and ``fact``, and its changes by names (``add_fact``, ``add_data``, ``replace``, ...), are these.

pyoxigraph lowers a language tag as a literal is made
(``Literal("colour", language="en-GB").language == "en-gb"``), so a tag's spelling can reach topostore
only beside the literal: ``onto.value("colour", language="en-GB")`` keeps it until a change asserts that
literal (same lexical form and tag: :meth:`OntologyValues.asserted`), and the store then spells its tag so
(the first spelling wins, as for documents: :mod:`topostore.stores.language_tags`).  The spellings of
the last :data:`PENDING` literals made wait (a value made to query or remove, never asserted, would
otherwise be held for ever); an older one asserted later is shown with its tag lowered.  Inside a unit of work
(:meth:`.ledger.ChangeLedger.undoable`) the spelling is the store's only once the unit succeeds: an
assertion it undoes gives none.
"""

from __future__ import annotations

from collections.abc import Collection, Iterable
from typing import TYPE_CHECKING

from pyoxigraph import Literal, NamedNode, RdfFormat, Triple, parse

from ..errors import InvalidValueError
from ..rdf.terms import check_literal, literal_of
from ..rdf.vocab import ASSERTED, TYPE, XSD
from ..stores.language_tags import literal_tags
from .spellings import holding, tag_notes

if TYPE_CHECKING:
    from .facade import Ontology


#: how many literals made with a tag's spelling wait to be asserted, at most (the oldest is dropped first)
PENDING = 4096


class OntologyValues:
    """Makes one ontology's literals and facts; keeps the tag spellings given with them until asserted."""

    def __init__(self, onto: Ontology) -> None:
        self.onto = onto
        #: (lexical form, lowered tag) -> spelling given to :meth:`value` for that literal, not yet asserted
        self._pending: dict[tuple[str, str], str] = {}
        #: spellings of literals asserted inside an open unit of work: (the index of the step that asserted
        #: them, literal, spelling)
        self._held: list[tuple[int, tuple[str, str], str]] = []
        #: spellings the store took from literals asserted since the last successful REASON (a failed one
        #: reverts those literals: :meth:`reverted`)
        self._adopted: list[tuple[tuple[str, str], str]] = []
        #: spellings the store read from documents, updates and uploads since the last successful REASON
        #: (:meth:`learned`): a failed one, reverting every change since, forgets them
        self._learned: list[str] = []

    def value(self, value: object, datatype: str | None = None, language: str | None = None) -> Literal:
        """A validated literal from a Python value (int → xsd:integer, ...), text + datatype or text + tag."""
        if language is not None:
            return self._tagged(value, datatype, language)
        if isinstance(value, Literal):
            check_literal(value)
            return value
        if datatype is not None:
            if not isinstance(datatype, str):
                raise TypeError(f"a datatype must be a string, not {type(datatype).__name__}")
            local = datatype[len(XSD):] if datatype.startswith(XSD) else datatype
            return literal_of(str(value), local)
        if isinstance(value, bool):
            return literal_of(str(value).lower(), "boolean")
        if isinstance(value, int):
            return literal_of(str(value), "integer")
        if isinstance(value, float):
            return literal_of(repr(value), "double")
        return Literal(str(value))

    def _tagged(self, value: object, datatype: str | None, language: str) -> Literal:
        """``value`` as text tagged ``language``, the tag's spelling kept until the literal is asserted."""
        if not isinstance(language, str):
            raise TypeError(f"a language tag must be a string, not {type(language).__name__}")
        if datatype is not None:
            raise InvalidValueError("a literal has a datatype or a language tag, not both")
        text = value.value if isinstance(value, Literal) else value
        if not isinstance(text, str):
            raise InvalidValueError(f"a language-tagged literal is text, not {type(value).__name__}")
        try:
            made = Literal(text, language=language)
        except ValueError as exc:
            raise InvalidValueError(f"{language!r} is not a valid language tag: {exc}") from None
        if not self.onto.store.forms.tags.known(made.language):
            self._wait((made.value, made.language), language)
        return made

    def _wait(self, key: tuple[str, str], spelling: str) -> None:
        """Keep ``spelling`` until the literal ``key`` is asserted (the first one given for it wins; past
        :data:`PENDING` literals waiting, the one made longest ago is dropped: a literal made again counts
        as made now)."""
        first = self._pending.pop(key, spelling)
        self._pending[key] = first
        if len(self._pending) > PENDING:
            del self._pending[next(iter(self._pending))]

    def fact(self, subject: str, prop: str, obj: object) -> Triple:
        """A triple from names: ``obj`` is an individual name, a Literal or a Python value."""
        onto = self.onto
        o = onto.iri(obj) if isinstance(obj, (str, NamedNode)) and not isinstance(obj, Literal) else self.value(obj)
        return Triple(onto.iri(subject), onto.iri(prop), o)

    # ---------------------------------------------------------------- changes by names (the ontology's)
    def add_fact(self, subject: str, prop: str, obj: object) -> int:
        return self._add(self.fact(subject, prop, obj))

    def remove_fact(self, subject: str, prop: str, obj: object) -> int:
        return self.onto.changes.remove(self.fact(subject, prop, obj))

    def add_type(self, individual: str, cls: str) -> int:
        return self.onto.changes.add(Triple(self.onto.iri(individual), TYPE, self.onto.iri(cls)))

    def remove_type(self, individual: str, cls: str) -> int:
        return self.onto.changes.remove(Triple(self.onto.iri(individual), TYPE, self.onto.iri(cls)))

    def add_data(self, prop: str, individual: str, value: object, datatype: str | None = None) -> int:
        return self._add(Triple(self.onto.iri(individual), self.onto.iri(prop), self.value(value, datatype)))

    def replace(self, subject: str, prop: str, new: object, old: object | None = None) -> int:
        """:meth:`AssertedChanges.replace`, then the spelling given for ``new``'s tag kept."""
        removed = self.onto.changes.replace(subject, prop, new, old)
        if self._pending:
            self.asserted([self.fact(subject, prop, new)])
        return removed

    def _add(self, t: Triple) -> int:
        """Assert one triple made from names (no blank node to name); a value held already in another
        spelling is said, as :meth:`Ontology.add` says it."""
        added = self.onto.changes.add(t, said=True)
        self.asserted((t,))
        return added

    @property
    def waiting(self) -> bool:
        """Whether a spelling given to :meth:`value` waits for its literal to be asserted."""
        return bool(self._pending)

    def asserted(self, triples: Iterable[Triple]) -> None:
        """``triples`` were asserted (the change committed): the spellings given for their literals are the
        store's now, or once the open unit of work succeeds (one look per literal while a spelling waits;
        none otherwise)."""
        if not self._pending:
            return
        given = [(key, self._pending.pop(key)) for t in triples if isinstance(o := t.object, Literal)
                 and o.language and (key := (o.value, o.language)) in self._pending]
        if not given:
            return
        step = self.onto.ledger.unit_step
        if step is None:
            self._adopt(given)
        else:
            self._held += [(step - 1, key, spelling) for key, spelling in given]

    def undone(self, start: int) -> None:
        """A unit of work undid its steps from ``start`` on: the spellings of the literals asserted there
        wait again (for that literal to be asserted by a change that stays)."""
        for step, key, spelling in self._held:
            if step >= start:
                self._wait(key, spelling)
        self._held = [h for h in self._held if h[0] < start]

    def settled(self) -> None:
        """The outermost unit of work ended and its changes stay: the spellings held for it are the store's."""
        if self._held:
            held, self._held = self._held, []
            self._adopt([(key, spelling) for _, key, spelling in held])

    def _adopt(self, given: list[tuple[tuple[str, str], str]]) -> None:
        """The spellings of asserted literals are the store's; the new ones noted while a failed REASON
        would revert their literals."""
        new = set(self.onto.store.forms.adopt_tags([spelling for _, spelling in given]))
        if new and self.onto.ledger.recording:
            self._adopted += [(key, spelling) for key, spelling in given if spelling in new]

    def learned(self, data: bytes | str, fmt: RdfFormat | None,
                only: Collection[tuple[str, str]] | None = None) -> None:
        """A document, a SPARQL update or an upload is in: the store learns its tags' spellings
        (:meth:`~topostore.stores.literal_forms.LiteralForms.learn_tags`), noted while a failed REASON
        would revert the literals they came with."""
        new = self.onto.store.forms.learn_tags(data, fmt, only)
        ledger = self.onto.ledger
        # a change reasoned before its text is read (a live reasoner's update) left nothing to revert
        if new and ledger.recording and ledger.added:
            self._learned += new

    def data_tag_notes(self, document: str, added: Collection[Triple]) -> list[str]:
        """The notes of the tagged literals an update's ``INSERT DATA`` s wrote (``document``: their triples as
        Turtle, tags as written) with a tag the graph spells otherwise, as a Graph Store write says them: the
        same value where the graph held it before (not among ``added``), else a new one spelled as stored.  Only
        a triple the graph holds after the update is said (one it removed again keeps no spelling)."""
        try:
            written = [Triple(q.subject, q.predicate, q.object) for q in parse(document, RdfFormat.TURTLE)
                       if isinstance(q.object, Literal) and q.object.language and isinstance(q.subject, NamedNode)]
        except (SyntaxError, ValueError):
            return []
        store = self.onto.store
        held = [t for t, present in zip(written, store.contains_each(written, ASSERTED), strict=True) if present]
        return tag_notes(store.forms.tags, (document, RdfFormat.TURTLE), lambda keys: holding(held, keys),
                         lambda t: t not in added, literal_tags(held))

    def reasoned(self) -> None:
        """A REASON succeeded: the literals asserted before it are no longer reverted by a failed one."""
        self._adopted.clear()
        self._learned.clear()

    def reverted(self) -> None:
        """A failed REASON reverted every asserted change since the last good one (and ended the open units'
        steps): a spelling stays the store's only while its literal is asserted; the others wait again, as
        after an undone unit of work."""
        held = [(key, spelling) for _, key, spelling in self._held]
        adopted, self._adopted, self._held = self._adopted, [], []
        gone = [(key, spelling) for key, spelling in adopted + held if not self._is_asserted(key)]
        self.onto.store.forms.forget_tags([spelling for key, spelling in gone if (key, spelling) in adopted])
        for key, spelling in gone:
            self._wait(key, spelling)
        self._adopt([h for h in held if h not in gone])  # asserted before the reverted changes: they stay
        # every literal added since the last good REASON is reverted, so are the spellings read with them
        # (one read from a document that also restated a literal kept included: it was not there before)
        learned, self._learned = self._learned, []
        self.onto.store.forms.forget_tags(learned)

    def _is_asserted(self, key: tuple[str, str]) -> bool:
        """Whether the literal ``key`` (lexical form, lowered tag) is the object of an asserted triple."""
        literal = Literal(key[0], language=key[1])
        return next(iter(self.onto.store.triples(None, None, literal, ASSERTED)), None) is not None


__all__ = ["PENDING", "OntologyValues"]
