"""The spelling of each language tag as users wrote it (``"colour"@en-GB``), beside a store that lowers tags.

Language tags are case-insensitive (BCP 47), and pyoxigraph lowers them wherever a literal is made
(``Literal("x", language="en-GB").language == "en-gb"``), so no stored literal keeps the case.  The
documents loaded are read for their tags' spellings (:meth:`LanguageTags.learn`); what topostore writes
back (a SAVEd file, an aRMOR reply) spells each tag as first written.  One spelling per tag: a tag is one
value whatever its case, so ``en-GB`` written first makes every ``en-gb`` literal of the store ``en-GB``.
"""

from __future__ import annotations

import re

from pyoxigraph import Literal, NamedNode, Quad, RdfFormat

from ..rdf.vocab import INTERNAL

#: the node a durable store keeps the spellings under (in the literal forms' graph)
SPELLING = NamedNode(INTERNAL + "language-tag")

_TAG = rb"[A-Za-z]+(?:-[A-Za-z0-9]+)*"
#: a tag after a Turtle / N-Triples string's closing quote (the quote is checked apart: a pattern that begins
#: with '@' is searched for five times faster), or as an RDF/XML xml:lang value
_WRITTEN = {
    "text": re.compile(rb"@(" + _TAG + rb")"),
    "xml": re.compile(rb"xml:lang\s*=\s*[\"'](" + _TAG + rb")[\"']"),
}
_QUOTES = (ord('"'), ord("'"))
_WHOLE_TAG = re.compile(_TAG.decode())
#: a whole string literal and its tag as pyoxigraph writes Turtle and N-Triples (escapes kept whole)
_TEXT_LITERAL = re.compile(rb'"(?:[^"\\\n]|\\.)*"@(' + _TAG + rb")")
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

    def learn(self, data: bytes | str, fmt: RdfFormat) -> list[Quad]:
        """Read the spellings of a document's tags (one that never spells a tag with a capital costs one
        scan); the quads persisting the new ones on a durable store (in ``graph``, see :meth:`quads`)."""
        if isinstance(data, str):
            data = data.encode("utf-8", errors="surrogatepass")
        xml = fmt == RdfFormat.RDF_XML
        new = []
        for m in _WRITTEN["xml" if xml else "text"].finditer(data):
            if not xml and not _closes_string(data, m.start()):
                continue  # @prefix, @base, an e-mail address or an escaped quote in a string
            tag = m.group(1).decode("ascii")
            lowered = tag.lower()
            if lowered not in self._spelled:
                self._spelled[lowered] = tag
                self._capitals |= tag != lowered
                new.append(tag)
        return new

    def spelled(self, tag: str) -> str:
        """``tag`` as first written (itself when never written with a capital)."""
        return self._spelled.get(tag.lower(), tag)

    def respell(self, data: bytes, fmt: RdfFormat) -> bytes:
        """A document pyoxigraph serialised, each language tag spelled as first written."""
        if not self._spelled:
            return data
        if fmt == RdfFormat.RDF_XML:
            return _XML_LANG.sub(lambda m: m.group(1) + self._bytes(m.group(2)) + m.group(3), data)
        return _TEXT_LITERAL.sub(lambda m: m.group(0)[:m.start(1) - m.start(0)] + self._bytes(m.group(1)), data)

    def rendered(self, text: str) -> str:
        """An aRMOR rendering of a term (``"lex"@tag``), its tag spelled as first written."""
        if not self._spelled:
            return text
        body, quote, tag = text.rpartition('"@')
        return f'{body}"@{self.spelled(tag)}' if quote and _WHOLE_TAG.fullmatch(tag) else text

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


def _closes_string(data: bytes, at: int) -> bool:
    """Whether the byte before ``at`` is a quote that is not escaped (an even run of backslashes before it)."""
    if at == 0 or data[at - 1] not in _QUOTES:
        return False
    backslashes = 0
    while at - 2 - backslashes >= 0 and data[at - 2 - backslashes] == ord("\\"):
        backslashes += 1
    return backslashes % 2 == 0


__all__ = ["SPELLING", "LanguageTags"]
