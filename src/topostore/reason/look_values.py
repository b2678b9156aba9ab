"""The values the look-up path's condition evaluator models, and the operators over them.

A condition compiled by :mod:`.look_filters` is a tree of the closures made here: each takes a
solution (variable name with its ``?`` -> term) and answers a modelled value or :data:`UNKNOWN`.
The modelled values: an int for an ``xsd:integer`` in its canonical spelling within Oxigraph's
64-bit range, a :class:`Str` for a simple literal, the term itself for an IRI or a blank node (and
for any other literal, which only the term tests accept), a bool for a test's answer.  Every
operator answers UNKNOWN where SPARQL's answer is not modelled exactly (an error, an overflow, a
value of another type): the caller then runs the operation's SPARQL text instead.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Mapping

from pyoxigraph import BlankNode, Literal, NamedNode

from ..rdf.vocab import XSD

#: the answer when the value is not modelled exactly (the caller falls back to SPARQL)
UNKNOWN = None

INTEGER, STRING = XSD + "integer", XSD + "string"
_MIN, MAX = -(2 ** 63), 2 ** 63 - 1
#: the canonical spelling of an xsd:integer (Oxigraph stores integers in it)
_CANONICAL = re.compile(r"-?(?:0|[1-9][0-9]*)\Z")


class Str(str):
    """A simple literal's value (kept apart from an IRI's text)."""


#: a compiled expression: the solution (variable name with its ``?`` -> term) to its value or UNKNOWN
Expr = Callable[[Mapping[str, object]], object]


#: literal -> its value (:func:`value`), for the next few thousand literals: a robot step reads the same
#: visit times and threshold at every step, and reading a literal's parts makes new objects each time;
#: public because the generated conditions read it inline (:mod:`.look_code`)
VALUES: dict[Literal, object] = {}
VALUES_MAX = 4096


def value(term) -> object:
    """A term's value as the evaluator models it: an int (xsd:integer), a :class:`Str` (simple
    literal), the term itself for an IRI or a blank node, and the term for any other literal (which
    only the term tests accept).  A value a BIND computed is already one."""
    if isinstance(term, Literal):
        found = VALUES.get(term)
        if found is None:
            if len(VALUES) >= VALUES_MAX:
                VALUES.clear()
            found = VALUES[term] = _literal_value(term)
        return found
    return term


def _literal_value(term: Literal) -> object:
    """:func:`value` of a literal."""
    if term.language is None:
        dt = term.datatype.value
        if dt == STRING:
            return Str(term.value)
        # 64 bits need at most 20 characters; a longer text is no value this evaluator models
        if dt == INTEGER and len(term.value) <= 20 and _CANONICAL.match(term.value):
            n = int(term.value)
            if _MIN <= n <= MAX:
                return n
    return term



def bound_value(solution: Mapping[str, object], name: str) -> object:
    term = solution.get(name)
    return UNKNOWN if term is None else value(term)


def is_int(x: object) -> bool:
    return type(x) is int


def _checked(n: int) -> object:
    return n if _MIN <= n <= MAX else UNKNOWN


def arith(op: str, left: Expr, right: Expr) -> Expr:
    def run(s):
        a, b = left(s), right(s)
        if not (is_int(a) and is_int(b)):
            return UNKNOWN
        return _checked(a + b if op == "+" else a - b)
    return run


def negate(arg: Expr) -> Expr:
    def run(s):
        a = arg(s)
        return _checked(-a) if is_int(a) else UNKNOWN
    return run


def plus(arg: Expr) -> Expr:
    def run(s):
        a = arg(s)
        return a if is_int(a) else UNKNOWN
    return run


_ORDER = {"<": lambda a, b: a < b, "<=": lambda a, b: a <= b, ">": lambda a, b: a > b,
          ">=": lambda a, b: a >= b, "=": lambda a, b: a == b, "!=": lambda a, b: a != b}


def compare(op: str, left: Expr, right: Expr) -> Expr:
    """Integers in any relation; simple strings, or two IRIs / blank nodes, in ``=`` and ``!=``."""
    test = _ORDER[op]
    equality = op in ("=", "!=")

    def run(s):
        a, b = left(s), right(s)
        if is_int(a) and is_int(b):
            return test(a, b)
        if not equality:
            return UNKNOWN
        if type(a) is Str and type(b) is Str:
            return test(str(a), str(b))
        if isinstance(a, (NamedNode, BlankNode)) and isinstance(b, (NamedNode, BlankNode)):
            return test(a, b)
        return UNKNOWN
    return run


def ebv(x: object) -> object:
    """SPARQL's effective boolean value of a modelled value (UNKNOWN for the others)."""
    if type(x) is bool:
        return x
    if is_int(x):
        return x != 0
    if type(x) is Str:
        return len(x) > 0
    return UNKNOWN


def not_(arg: Expr) -> Expr:
    def run(s):
        b = ebv(arg(s))
        return UNKNOWN if b is UNKNOWN else not b
    return run


def all_of(parts: list[Expr]) -> Expr:
    """``&&`` of ``parts`` (a FILTER's several conditions too): True when there are none."""
    return _junction(parts, False)


def any_of(parts: list[Expr]) -> Expr:
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


def term_test(name: str, args: list) -> Expr:
    """``sameTerm`` of two arguments or an ``isIRI``-like test of one (the parser checked how many)."""
    if name == "SAMETERM":
        left, right = args

        def same(s):
            a, b = left(s), right(s)
            return UNKNOWN if a is None or b is None else a == b
        return same
    kind = {"ISIRI": NamedNode, "ISURI": NamedNode, "ISBLANK": BlankNode, "ISLITERAL": Literal}[name]
    arg = args[0]

    def test(s):
        a = arg(s)
        return UNKNOWN if a is None else isinstance(a, kind)
    return test


def str_of(arg: Expr) -> Expr:
    def run(s):
        a = arg(s)
        if isinstance(a, NamedNode):
            return Str(a.value)
        return a if type(a) is Str else UNKNOWN
    return run


def substring(before: bool, text: Expr, sep: Expr) -> Expr:
    def run(s):
        a, b = text(s), sep(s)
        if type(a) is not Str or type(b) is not Str:
            return UNKNOWN
        at = a.find(b)
        if at < 0:
            return Str("")
        return Str(a[:at] if before else a[at + len(b):])
    return run



def filter_of(expr: Expr) -> Callable[[Mapping[str, object]], object]:
    """A FILTER of ``expr``: True / False by its effective boolean value, UNKNOWN when not exact."""
    return lambda s: ebv(expr(s))


def term_of(x: object) -> object:
    """A value as the term SPARQL holds for it (Oxigraph writes computed values canonically, as here);
    UNKNOWN stays UNKNOWN."""
    if type(x) is bool:
        return Literal("true" if x else "false", datatype=NamedNode(XSD + "boolean"))
    if is_int(x):
        return Literal(str(x), datatype=NamedNode(INTEGER))
    if type(x) is Str:
        return Literal(str(x))
    return x


__all__ = ["UNKNOWN", "VALUES", "Expr", "Str", "all_of", "any_of", "arith", "bound_value", "compare", "ebv", "filter_of",
           "negate", "not_", "plus", "str_of", "substring", "term_of", "term_test", "value"]
