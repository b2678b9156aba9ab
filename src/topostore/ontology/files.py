"""An ontology's documents: loading (all or nothing, rules compiled first) and saving.

A named part of :class:`topostore.ontology.facade.Ontology` (``onto.files``), apart from the facade
because loading has rules of its own: a document that changes the schema is
compiled on a scratch copy first, so an untranslatable rule leaves the ontology
as it was.  The first document of an empty in-memory ontology is compiled where
it is added instead (taken out again when it is refused): a big map is then
written once, not twice; and it is written as it is parsed (:mod:`.streamed`),
without a list of its triples, unless it needs what only the list gives (its
rules repaired, a refusal's message).
"""

from __future__ import annotations

import os
from collections.abc import Callable, Collection, Sequence
from pathlib import Path
from typing import TYPE_CHECKING

from pyoxigraph import NamedNode, RdfFormat, Triple

from ..compile import RuleSet, compile_ontology
from ..compile.notices import RULE_REPAIRED, RULE_SKIPPED, Notice, grouped, publish
from ..compile.swrl_repair import repair_rules, skip_rule
from ..compile.swrl_text import rules_among
from ..errors import IncompleteOntologyError, RuleCompileError, TopostoreError
from ..rdf.collector import collector_paused
from ..rdf.declarations import declared
from ..rdf.safeio import atomic_write, read_regular_file
from ..rdf.terms import Term
from ..rdf.vocab import (
    ASSERTED,
    DIFFERENT_FROM,
    FIRST,
    OWL,
    RDF,
    RDFS,
    REST,
    STANFORD_SWRL,
    SWRL,
    SWRLB,
    TYPE,
    XSD,
    is_skolem,
    owl,
)
from ..stores import check_rules, memory_store
from ..stores.base import Store, guess_format, serialize
from .schema_lists import list_change_is_schema
from .spellings import Written, joined, published
from .streamed import rules_need_repair, schema_triples, stream_into_empty
from .streamed_child import child_wanted, stream_through_child
from .xml_literals import canonical_xml_literals

if TYPE_CHECKING:  # pragma: no cover
    from .facade import Ontology

SCHEMA_NAMESPACES = (RDF, RDFS, OWL, SWRL, STANFORD_SWRL)
#: the OWL 2 facets of a datatype restriction (``_:f xsd:maxInclusive 10``): predicates of schema triples outside the
#: schema namespaces (a data property its user named in the XSD namespace stays a fact property)
FACET_PREDICATES = frozenset(XSD + name for name in (
    "minInclusive", "maxInclusive", "minExclusive", "maxExclusive", "length", "minLength", "maxLength", "pattern",
    "totalDigits", "fractionDigits"))


def schema_predicate(p: NamedNode) -> bool:
    """Whether ``p`` names schema triples wherever it is used (a vocabulary property or a facet)."""
    return p.value.startswith(SCHEMA_NAMESPACES) or p.value in FACET_PREDICATES


_ABOX_PREDICATES = {TYPE, owl("sameAs"), DIFFERENT_FROM, FIRST, REST, owl("distinctMembers"), owl("members")}


def is_schema_triple(t: Triple) -> bool:
    """True for triples that change the rules (TBox axioms, SWRL rules), not just facts: a datatype
    restriction's facet (``_:f xsd:maxInclusive 10``, a member of its ``owl:withRestrictions`` list) is one
    too (:data:`FACET_PREDICATES`)."""
    p = t.predicate
    if p == TYPE:
        if is_skolem(t.object):  # a type that is an anonymous class expression: the compiler keeps its node
            return True          # (compile/alike.py merges only expressions no individual is typed with)
        return isinstance(t.object, NamedNode) and t.object.value.startswith(SCHEMA_NAMESPACES) and t.object not in (
            owl("NamedIndividual"), owl("Thing"), owl("AllDifferent"))
    if p in _ABOX_PREDICATES:
        return False
    return schema_predicate(p)


def changes_schema(store: Store, triples: Sequence[Triple]) -> bool:
    """True when the change ``triples`` changes the rules: a schema triple, or the cell of a list the TBox
    reads (a union's members, a property chain, a rule's atoms: :mod:`.schema_lists`), which
    :func:`is_schema_triple` cannot tell from the triple alone."""
    for t in triples:  # a loop, not any() over a generator: a manipulation changes one or two triples
        if is_schema_triple(t):
            return True
    return list_change_is_schema(store, triples, is_schema_triple)


class OntologyFiles:
    """Loading and saving: a named part of one :class:`~topostore.ontology.facade.Ontology` (``onto.files``).

    It adds through the ontology's ``changes`` part (so the change ledger sees every triple) and reads its
    ``store``, ``prefix``, ``rules`` and ``visible_graphs``; the compiled rules a load checked are
    handed back to the ontology so they are not compiled twice.
    """

    def __init__(self, onto: Ontology) -> None:
        self.onto = onto
        #: what the documents loaded wrote and the graph does not show as written (:mod:`.spellings`)
        self.spelling_notes: list[str] = []

    def load(self, path: str | os.PathLike[str], fmt: str | None = None, base_iri: str | None = None,
             progress: Callable[[int], None] | None = None) -> int:
        """Add a document's triples to the asserted graph; all or nothing.

        Rules are compiled before anything is added, so a file with a rule that
        cannot be translated is refused and leaves the ontology as it was.
        ``progress(n)`` is told how many triples have been parsed so far.
        """
        data = read_regular_file(path)  # regular files only, size-limited (LoadError otherwise)
        added, shown, notes = self._loaded(data, guess_format(path, fmt), base_iri, str(path), progress)
        _published(shown, notes, str(path))
        return added

    def load_data(self, data: str | bytes, fmt: str = "turtle", base_iri: str | None = None) -> int:
        """Add a document given as text or bytes; all or nothing.  How many facts the asserted graph
        gained, as :meth:`load` counts them."""
        added, shown, notes = self._loaded(data, guess_format("x", fmt), base_iri, "<data>")
        _published(shown, notes, "<data>")
        return added

    def _loaded(self, data: str | bytes, fmt: RdfFormat, base_iri: str | None, source: str,
                progress: Callable[[int], None] | None = None) -> tuple[int, list[Notice], list[str]]:
        """Load a document: how many facts the asserted graph gained (a value is one fact, whatever its
        spellings in the document), what loading it repaired or set aside, and what it wrote that the
        graph does not show as written: a value's later spelling, a language tag spelled otherwise
        (:mod:`.spellings`, kept for :meth:`notice_lines`)."""
        added, shown, written = self._load_bytes(data, fmt, base_iri, source, progress)
        self.onto.values.learned(data, fmt)  # once the document is in (all or nothing)
        notes = written.notes(self.onto.store, data, fmt)
        self.spelling_notes += notes
        return added, shown, notes

    def _load_bytes(self, data: str | bytes, fmt: RdfFormat, base_iri: str | None, source: str,
                    progress: Callable[[int], None] | None = None) -> tuple[int, list[Notice], Written]:
        """A document given as its bytes: streamed into an empty graph where that is possible, else (or
        when the stream finds what only the ordinary load handles) parsed into triples and added.
        (Facts added, notices to publish, what it wrote that may not be stored as written.)"""
        if self._streaming_possible():
            done = self._streamed(data, fmt, base_iri, source, progress)
            if done is not None:
                return done
        with collector_paused():
            triples = self.onto.store.parse_bytes(data, fmt, base_iri, source=source, progress=progress)
            written = Written.before(triples, self.onto.store, data, fmt)
        added, notices = self._add_document(triples)
        written.after(added)
        return added, notices, written

    def _add_document(self, triples: list[Triple]) -> tuple[int, list[Notice]]:
        """Add a document: its SWRL rules repaired first (:mod:`.compile.swrl_repair`), then
        checked; what was repaired or set aside is kept in :attr:`load_notices` once the document is
        in.  (Facts added, notices to publish.)"""
        with collector_paused():
            triples, unreadable = canonical_xml_literals(triples)
            triples, notices = repair_rules(triples)
        notices += unreadable
        known = self._known_notices()
        added, notices = self._add_checked(triples, notices)
        return added, self._kept(notices, known)

    def _known_notices(self) -> set[Notice]:
        """What the current rules' compiling reported already (not published again)."""
        return set(self.onto._rules.notices) if self.onto._rules is not None else set()

    def _kept(self, notices: list[Notice], known: set[Notice]) -> list[Notice]:
        """A document is in: what loading it repaired or set aside kept; returned with what its compiling
        found that was not known before (what is published)."""
        self.onto.load_notices += notices
        compiled = self.onto._rules.notices if self.onto._rules is not None else []
        return [*notices, *(n for n in compiled if n not in known)]

    # ------------------------------------------------------------ a document streamed into an empty graph
    def _streaming_possible(self) -> bool:
        """Whether a document may be written as it is parsed (:mod:`.streamed`): the asserted graph is empty
        and in memory (see :meth:`_in_place_possible`), no change is being recorded and no transaction is
        open (both need each triple)."""
        return (not self.onto.ledger.tracking and not self.onto.store._depth and self._in_place_possible())

    def _streamed(self, data: str | bytes, fmt: RdfFormat, base_iri: str | None, source: str,
                  progress: Callable[[int], None] | None) -> tuple[int, list[Notice], Written] | None:
        """Stream the document into the empty asserted graph, then test and compile it there.  None when it
        is taken out again for the ordinary load, whose answer (repair, skip, refusal, error) is then the one
        given: an error of any kind, a rule that needs repair, a rule that cannot be compiled, strict loading
        refusing it."""
        store = self.onto.store
        known = self._known_notices()
        store.data_writes += 1  # a stream into the store writes past Store._write
        try:
            with collector_paused():
                stream = stream_through_child if child_wanted(store, data) else stream_into_empty
                found = stream(store, data, fmt, base_iri, source, progress)
                schema = next(schema_triples(store, found.predicates, is_schema_triple), None)
                if schema is not None and rules_need_repair(store, found.predicates):
                    raise _Ordinary
            rules = self._compiled_here(found.notices) if schema is not None else None
        except (TopostoreError, _Ordinary):
            store.clear(ASSERTED)
            return None
        except BaseException:
            store.clear(ASSERTED)
            raise
        self.onto.changes.touch([schema] if schema is not None else [])
        if rules is not None:
            # compiled on the graph as it now is: their keys' form and list notices are its own, so the next
            # REASON need not read the member lists again (0.3-0.45 s at 100,000 locations)
            self.onto._rules = rules
            self.onto.groups_touched = False
        else:  # the streamed triples are not listed: their member lists are counted again
            self.onto.groups_touched = True
        return found.triples, self._kept(found.notices, known), Written(found.again)

    def _compiled_here(self, notices: list[Notice], refuse: Collection[Term] = ()) -> RuleSet:
        """The rules of the asserted graph as it now is, checked as the ordinary load checks them (the rules of
        ``refuse`` refused, not set aside, when they cannot be compiled)."""
        rules = compile_ontology(self.onto.store, ASSERTED, refuse)
        if self.onto.strict:
            _refuse_incomplete([*notices, *rules.notices])
        check_rules(self.onto.store, rules)
        return rules

    def _add_checked(self, triples: list[Triple], repaired: list[Notice] | None = None,
                     added_rules: bool = False) -> tuple[int, list[Notice]]:
        """Add loaded triples; when they change the rules, compile first on a copy,
        so that a refused rule leaves the ontology untouched, and keep
        that compilation (it is the one the new asserted graph gives).

        A rule that cannot be translated is set aside with a notice; one that was repaired (``repaired``) is
        skipped (a notice, its triples not added); the rules of ``triples`` when they are ``added_rules`` (a
        rule a command adds) refuse them.  Returns (triples added, notices).
        """
        notices = list(repaired or [])
        if not changes_schema(self.onto.store, triples):
            return self._add_all(triples), notices
        refuse = {n.node for n in notices if n.kind == RULE_REPAIRED} | (rules_among(triples) if added_rules else set())
        if self._in_place_possible():
            done = self._add_compiled_in_place(triples, notices, refuse)
            if done is not None:
                return done
        while True:
            scratch = memory_store()
            scratch.add(self.onto.store.triples(graph=ASSERTED), ASSERTED)
            scratch.add(triples, ASSERTED)
            try:
                rules = compile_ontology(scratch, ASSERTED, refuse)  # raises RuleCompileError, nothing added
                break
            except RuleCompileError as exc:
                done = next((n for n in notices if n.kind == RULE_REPAIRED and n.node == exc.rule), None)
                if done is None:
                    raise
                triples, skipped = skip_rule(triples, exc.rule, f"repaired ({done.reason}) but "
                                             f"it still cannot be translated: {exc}")
                notices = [skipped if n is done else n for n in notices]
                refuse.discard(exc.rule)
        if self.onto.strict:
            _refuse_incomplete([*notices, *rules.notices])
        check_rules(self.onto.store, rules)
        added = self._add_all(triples)
        self.onto._rules = rules
        return added, notices

    def _add_all(self, triples: list[Triple]) -> int:
        """Add a document's triples through the ontology, the cycle collector paused (the compiling
        around it runs with the collector on: a big TBox's expressions may well make cycles)."""
        with collector_paused():
            return self.onto.changes.add(*triples)

    def _in_place_possible(self) -> bool:
        """Whether a document may be compiled where it is added: the asserted graph is empty and
        in memory, so taking a refused document out again leaves exactly what was there (a
        durable store could keep half of it through a crash, a remote one pays every write twice)."""
        store = self.onto.store
        return not store.durable and not store.round_trips and store.is_empty(ASSERTED)

    def _add_compiled_in_place(self, triples: list[Triple], notices: list[Notice],
                               refuse: Collection[Term]) -> tuple[int, list[Notice]] | None:
        """Add the document, then compile the asserted graph it makes (no scratch copy).

        A refusal (an untranslatable rule, strict loading, a rule too large for the store) takes
        the document out again, leaving the graph empty as it was, and returns None: the scratch
        path then repairs or refuses it with its own messages.
        """
        dirty = self.onto.dirty
        added = self._add_all(triples)
        try:
            rules = self._compiled_here(notices, refuse)
        except BaseException as exc:
            self.onto.changes.remove(*triples)
            self.onto.dirty = dirty
            if isinstance(exc, TopostoreError):
                return None
            raise
        self.onto._rules = rules
        return added, notices

    @property
    def notices(self) -> list[Notice]:
        """What loading repaired or set aside, then what the current rules set aside or reason only in part."""
        return [*self.onto.load_notices, *self.onto.rules.notices]

    def notice_lines(self) -> list[str]:
        """:attr:`notices` one line per kind (and axiom kind), naming each rule or axiom with its reason;
        then, in one line, each spelling a loaded document wrote and the graph does not show
        (:attr:`spelling_notes`)."""
        return [*grouped(self.notices), *filter(None, [joined(self.spelling_notes)])]

    def triples(self, inferred: bool = False) -> list[Triple]:
        graphs = self.onto.visible_graphs() if inferred else [ASSERTED]
        return self.onto.store.dump(graphs, restore_literals_from=ASSERTED)

    def serialize(self, fmt: str | RdfFormat = "turtle", inferred: bool = False) -> bytes:
        """The ontology as a document, with the declarations its facts need and the graph may lack
        (:mod:`topostore.rdf.declarations`); the stored graph is unchanged."""
        rdf_format = guess_format("x", fmt) if isinstance(fmt, str) else fmt
        prefixes = {"owl": OWL, "rdf": RDF, "rdfs": RDFS, "xsd": XSD, "swrl": SWRL,
                    "swrlb": SWRLB, "": self.onto.prefix}
        written = serialize(declared(self.triples(inferred)), rdf_format, prefixes)
        return self.onto.store.forms.tags.respell(written, rdf_format)  # pyoxigraph lowers language tags

    def save(self, path: str | os.PathLike[str], fmt: str | None = None, inferred: bool = False) -> Path:
        """Write asserted (or asserted + inferred) triples; the format follows the extension."""
        path = Path(path)
        data = self.serialize(guess_format(path, fmt), inferred)
        return atomic_write(path, data)  # temporary file beside it, never through a symlink, removed on failure


def _published(notices: list[Notice], notes: list[str], source: str) -> None:
    """Warn of and log what loading a document repaired, set aside or reasons only in part, and what it
    wrote that the graph does not show as written."""
    publish(notices, source)  # its warnings point at the caller of Ontology.load / load_data
    published(notes, source)


class _Ordinary(Exception):
    """A document streamed into the empty graph needs what only the ordinary load does (its rules repaired)."""


def _refuse_incomplete(notices: list[Notice]) -> None:
    """Strict loading: IncompleteOntologyError naming every axiom not reasoned completely or rule skipped."""
    blocking = [n for n in notices if n.incomplete or n.kind == RULE_SKIPPED]
    if blocking:
        raise IncompleteOntologyError("refused (strict): " + "; ".join(grouped(blocking)))


__all__ = ["OntologyFiles", "changes_schema", "is_schema_triple"]
