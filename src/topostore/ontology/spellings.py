"""What is said of a spelling written but not stored: one wording for every way a document comes in.

The store keeps one value once (``"1"^^xsd:integer`` and ``"01"^^xsd:integer`` are one fact, in the spelling
written first) and one spelling per language tag (``EN`` and ``en`` are one tag, spelled as first written).
A document, an upload or a change that writes another spelling is never silently respelled: each such
spelling gets a note naming the one the graph shows instead.  A load (:mod:`.files`: the Python API, the
CLI, an aRMOR LOAD) publishes its notes as a :class:`SpellingKeptWarning` and on the ``topostore.load``
log, and keeps them for the load's reply (:meth:`OntologyFiles.notice_lines`); a Graph Store write puts
them in its reply; a change (:mod:`.changes`) warns of them.
"""

from __future__ import annotations

import logging
from collections.abc import Callable, Collection, Iterable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from pyoxigraph import Literal, RdfFormat, Triple

from ..compile.notices import OntologyWarning, warn
from ..rdf.skolem import unskolem
from ..rdf.terms import value_key
from ..rdf.vocab import ASSERTED, RDF

if TYPE_CHECKING:  # pragma: no cover
    from ..stores.base import Store
    from ..stores.language_tags import LanguageTags

#: the load notices' log (:mod:`topostore.compile.notices`): the CLI shows it as ``warning:`` lines
logger = logging.getLogger("topostore.load")

#: rdf:XMLLiteral, whose values are stored in canonical form
XML_LITERAL = RDF + "XMLLiteral"
#: why a document's second spelling of one value is not taken
AGAIN = "written again in the document"
#: why a change's second spelling of one value is not taken
AGAIN_IN_CHANGE = "written again in the same change"
#: why a change's spelling of a value an earlier change of the open transaction added is not taken
EARLIER_IN_TRANSACTION = "written earlier in the same transaction"
#: why a change's spelling of a value it removes too is not taken
REMOVED_AND_ADDED = ("removed and added in one change (to change only the spelling, remove it in one change and "
                     "add the new one in the next)")
#: why a spelling of a value an earlier change of the open transaction removed is not taken
REMOVED_AND_ADDED_IN_TRANSACTION = ("removed and added in one transaction (to change only the spelling, remove it "
                                    "in one transaction and add the new one in the next)")
#: why an upload's spelling of a value the graph holds is not taken, and how to change only the spelling
HELD = "already in the graph (to change only its spelling, remove it first and add it then)"
#: why a language tag's spelling is not taken
TAG_KEPT = "its language tag spelled otherwise (a tag keeps the spelling it was first written with)"


class SpellingKeptWarning(OntologyWarning):
    """A spelling written was not stored: the graph keeps the one it shows instead (``"3"^^xsd:integer`` and
    ``"3.0"^^xsd:decimal`` are one value, one fact; ``EN`` and ``en`` one language tag, spelled one way).  A
    load notice like the others (an :class:`OntologyWarning`), said of a change's spellings too."""


def shown(t: Triple, tag: str | None = None) -> str:
    """``t`` as a GET of the graph writes it: a blank node as ``_:id`` (the store names it by a skolem
    IRI), and the object's language tag spelled ``tag`` when given (pyoxigraph lowers every tag)."""
    obj = str(unskolem(t.object))
    if tag is not None and isinstance(t.object, Literal) and t.object.language:
        obj = obj[:-len(t.object.language)] + tag
    return f"{unskolem(t.subject)} {t.predicate} {obj}"


def _text(t: Triple | str) -> str:
    return shown(t) if isinstance(t, Triple) else t


def spelling_kept(kept: Triple | str, other: Triple | str, why: str) -> str:
    """The note that ``kept`` stays the asserted graph's spelling of the value ``other`` writes too, ``why``
    the other is not taken.  Each is a triple or a triple already written by :func:`shown` (a tag spelled)."""
    return f"{_text(kept)} stays as written: {_text(other)} is the same value, {why}"


def tag_respelled(stored: Triple | str, written: Triple | str) -> str:
    """The note that a new value ``written`` is stored, and shown, as ``stored``: its tag is spelled as the
    store spells it, first written on another literal (no spelling of this value stays as written)."""
    return (f"{_text(written)} is stored as {_text(stored)}: a new value, its language tag spelled as the store "
            "spells it (a tag keeps the spelling it was first written with)")


def value_of(t: Triple) -> tuple:
    """The key of the fact ``t`` writes: one per value of a literal, whatever its spelling."""
    return (t.subject, t.predicate, value_key(t.object))


def one_spelling(triples: Iterable[Triple]) -> tuple[list[Triple], list[tuple[Triple, Triple]]]:
    """``triples`` with one spelling per value (the first written), and each later spelling with the first:
    the store keeps one value once, so a document writing ``"7"^^xsd:long`` and ``"07"^^xsd:long`` asserts
    one fact, counted once and said once.  A triple written twice is one fact, nothing to say."""
    first: dict[tuple, Triple] = {}
    kept, again = [], {}
    for t in triples:
        if not isinstance(t.object, Literal):
            if t not in first:
                first[t] = t
                kept.append(t)
            continue
        seen = first.setdefault(value_of(t), t)
        if seen is t:
            kept.append(t)
        elif seen != t:
            again.setdefault(t, seen)
    return kept, [(seen, later) for later, seen in again.items()]


def again_notes(again: Iterable[tuple[Triple, Triple]], stays: Callable[[Triple], Triple]) -> list[str]:
    """The notes for a document's later spellings of a value (``again``: (first, later) pairs), ``stays``
    giving the spelling the graph keeps of a first one (a stored one, if the graph had the value)."""
    pairs = [(stays(first), later) for first, later in again]
    return [spelling_kept(kept, later, AGAIN) for kept, later in pairs if kept != later]


def tag_notes(tags: LanguageTags, written: tuple[bytes | str, RdfFormat | None],
              holders: Callable[[Collection[tuple[str, str]]], Iterable[Triple]],
              held: Callable[[Triple], bool], literals: Collection[tuple[str, str]] | None = None) -> list[str]:
    """A note for each spelling of a written literal's language tag that the graph does not show: the
    parser lowers tags, so two spellings of one literal meet as one triple, and the store spells each tag
    one way (:mod:`~topostore.stores.language_tags`).

    ``written``: the document and its format; ``literals``: the (lexical form, lowered tag) pairs it added
    (None: every one it writes); ``holders``: the triples of the document holding some of them; ``held``:
    whether the graph held a triple before the document came.  The same value is said to stay where the
    graph held it or the document writes it in the spelling kept too; else it is a new value, whose tag
    is spelled as another literal first wrote it."""
    data, fmt = written
    if isinstance(data, str):
        data = data.encode("utf-8", errors="surrogatepass")
    others: dict[tuple[str, str], list[str]] = {}
    for key, tag in tags.not_taken(data, fmt, literals):
        others.setdefault(key, []).append(tag)
    if not others:
        return []
    as_kept = {(lexical, tag) for lexical, tag in tags.written(data, fmt)}
    notes = []
    for t in holders(others.keys()):
        lit = t.object
        for tag in others.get((lit.value, lit.language), ()) if isinstance(lit, Literal) else ():
            kept, other = shown(t, tags.spelled(tag)), shown(t, tag)
            if held(t) or (lit.value, tags.spelled(tag)) in as_kept:
                notes.append(spelling_kept(kept, other, TAG_KEPT))
            else:
                notes.append(tag_respelled(kept, other))
    return notes


def holding(triples: Iterable[Triple], keys: Collection[tuple[str, str]]) -> list[Triple]:
    """The triples whose object is one of the tagged literals ``keys`` (lexical form, lowered tag)."""
    return [t for t in triples if isinstance(o := t.object, Literal) and (o.value, o.language) in keys]


def joined(notes: Iterable[str]) -> str:
    """The notes as one line, each said once."""
    return "; ".join(dict.fromkeys(notes))


def published(notes: list[str], source: str) -> None:
    """Warn (:class:`SpellingKeptWarning`) of and log what a load of ``source`` wrote and did not store."""
    if not notes:
        return
    line = f"{source}: {joined(notes)}"
    logger.warning("%s", line)
    # the caller of Ontology.load/load_data: published ← _published ← OntologyFiles.load* ← Ontology.load*
    warn(line, SpellingKeptWarning, stacklevel=5)


@dataclass
class Written:
    """What a loaded document wrote that the graph may not show as written: each later spelling of a value
    with the first (``again``), its triples (None: streamed into an empty graph, read back from there), its
    tagged triples the graph held before it came (``held``), and whether it gained fewer facts than it has
    triples (``short``: only then may a value it wrote be held in another spelling)."""

    again: list[tuple[Triple, Triple]] = field(default_factory=list)
    triples: list[Triple] | None = None
    held: frozenset[Triple] = frozenset()
    short: bool = False

    @classmethod
    def before(cls, triples: list[Triple], store: Store, data: bytes | str, fmt: RdfFormat) -> Written:
        """A parsed document about to be added to ``store``: the tagged triples held already whose tag the
        document spells otherwise than the store does (one search of the document when it writes every
        tag as the store spells it; a tag the store does not know yet is spelled by this document)."""
        tags = store.forms.tags
        if isinstance(data, str):
            data = data.encode("utf-8", errors="surrogatepass")
        keys = {key for key, tag in tags.not_taken(data, fmt) if tags.known(tag)}
        tagged = holding(triples, keys) if keys else []
        held = frozenset(t for t, present in zip(tagged, store.contains_each(tagged, ASSERTED)) if present)
        return cls([], triples, held)

    def after(self, added: int) -> None:
        """The document is in, ``added`` facts gained: its later spellings of a value, looked for only when
        it gained fewer facts than it has triples (a document of distinct new facts has none), and only
        where a subject and property have two literals (a value key made for those alone)."""
        if self.triples is None or added == len(self.triples):
            return
        self.short = True
        by_pair: dict[tuple, list[Triple]] = {}
        for t in self.triples:
            if isinstance(t.object, Literal):
                by_pair.setdefault((t.subject, t.predicate), []).append(t)
        self.again = [pair for group in by_pair.values() if len(group) > 1 for pair in one_spelling(group)[1]]

    def notes(self, store: Store, data: bytes | str, fmt: RdfFormat) -> list[str]:
        """The notes of the document once it is in (its tags' spellings learned)."""
        def stays(first: Triple) -> Triple:
            lit = store.original_literal(ASSERTED, first.subject, first.predicate, first.object)
            return Triple(first.subject, first.predicate, lit)

        def holders(keys: Collection[tuple[str, str]]) -> Iterable[Triple]:
            if self.triples is not None:
                return holding(self.triples, keys)
            return [t for lexical, tag in keys for t in store.triples(None, None, Literal(lexical, language=tag),
                                                                     ASSERTED)]

        return [*self._held_notes(stays), *again_notes(self.again, stays),
                *tag_notes(store.forms.tags, (data, fmt), holders, self.held.__contains__)]

    def _held_notes(self, stays: Callable[[Triple], Triple]) -> list[str]:
        """A note for each value the document wrote that the graph held already in another spelling (a
        later spelling of the document's own is said by :func:`again_notes`; an rdf:XMLLiteral is stored
        in canonical form, said by its own notice)."""
        if not self.short or self.triples is None:
            return []
        later = {t for _, t in self.again}
        notes = []
        for t in self.triples:
            o = t.object
            if isinstance(o, Literal) and o.datatype.value != XML_LITERAL and t not in later:
                kept = stays(t)
                if kept != t:
                    notes.append(spelling_kept(kept, t, HELD))
        return notes


__all__ = ["AGAIN", "AGAIN_IN_CHANGE", "EARLIER_IN_TRANSACTION", "HELD", "REMOVED_AND_ADDED",
           "REMOVED_AND_ADDED_IN_TRANSACTION", "TAG_KEPT", "SpellingKeptWarning", "Written", "again_notes", "holding",
           "joined", "one_spelling", "published", "shown", "spelling_kept", "tag_notes", "tag_respelled", "value_of"]
