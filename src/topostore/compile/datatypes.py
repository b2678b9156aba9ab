"""Datatype subsumption: the ranges a data property's told ranges imply.

The value spaces of the OWL 2 datatype map nest (XML Schema Part 2 §3): ``xsd:byte`` ⊂
``xsd:short`` ⊂ ``xsd:int`` ⊂ ``xsd:long`` ⊂ ``xsd:integer`` ⊂ ``xsd:decimal`` ⊂
``owl:rational`` ⊂ ``owl:real``, and the string types under ``xsd:string`` ⊂ ``rdf:PlainLiteral``.
A property whose values are all bytes has every value a short, so ``p rdfs:range xsd:byte``
entails ``p rdfs:range xsd:short``.  With several ranges the values lie in their intersection:
the integer types are intervals (``xsd:short`` ∩ ``xsd:unsignedInt`` is ``[0, 32767]``, inside
``xsd:unsignedShort``), and a datatype restricted by numeric facets narrows its base's interval.
Which literal is in which value space is decided elsewhere (:func:`.snippets.in_datatype`); this
module only names the implied ranges, as schema facts the rules state once.
"""

from __future__ import annotations

import math
import re
import struct
from collections.abc import Iterable
from dataclasses import dataclass
from decimal import ROUND_CEILING, ROUND_FLOOR, Decimal, InvalidOperation
from functools import lru_cache

from pyoxigraph import Literal, NamedNode

from ..rdf.terms import INTEGER_TYPES, Term, sparql
from ..rdf.vocab import OWL, RDF, XSD, rdfs
from . import data_ranges
from .model import TBox
from .reach import reachable
from .rule import Atom, Rule

#: Each datatype's direct super-datatypes (value-space inclusion), integers apart (intervals).
#: an integer's canonical-enough lexical form (a sign, digits): what :func:`surely_in` decides alone
_INTEGER_TEXT = re.compile(r"[+-]?[0-9]+")

_PARENTS: dict[str, tuple[str, ...]] = {
    XSD + "integer": (XSD + "decimal",),
    XSD + "decimal": (OWL + "rational",),
    OWL + "rational": (OWL + "real",),
    XSD + "normalizedString": (XSD + "string",),
    XSD + "token": (XSD + "normalizedString",),
    XSD + "language": (XSD + "token",),
    XSD + "NMTOKEN": (XSD + "token",),
    XSD + "Name": (XSD + "token",),
    XSD + "NCName": (XSD + "Name",),
    XSD + "string": (RDF + "PlainLiteral",),
    XSD + "dateTimeStamp": (XSD + "dateTime",),
}
#: The datatype families whose value spaces are pairwise disjoint (OWL 2 Structural Spec. §4).
_FAMILY_TOPS = (OWL + "real", RDF + "PlainLiteral", XSD + "float", XSD + "double", XSD + "boolean",
                XSD + "dateTime", XSD + "hexBinary", XSD + "base64Binary", XSD + "anyURI", RDF + "XMLLiteral")


def _ancestors(dt: str) -> set[str]:
    """``dt`` and every datatype whose value space contains its value space."""
    if dt[len(XSD):] in INTEGER_TYPES and dt.startswith(XSD):
        dt = XSD + "integer"
    return reachable(dt, lambda d: _PARENTS.get(d, ()))


def _family(dt: str) -> str | None:
    """The disjoint family a datatype belongs to (None: unknown, or rdfs:Literal)."""
    tops = [t for t in _ancestors(dt) if t in _FAMILY_TOPS]
    return tops[0] if tops else None


@dataclass
class _Interval:
    """Integers from ``low`` to ``high`` (None: unbounded)."""

    low: int | None = None
    high: int | None = None

    def narrow(self, low: int | None, high: int | None) -> None:
        if low is not None:
            self.low = low if self.low is None else max(self.low, low)
        if high is not None:
            self.high = high if self.high is None else min(self.high, high)

    @property
    def empty(self) -> bool:
        return self.low is not None and self.high is not None and self.low > self.high

    def within(self, low: int | None, high: int | None) -> bool:
        return ((low is None or (self.low is not None and self.low >= low))
                and (high is None or (self.high is not None and self.high <= high)))


#: a bound farther than every bounded integer type's (2**64): facets beyond it are clamped to it
_FAR = Decimal(2 ** 70)


def _facet_bounds(op: str, literal: str) -> tuple[int | None, int | None]:
    """The integer bounds one numeric facet sets (``>= 2.5`` → low 3); (None, None) if unreadable."""
    try:
        v = Decimal(literal.split("^^")[0].strip('"'))
    except InvalidOperation:
        return None, None
    if not v.is_finite():
        return None, None
    v = max(-_FAR, min(_FAR, v))  # beyond every bounded integer type: no huge int is ever built
    up, down = int(v.to_integral_value(ROUND_CEILING)), int(v.to_integral_value(ROUND_FLOOR))
    return {">=": (up, None), ">": (down + 1, None), "<=": (None, down), "<": (None, up - 1)}.get(op, (None, None))


def _base(dt: NamedNode) -> tuple[str, list[tuple[str, str]]]:
    """(the named datatype, its numeric facets) of a told range."""
    found = data_ranges.parts(dt)
    return (found[0].value, found[1]) if found is not None else (dt.value, [])


def implied_ranges(told: Iterable[NamedNode]) -> set[NamedNode]:
    """The named datatypes whose value space contains every value a property with the ``told``
    ranges can have (told ones included).  An empty intersection (no value possible): every
    datatype of the table."""
    bases = [_base(dt) for dt in told]
    integers = _integers(bases)
    everything = set(_PARENTS) | {p for ps in _PARENTS.values() for p in ps} | set(_FAMILY_TOPS) | {
        XSD + k for k in INTEGER_TYPES}
    if _none_in_all(bases):
        return {NamedNode(dt) for dt in everything}
    out: set[str] = set()
    for base, _ in bases:
        out |= _ancestors(base)
    if integers is not None:
        out |= {XSD + k for k, (low, high) in INTEGER_TYPES.items() if integers.within(low, high)}
    return {NamedNode(dt) for dt in out}


def _integers(bases: list[tuple[str, list[tuple[str, str]]]]) -> _Interval | None:
    """The integers every integer datatype of ``bases`` (named, facets) holds; None where there is none."""
    integers, is_integer = _Interval(), False
    for base, facets in bases:
        local = base[len(XSD):] if base.startswith(XSD) else ""
        if local in INTEGER_TYPES:
            is_integer = True
            integers.narrow(*INTEGER_TYPES[local])
            for op, literal in facets:
                integers.narrow(*_facet_bounds(op, literal))
    return integers if is_integer else None


def _none_in_all(bases: list[tuple[str, list[tuple[str, str]]]]) -> bool:
    """Whether no value lies in every one of ``bases``: two of disjoint families, or integer ranges that
    do not meet."""
    families = {_family(b) for b, _ in bases} - {None}
    integers = _integers(bases)
    return len(families) > 1 or (integers is not None and integers.empty)


def disjoint_datatypes(a: NamedNode, b: NamedNode) -> bool:
    """Whether no value lies in both ``a`` and ``b`` (each a named datatype or one restricted by numeric
    facets): they are of two disjoint families, one of them is empty, or they are integer ranges that do
    not overlap, or one is the strings with a language tag and the other the strings without one.  False
    where that is not known (a datatype of the ontology's own)."""
    if is_empty(a) or is_empty(b):
        return True
    bases = [_base(a), _base(b)]
    tagged = [base for base, _ in bases if base == RDF + "langString"]
    if len(tagged) == 1:  # rdf:langString is under rdf:PlainLiteral, beside xsd:string
        other = next(base for base, _ in bases if base != RDF + "langString")
        return XSD + "string" in _ancestors(other) or _family(other) not in (None, RDF + "PlainLiteral")
    return _none_in_all(bases)


def surely_in(value: Term, datatype: str) -> bool:
    """Whether ``value`` certainly lies in ``datatype``'s value space, as the compiled range test
    (:func:`.snippets.in_datatype`) would find: decided here only for an integer literal of an XSD
    integer type in a named integer (or decimal, real, rational) datatype; False means "ask".
    (A robot's range checks ask it of each step's clock and visit time: each part of the literal is
    read once, and the bounds of the pair of types are made once, :func:`_integer_bounds`.)"""
    if not isinstance(value, Literal):
        return False
    return text_surely_in(value.value, value.datatype.value, datatype)


def text_surely_in(text: str, own_type: str, datatype: str) -> bool:
    """:func:`surely_in` of the literal of lexical form ``text`` and datatype IRI ``own_type`` (a caller
    that read them once decides by their texts, and keeps the answer by them)."""
    bounds = _integer_bounds(own_type, datatype)
    if bounds is None:
        return False
    if len(text) > 40 or not _INTEGER_TEXT.fullmatch(text):
        return False
    number = int(text)
    low, high = bounds
    return (low is None or number >= low) and (high is None or number <= high)


@lru_cache(maxsize=1024)  # a few pairs per ontology, asked on every robot step
def _integer_bounds(own_type: str, datatype: str) -> tuple[int | None, int | None] | None:
    """(least, greatest) integer (None: unbounded) that lies in the XSD integer type ``own_type`` and in
    ``datatype`` (a named integer type, or decimal, real, rational: unbounded); None where either is not
    such a type (:func:`surely_in` then says "ask")."""
    own = INTEGER_TYPES.get(own_type[len(XSD):]) if own_type.startswith(XSD) else None
    target = INTEGER_TYPES.get(datatype[len(XSD):]) if datatype.startswith(XSD) else None
    if own is None or (target is None and datatype not in (XSD + "decimal", OWL + "real", OWL + "rational")):
        found = None
    else:
        lows = [b for b in (own[0], None if target is None else target[0]) if b is not None]
        highs = [b for b in (own[1], None if target is None else target[1]) if b is not None]
        found = (max(lows) if lows else None, min(highs) if highs else None)
    return found


def _float_bounds(width: str, facets: list[tuple[str, str]]) -> tuple[float, float] | None:
    """(least, greatest) value of a float or double range restricted by ``facets``, stepping over an
    exclusive bound to the adjacent value (these value spaces are discrete); None if unreadable."""
    fit = _to_float32 if width == "float" else float
    low, high = -math.inf, math.inf
    for op, literal in facets:
        try:
            v = fit(float(literal.split("^^")[0].strip('"')))
        except ValueError:
            return None
        if math.isnan(v):
            return None
        if op in (">", ">="):
            low = max(low, v if op == ">=" else _next(v, math.inf, width))
        else:
            high = min(high, v if op == "<=" else _next(v, -math.inf, width))
    return low, high


def _to_float32(v: float) -> float:
    return struct.unpack("<f", struct.pack("<f", v))[0] if math.isfinite(v) and abs(v) < 3.5e38 else v


def _next(v: float, toward: float, width: str) -> float:
    """The value next to ``v`` toward ``toward`` in the float or double value space."""
    if width != "float":
        return math.nextafter(v, toward)
    if v == 0:
        return math.copysign(1.401298464324817e-45, toward)
    bits = struct.unpack("<i", struct.pack("<f", v))[0]
    bits += 1 if (v < toward) == (v > 0) else -1
    return struct.unpack("<f", struct.pack("<i", bits))[0]


def is_empty(datatype: NamedNode) -> bool:
    """Whether a datatype restricted by numeric facets has no value (an integer range whose bounds
    cross, a float range between two adjacent floats, a decimal range with ``> a`` and ``< a``); a range built
    of others is decided by :func:`.range_values.emptiness`."""
    found = data_ranges.parts(datatype)
    if found is None:
        return False
    base, tests = found[0].value, found[1]
    local = base[len(XSD):] if base.startswith(XSD) else ""
    if local in INTEGER_TYPES:
        interval = _Interval(*INTEGER_TYPES[local])
        for op, literal in tests:
            interval.narrow(*_facet_bounds(op, literal))
        return interval.empty
    if local in ("float", "double"):
        bounds = _float_bounds(local, tests)
        return bounds is not None and bounds[0] > bounds[1]
    if local == "decimal" or base in (OWL + "real", OWL + "rational"):
        return _dense_empty(tests)
    return False


def _dense_empty(tests: list[tuple[str, str]]) -> bool:
    """A range of a dense value space (decimal, rational, real) is empty when its bounds cross."""
    low: tuple[Decimal, bool] | None = None   # (bound, inclusive)
    high: tuple[Decimal, bool] | None = None
    for op, literal in tests:
        try:
            v = Decimal(literal.split("^^")[0].strip('"'))
        except InvalidOperation:
            return False
        if op in (">", ">="):
            low = max(low, (v, op == ">="), key=lambda b: (b[0], not b[1])) if low else (v, op == ">=")
        else:
            high = min(high, (v, op == "<="), key=lambda b: (b[0], b[1])) if high else (v, op == "<=")
    if low is None or high is None:
        return False
    return low[0] > high[0] or (low[0] == high[0] and not (low[1] and high[1]))


def range_rules(tb: TBox) -> list[Rule]:
    """``p rdfs:range D`` for every datatype ``D`` the told ranges of ``p`` imply and the file does
    not state; the rule reads the told range triples, so an explanation ends in them."""
    told: dict[NamedNode, set[NamedNode]] = {}
    for p, dt in tb.data_range:
        told.setdefault(p, set()).add(dt)
    rules = []
    for p, ranges in sorted(told.items(), key=lambda kv: kv[0].value):
        body = tuple(Atom(sparql(p), RANGE, sparql(tb.data_range_node.get((p, dt), dt)))
                     for dt in sorted(ranges, key=lambda t: t.value))
        origin = " and ".join(sorted(_short(dt) for dt in ranges))
        for dt in sorted(implied_ranges(ranges) - ranges, key=lambda t: t.value):
            rules.append(Rule("ext-dt-range", f"{_short(p)} range {origin}: every value is in {_short(dt)}", body,
                              Atom(sparql(p), RANGE, sparql(dt))))
    return rules


def _short(t: NamedNode) -> str:
    return data_ranges.readable(t) or t.value.rsplit("#", 1)[-1]


RANGE = str(rdfs("range"))
LITERAL = rdfs("Literal")

__all__ = ["implied_ranges", "is_empty", "range_rules"]
