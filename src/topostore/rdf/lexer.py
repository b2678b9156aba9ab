"""The one SPARQL tokenizer: every module that inspects SPARQL text lexes it here.

Users' SPARQL (checked by :mod:`topostore.sparql.guard` before anything parses it), the
parameters of named queries (:mod:`topostore.ontology.named_queries`) and the filter lines of the rule files
(:mod:`topostore.compile.condition`) all need the same lexing rule: braces, keywords and
variables inside IRIs, strings and comments are not syntax.  pyoxigraph parses SPARQL but does
not expose its algebra, so the tokens are taken here, once, rather than by a scanner per module.

The tokenizer follows SPARQL's lexical rules closely enough for inspection (it is not a
validator): a word just after a name character or just before ``:`` is part of a prefixed name,
never a keyword; ``?x`` and ``$x`` are variables.
"""

from __future__ import annotations

import re
from collections.abc import Iterator
from dataclasses import dataclass

#: IRIREF per the SPARQL grammar: no spaces, quotes, braces, pipes or carets inside.
IRIREF = re.compile(r"<[^<>\"{}|^`\\\x00-\x20]*>")

_ESCAPE = re.compile(r"\\u([0-9A-Fa-f]{4})|\\U([0-9A-Fa-f]{8})")
_WORD = re.compile(r"[A-Za-z_][A-Za-z0-9_\-]*")
#: a variable's name (SPARQL's VARNAME: letters, digits, underscore; no hyphen)
_VARNAME = re.compile(r"\w+")
_NAME_CHARS = set("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-.:")
#: characters that, just before a word, make it part of a name rather than a keyword
_JOINERS = _NAME_CHARS - {"."}

OPEN, CLOSE = "({[", ")}]"

#: token kinds
IRI, STRING, COMMENT, VARIABLE = "iri", "string", "comment", "variable"
KEYWORD, NAME, PUNCT = "keyword", "name", "punct"


@dataclass(frozen=True, slots=True)
class Token:
    """One token: its kind, its text as written, and where it starts."""

    kind: str
    text: str
    start: int

    @property
    def word(self) -> str:
        """A keyword's word, upper-cased (without name characters that follow it, as in ``LOAD.``)."""
        m = _WORD.match(self.text)
        return m.group(0).upper() if m else self.text.upper()


def skip_non_code(text: str, i: int) -> int | None:
    """Index just past the comment, string or IRI that starts at ``i`` (None if none does).

    The one SPARQL lexing rule every scanner of query text needs: braces and
    keywords inside these are not syntax.
    """
    c = text[i]
    if c == "#":
        j = text.find("\n", i)
        return len(text) if j < 0 else j + 1
    if c in "\"'":
        quote = text[i:i + 3] if text[i:i + 3] in ('"""', "'''") else c
        j = i + len(quote)
        while j < len(text) and text[j:j + len(quote)] != quote:
            j += 2 if text[j] == "\\" else 1
        return j + len(quote)
    if c == "<":
        m = IRIREF.match(text, i)
        if m:
            return m.end()
    return None


def decode_escapes(text: str) -> str:
    """Apply SPARQL's ``\\u``/``\\U`` code point escapes (done before parsing, §19.2)."""

    def repl(m: re.Match[str]) -> str:
        code = int(m.group(1) or m.group(2), 16)
        return chr(code) if code <= 0x10FFFF else m.group(0)

    return _ESCAPE.sub(repl, text)


def tokens(text: str) -> Iterator[Token]:
    """The tokens of ``text`` in order (whitespace dropped; comments kept as :data:`COMMENT`)."""
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        if c.isspace():
            i += 1
            continue
        nxt = skip_non_code(text, i)
        if nxt is not None:
            kind = IRI if c == "<" else COMMENT if c == "#" else STRING
            yield Token(kind, text[i:nxt], i)
            i = nxt
            continue
        if c in "?$":
            m = _VARNAME.match(text, i + 1)
            if m:
                yield Token(VARIABLE, text[i:m.end()], i)
                i = m.end()
            else:
                yield Token(PUNCT, c, i)
                i += 1
            continue
        m = _WORD.match(text, i)
        if m:
            prev = text[i - 1] if i > 0 else " "
            after = text[m.end()] if m.end() < n else " "
            kind = KEYWORD if prev not in _JOINERS and after != ":" else NAME
            end = m.end()
            # the rest of a prefixed name (ex:LOAD) is not a keyword
            while end < n and text[end] in _NAME_CHARS:
                end += 1
            yield Token(kind, text[i:end], i)
            i = end
            continue
        yield Token(PUNCT, c, i)
        i += 1


def variables(text: str) -> frozenset[str]:
    """The variables ``text`` mentions, written ``?name`` (``$name`` is the same variable)."""
    return frozenset("?" + t.text[1:] for t in tokens(text) if t.kind == VARIABLE)


def negates_exists(text: str) -> bool:
    """Whether ``text`` tests the *absence* of data: ``NOT EXISTS``, or ``EXISTS`` under a ``!``.

    Such a filter makes a rule non-monotone.  The walk keeps, per open
    bracket, whether it was opened right after a ``!``; an EXISTS inside one
    is negated.
    """
    negated_brackets: list[bool] = []
    prev: Token | None = None
    for t in tokens(text):
        if t.kind == PUNCT and t.text in OPEN:
            negated_brackets.append(prev is not None and prev.text == "!")
        elif t.kind == PUNCT and t.text in CLOSE:
            if negated_brackets:
                negated_brackets.pop()
        elif t.kind == KEYWORD and t.word == "EXISTS":
            if prev is not None and (prev.word == "NOT" or prev.text == "!") or any(negated_brackets):
                return True
        if t.kind != COMMENT:
            prev = t
    return False


def reads_graph(text: str) -> bool:
    """Whether ``text`` holds a graph pattern (``EXISTS`` of either sign), i.e. reads facts, not only values."""
    return any(t.kind == KEYWORD and t.word == "EXISTS" for t in tokens(text))


__all__ = ["CLOSE", "COMMENT", "IRI", "IRIREF", "KEYWORD", "NAME", "OPEN", "PUNCT", "STRING", "Token", "VARIABLE",
           "decode_escapes", "negates_exists", "reads_graph", "skip_non_code", "tokens", "variables"]
