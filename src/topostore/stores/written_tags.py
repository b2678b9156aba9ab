"""Where a document or a change's text writes language tags, read without mistaking text for a tag.

The readers :mod:`.language_tags` learns spellings with: Turtle, N-Triples and SPARQL Update read token
by token (a quote, an '@' or a comma inside a string is never taken for syntax), RDF/XML and JSON-LD read
with their language scopes (``xml:lang`` inherited, a JSON-LD context's default or term language), each
literal as its lexical form and its tag as written, so that a change's spelling is taken only from a literal
it added.
"""

from __future__ import annotations

import io
import json
import re
import xml.sax
import xml.sax.handler
from collections.abc import Collection

from ..rdf.vocab import RDF, XML

_TAG = rb"[A-Za-z]+(?:-[A-Za-z0-9]+)*"
#: a tag after a Turtle / N-Triples string's closing quote (the quote is checked apart: a pattern that begins
#: with '@' is searched for five times faster), or as an RDF/XML xml:lang value
_WRITTEN = {
    "text": re.compile(rb"@(" + _TAG + rb")"),
    "xml": re.compile(rb"xml:lang\s*=\s*[\"'](" + _TAG + rb")[\"']"),
}
_QUOTES = (ord('"'), ord("'"))
#: Turtle / N-Triples read token by token: a string whole (its tag captured), a comment, an IRI, or a run of
#: anything else; a quote or '@' inside a string, a comment or an IRI is then never taken for a tag
_TEXT_TOKEN = re.compile(
    rb'(?:"""(?:[^"\\]|\\.|"(?!""))*"""' rb"|'''(?:[^'\\]|\\.|'(?!''))*'''"
    rb'|"(?:[^"\\\n]|\\.)*"' rb"|'(?:[^'\\\n]|\\.)*')(?:@(" + _TAG + rb"))?"
    rb"|#[^\n]*|<[^>\s]*>|[^\"'#<]+|[\"'#<]", re.S)
WHOLE_TAG = re.compile(_TAG.decode())
#: the SPARQL Update keywords that open a part whose literals are inserted (INSERT) or not (DELETE, WHERE);
#: a prefixed name or a variable that merely ends so is no keyword
_UPDATE_PART = re.compile(rb"(?<![\w:?$])(INSERT|DELETE|WHERE)(?![\w:-])", re.I)
#: the opening of a STRLANG call (the literal it makes has no written ``@tag``: its tag is the last argument)
_STRLANG = re.compile(rb"(?<![\w:?$])STRLANG\s*\(", re.I)
#: a SPARQL expression read token by token: a string whole, an IRI, a parenthesis, a comma, or a run of
#: anything else (a comma or a parenthesis inside a string is never taken for the call's own)
_ARGUMENT_TOKEN = re.compile(
    rb'"""(?:[^"\\]|\\.|"(?!""))*"""' rb"|'''(?:[^'\\]|\\.|'(?!''))*'''"
    rb'|"(?:[^"\\\n]|\\.)*"' rb"|'(?:[^'\\\n]|\\.)*'" rb'|<[^<>"\s]*>|[(),]|[^"' rb"'(),<]+|[<\"']", re.S)
#: a plain string argument holding a tag
_TAG_ARGUMENT = re.compile(rb"(\"|')(" + _TAG + rb")\1")
#: a string's escapes (Turtle and SPARQL): a character escape or a code point
_ESCAPE = re.compile(r"\\(?:([tbnrf\"'\\])|u([0-9A-Fa-f]{4})|U([0-9A-Fa-f]{8}))")
_ESCAPED = {"t": "\t", "b": "\b", "n": "\n", "r": "\r", "f": "\f", '"': '"', "'": "'", "\\": "\\"}

#: an added literal as pyoxigraph keeps it: its lexical form and its lowered tag
Added = tuple[str, str]


def added_spellings(data: bytes, added: Collection[Added], update: bool) -> list[str]:
    """The spellings of ``added``'s tags where the text writes one of those literals (same lexical form,
    same tag in any case); in an update, a literal written in an INSERT part (INSERT DATA or an INSERT
    template) before one written elsewhere (a WHERE's VALUES), and the tag argument of a STRLANG call
    last, as its literal's form is not written."""
    inserting = not update  # a document's literals are all added
    best: dict[str, tuple[int, str]] = {}  # lowered tag -> (rank, first spelling of that rank)
    tags = {t for _, t in added}
    settled = 0  # how many of ``tags`` have a spelling of the best rank: the reading stops once all have
    for m in _TEXT_TOKEN.finditer(data):
        raw = m.group(1)
        if raw is None:
            if update and m.group(0)[0] not in b"\"'#<":
                parts = _UPDATE_PART.findall(m.group(0))
                if parts:
                    inserting = parts[-1].upper() == b"INSERT"
            continue
        tag = raw.decode("ascii")
        if (_token_lexical(m), tag.lower()) in added:
            if inserting and best.get(tag.lower(), (1,))[0] > 0:
                settled += 1  # its first spelling of the best rank
            _prefer(best, tag, 0 if inserting else 1)
            if settled == len(tags):
                break
    if update and settled < len(tags):
        for tag in _strlang_tags(data):
            if tag.lower() in tags:
                _prefer(best, tag, 2)
    return [spelling for _, spelling in best.values()]


def _strlang_tags(data: bytes) -> list[str]:
    """The tags STRLANG calls give as a plain string, their last argument: each call read token by token
    (:data:`_ARGUMENT_TOKEN`), so that a nested call or a comma inside a string does not end an argument."""
    found = []
    for m in _STRLANG.finditer(data):
        depth, last = 0, m.end()
        for token in _ARGUMENT_TOKEN.finditer(data, m.end()):
            text = token.group(0)
            if text == b"(":
                depth += 1
            elif text == b"," and depth == 0:
                last = token.end()
            elif text == b")":
                if depth == 0:
                    argument = _TAG_ARGUMENT.fullmatch(data[last:token.start()].strip())
                    if argument is not None and last > m.end():
                        found.append(argument.group(2).decode("ascii"))
                    break
                depth -= 1
    return found


def _prefer(best: dict[str, tuple[int, str]], tag: str, rank: int) -> None:
    """Keep ``tag`` as its lowered tag's spelling if no spelling of a better (lower) rank was met first."""
    held = best.get(tag.lower())
    if held is None or rank < held[0]:
        best[tag.lower()] = (rank, tag)


def _token_lexical(m: re.Match[bytes]) -> str:
    """The lexical form of a tagged literal token of :data:`_TEXT_TOKEN` (the token up to its ``@``)."""
    return _lexical(m.group(0)[:m.start(1) - m.start(0) - 1])


def _lexical(token: bytes) -> str:
    """A written string's lexical form: its quotes off, its escapes read."""
    quotes = 3 if token[:3] in (b'"""', b"'''") else 1
    body = token[quotes:-quotes].decode("utf-8", errors="surrogatepass")
    return _ESCAPE.sub(_unescaped, body) if "\\" in body else body


def _unescaped(m: re.Match[str]) -> str:
    if m.group(1):
        return _ESCAPED[m.group(1)]
    try:
        return chr(int(m.group(2) or m.group(3), 16))
    except ValueError:  # past the last code point: pyoxigraph refuses it before this is read
        return m.group(0)


def json_ld_tags(data: bytes) -> list[str]:
    """A JSON-LD document's ``@language`` values in the order written (a context's default included);
    nothing from a document that is no JSON (pyoxigraph read it first and would have refused it)."""
    try:
        doc = json.loads(data)
    except (ValueError, RecursionError):
        return []
    found: list[str] = []
    todo = [doc]
    while todo:
        node = todo.pop()
        if isinstance(node, dict):
            lang = node.get("@language")
            if isinstance(lang, str) and WHOLE_TAG.fullmatch(lang):
                found.append(lang)
            todo.extend(reversed([v for v in node.values() if isinstance(v, (dict, list))]))
        elif isinstance(node, list):
            todo.extend(reversed([v for v in node if isinstance(v, (dict, list))]))
    return found


def json_ld_literals(data: bytes) -> list[tuple[str, str]]:
    """A JSON-LD document's tagged literals (lexical form, tag as written) in the order written: value
    objects with ``@language``, and plain strings under a term whose context (the node's or an enclosing
    one's) gives a default ``@language`` or the term's own; nothing from a document that is no JSON."""
    try:
        doc = json.loads(data)
    except (ValueError, RecursionError):
        return []
    found: list[tuple[str, str]] = []
    # a stack of nodes to read and of strings already read, popped in the order they are written
    todo: list[tuple[object, _Scope | None]] = [(doc, _Scope(None, {}))]
    while todo:
        node, scope = todo.pop()
        if scope is None:  # a tagged string, reached in its place
            found.append(node)  # type: ignore[arg-type]
            continue
        if isinstance(node, list):
            todo.extend(reversed([(v, scope) for v in node]))
            continue
        if not isinstance(node, dict):
            continue
        scope = scope.within(node.get("@context"))
        if isinstance(value := node.get("@value"), str):
            if isinstance(lang := node.get("@language"), str) and WHOLE_TAG.fullmatch(lang):
                found.append((value, lang))
            continue
        later: list[tuple[object, _Scope | None]] = []
        for key, v in node.items():
            if key.startswith("@") and key not in ("@graph", "@included", "@reverse", "@list", "@set"):
                continue
            for item in v if isinstance(v, list) else (v,):
                lang = scope.language(key)
                if isinstance(item, str) and not key.startswith("@") and lang is not None:
                    later.append(((item, lang), None))
                elif isinstance(item, (dict, list)):
                    later.append((item, scope))
        todo.extend(reversed(later))  # strings and nested nodes read in the order written
    return found


class _Scope:
    """The language a JSON-LD context in force gives a plain string: its default, or a term's own."""

    def __init__(self, default: str | None, terms: dict[str, str | None]) -> None:
        self.default, self.terms = default, terms

    def within(self, context: object) -> _Scope:
        """The scope inside a node with ``context`` (a context object or a list of them; IRIs not read)."""
        default, terms = self.default, self.terms
        for c in context if isinstance(context, list) else (context,):
            if isinstance(c, dict):
                if "@language" in c:
                    lang = c["@language"]
                    default = lang if isinstance(lang, str) and WHOLE_TAG.fullmatch(lang) else None
                for term, definition in c.items():
                    if isinstance(definition, dict) and ("@language" in definition or "@type" in definition):
                        lang = definition.get("@language")
                        terms = {**terms, term: lang if isinstance(lang, str) and WHOLE_TAG.fullmatch(lang)
                                 else None}
        return self if (default, terms) == (self.default, self.terms) else _Scope(default, terms)

    def language(self, term: str) -> str | None:
        return self.terms[term] if term in self.terms else self.default


def xml_literals(data: bytes) -> list[tuple[str, str]]:
    """An RDF/XML document's tagged literals (lexical form, tag as written) in the order written: the text
    of a property element with no child element, or a property attribute, where an ``xml:lang`` is in force
    (its own or an ancestor's); nothing from a document that is no XML (the parser refused it first)."""
    handler = _XmlLiterals()
    parser = xml.sax.make_parser()
    parser.setFeature(xml.sax.handler.feature_namespaces, True)
    parser.setFeature(xml.sax.handler.feature_external_ges, False)
    parser.setFeature(xml.sax.handler.feature_external_pes, False)
    parser.setContentHandler(handler)
    try:
        parser.parse(io.BytesIO(data))
    except (xml.sax.SAXException, ValueError):
        return []
    return handler.found




class _XmlLiterals(xml.sax.handler.ContentHandler):
    """Collects :func:`xml_literals`: a stack of (language in force, text so far, whether the element's text
    is no literal: it has a child element or an ``rdf:`` attribute)."""

    def __init__(self) -> None:
        super().__init__()
        self.found: list[tuple[str, str]] = []
        self._open: list[tuple[str | None, list[str], list[bool]]] = []

    def startElementNS(self, name, qname, attrs) -> None:  # noqa: ANN001, N802 - the SAX interface
        lang = attrs.get((XML, "lang"), self._open[-1][0] if self._open else None)
        if self._open:
            self._open[-1][2][0] = True
        if lang:
            for (uri, _local), value in attrs.items():
                if uri not in (XML, RDF, None):
                    self.found.append((value, lang))
        # an element with rdf:resource, rdf:datatype, ... holds no tagged text (its children may)
        literal = not any(uri == RDF and local != "ID" for uri, local in attrs.keys())
        self._open.append((lang or None, [], [not literal]))

    def characters(self, content: str) -> None:
        if self._open:
            self._open[-1][1].append(content)

    def endElementNS(self, name, qname) -> None:  # noqa: ANN001, N802
        lang, text, no_text = self._open.pop()
        if lang and not no_text[0] and name[0] != RDF:
            self.found.append(("".join(text), lang))


def written_literals(data: bytes, syntax: str) -> list[tuple[str, str]]:
    """A document's tagged literals (lexical form, tag as written) in the order written; ``syntax`` is
    ``"json-ld"``, ``"xml"`` (RDF/XML) or ``"text"`` (Turtle, N-Triples, N3), read token by token."""
    if syntax == "json-ld":
        return json_ld_literals(data)
    if syntax == "xml":
        return xml_literals(data)
    return [(_token_lexical(m), m.group(1).decode("ascii")) for m in _TEXT_TOKEN.finditer(data) if m.group(1) is not None]


def candidate_tags(data: bytes, xml: bool) -> set[str]:
    """Every spelling a fast search finds where a tag may be written (a superset of the real ones)."""
    return {m.group(1).decode("ascii") for m in _WRITTEN["xml" if xml else "text"].finditer(data)}


def written_tags(data: bytes, xml: bool) -> list[str]:
    """The document's tags in the order written, each spelling where a literal first carries it.

    A fast search for ``@tag`` (or ``xml:lang=``) finds the candidates; where one of them has a capital
    (the spelling then matters), a Turtle document is read again token by token (:data:`_TEXT_TOKEN`,
    ten times slower) so that text inside a string, a comment or an IRI is never taken for a tag; the
    reading stops once each candidate's tag has been met on a real literal."""
    if xml:
        return [m.group(1).decode("ascii") for m in _WRITTEN["xml"].finditer(data) if _in_xml_tag(data, m.start())]
    found = [m.group(1).decode("ascii") for m in _WRITTEN["text"].finditer(data) if _closes_string(data, m.start())]
    if all(tag == tag.lower() for tag in found):
        return found  # every spelling the lowered one: which of them are real literals changes nothing
    wanted = {tag.lower() for tag in found}
    first: dict[str, str] = {}
    for m in _TEXT_TOKEN.finditer(data):
        tag = m.group(1)
        if tag is not None:
            first.setdefault(tag.decode("ascii").lower(), tag.decode("ascii"))
            if wanted <= first.keys():
                break
    return list(first.values())


def _in_xml_tag(data: bytes, at: int) -> bool:
    """Whether position ``at`` of an RDF/XML document lies inside an element's tag: not in text content
    (where no raw '<' may stand), a comment, CDATA or a processing instruction."""
    start = data.rfind(b"<", 0, at)
    return start >= 0 and data.rfind(b">", start, at) < 0 and data[start + 1:start + 2] not in (b"!", b"?")


def _closes_string(data: bytes, at: int) -> bool:
    """Whether the byte before ``at`` is a quote that is not escaped (an even run of backslashes before it)."""
    if at == 0 or data[at - 1] not in _QUOTES:
        return False
    backslashes = 0
    while at - 2 - backslashes >= 0 and data[at - 2 - backslashes] == ord("\\"):
        backslashes += 1
    return backslashes % 2 == 0



__all__ = ["WHOLE_TAG", "Added", "added_spellings", "json_ld_literals", "json_ld_tags", "written_tags",
           "xml_literals"]
