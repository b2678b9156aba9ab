"""``swrlb:date``, ``swrlb:dateTime`` and ``swrlb:time`` with a bound first argument: the value split into its parts.

``swrlb:date(?t, ?y, ?m, ?d[, ?tz])``, ``swrlb:dateTime(?t, ?y, ?m, ?d, ?h, ?mi, ?s[, ?tz])`` and
``swrlb:time(?t, ?h, ?mi, ?s[, ?tz])`` hold where the parts are those of ``?t``: each part still unbound is
bound (a BIND), each bound one compared (Pellet's ``swrlb:equal``).  Pellet 2.3.1 (``DateTimeOperators``) splits
any value of a Gregorian calendar type, and its parts are what ``XMLGregorianCalendar`` answers, so the rule text
reproduces them:

* a field the value has not (the hour of a date, the year of a time) is ``-2147483648`` (Java's
  ``FIELD_UNDEFINED``), not a failure;
* the seconds are a decimal (the fraction kept), the other parts integers;
* the time zone is a string: ``"Z"`` for UTC, ``"±hh:02d"`` otherwise (its hours, and Pellet's format
  string's literal ``:02d`` for the minutes; an offset under an hour is ``"+00:02d"``).  Without one,
  ``date`` gives ``""``, ``dateTime`` and ``time`` nothing: an unbound time zone then fails, a bound one is
  not compared;
* a value of any other type (a string, a number) is false.

Not translated (the rule is set aside with its notice): an unbound first argument, which Pellet builds from
the parts' lexical forms, and ``dateTime`` or ``time`` with every part bound, which Pellet also evaluates by
building the value from the parts rather than by splitting it, and one unbound variable given for two parts (Pellet
binds each part on its own, and stops with an internal error).
"""

from __future__ import annotations

from collections.abc import Collection

from ..errors import RuleCompileError
from ..rdf.terms import CALENDAR_TYPES
from ..rdf.vocab import XSD
from .comparisons import comparison
from .condition import Condition, bind, test

#: Java's ``DatatypeConstants.FIELD_UNDEFINED``: the part Pellet gives for a field the value has not
UNDEFINED = "-2147483648"

_CALENDAR = ", ".join(f"<{XSD}{t}>" for t in sorted(CALENDAR_TYPES))

#: the parts after the value, by built-in: the SPARQL function reading each (the time zone last)
_PARTS = {
    "date": ("YEAR", "MONTH", "DAY"),
    "dateTime": ("YEAR", "MONTH", "DAY", "HOURS", "MINUTES", "SECONDS"),
    "time": ("HOURS", "MINUTES", "SECONDS"),
}
#: the built-ins whose value without a time zone gives none (``date`` gives ``""``)
_NO_ZONE = frozenset({"dateTime", "time"})

NAMES = frozenset(_PARTS)


def _part(function: str, value: str) -> str:
    return f"COALESCE({function}({value}), {UNDEFINED})"


def _zone(value: str) -> str:
    """The time zone as Pellet writes it (``String.format("%+03d:02d", minutes / 60, …)``)."""
    tz = f"TZ({value})"
    return (f'IF({tz} IN ("", "Z"), {tz}, IF(STRSTARTS({tz}, "-00:"), "+00:02d", '
            f'CONCAT(SUBSTR({tz}, 1, 3), ":02d")))')


def translate(local: str, args: list[str], bound: set[str], numbers: Collection[str]) -> tuple[Condition, ...] | None:
    """The conditions of ``swrlb:date``/``swrlb:dateTime`` (``local``) on argument texts ``args``, the first
    bound: a test that it is a calendar value, then per part a BIND or a comparison (None while the first
    argument is unbound and some part too: it may be bound by another built-in).  Raises
    :class:`RuleCompileError` for a wrong arity and for the forms Pellet evaluates by building the value."""
    functions = _PARTS[local]
    if not len(functions) + 1 <= len(args) <= len(functions) + 2:
        raise RuleCompileError(f"swrlb:{local} takes {len(functions) + 1} or {len(functions) + 2} arguments, "
                               f"got {len(args)}")

    def is_bound(a: str) -> bool:
        return not a.startswith("?") or a in bound

    value, parts = args[0], args[1:]
    if not is_bound(value):
        if all(is_bound(a) for a in parts):
            raise RuleCompileError(f"swrlb:{local} with an unbound first argument (building the value from its "
                                   "parts) is not translated")
        return None
    if local in _NO_ZONE and all(is_bound(a) for a in parts):
        raise RuleCompileError(f"swrlb:{local} with every part bound (Pellet builds the value from the parts' "
                               "lexical forms and compares) is not translated")
    unbound = [a for a in parts if not is_bound(a)]
    if len(set(unbound)) < len(unbound):
        raise RuleCompileError(f"swrlb:{local} with a variable given for two unbound parts is not translated "
                               "(Pellet stops on it: its parts are bound one by one)")
    out = [test(f"isLiteral({value}) && datatype({value}) IN ({_CALENDAR})")]
    for i, arg in enumerate(parts):
        is_zone = i == len(functions)
        expr = _zone(value) if is_zone else _part(functions[i], value)
        if not is_bound(arg):
            if is_zone and local in _NO_ZONE:
                out.append(test(f'TZ({value}) != ""'))
            out.append(bind(expr, arg))
            continue
        check = comparison("equal", arg, expr, numbers if is_zone else {*numbers, expr})
        out.append(test(f'(TZ({value}) = "" || {check})' if is_zone and local in _NO_ZONE else check))
    return tuple(out)


def number_part(local: str, args: list[str], variable: str) -> bool:
    """Whether ``variable`` is bound by a numeric part (every part but the time zone)."""
    return variable in args[1:len(_PARTS[local]) + 1]
