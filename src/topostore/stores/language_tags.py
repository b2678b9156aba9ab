"""The spelling of each language tag as users wrote it (``"colour"@en-GB``), beside a store that lowers tags.

Language tags are case-insensitive (BCP 47), and pyoxigraph lowers them wherever a literal is made
(``Literal("x", language="en-GB").language == "en-gb"``), so no stored literal keeps the case.  The
documents loaded are read for their tags' spellings (:meth:`LanguageTags.learn`); what topostore writes
back (a SAVEd file, an aRMOR reply) spells each tag as first written.  A change made another way learns the
spellings of the literals it added, from the text it was written in (a SPARQL update, a Graph Store upload:
:meth:`LanguageTags.learn` with ``only``) or as given (the Python API: :meth:`LanguageTags.adopt`).  One spelling per tag: a tag is one
value whatever its case, so ``en-GB`` written first makes every ``en-gb`` literal of the store ``en-GB``.
"""

from __future__ import annotations

import json
import re
from collections.abc import Collection, Iterable

from pyoxigraph import Literal, NamedNode, Quad, QueryResultsFormat, RdfFormat, Triple

from ..rdf.vocab import INTERNAL
from .written_tags import (
    WHOLE_TAG,
    Added,
    added_spellings,
    candidate_tags,
    json_ld_tags,
    written_literals,
    written_tags,
)

#: the node a durable store keeps the spellings under (in the literal forms' graph)
SPELLING = NamedNode(INTERNAL + "language-tag")

_TAG = rb"[A-Za-z]+(?:-[A-Za-z0-9]+)*"
#: pyoxigraph's Turtle, TriG, N-Triples and N-Quads read token by token: an IRI whole, or a string whole and
#: its tag if it has one (pyoxigraph writes each string on one line between '"', its escapes kept whole); the
#: search moves on only past whole tokens, so a quote or an '@' inside a string is never taken for a tag
_TEXT_LITERAL = re.compile(rb'<[^<>"\s]*>|"(?:[^"\\\n]|\\.)*"(?:@(' + _TAG + rb"))?")
#: an xml:lang attribute inside a tag of pyoxigraph's RDF/XML (text content holds no raw '<')
_XML_LANG = re.compile(rb'(<[^<>]*\sxml:lang=")(' + _TAG + rb')(")')


class LanguageTags:
    """Each lowered language tag's spelling as first written, where it is not the lowered one."""

    def __init__(self) -> None:
        #: each lowered tag's first spelling, lowered ones included (a later capital does not respell it)
        self._spelled: dict[str, str] = {}
        #: whether some first spelling differs from its lowered tag (else nothing is ever respelled)
        self._capitals = False

    def __bool__(self) -> bool:
        return self._capitals

    def learn(self, data: bytes | str, fmt: RdfFormat | None, only: Collection[Added] | None = None) -> list[str]:
        """Read the spellings of a document's tags (one that never spells a tag with a capital costs one
        scan); the new ones, for the caller to persist on a durable store (see :meth:`quads`).

        ``fmt`` None reads Turtle-like text that is no document: a SPARQL update, whose literals are written
        as Turtle's.  ``only``: the literals a change added (:func:`literal_tags`); a spelling is taken only
        from a written literal of the same lexical form and tag (one the text writes elsewhere, in a pattern
        or a deleted triple, is no spelling of what is stored), an update's INSERT parts before the rest."""
        if isinstance(data, str):
            data = data.encode("utf-8", errors="surrogatepass")
        if only is not None and not only:
            return []
        json_ld = fmt in (RdfFormat.JSON_LD, RdfFormat.STREAMING_JSON_LD)
        if only is None:
            return self.adopt(json_ld_tags(data) if json_ld else written_tags(data, fmt == RdfFormat.RDF_XML))
        if json_ld or fmt == RdfFormat.RDF_XML:
            written = written_literals(data, _syntax(fmt))
            return self.adopt([tag for lexical, tag in written if (lexical, tag.lower()) in only])
        return self.adopt(added_spellings(data, only, update=fmt is None))

    def adopt(self, tags: Iterable[str]) -> list[str]:
        """Take ``tags`` as written (the first spelling of each lowered tag wins); the new ones."""
        new = []
        for tag in tags:
            lowered = tag.lower()
            if lowered not in self._spelled:
                self._spelled[lowered] = tag
                self._capitals |= tag != lowered
                new.append(tag)
        return new

    def forget(self, tags: Iterable[str]) -> list[str]:
        """Drop ``tags`` as spellings (each only where it is its lowered tag's spelling): the literal it came
        with was reverted.  The ones dropped, for the caller to unpersist (see :meth:`quads`)."""
        dropped = [tag for tag in dict.fromkeys(tags) if self._spelled.get(tag.lower()) == tag]
        for tag in dropped:
            del self._spelled[tag.lower()]
        if dropped:
            self._capitals = any(tag != lowered for lowered, tag in self._spelled.items())
        return dropped

    def not_taken(self, data: bytes, fmt: RdfFormat | None,
                  literals: Collection[Added]) -> list[tuple[Added, str]]:
        """Each of ``literals`` (lexical form, lowered tag) that ``data`` writes with its tag spelled other
        than as the store spells it, with that spelling: what a document wrote and the store does not show
        (one spelling per tag).  A document whose every possible tag is spelled as kept costs one search."""
        if not literals:
            return []
        syntax = _syntax(fmt)
        if syntax != "json-ld" and all(self.spelled(tag) == tag for tag in candidate_tags(data, syntax == "xml")):
            return []
        found = dict.fromkeys(((lexical, tag.lower()), tag) for lexical, tag in written_literals(data, syntax))
        return [(key, tag) for key, tag in found if key in literals and tag != self.spelled(tag)]

    def known(self, tag: str) -> bool:
        """Whether ``tag`` (any case) has a spelling already: a later one does not respell it."""
        return tag.lower() in self._spelled

    def spelled(self, tag: str) -> str:
        """``tag`` as first written (itself when never written with a capital)."""
        return self._spelled.get(tag.lower(), tag)

    def respell(self, data: bytes, fmt: RdfFormat) -> bytes:
        """A document pyoxigraph serialised, each language tag spelled as first written."""
        if not self._spelled:
            return data
        if fmt == RdfFormat.RDF_XML:
            return self._xml(data)
        if fmt in (RdfFormat.JSON_LD, RdfFormat.STREAMING_JSON_LD):
            return self._json_ld(data)
        return self._text(data)

    def respell_results(self, data: bytes, fmt: QueryResultsFormat) -> bytes:
        """SPARQL results pyoxigraph serialised (XML, TSV), each language tag spelled as first written;
        JSON is spelled as it is built (:func:`~topostore.sparql.results.solutions_json`), CSV has no tags."""
        if not self._spelled:
            return data
        if fmt == QueryResultsFormat.XML:
            return self._xml(data)
        if fmt == QueryResultsFormat.TSV:  # terms written as in Turtle
            return self._text(data)
        return data

    def _xml(self, data: bytes) -> bytes:
        """XML (RDF/XML, SPARQL XML results) with each ``xml:lang`` attribute's tag spelled as first written
        (text content escapes '<': a tag's attribute is all the pattern can match)."""
        return _XML_LANG.sub(lambda m: m.group(1) + self._bytes(m.group(2)) + m.group(3), data)

    def _text(self, data: bytes) -> bytes:
        """Turtle-like text (Turtle, N-Triples, N-Quads, TriG, TSV results): each tagged string respelled."""
        return _TEXT_LITERAL.sub(self._respelled_token, data)

    def rendered(self, text: str) -> str:
        """An aRMOR rendering of a term (``"lex"@tag``), its tag spelled as first written."""
        if not self._spelled:
            return text
        body, quote, tag = text.rpartition('"@')
        return f'{body}"@{self.spelled(tag)}' if quote and WHOLE_TAG.fullmatch(tag) else text

    def _json_ld(self, data: bytes) -> bytes:
        """A JSON-LD document with each ``@language`` value spelled as first written (read as JSON: a
        lexical form that looks like one is left alone)."""
        doc = json.loads(data)
        todo = [doc]
        while todo:
            node = todo.pop()
            if isinstance(node, dict):
                if isinstance(lang := node.get("@language"), str):
                    node["@language"] = self.spelled(lang)
                todo.extend(v for v in node.values() if isinstance(v, (dict, list)))
            elif isinstance(node, list):
                todo.extend(v for v in node if isinstance(v, (dict, list)))
        return json.dumps(doc, ensure_ascii=False).encode("utf-8")

    def _respelled_token(self, m: re.Match[bytes]) -> bytes:
        """A token of :data:`_TEXT_LITERAL`: a tagged string with its tag spelled as first written, else as it was."""
        if m.group(1) is None:
            return m.group(0)
        return m.group(0)[:m.start(1) - m.start(0)] + self._bytes(m.group(1))

    def _bytes(self, tag: bytes) -> bytes:
        return self.spelled(tag.decode("ascii")).encode("ascii")

    def quads(self, spellings: list[str], graph: NamedNode) -> list[Quad]:
        """The quads persisting ``spellings`` in ``graph``."""
        return [Quad(SPELLING, SPELLING, Literal(s), graph) for s in spellings]

    def restore(self, quad: Quad) -> bool:
        """Take back a persisted spelling; False when ``quad`` is not one."""
        if quad.subject != SPELLING or not isinstance(quad.object, Literal):
            return False
        tag = quad.object.value
        self._capitals |= self._spelled.setdefault(tag.lower(), tag) != tag.lower()
        return True


def literal_tags(triples: Iterable[Triple]) -> set[Added]:
    """The tagged literals among ``triples``' objects: each one's lexical form and (lowered) tag."""
    return {(o.value, o.language) for t in triples if isinstance(o := t.object, Literal) and o.language}



__all__ = ["SPELLING", "LanguageTags", "literal_tags"]


def _syntax(fmt: RdfFormat | None) -> str:
    """How :func:`.written_tags.written_literals` reads a document of format ``fmt``."""
    if fmt in (RdfFormat.JSON_LD, RdfFormat.STREAMING_JSON_LD):
        return "json-ld"
    return "xml" if fmt == RdfFormat.RDF_XML else "text"
