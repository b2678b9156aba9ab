"""Deciding without a query that a difference-by-values flip finds nothing.

Why this exists
---------------
A rule that concludes two things differ because their values of a predicate
differ (``?a p ?v1 . ?b p ?v2`` with ``distinct_values(?v1, ?v2)``, see
:func:`~..compile.snippets.distinct_values`) is a flip rule of every clean
replacement of ``p`` (:mod:`.flip`): the robot's ``visitedAt`` moves each step.
Its flip query pairs the replaced subject with every candidate partner; it
costs as much as the rest of the step's flips and almost always finds nothing,
because a pair's answer can only change when the partner's value *equals* the
old or the new value.  An index of the predicate's values by equality answers
that in a dictionary look-up: when no partner value may equal them, nothing
flips and the query is left out; otherwise the query runs as before.

Equality here is SPARQL's ``sameTerm`` or ``=``, approximated from above (a value
that may be equal is always found, see :func:`probe_keys`): a
shared key only costs the query that would have run anyway.
"""

from __future__ import annotations

import math
import struct
from collections.abc import Collection, Iterable
from decimal import Decimal, InvalidOperation
from functools import lru_cache

from pyoxigraph import Literal, Triple

from ..compile.condition import BIND, TEST
from ..compile.rule import Rule
from ..compile.snippets import distinct_values
from ..rdf.terms import CALENDAR_TYPES, NUMERIC_TYPES, REAL_TYPES
from ..rdf.vocab import XSD
from .flip import compared_only

#: XSD types whose values SPARQL compares as numbers (promoted to a common type)
_NUMERIC = NUMERIC_TYPES
#: XSD types whose values SPARQL compares by value in ways not modelled here (time zones): one key for all
_TEMPORAL = CALENDAR_TYPES | {"duration", "dayTimeDuration", "yearMonthDuration"}


def _double(local: str, text: str) -> float | None:
    """The value as an xsd:double; None for an ill-typed lexical form (in no value space: only
    ``sameTerm`` can make it equal) or NaN (equal to nothing).  Forms Python reads more liberally
    than XSD (``1_000``) get a value too: a key too many only ever costs the query."""
    text = text.strip()
    try:
        if local in REAL_TYPES:
            try:
                value = float(int(text))
            except ValueError:
                value = float(Decimal(text))
        else:
            value = float(text.replace("INF", "inf"))
    except (InvalidOperation, ValueError, OverflowError):
        return None
    return None if math.isnan(value) else value


def _single(value: float) -> float:
    """``value`` rounded to an xsd:float (single precision), as SPARQL promotes a value compared with one."""
    try:
        return struct.unpack("f", struct.pack("f", value))[0]
    except OverflowError:
        return math.copysign(math.inf, value)


def _around(value: float, single: bool) -> list[float]:
    """``value`` and its two neighbours in its precision: a conversion rounded otherwise still meets it."""
    if not math.isfinite(value):
        return [value]
    if not single:
        return [math.nextafter(value, -math.inf), value, math.nextafter(value, math.inf)]
    bits = struct.unpack("<i", struct.pack("<f", value))[0]
    out = [value]
    for near in (bits - 1, bits + 1):
        if -2 ** 31 <= near < 2 ** 31:
            other = struct.unpack("<f", struct.pack("<i", near))[0]
            if not math.isnan(other):
                out.append(other)
    return out


def _kind(term) -> tuple[str, object]:
    """What decides a term's equality: ("number", (local, double)), ("other", keys) or ("term", text)."""
    if not isinstance(term, Literal):
        return "term", str(term)
    dt = term.datatype.value
    local = dt[len(XSD):] if dt.startswith(XSD) else ""
    if local in _NUMERIC:
        value = _double(local, term.value)
        return ("term", str(term)) if value is None else ("number", (local, value))
    if local in _TEMPORAL:
        return "other", ("temporal",)
    if local == "boolean" and term.value.strip() in ("true", "false", "1", "0"):
        return "other", ("boolean", term.value.strip() in ("true", "1"))
    return "other", ("lexical", term.value.lower())


def _stored(term) -> tuple[tuple, ...]:
    kind, what = _kind(term)
    if kind == "number":
        local, value = what
        return (("double", value), ("single", _single(value))) if local == "float" else (("double", value),)
    return ((kind, what),) if kind == "term" else (what,)


@lru_cache(maxsize=4096)
def stored_keys(term) -> tuple:
    """The keys a value is indexed under (see :func:`probe_keys`): numbers by their double, an
    xsd:float also by its single-precision value; a term SPARQL cannot compare by value (an IRI,
    an ill-typed literal) by itself.  An index counts apart its numbers that are no xsd:float."""
    return _stored(term)


@lru_cache(maxsize=4096)
def probe_keys(term) -> tuple:
    """Keys such that a value SPARQL may call equal to ``term`` (``sameTerm`` or ``=``) is indexed
    under one of them (:func:`stored_keys`), but for a number no xsd:float compared with an xsd:float
    (see :meth:`EqualityIndex.other_subject`).

    Coarser than SPARQL where exactness would need its rules in full: numbers meet in double
    precision, and an xsd:float in single precision (SPARQL compares a pair with one as floats),
    each with its neighbours; every date or time meets every other; every other literal meets
    those of the same lexical form, whatever their datatype."""
    kind, what = _kind(term)
    if kind != "number":
        return ((kind, what),) if kind == "term" else (what,)
    local, value = what
    return tuple([("double", v) for v in _around(value, False)] + [("single", v) for v in _around(_single(value), True)])


@lru_cache(maxsize=4096)
def double_keys(term) -> tuple[tuple, bool]:
    """:func:`probe_keys` without the single-precision keys, and whether ``term`` is a number of
    type xsd:float: enough against an index that holds no xsd:float (only an xsd:float is stored
    under a single-precision key), at a third of the cost for a number."""
    kind, what = _kind(term)
    if kind != "number":
        return (((kind, what),) if kind == "term" else (what,)), False
    return tuple(("double", v) for v in _around(what[1], False)), what[0] == "float"


def may_equal(a, b) -> bool:
    """Whether SPARQL may call ``a`` and ``b`` equal (as :class:`EqualityIndex` answers, for one pair)."""
    if _is_float(a) and not _is_float(b) and _kind(b)[0] == "number":
        return True
    return not set(probe_keys(a)).isdisjoint(stored_keys(b))


def _is_float(term) -> bool:
    return isinstance(term, Literal) and term.datatype.value == XSD + "float"


class EqualityIndex:
    """The subjects of one predicate's facts by :func:`stored_keys` of their values (one subject
    kept as its text, several as a count per subject), and the numbers that are no xsd:float."""

    def __init__(self, triples: Iterable[Triple]) -> None:
        self._subjects: dict[tuple, str | dict[str, int]] = {}
        self._numbers: dict[str, int] = {}
        #: whether an xsd:float was ever added (never unset: a float's single-precision keys may be held)
        self._floats = False
        for t in triples:
            self._add(t, _stored(t.object))

    def add(self, t: Triple) -> None:
        self._add(t, stored_keys(t.object))

    def _add(self, t: Triple, keys: tuple) -> None:
        subject = str(t.subject)
        for key in keys:
            held = self._subjects.get(key)
            if held is None:
                self._subjects[key] = subject
                continue
            if isinstance(held, str):
                held = self._subjects[key] = {held: 1}
            held[subject] = held.get(subject, 0) + 1
        if keys[0][0] == "double":
            if _is_float(t.object):
                self._floats = True
            else:
                self._numbers[subject] = self._numbers.get(subject, 0) + 1

    def discard(self, t: Triple) -> None:
        """Forget one fact (a fact never added leaves the index as it is: it only ever over-answers)."""
        subject = str(t.subject)
        keys = stored_keys(t.object)
        for key in keys:
            held = self._subjects.get(key)
            if held == subject:
                del self._subjects[key]
            elif isinstance(held, dict) and subject in held:
                held[subject] -= 1
                if not held[subject]:
                    del held[subject]
                    if not held:
                        del self._subjects[key]
        if keys[0][0] == "double" and not _is_float(t.object) and self._numbers.get(subject):
            self._numbers[subject] -= 1
            if not self._numbers[subject]:
                del self._numbers[subject]

    def other_subject(self, value, subject: str | None) -> bool:
        """Whether a fact whose subject is not ``subject`` (None: any) may have a value equal to
        ``value`` (an xsd:float: whenever another subject holds a number that is no xsd:float)."""
        keys, number_float = double_keys(value)
        for key in probe_keys(value) if self._floats else keys:
            held = self._subjects.get(key)
            if held is not None and _other(held, subject):
                return True
        return number_float and _other(self._numbers, subject)


def _other(held: str | dict[str, int], subject: str | None) -> bool:
    if isinstance(held, str):
        return held != subject
    return bool(held) and (subject is None or len(held) > 1 or subject not in held)


def difference_pairs(rule: Rule, changed: Collection[int]) -> list[tuple[int, int]] | None:
    """The (atom, atom) pairs whose values the rule's tests on the ``changed`` atoms' values compare,
    when every condition mentioning one of those values is ``distinct_values`` of two compared-only
    atoms' values on named predicates (else None: the flip cannot be decided by equality)."""
    values = {rule.body[j].o for j in changed}
    holder = {atom.o: j for j, atom in enumerate(rule.body) if compared_only(rule, j)}
    pairs = []
    for c in rule.conditions:
        if not (c.variables & values):
            continue
        if c.kind == BIND or c.kind != TEST or len(c.variables) != 2:
            return None
        a, b = sorted(c.variables)
        if c.expression not in (distinct_values(a, b), distinct_values(b, a)) or a not in holder or b not in holder:
            return None
        pairs.append((holder[a], holder[b]))
    return pairs


__all__ = ["EqualityIndex", "difference_pairs", "double_keys", "may_equal", "probe_keys", "stored_keys"]
