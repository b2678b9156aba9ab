"""A document written straight into an empty asserted graph: one pass over the parser's quads, no triple list.

The ordinary load (:mod:`.files`) parses a document into a list of triples that every check reads in turn
(skolemisation, XML literals, the SWRL repair's scan, literal validation and forms, the schema test, the
deduplication) before the store is written.  Into an empty in-memory graph a document can be written as
the parser makes its quads, each term read once, because taking it out again leaves exactly what was there;
the checks run on the few triples that need them, as the quads go by or read back from the graph.  In
memory the triples go to the store as N-Triples text, a piece at a time, each piece indexed in a second
thread where a core is free (:mod:`topostore.stores.text_writer`).  RDF/XML, Turtle and N-Triples are
serialised by pyoxigraph as it parses, and the text changed as bytes (:func:`_text_pass`,
:mod:`topostore.rdf.ntriples_text`: no Python frame per triple, only the literal lines read as terms);
JSON-LD and N3 quad by quad (:func:`written_triples`: a new triple only where a term changes).  Elsewhere
the triples go as quads of the asserted graph (one ``extend``).  A big document may be parsed in a child
process instead (:mod:`.streamed_child`), through :func:`written_triples`.

* a blank node becomes its skolem IRI as its triple is made;
* a literal is validated, an rdf:XMLLiteral put in canonical form, and only the first spelling of a value
  for a (subject, predicate) is written (document order, as the ordinary load keeps it) and recorded as
  the form users wrote;
* the schema test reads one triple per predicate the pass met, and per class the graph types;
* the SWRL rules are read back from the graph, a few nodes each, and asked whether they need repair.

:class:`StreamedDocument` reports what the pass found; :mod:`.files` decides, and whatever the ordinary
load would repair, skip or refuse takes the document out again and goes the ordinary way.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from dataclasses import dataclass, field
from itertools import islice

from pyoxigraph import BlankNode, Literal, NamedNode, Quad, RdfFormat, Triple, serialize
from pyoxigraph import parse as ox_parse

from ..compile.notices import Notice
from ..compile.swrl_repair import needs_repair
from ..rdf.ntriples_text import literal_lines, named_blank_nodes, put_back, subject_named
from ..rdf.ntriples_text import predicates as line_predicates
from ..rdf.syntax import PROGRESS_EVERY, document_bytes, parse_error, parsed_quads, parser
from ..rdf.terms import Term, check_literal, value_key
from ..rdf.vocab import ASSERTED, SKOLEM_PREFIX, TYPE, swrl
from ..stores.base import Store
from .xml_literals import XML_LITERAL, canonical_xml_literal

#: triples per piece of N-Triples text written into the store (about 2 MB of text at 16,384)
TEXT_CHUNK = 16384
#: the formats whose parser gives triples of the default graph only, each written on one N-Triples line by
#: the serialiser (:func:`_text_pass`); the others (JSON-LD, N3) are read quad by quad (:func:`written_triples`)
TEXT_FORMATS = frozenset({RdfFormat.RDF_XML, RdfFormat.TURTLE, RdfFormat.N_TRIPLES})


@dataclass
class StreamedDocument:
    """What writing one document into the empty asserted graph found."""

    #: the facts the document stored, as the ordinary load counts them (one per value, whatever its spellings)
    triples: int = 0
    #: every predicate the document uses
    predicates: set[NamedNode] = field(default_factory=set)
    #: rdf:XMLLiteral objects that are not well-formed XML (kept as written), in document order
    notices: list[Notice] = field(default_factory=list)
    #: each later spelling of a value the document wrote, with the first (which the graph keeps): (first, later)
    again: list[tuple[Triple, Triple]] = field(default_factory=list)


class _Literals:
    """The literal objects of one document as the pass meets them: validated, XML in canonical form, the
    first spelling of each (subject, predicate, value) kept, each later one noted (``found.again``)."""

    def __init__(self, found: StreamedDocument) -> None:
        self.found = found
        #: (subject, predicate, value key) -> the spelling written
        self.spelled: dict[tuple, Literal] = {}
        #: each later spelling noted in ``found.again`` (a document may repeat one: it is noted once)
        self._noted: set[tuple] = set()

    def written(self, s: Term, p: NamedNode, o: Literal) -> Literal | None:
        """``o`` as it is written, or None when an earlier spelling of its value was (InvalidValueError
        when it is no valid value of its datatype)."""
        check_literal(o)
        if o.datatype.value == XML_LITERAL:
            o, notice = canonical_xml_literal(p, o)
            if notice is not None:
                self.found.notices.append(notice)
        return self._first(s, p, o)

    def _first(self, s: Term, p: NamedNode, o: Literal) -> Literal | None:
        """``o`` where it is the first spelling of its value for (``s``, ``p``); None where it repeats that
        spelling (one triple, met again) or spells the value otherwise (noted once).  One hash of the
        (subject, predicate, value) key per literal: the spelling kept answers both tests."""
        first = self.spelled.setdefault((s, p, value_key(o)), o)
        if first is o:
            return o
        if first != o and (later := (s, p, o)) not in self._noted:  # an earlier spelling: said, not written
            self._noted.add(later)
            self.found.again.append((Triple(s, p, first), Triple(s, p, o)))
        return None

    def kept_lines(self, lines: list[bytes]) -> list[bytes]:
        """The lines of the serialiser's text whose object is a literal (:func:`literal_lines`), as they are to
        be written: each read back as terms (one quad per line, in order) and decided by :meth:`written`, its
        line kept as it is where the literal is (a blank subject renamed in the text), a new line where the
        literal is respelled, an empty one where an earlier spelling of its value was written.  A line whose
        object is an RDF 1.2 triple term holding a literal is kept, its subject named (the object is, as
        ever).  Where no line names rdf:XMLLiteral, the literals are only checked and their first spellings
        kept (:meth:`_first`): no datatype read per literal."""
        kept: list[bytes] = []
        text = b"".join(lines)
        blank, literal, named, prefix = BlankNode, Literal, NamedNode, SKOLEM_PREFIX
        written = self.written if _XML_LITERAL_IRI in text else self._checked
        add, append = self.found.predicates.add, kept.append
        for line, q in zip(lines, ox_parse(text, format=RdfFormat.N_TRIPLES, lenient=True)):
            s, p, o = q.subject, q.predicate, q.object
            add(p)
            if type(s) is blank:
                s = named(prefix + s.value)
                line = subject_named(line, prefix)
            if type(o) is not literal:
                append(line)
                continue
            spelled = written(s, p, o)
            if spelled is o:
                append(line)
            elif spelled is None:
                append(b"")
            else:
                append(serialize([Triple(s, p, spelled)], None, RdfFormat.N_TRIPLES))
        return kept

    def _checked(self, s: Term, p: NamedNode, o: Literal) -> Literal | None:
        """:meth:`written` of a literal known not to be an rdf:XMLLiteral."""
        check_literal(o)
        return self._first(s, p, o)


#: the datatype IRI of an XML literal as the serialiser writes it (a text without it holds none)
_XML_LITERAL_IRI = f"<{XML_LITERAL}>".encode()


def stream_into_empty(store: Store, data: bytes | str, fmt: RdfFormat, base_iri: str | None, source: str,
                      progress: Callable[[int], None] | None = None) -> StreamedDocument:
    """Write a document into the empty asserted graph of ``store`` in one pass (one commit), its literal
    forms recorded; what it found.  An error (syntax, an invalid value) leaves the graph as it was only
    where the commit is all or nothing: the caller takes the graph back to empty on any failure."""
    found = StreamedDocument()
    literals = _Literals(found)
    if callable(getattr(store, "text_writer", None)) and store.bulk_stream_possible():
        if fmt in TEXT_FORMATS:
            gained: int | None = _text_pass(store, document_bytes(data), fmt, base_iri, source, literals, progress)
        else:
            gained = _written_as_text(store, _parsed(data, fmt, base_iri, source, progress), literals)
    else:
        quads = _parsed(data, fmt, base_iri, source, progress)
        gained = store._commit_stream(_written(quads, literals, store), [], count=True)
    # one quad per fact: a value's first spelling; a durable store's gain counts the persisted forms too
    found.triples = store.count(ASSERTED) if gained is None or store.durable else gained
    return found


def _parsed(data: bytes | str, fmt: RdfFormat, base_iri: str | None, source: str,
            progress: Callable[[int], None] | None) -> Iterator[Quad]:
    quads = parsed_quads(data, fmt, base_iri, source)
    return quads if progress is None else _counted(quads, progress)


def _written(quads: Iterator[Quad], literals: _Literals, store: Store) -> Iterator[Quad]:
    """The quads to write into the asserted graph, then the quads persisting the literal forms (none in
    memory).  Each term of a parsed quad is read once: a read makes a new object, the bulk of the cost;
    a blank node is named as :func:`topostore.rdf.skolem.skolem` names it, inline (no call per term)."""
    graph, blank, literal, named = ASSERTED, BlankNode, Literal, NamedNode
    predicates = literals.found.predicates
    written = literals.written
    for q in quads:
        s, p, o = q.subject, q.predicate, q.object
        predicates.add(p)
        if type(s) is blank:
            s = named(SKOLEM_PREFIX + s.value)
        kind = type(o)
        if kind is literal:
            o = written(s, p, o)
            if o is None:
                continue
        elif kind is blank:
            o = named(SKOLEM_PREFIX + o.value)
        yield Quad(s, p, o, graph)
    yield from store.forms.record_loaded(graph, list(literals.spelled.items()))


def written_triples(quads: Iterator[Quad], literals: _Literals) -> Iterator[Quad | Triple]:
    """The document's triples as the asserted graph is to hold them: a quad that needs no change is passed on
    as it is (no new object), a blank node named as :func:`topostore.rdf.skolem.skolem` names it.  Handed
    to ``pyoxigraph.serialize``, which writes as it pulls: 2.7 s for 900,000 triples (parse included) where
    chunks made as lists took 3.5-3.9 s (a list, a length test and a call per chunk)."""
    blank, literal, named, triple, prefix = BlankNode, Literal, NamedNode, Triple, SKOLEM_PREFIX
    add = literals.found.predicates.add
    written = literals.written
    for q in quads:
        s, p, o = q.subject, q.predicate, q.object
        add(p)
        kind = type(o)
        if type(s) is blank:
            s = named(prefix + s.value)
            if kind is blank:
                o = named(prefix + o.value)
            elif kind is literal and (o := written(s, p, o)) is None:
                continue
            yield triple(s, p, o)
        elif kind is blank:
            yield triple(s, p, named(prefix + o.value))
        elif kind is literal:
            kept = written(s, p, o)
            if kept is not None:
                yield q if kept is o else triple(s, p, kept)
        else:
            yield q


def _written_as_text(store: Store, quads: Iterator[Quad], literals: _Literals) -> int:
    """The document written through N-Triples text, :data:`TEXT_CHUNK` triples at a time, each piece indexed
    by the store in a second thread while the next is made (``store.text_writer``), then its literal forms
    recorded; the quads gained.  A quad of the asserted graph made per triple and ``extend`` cost more
    than a triple made only where a blank node is renamed or a literal respelled, serialised and read
    by the store (100,000 locations: 5.2-5.4 against 4.8-5.0 s CPU); a chunk bounds the text held."""
    triples = written_triples(quads, literals)
    before = store.quad_total()
    with store.text_writer(ASSERTED) as writer:
        while text := serialize(islice(triples, TEXT_CHUNK), None, RdfFormat.N_TRIPLES):
            writer.write(text)
    gained = store.quad_total() - before
    extra = store.forms.record_loaded(ASSERTED, list(literals.spelled.items()))
    if extra:  # pragma: no cover - in memory, literal forms are not persisted as quads
        store._commit(extra, [])
    return gained


def _text_pass(store: Store, data: bytes, fmt: RdfFormat, base_iri: str | None, source: str, literals: _Literals,
               progress: Callable[[int], None] | None) -> int:
    """The document written through pyoxigraph's own N-Triples text, changed as bytes
    (:mod:`topostore.rdf.ntriples_text`): the parser's quads pulled by the serialiser in C, :data:`TEXT_CHUNK` at
    a time, with no Python frame per triple; then in each piece the blank nodes renamed by whole-text
    replacements and only the lines holding a literal read as terms (:meth:`_Literals.kept_lines`); each piece
    indexed by the store in a second thread while the next is made.  The quads gained."""
    quads = parser(data, fmt, base_iri, source)
    before, parsed, predicates = store.quad_total(), 0, set()
    with store.text_writer(ASSERTED) as writer:
        while True:
            try:
                text = serialize(islice(quads, TEXT_CHUNK), None, RdfFormat.N_TRIPLES)
            except (SyntaxError, ValueError) as exc:
                raise parse_error(exc, data, fmt, source) from exc
            if not text:
                break
            writer.write(_named_text(text, literals, predicates))
            if progress is not None:
                parsed = _told(progress, parsed, text.count(b"\n"))
        # while the worker indexes the last pieces (the caller's clear of a failed load forgets the forms)
        literals.found.predicates.update(NamedNode(p[1:-1].decode()) for p in predicates)
        extra = store.forms.record_loaded(ASSERTED, list(literals.spelled.items()))
    if extra:  # pragma: no cover - in memory, literal forms are not persisted as quads
        store._commit(extra, [])
    return store.quad_total() - before


def _named_text(text: bytes, literals: _Literals, predicates: set[bytes]) -> bytes:
    """One piece of the serialiser's text as the asserted graph is to hold it, in the same order: blank
    nodes as skolem IRIs, the literal lines decided one by one, the predicates of the others added to
    ``predicates``.  A piece that may hold an RDF 1.2 triple term (``<<(``: its inner terms are separated
    by spaces too) is read as terms instead, as :func:`written_triples` reads it."""
    if b"<<(" in text:
        return serialize(written_triples(ox_parse(text, format=RdfFormat.N_TRIPLES), literals), None,
                         RdfFormat.N_TRIPLES)
    plain, literal = literal_lines(text)
    predicates |= line_predicates(plain)
    return put_back(named_blank_nodes(plain, SKOLEM_PREFIX), literals.kept_lines(literal))


def _told(progress: Callable[[int], None], before: int, more: int) -> int:
    """Tell ``progress`` each multiple of ``PROGRESS_EVERY`` from ``before`` to ``before + more`` triples."""
    after = before + more
    for n in range(before - before % PROGRESS_EVERY + PROGRESS_EVERY, after + 1, PROGRESS_EVERY):
        progress(n)
    return after


def _counted(quads: Iterator[Quad], progress: Callable[[int], None]) -> Iterator[Quad]:
    """``quads``, telling ``progress`` every ``PROGRESS_EVERY`` of them."""
    n = 0
    for q in quads:
        yield q
        n += 1
        if n % PROGRESS_EVERY == 0:
            progress(n)


def schema_triples(store: Store, predicates: set[NamedNode], is_schema: Callable[[Triple], bool]) -> Iterator[Triple]:
    """One schema triple (``is_schema``) of the asserted graph per predicate and per class typed that makes
    one: whether a triple is one depends on its predicate alone, or for rdf:type on its class alone."""
    for p in predicates:
        if p == TYPE:
            classes = store.query(f"SELECT DISTINCT ?c WHERE {{ GRAPH {ASSERTED} {{ ?x {TYPE} ?c }} }}")
            for c in [row["c"] for row in classes]:
                yield from _first_schema(store.triples(None, TYPE, c, ASSERTED), is_schema)
        else:
            yield from _first_schema(store.triples(None, p, None, ASSERTED), is_schema)


def _first_schema(triples: Iterator[Triple], is_schema: Callable[[Triple], bool]) -> Iterator[Triple]:
    first = next(triples, None)
    if first is not None and is_schema(first):
        yield first


def rules_need_repair(store: Store, predicates: set[NamedNode]) -> bool:
    """Whether the SWRL rules of the asserted graph need the repair (:mod:`topostore.compile.swrl_repair`),
    reading only their nodes from the graph."""
    if TYPE not in predicates:
        return False
    imps = [t.subject for t in store.triples(None, TYPE, swrl("Imp"), ASSERTED)]
    return bool(imps) and needs_repair(lambda node: store.triples(node, None, None, ASSERTED), imps)


__all__ = ["StreamedDocument", "rules_need_repair", "schema_triples", "stream_into_empty", "written_triples"]
