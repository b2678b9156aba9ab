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
"""

from __future__ import annotations

import re
from collections.abc import Callable, Mapping

from pyoxigraph import BlankNode, Literal, NamedNode

from ..rdf.vocab import XSD

#: the answer when the value is not modelled exactly (the caller falls back to SPARQL)
UNKNOWN = None

_INTEGER, _STRING = XSD + "integer", XSD + "string"
_MIN, _MAX = -(2 ** 63), 2 ** 63 - 1
#: the canonical spelling of an xsd:integer (Oxigraph stores integers in it)
_CANONICAL = re.compile(r"-?(?:0|[1-9][0-9]*)\Z")

_SPACE = re.compile(r"\s*")
_VAR = re.compile(r"[?$](\w+)")
_IRI = re.compile(r"<([^<>\"{}|^`\\\x00-\x20]*)>")
_INT = re.compile(r"[0-9]+(?![0-9.eE])")
_NAME = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")
_STR = re.compile(r"\"((?:[^\"\\\n\r]|\\[tnrbf\"'\\])*)\"(?!\")|'((?:[^'\\\n\r]|\\[tnrbf\"'\\])*)'(?!')")
#: a typed literal's datatype (the two the evaluator models, written in full); a language tag is refused
_TYPED = re.compile(r"\^\^<(" + re.escape(_INTEGER) + "|" + re.escape(_STRING) + r")>")
_ECHAR = {"t": "\t", "n": "\n", "r": "\r", "b": "\b", "f": "\f", '"': '"', "'": "'", "\\": "\\"}
_RELATIONS = ("<=", ">=", "!=", "=", "<", ">")


class _Str(str):
    """A simple literal's value (kept apart from an IRI's text)."""


#: a compiled expression: the solution (variable name with its ``?`` -> term) to its value or UNKNOWN
Expr = Callable[[Mapping[str, object]], object]


class Unsupported(ValueError):
    """The text is outside the subset: its condition is never evaluated here."""


#: literal -> its value (:func:`value`), for the next few thousand literals: a robot step reads the same
#: visit times and threshold at every step, and reading a literal's parts makes new objects each time
_VALUES: dict[Literal, object] = {}
_VALUES_MAX = 4096


def value(term) -> object:
    """A term's value as the evaluator models it: an int (xsd:integer), a :class:`_Str` (simple
    literal), the term itself for an IRI or a blank node, and the term for any other literal (which
    only the term tests accept).  A value a BIND computed is already one."""
    if isinstance(term, Literal):
        found = _VALUES.get(term)
        if found is None:
            if len(_VALUES) >= _VALUES_MAX:
                _VALUES.clear()
            found = _VALUES[term] = _literal_value(term)
        return found
    return term


def _literal_value(term: Literal) -> object:
    """:func:`value` of a literal."""
    if term.language is None:
        dt = term.datatype.value
        if dt == _STRING:
            return _Str(term.value)
        # 64 bits need at most 20 characters; a longer text is no value this evaluator models
        if dt == _INTEGER and len(term.value) <= 20 and _CANONICAL.match(term.value):
            n = int(term.value)
            if _MIN <= n <= _MAX:
                return n
    return term


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

    def parse(self) -> Expr:
        expr = self.or_()
        self.skip()
        if self.i != len(self.text):
            raise self.fail()
        return expr

    def or_(self) -> Expr:
        parts = [self.and_()]
        while self.take("||"):
            parts.append(self.and_())
        return parts[0] if len(parts) == 1 else _any(parts)

    def and_(self) -> Expr:
        parts = [self.relation()]
        while self.take("&&"):
            parts.append(self.relation())
        return parts[0] if len(parts) == 1 else all_of(parts)

    def relation(self) -> Expr:
        left = self.additive()
        self.skip()
        op = next((op for op in _RELATIONS if self.text.startswith(op, self.i)), None)
        if op is None:
            return left
        if op == "<" and _IRI.match(self.text, self.i):
            raise self.fail()  # ambiguous with an IRI: left to SPARQL
        self.i += len(op)
        return _compare(op, left, self.additive())

    def additive(self) -> Expr:
        expr = self.unary()
        while True:
            self.skip()
            if self.text.startswith(("+", "-"), self.i):
                op = self.text[self.i]
                self.i += 1
                expr = _arith(op, expr, self.unary())
            elif self.text.startswith(("*", "/"), self.i):
                raise self.fail()
            else:
                return expr

    def unary(self) -> Expr:
        self.skip()
        if self.text.startswith("!=", self.i):
            raise self.fail()
        if self.take("!"):
            return _not(self.unary())
        if self.take("-"):
            return _negate(self.unary())
        if self.take("+"):
            return _plus(self.unary())
        return self.primary()

    def primary(self) -> Expr:
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
            flag = name == "true"
            return lambda _s: flag
        return self.call(name.upper())

    def literal(self, m: re.Match) -> Expr:
        """A string constant: simple, or typed ``xsd:integer`` / ``xsd:string`` (as the store reads it)."""
        raw = m.group(1) if m.group(1) is not None else m.group(2)
        lex = re.sub(r"\\(.)", lambda e: _ECHAR[e.group(1)], raw)
        typed = _TYPED.match(self.text, self.i)
        if typed is None:
            if self.text.startswith(("@", "^^"), self.i):
                raise self.fail()
            string = _Str(lex)
            return lambda _s: string
        self.i = typed.end()
        found = value(Literal(lex, datatype=NamedNode(typed.group(1))))
        if isinstance(found, Literal):
            raise self.fail()  # an ill-typed or non-canonical integer: left to SPARQL
        return lambda _s: found

    def call(self, name: str) -> Expr:
        self.expect("(")
        if name in ("SAMETERM", "ISIRI", "ISURI", "ISBLANK", "ISLITERAL"):
            args = [self.term_arg()]
            while self.take(","):
                args.append(self.term_arg())
            self.expect(")")
            return _term_test(name, args, self)
        args = [self.or_()]
        while self.take(","):
            args.append(self.or_())
        self.expect(")")
        if name == "STR" and len(args) == 1:
            return _str(args[0])
        if name in ("STRBEFORE", "STRAFTER") and len(args) == 2:
            return _substring(name == "STRBEFORE", *args)
        raise self.fail()

    def term_arg(self) -> Callable[[Mapping[str, object]], object]:
        """A term test's argument: a variable (its bound term) or an IRI."""
        self.skip()
        m = _VAR.match(self.text, self.i)
        if m is not None:
            self.i = m.end()
            name = "?" + m.group(1)
            return lambda s: term_of(s.get(name))
        m = _IRI.match(self.text, self.i)
        if m is not None:
            self.i = m.end()
            iri = NamedNode(m.group(1))
            return lambda _s: iri
        raise self.fail()


def _constant_or_variable(m: re.Match) -> Expr:
    text = m.group(0)
    if text[0] in "?$":
        name = "?" + m.group(1)
        return lambda s: _bound_value(s, name)
    if text[0] == "<":
        iri = NamedNode(m.group(1))
        return lambda _s: iri
    n = int(text) if len(text) <= 20 else _MAX + 1
    if n > _MAX:
        raise Unsupported(f"integer beyond 64 bits: {text}")
    return lambda _s: n


def _bound_value(solution: Mapping[str, object], name: str) -> object:
    term = solution.get(name)
    return UNKNOWN if term is None else value(term)


def _is_int(x: object) -> bool:
    return type(x) is int


def _checked(n: int) -> object:
    return n if _MIN <= n <= _MAX else UNKNOWN


def _arith(op: str, left: Expr, right: Expr) -> Expr:
    def run(s):
        a, b = left(s), right(s)
        if not (_is_int(a) and _is_int(b)):
            return UNKNOWN
        return _checked(a + b if op == "+" else a - b)
    return run


def _negate(arg: Expr) -> Expr:
    def run(s):
        a = arg(s)
        return _checked(-a) if _is_int(a) else UNKNOWN
    return run


def _plus(arg: Expr) -> Expr:
    def run(s):
        a = arg(s)
        return a if _is_int(a) else UNKNOWN
    return run


_ORDER = {"<": lambda a, b: a < b, "<=": lambda a, b: a <= b, ">": lambda a, b: a > b,
          ">=": lambda a, b: a >= b, "=": lambda a, b: a == b, "!=": lambda a, b: a != b}


def _compare(op: str, left: Expr, right: Expr) -> Expr:
    """Integers in any relation; simple strings, or two IRIs / blank nodes, in ``=`` and ``!=``."""
    test = _ORDER[op]
    equality = op in ("=", "!=")

    def run(s):
        a, b = left(s), right(s)
        if _is_int(a) and _is_int(b):
            return test(a, b)
        if not equality:
            return UNKNOWN
        if type(a) is _Str and type(b) is _Str:
            return test(str(a), str(b))
        if isinstance(a, (NamedNode, BlankNode)) and isinstance(b, (NamedNode, BlankNode)):
            return test(a, b)
        return UNKNOWN
    return run


def ebv(x: object) -> object:
    """SPARQL's effective boolean value of a modelled value (UNKNOWN for the others)."""
    if type(x) is bool:
        return x
    if _is_int(x):
        return x != 0
    if type(x) is _Str:
        return len(x) > 0
    return UNKNOWN


def _not(arg: Expr) -> Expr:
    def run(s):
        b = ebv(arg(s))
        return UNKNOWN if b is UNKNOWN else not b
    return run


def all_of(parts: list[Expr]) -> Expr:
    """``&&`` of ``parts`` (a FILTER's several conditions too): True when there are none."""
    return _junction(parts, False)


def _any(parts: list[Expr]) -> Expr:
    return _junction(parts, True)


def _junction(parts: list[Expr], decisive: bool) -> Expr:
    """``&&`` (``decisive`` False) or ``||`` (True) in SPARQL's logic: one decisive operand decides,
    even beside an error; otherwise an error (UNKNOWN) among them leaves the answer unknown."""
    def run(s):
        answer = not decisive
        for part in parts:
            b = ebv(part(s))
            if b is decisive:
                return decisive
            if b is UNKNOWN:
                answer = UNKNOWN
        return answer
    return run


def _term_test(name: str, args: list, parser: _Parser) -> Expr:
    if name == "SAMETERM":
        if len(args) != 2:
            raise parser.fail()
        left, right = args

        def same(s):
            a, b = left(s), right(s)
            return UNKNOWN if a is None or b is None else a == b
        return same
    if len(args) != 1:
        raise parser.fail()
    kind = {"ISIRI": NamedNode, "ISURI": NamedNode, "ISBLANK": BlankNode, "ISLITERAL": Literal}[name]
    arg = args[0]

    def test(s):
        a = arg(s)
        return UNKNOWN if a is None else isinstance(a, kind)
    return test


def _str(arg: Expr) -> Expr:
    def run(s):
        a = arg(s)
        if isinstance(a, NamedNode):
            return _Str(a.value)
        return a if type(a) is _Str else UNKNOWN
    return run


def _substring(before: bool, text: Expr, sep: Expr) -> Expr:
    def run(s):
        a, b = text(s), sep(s)
        if type(a) is not _Str or type(b) is not _Str:
            return UNKNOWN
        at = a.find(b)
        if at < 0:
            return _Str("")
        return _Str(a[:at] if before else a[at + len(b):])
    return run


def compile_expression(text: str) -> Expr:
    """The expression ``text`` as a function of a solution; raises :class:`Unsupported` outside the subset."""
    return _Parser(text).parse()


def filter_of(expr: Expr) -> Callable[[Mapping[str, object]], object]:
    """A FILTER of ``expr``: True / False by its effective boolean value, UNKNOWN when not exact."""
    return lambda s: ebv(expr(s))


def term_of(x: object) -> object:
    """A value as the term SPARQL holds for it (Oxigraph writes computed values canonically, as here);
    UNKNOWN stays UNKNOWN."""
    if type(x) is bool:
        return Literal("true" if x else "false", datatype=NamedNode(XSD + "boolean"))
    if _is_int(x):
        return Literal(str(x), datatype=NamedNode(_INTEGER))
    if type(x) is _Str:
        return Literal(str(x))
    return x


__all__ = ["UNKNOWN", "Unsupported", "compile_expression", "ebv", "term_of", "filter_of", "value"]
