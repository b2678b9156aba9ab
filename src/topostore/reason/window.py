"""Windows of compared values: the facts a clock move can flip, found by index, not by a scan.

Why
---
A clock tick replaces ``now(Robot1)``; the Urgency rule compares it with every
location's ``visitedAt`` (``now - visitedAt > threshold``).  The flip query of
:mod:`.flip` pairs the old and the new clock with *every* visit time and
evaluates the filters twice per row: on a map of 100,000 locations that scan
is the whole cost of a step, although only the locations whose visit time
lies between the two thresholds can change.

What is exact here
------------------
For a rule whose tests are comparisons of *linear* expressions (variables,
numbers, ``+`` and ``-``: what the swrlb arithmetic and comparison built-ins
compile to), a test ``L(v, t, rest) op 0`` with ``L = a·v + c·t + r`` can
only answer differently for the old and the new value of ``t`` when ``v``
lies between the two thresholds ``-(c·t_old + r)/a`` and ``-(c·t_new + r)/a``
(both included; every comparison operator changes its answer only there).  A
conjunction of tests can only flip where one of its tests flips.  So the
flipping values of ``v`` lie in the union of those closed intervals, one per
binding of the other variables; the flip query then evaluates the exact
filters on the facts in the window only, so a window that is a little too
wide costs a row, never a wrong answer.  Values that are not numbers make the
arithmetic fail in both states (no flip) and are left out; a test that does
not mention ``v`` but may flip, a non-linear test on ``t`` or a binding that is
not a number give no window: the query scans, as before.

The values are read from :class:`ValueIndex`, a sorted index per compared
predicate kept from the asserted changes of every REASON; it is used only for
predicates no rule that can fire derives (their facts are all asserted).
"""

from __future__ import annotations

import bisect
import math
import re
from collections.abc import Iterable
from dataclasses import dataclass
from decimal import Decimal, InvalidOperation
from fractions import Fraction

from pyoxigraph import Literal, NamedNode, Triple

from ..compile.condition import BIND, TEST
from ..compile.rule import Rule
from ..rdf.terms import Term
from ..rdf.vocab import XSD
from .look_values import value as literal_value

#: A linear form: coefficient per variable name (without ``?``) and a constant.
Linear = tuple[dict[str, Fraction], Fraction]

_TOKEN = re.compile(r"\s*(?:(\?\w+)|(\d+(?:\.\d*)?|\.\d+)|(>=|<=|!=|=|>|<|\+|-|\(|\)))")
_FLOAT = NamedNode(XSD + "float")
_COMPARISON = (">=", "<=", "!=", "=", ">", "<")
#: numeric datatypes whose lexical form Python reads exactly (others: float)
_EXACT = ("integer", "decimal", "long", "int", "short", "byte", "nonNegativeInteger", "positiveInteger",
          "nonPositiveInteger", "negativeInteger", "unsignedLong", "unsignedInt", "unsignedShort", "unsignedByte")


class _NotLinear(Exception):
    """The expression is not made of variables, numbers, + and - only."""


def _tokens(text: str) -> list[str]:
    out, at = [], 0
    text = text.strip()
    while at < len(text):
        m = _TOKEN.match(text, at)
        if m is None or m.end() == at:
            raise _NotLinear(text[at:])
        out.append(m.group(m.lastindex))
        at = m.end()
    return out


class _Parser:
    """``expr := term (('+'|'-') term)*``, ``term := ['-'|'+'] (number | ?var | '(' expr ')')``."""

    def __init__(self, tokens: list[str], binds: dict[str, Linear]) -> None:
        self.tokens, self.at, self.binds = tokens, 0, binds

    def peek(self) -> str | None:
        return self.tokens[self.at] if self.at < len(self.tokens) else None

    def take(self) -> str:
        tok = self.peek()
        if tok is None:
            raise _NotLinear("unexpected end")
        self.at += 1
        return tok

    def expr(self) -> Linear:
        acc = self.term()
        while self.peek() in ("+", "-"):
            sign = 1 if self.take() == "+" else -1
            acc = _add(acc, self.term(), sign)
        return acc

    def term(self) -> Linear:
        tok = self.take()
        if tok in ("+", "-"):
            inner = self.term()
            return inner if tok == "+" else _add(({}, Fraction(0)), inner, -1)
        if tok == "(":
            inner = self.expr()
            if self.take() != ")":
                raise _NotLinear("unbalanced")
            return inner
        if tok.startswith("?"):
            name = tok[1:]
            return self.binds.get(name, ({name: Fraction(1)}, Fraction(0)))
        if tok[0].isdigit() or tok[0] == ".":
            return {}, Fraction(Decimal(tok))
        raise _NotLinear(tok)


def _add(a: Linear, b: Linear, sign: int) -> Linear:
    coefs = dict(a[0])
    for k, v in b[0].items():
        coefs[k] = coefs.get(k, Fraction(0)) + sign * v
    return {k: v for k, v in coefs.items() if v}, a[1] + sign * b[1]


@dataclass(frozen=True)
class Test:
    """One test of a rule: linear (``form op 0``), or not (``form`` None) with the variables it reads."""

    form: Linear | None
    variables: frozenset[str]


def tests(rule: Rule) -> list[Test]:
    """The rule's tests with its BINDs substituted (a BIND that is not linear makes its uses non-linear)."""
    binds: dict[str, Linear] = {}
    deps: dict[str, frozenset[str]] = {}  # BIND results: the body variables they are computed from
    opaque: set[str] = set()  # BIND results that are not linear
    out: list[Test] = []
    for c in rule.conditions:
        names = frozenset(v[1:] for v in c.variables) - ({c.binds[1:]} if c.binds else set())
        reads = frozenset().union(*(deps.get(n, frozenset({n})) for n in names))
        linear_inputs = not (names & opaque)
        if c.kind == BIND:
            target = c.binds[1:]
            deps[target] = reads
            form = _linear(c.expression, binds) if linear_inputs else None
            if form is None:
                opaque.add(target)
            else:
                binds[target] = form
            continue
        form = _comparison(c.expression, binds) if c.kind == TEST and linear_inputs else None
        out.append(Test(form, reads))
    return out


def _linear(text: str | list[str], binds: dict[str, Linear]) -> Linear | None:
    """The linear form of a whole expression (its text or tokens), or None."""
    try:
        parser = _Parser(_tokens(text) if isinstance(text, str) else text, binds)
        form = parser.expr()
    except _NotLinear:
        return None
    return form if parser.peek() is None else None


def _comparison(text: str, binds: dict[str, Linear]) -> Linear | None:
    """``left op right`` as the linear form ``left - right`` (compared with 0), or None."""
    try:
        toks = _tokens(text)
    except _NotLinear:
        return None
    ops = [i for i, t in enumerate(toks) if t in _COMPARISON]
    if len(ops) != 1:
        return None
    left, right = _linear(toks[:ops[0]], binds), _linear(toks[ops[0] + 1:], binds)
    return None if left is None or right is None else _add(left, right, -1)


def margin(terms: list[Term], values: list[Fraction]) -> Fraction:
    """How much to widen a window whose bounds were computed from ``terms`` (read as ``values``):
    nothing when every one is of an exact numeric type, else enough for double rounding."""
    exact = all(isinstance(t, Literal) and t.datatype.value.rsplit("#", 1)[1] in _EXACT for t in terms)
    return Fraction(0) if exact else Fraction(1, 10**9) * (1 + sum(abs(x) for x in values))


def single_precision(terms: Iterable[Term | None]) -> bool:
    """Whether one of ``terms`` is an ``xsd:float``: SPARQL computes with it in single precision (a
    24-bit mantissa: near 1.6e9 only multiples of 128), so a window's bounds, computed exactly, could
    leave out a value whose test flips; such a window is not taken (every fact is read)."""
    return any(isinstance(term, Literal) and term.datatype == _FLOAT for term in terms)


def possible(found: list[Test], t: str) -> bool:
    """Whether a window can exist: every test that reads ``t`` is linear (checked before any query)."""
    return all(test.form is not None for test in found if t in test.variables)


def number(term: Term | None) -> Fraction | None:
    """The exact value of a numeric literal (None for anything else, NaN and infinities)."""
    if not isinstance(term, Literal) or not term.datatype.value.startswith(XSD):
        return None
    local = term.datatype.value.rsplit("#", 1)[1]
    try:
        if local in _EXACT:
            return Fraction(Decimal(term.value.strip()))
        if local in ("double", "float"):
            f = float(term.value.strip())
            return Fraction(f) if math.isfinite(f) else None
    except (InvalidOperation, ValueError):
        return None
    return None


def interval(found: list[Test], v: str, t: str, old: Fraction, new: Fraction,
             rest: dict[str, Fraction], margin: Fraction) -> tuple[Fraction, Fraction] | None | bool:
    """The closed interval of ``v`` outside which no test can flip when ``t`` goes ``old`` → ``new``.

    Returns False when no test can flip at all, None when there is no window (scan).
    ``margin`` widens the interval (rounding of double arithmetic).
    """
    lo = hi = None
    for test in found:
        if t not in test.variables:
            continue  # cannot answer differently: nothing it reads changed
        if test.form is None:
            return None
        coefs, const = test.form
        a, c = coefs.get(v, Fraction(0)), coefs.get(t, Fraction(0))
        if not c:
            continue
        others = [k for k in coefs if k not in (v, t)]
        if any(k not in rest for k in others):
            return None
        r = const + sum(coefs[k] * rest[k] for k in others)
        if not a:
            if c * old == c * new:
                continue  # the same value in both states
            return None  # flips for every v or for none: no window to look through
        ends = (-(c * old + r) / a, -(c * new + r) / a)
        lo = min(ends) if lo is None else min(lo, *ends)
        hi = max(ends) if hi is None else max(hi, *ends)
    if lo is None:
        return False
    return lo - margin, hi + margin


#: a linear test read for :func:`integer_interval`: the coefficients of ``v`` and ``t``, the other
#: variables' coefficients and the constant, all ints
IntegerForm = tuple[int, int, tuple[tuple[str, int], ...], int]


def integer_forms(found: list[Test], v: str, t: str) -> tuple[IntegerForm, ...] | None:
    """The tests that read ``t`` as :data:`IntegerForm` (tests that cannot flip left out), for
    :func:`integer_interval`; None where one is not linear or has a coefficient that is not an integer
    (:func:`interval` then computes in fractions).  A property of the rule: made once."""
    out = []
    for test in found:
        if t not in test.variables:
            continue
        if test.form is None:
            return None
        coefs, const = test.form
        if any(x.denominator != 1 for x in (*coefs.values(), const)):
            return None
        c = int(coefs.get(t, 0))
        if c:
            others = tuple((k, int(x)) for k, x in coefs.items() if k not in (v, t))
            out.append((int(coefs.get(v, 0)), c, others, int(const)))
    return tuple(out)


def integer_interval(forms: tuple[IntegerForm, ...], old: int, new: int,
                     rest: dict[str, int]) -> tuple[int | Fraction, int | Fraction] | None | bool:
    """:func:`interval` for :func:`integer_forms` and int values (no margin: the arithmetic is exact),
    without making a fraction unless a coefficient of ``v`` is not ±1 (a clock's test: every step)."""
    lo = hi = None
    for a, c, others, const in forms:
        if any(k not in rest for k, _ in others):
            return None
        r = const + sum(x * rest[k] for k, x in others)
        if not a:
            if c * old == c * new:
                continue
            return None
        ends = [-(c * x + r) * a if a in (1, -1) else Fraction(-(c * x + r), a) for x in (old, new)]
        lo = min(ends) if lo is None else min(lo, *ends)
        hi = max(ends) if hi is None else max(hi, *ends)
    if lo is None:
        return False
    return lo, hi


class ValueIndex:
    """The facts of one predicate sorted by their numeric object; non-numbers are left out.
    :attr:`single` counts the ``xsd:float`` values held (a window over them is not exact, see
    :func:`single_precision`)."""

    def __init__(self, triples: Iterable[Triple]) -> None:
        self._keys: list[tuple[Fraction, str, str]] = []
        self._facts: dict[tuple[Fraction, str, str], Triple] = {}
        #: how many of the values held are ``xsd:float``
        self.single = 0
        for t in triples:
            self.add(t, insort=False)
        self._keys.sort()

    def _key(self, t: Triple) -> tuple[Fraction, str, str] | None:
        """The fact's sort key: an int for a canonical xsd:integer (read as :mod:`.look_values` reads it,
        cheaper than a fraction and equal to it), else its :func:`number`."""
        value = literal_value(t.object)
        if type(value) is not int:
            value = number(t.object)
        return None if value is None else (value, str(t.subject), str(t.object))

    def add(self, t: Triple, insort: bool = True) -> None:
        key = self._key(t)
        if key is None or key in self._facts:
            return
        self._facts[key] = t
        if type(key[0]) is not int and t.object.datatype == _FLOAT:
            self.single += 1
        if insort:
            bisect.insort(self._keys, key)
        else:
            self._keys.append(key)

    def discard(self, t: Triple) -> None:
        key = self._key(t)
        if key is None or self._facts.pop(key, None) is None:
            return
        if type(key[0]) is not int and t.object.datatype == _FLOAT:
            self.single -= 1
        del self._keys[bisect.bisect_left(self._keys, key)]

    def exact_for(self, terms: Iterable[Term | None]) -> bool:
        """Whether a window over these values, bounded by ``terms``, is exact: no ``xsd:float`` on either
        side (see :func:`single_precision`)."""
        return not self.single and not single_precision(terms)

    def between(self, lo: Fraction, hi: Fraction, limit: int) -> list[Triple] | None:
        """The facts with lo ≤ value ≤ hi (None when more than ``limit``: a scan is as cheap)."""
        start = bisect.bisect_left(self._keys, (lo,))
        out = []
        for key in self._keys[start:]:
            if key[0] > hi:
                break
            out.append(self._facts[key])
            if len(out) > limit:
                return None
        return out

    def __len__(self) -> int:
        return len(self._keys)


__all__ = ["IntegerForm", "Linear", "Test", "ValueIndex", "integer_forms", "integer_interval", "interval", "margin",
           "number", "possible", "single_precision", "tests"]
