"""The human syntax of SWRL rules Protégé shows, read into atoms (nothing here touches a store).

``LOCATION(?l) ^ visitedAt(?l, ?v) ^ swrlb:greaterThan(?v, 5) -> URGENT(?l)`` is read
by a small recursive-descent parser (the grammar is six productions; a parser
generator would add a dependency for no gain)::

    rule  := atoms ("->" | "→") atoms
    atoms := atom (("^" | "∧") atom)*
    atom  := name "(" arg ("," arg)* ")"
    arg   := "?"name | name | <iri> | number | "text" ["^^" name | "@" lang] | true | false

Names are entities of the ontology's namespace, ``prefix:local`` with a known
prefix (``swrlb:``, ``xsd:``, ``rdf:``, ``rdfs:``, ``owl:``, ``:``), or
``<full IRI>`` (:func:`name_resolver`).  What each atom is (class, property,
built-in, ...) is decided by :mod:`.swrl_text` against the ontology.
"""

from __future__ import annotations

import re
from collections.abc import Callable
from dataclasses import dataclass

from pyoxigraph import Literal, NamedNode

from ..errors import RuleCompileError
from ..rdf.terms import entity
from ..rdf.vocab import OWL, RDF, RDFS, SWRL, SWRLB, XSD, xsd

#: The prefixes a rule's text may use besides the ontology's own ``:``.
PREFIXES = {"swrlb": SWRLB, "xsd": XSD, "rdf": RDF, "rdfs": RDFS, "owl": OWL, "swrl": SWRL}

_TOKEN = re.compile(r"""
    (?P<ws>\s+)
  | (?P<arrow>->|→)
  | (?P<and>\^\^|\^|∧)
  | (?P<punct>[(),@])
  | (?P<iri><[^<>"{}|\\^`\s]*>)
  | (?P<string>"(?:[^"\\]|\\.)*")
  | (?P<number>[+-]?(?:\d+\.\d*|\.\d+|\d+)(?:[eE][+-]?\d+)?)
  | (?P<var>\?[A-Za-z_][\w-]*)
  | (?P<name>[A-Za-z_][\w.-]*(?::[\w.-]*)?|:[\w.-]+)
""", re.X)


@dataclass(frozen=True)
class Token:
    """One lexical unit of a rule's text, with where it starts (errors name the position)."""

    kind: str
    text: str
    pos: int


@dataclass(frozen=True)
class TextAtom:
    """One parsed atom: the predicate as written and its arguments (terms; variables by name)."""

    name: str
    args: tuple[object, ...]  # NamedNode / Literal, or str "?x" for a variable
    text: str

    def variables(self) -> list[str]:
        return [a for a in self.args if isinstance(a, str)]


def tokenize(text: str) -> list[Token]:
    """The tokens of ``text``, blanks dropped; RuleCompileError at the first character no token fits."""
    out: list[Token] = []
    pos = 0
    while pos < len(text):
        m = _TOKEN.match(text, pos)
        if not m:
            raise RuleCompileError(f"unexpected character {text[pos]!r} at position {pos + 1} of the rule")
        kind = m.lastgroup or ""
        if kind != "ws":
            out.append(Token("hat" if m.group() == "^^" else kind, m.group(), pos))
        pos = m.end()
    return out


class Parser:
    """Recursive descent over the tokens; terms are resolved with ``resolve`` (name → IRI)."""

    def __init__(self, text: str, resolve: Callable[[str], NamedNode]) -> None:
        self.text = text
        self.tokens = tokenize(text)
        self.i = 0
        self.resolve = resolve

    def peek(self) -> Token | None:
        return self.tokens[self.i] if self.i < len(self.tokens) else None

    def take(self, kind: str, what: str, *more: str) -> Token:
        """The next token, which must be of ``kind`` (or one of ``more``); else an error naming ``what``."""
        return self._next(lambda t: t.kind == kind or t.kind in more, what)

    def expect(self, text: str, what: str) -> Token:
        """The next token, which must be ``text`` (punctuation); else an error naming ``what``."""
        return self._next(lambda t: t.text == text, what)

    def _next(self, fits: Callable[[Token], bool], what: str) -> Token:
        tok = self.peek()
        if tok is None or not fits(tok):
            found = f"{tok.text!r} at position {tok.pos + 1}" if tok else "the end of the rule"
            raise RuleCompileError(f"expected {what}, found {found}")
        self.i += 1
        return tok

    def rule(self) -> tuple[list[TextAtom], list[TextAtom]]:
        body = self.atoms("a body atom")
        self.take("arrow", "'->' between body and head")
        head = self.atoms("a head atom")
        if self.peek() is not None:
            tok = self.peek()
            raise RuleCompileError(f"unexpected {tok.text!r} at position {tok.pos + 1} after the head")
        return body, head

    def atoms(self, what: str) -> list[TextAtom]:
        out = [self.atom(what)]
        while (tok := self.peek()) is not None and tok.kind == "and":
            self.i += 1
            out.append(self.atom(what))
        return out

    def atom(self, what: str) -> TextAtom:
        tok = self.peek()
        start = tok.pos if tok else len(self.text)
        name = self.take("name", what, "iri").text
        self.expect("(", f"'(' after {name}")
        args = [self.arg()]
        while (t := self.peek()) is not None and t.text == ",":
            self.i += 1
            args.append(self.arg())
        close = self.expect(")", "',' or ')'")
        return TextAtom(name, tuple(args), self.text[start:close.pos + 1])

    def arg(self) -> object:
        tok = self.peek()
        if tok is None:
            raise RuleCompileError("expected an argument, found the end of the rule")
        self.i += 1
        if tok.kind == "var":
            return tok.text
        if tok.kind == "number":
            local = "integer" if re.fullmatch(r"[+-]?\d+", tok.text) else (
                "double" if "e" in tok.text.lower() else "decimal")
            return Literal(tok.text, datatype=xsd(local))
        if tok.kind == "string":
            return self.literal_rest(_unescape(tok.text[1:-1]))
        if tok.kind in ("name", "iri"):
            if tok.text in ("true", "false"):
                return Literal(tok.text, datatype=xsd("boolean"))
            return self.resolve(tok.text)
        raise RuleCompileError(f"expected an argument, found {tok.text!r} at position {tok.pos + 1}")

    def literal_rest(self, value: str) -> Literal:
        tok = self.peek()
        if tok is not None and tok.kind == "hat":
            self.i += 1
            dt = self.take("name", "a datatype after '^^'", "iri")
            return Literal(value, datatype=self.resolve(dt.text))
        if tok is not None and tok.text == "@":
            self.i += 1
            return Literal(value, language=self.take("name", "a language tag after '@'").text)
        return Literal(value)


def _unescape(s: str) -> str:
    return re.sub(r"\\(.)", lambda m: {"n": "\n", "t": "\t"}.get(m.group(1), m.group(1)), s)


def name_resolver(prefix: str) -> Callable[[str], NamedNode]:
    """Names of the ontology namespace, known ``prefix:local`` names and ``<IRI>``s → IRIs."""

    def resolve(name: str) -> NamedNode:
        if name.startswith("<"):
            return entity(name, prefix)
        if name.startswith(":"):
            return entity(name[1:], prefix)
        if ":" in name:
            p, local = name.split(":", 1)
            if p not in PREFIXES:
                raise RuleCompileError(f"unknown prefix {p!r} in {name!r} (known: {', '.join(sorted(PREFIXES))}, or <IRI>)")
            return NamedNode(PREFIXES[p] + local)
        return entity(name, prefix)

    return resolve


__all__ = ["PREFIXES", "Parser", "TextAtom", "Token", "name_resolver", "tokenize"]
