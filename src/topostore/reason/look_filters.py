"""An exact evaluator for a small subset of SPARQL expressions: a rule's FILTERs and BINDs decided in
Python, for the compiled step's look-up path (:mod:`.direct`).

Why this exists
---------------
A rule with a condition could only run as SPARQL text, whose parsing and planning costs tens of
microseconds while its few facts cost a microsecond each to look up.  This module compiles a
condition's expression once into Python closures that answer True, False or :data:`UNKNOWN`.

Exactness is the rule: UNKNOWN stands for anything not modelled exactly (a syntax outside the
subset, a value outside the modelled types, an arithmetic overflow, any SPARQL error), and one
UNKNOWN anywhere makes the caller run the operation's SPARQL text instead — never a guess.

The subset: ``!``, ``&&``, ``||`` (three-valued: ``false && UNKNOWN`` is false, ``true || UNKNOWN``
is true, as SPARQL's error rules give whatever the UNKNOWN stands for); ``sameTerm``, ``isIRI`` /
``isURI``, ``isBlank``, ``isLiteral`` on variables and IRIs; ``STR`` of an IRI or a simple string;
``STRBEFORE`` / ``STRAFTER`` and ``=`` / ``!=`` on simple strings; ``+``, ``-`` (also unary) and
``< <= > >= = !=`` on ``xsd:integer`` literals in their canonical spelling within Oxigraph's 64-bit
range (a result outside it is an error there, UNKNOWN here); ``=`` / ``!=`` between two IRIs or
blank nodes; the constants ``true``, ``false``, integers, IRIs and plain strings.

Where the parts live: this module parses a condition's text into a tree of tuples, made the closures
of :mod:`.look_values` (which holds the modelled values and the operators that evaluate them) by
:func:`closure`, or one generated function with a rule's other conditions by :mod:`.look_code`.
"""

from __future__ import annotations

import re

from pyoxigraph import Literal, NamedNode

from .look_values import (
    INTEGER,
    MAX,
    STRING,
    Expr,
    Str,
    all_of,
    any_of,
    arith,
    bound_value,
    compare,
    negate,
    not_,
    plus,
    str_of,
    substring,
    term_of,
    term_test,
    value,
)

_SPACE = re.compile(r"\s*")
_VAR = re.compile(r"[?$](\w+)")
_IRI = re.compile(r"<([^<>\"{}|^`\\\x00-\x20]*)>")
_INT = re.compile(r"[0-9]+(?![0-9.eE])")
_NAME = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")
_STR = re.compile(r"\"((?:[^\"\\\n\r]|\\[tnrbf\"'\\])*)\"(?!\")|'((?:[^'\\\n\r]|\\[tnrbf\"'\\])*)'(?!')")
#: a typed literal's datatype (the two the evaluator models, written in full); a language tag is refused
_TYPED = re.compile(r"\^\^<(" + re.escape(INTEGER) + "|" + re.escape(STRING) + r")>")
_ECHAR = {"t": "\t", "n": "\n", "r": "\r", "b": "\b", "f": "\f", '"': '"', "'": "'", "\\": "\\"}
_RELATIONS = ("<=", ">=", "!=", "=", "<", ">")


class Unsupported(ValueError):
    """The text is outside the subset: its condition is never evaluated here."""



class _Parser:
    """Recursive descent over the text, lexing where each rule expects a token (so that ``<`` is an
    IRI only where a term may start)."""

    def __init__(self, text: str) -> None:
        self.text = text
        self.i = 0

    def fail(self) -> Unsupported:
        return Unsupported(f"outside the evaluated subset at {self.i}: {self.text!r}")

    def skip(self) -> None:
        self.i = _SPACE.match(self.text, self.i).end()

    def take(self, word: str) -> bool:
        self.skip()
        if self.text.startswith(word, self.i):
            self.i += len(word)
            return True
        return False

    def expect(self, word: str) -> None:
        if not self.take(word):
            raise self.fail()

    def parse(self) -> tuple:
        expr = self.or_()
        self.skip()
        if self.i != len(self.text):
            raise self.fail()
        return expr

    def or_(self) -> tuple:
        parts = [self.and_()]
        while self.take("||"):
            parts.append(self.and_())
        return parts[0] if len(parts) == 1 else ("or", parts)

    def and_(self) -> tuple:
        parts = [self.relation()]
        while self.take("&&"):
            parts.append(self.relation())
        return parts[0] if len(parts) == 1 else ("and", parts)

    def relation(self) -> tuple:
        left = self.additive()
        self.skip()
        op = next((op for op in _RELATIONS if self.text.startswith(op, self.i)), None)
        if op is None:
            return left
        if op == "<" and _IRI.match(self.text, self.i):
            raise self.fail()  # ambiguous with an IRI: left to SPARQL
        self.i += len(op)
        return ("compare", op, left, self.additive())

    def additive(self) -> tuple:
        expr = self.unary()
        while True:
            self.skip()
            if self.text.startswith(("+", "-"), self.i):
                op = self.text[self.i]
                self.i += 1
                expr = ("arith", op, expr, self.unary())
            elif self.text.startswith(("*", "/"), self.i):
                raise self.fail()
            else:
                return expr

    def unary(self) -> tuple:
        self.skip()
        if self.text.startswith("!=", self.i):
            raise self.fail()
        if self.take("!"):
            return ("not", self.unary())
        if self.take("-"):
            return ("negate", self.unary())
        if self.take("+"):
            return ("plus", self.unary())
        return self.primary()

    def primary(self) -> tuple:
        self.skip()
        if self.take("("):
            expr = self.or_()
            self.expect(")")
            return expr
        m = _VAR.match(self.text, self.i) or _IRI.match(self.text, self.i) or _INT.match(self.text, self.i) \
            or _STR.match(self.text, self.i)
        if m is not None:
            self.i = m.end()
            if m.group(0)[0] in "\"'":
                return self.literal(m)
            return _constant_or_variable(m)
        m = _NAME.match(self.text, self.i)
        if m is None:
            raise self.fail()
        self.i = m.end()
        name = m.group(0)
        if name in ("true", "false"):
            return ("const", name == "true")
        return self.call(name.upper())

    def literal(self, m: re.Match) -> tuple:
        """A string constant: simple, or typed ``xsd:integer`` / ``xsd:string`` (as the store reads it)."""
        raw = m.group(1) if m.group(1) is not None else m.group(2)
        lex = re.sub(r"\\(.)", lambda e: _ECHAR[e.group(1)], raw)
        typed = _TYPED.match(self.text, self.i)
        if typed is None:
            if self.text.startswith(("@", "^^"), self.i):
                raise self.fail()
            return ("const", Str(lex))
        self.i = typed.end()
        found = value(Literal(lex, datatype=NamedNode(typed.group(1))))
        if isinstance(found, Literal):
            raise self.fail()  # an ill-typed or non-canonical integer: left to SPARQL
        return ("const", found)

    def call(self, name: str) -> tuple:
        self.expect("(")
        if name in ("SAMETERM", "ISIRI", "ISURI", "ISBLANK", "ISLITERAL"):
            args = [self.term_arg()]
            while self.take(","):
                args.append(self.term_arg())
            self.expect(")")
            if len(args) != (2 if name == "SAMETERM" else 1):
                raise self.fail()
            return ("term_test", name, args)
        args = [self.or_()]
        while self.take(","):
            args.append(self.or_())
        self.expect(")")
        if name == "STR" and len(args) == 1:
            return ("str", args[0])
        if name in ("STRBEFORE", "STRAFTER") and len(args) == 2:
            return ("substring", name == "STRBEFORE", *args)
        raise self.fail()

    def term_arg(self) -> tuple:
        """A term test's argument: a variable (its bound term) or an IRI."""
        self.skip()
        m = _VAR.match(self.text, self.i)
        if m is not None:
            self.i = m.end()
            return ("term_of", "?" + m.group(1))
        m = _IRI.match(self.text, self.i)
        if m is not None:
            self.i = m.end()
            return ("const", NamedNode(m.group(1)))
        raise self.fail()



def _constant_or_variable(m: re.Match) -> tuple:
    text = m.group(0)
    if text[0] in "?$":
        return ("var", "?" + m.group(1))
    if text[0] == "<":
        return ("const", NamedNode(m.group(1)))
    n = int(text) if len(text) <= 20 else MAX + 1
    if n > MAX:
        raise Unsupported(f"integer beyond 64 bits: {text}")
    return ("const", n)


def parse_expression(text: str) -> tuple:
    """The expression ``text`` as a tree of tuples (kind first, as :func:`closure` reads them); raises
    :class:`Unsupported` outside the subset."""
    return _Parser(text).parse()


def compile_expression(text: str) -> Expr:
    """The expression ``text`` as a function of a solution; raises :class:`Unsupported` outside the subset."""
    return closure(parse_expression(text))


def closure(node: tuple) -> Expr:
    """An expression tree (:func:`parse_expression`) as the closures of :mod:`.look_values`."""
    kind = node[0]
    if kind == "var":
        name = node[1]
        return lambda s: bound_value(s, name)
    if kind == "term_of":
        name = node[1]
        return lambda s: term_of(s.get(name))
    if kind == "const":
        found = node[1]
        return lambda _s: found
    if kind in ("and", "or"):
        return (all_of if kind == "and" else any_of)([closure(n) for n in node[1]])
    if kind in ("compare", "arith"):
        return (compare if kind == "compare" else arith)(node[1], closure(node[2]), closure(node[3]))
    if kind == "term_test":
        return term_test(node[1], [closure(n) for n in node[2]])
    if kind == "substring":
        return substring(node[1], closure(node[2]), closure(node[3]))
    return {"not": not_, "negate": negate, "plus": plus, "str": str_of}[kind](closure(node[1]))


__all__ = ["Unsupported", "closure", "compile_expression", "parse_expression"]
