"""SWRL built-ins (swrlb) → SPARQL expressions.

Each built-in either *tests* its arguments (a FILTER) or, for the arithmetic and
string functions whose first argument is the result, *binds* the first argument
when it is still unbound (a BIND) and compares it when it is bound (a FILTER).  A BIND is
followed by :func:`defined`: the built-in holds only where its value could be computed.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Collection, Mapping

from pyoxigraph import Literal, NamedNode

from ..errors import RuleCompileError
from ..rdf.terms import Term
from ..rdf.vocab import POW_FUNCTION, SWRLB, XSD, xsd
from . import calendar_builtins
from .comparisons import OPERATORS, comparison
from .condition import Condition, bind, test

_COMPARISONS = OPERATORS


def _trunc_div(a: str, b: str) -> str:
    return f"xsd:integer(IF(({a} / {b}) < 0, CEIL({a} / {b}), FLOOR({a} / {b})))"


def _pow(a: str, b: str) -> str:
    if b.isdigit() or (b.startswith('"') and b.split('"')[1].isdigit() and "integer" in b):
        n = int(b) if b.isdigit() else int(b.split('"')[1])
        if n <= 16:
            return "1" if n == 0 else "(" + " * ".join([a] * n) + ")"
    return f"{POW_FUNCTION}({a}, {b})"


# name -> (minimum args after the result, maximum (None = any), expression builder)
_FUNCTIONS: dict[str, tuple[int, int | None, Callable[[list[str]], str]]] = {
    "add": (1, None, lambda a: "(" + " + ".join(a) + ")"),
    "subtract": (2, 2, lambda a: f"({a[0]} - {a[1]})"),
    "multiply": (1, None, lambda a: "(" + " * ".join(a) + ")"),
    "divide": (2, 2, lambda a: f"({a[0]} / {a[1]})"),
    "integerDivide": (2, 2, lambda a: _trunc_div(a[0], a[1])),
    "mod": (2, 2, lambda a: f"({a[0]} - {a[1]} * {_trunc_div(a[0], a[1])})"),
    "pow": (2, 2, lambda a: _pow(a[0], a[1])),
    "unaryPlus": (1, 1, lambda a: f"(+{a[0]})"),
    "unaryMinus": (1, 1, lambda a: f"(-{a[0]})"),
    "abs": (1, 1, lambda a: f"ABS({a[0]})"),
    "round": (1, 1, lambda a: f"ROUND({a[0]})"),
    "floor": (1, 1, lambda a: f"FLOOR({a[0]})"),
    "ceiling": (1, 1, lambda a: f"CEIL({a[0]})"),
    "stringConcat": (0, None, lambda a: "CONCAT(" + ", ".join(f"STR({x})" for x in a) + ")" if a else '""'),
    # the string built-ins read a value's lexical form, as Pellet does (the length of 123 is 3)
    "stringLength": (1, 1, lambda a: f"STRLEN(STR({a[0]}))"),
    # fn:upper-case, fn:lower-case and fn:substring give an xs:string: SPARQL's functions keep a language tag
    "upperCase": (1, 1, lambda a: f"UCASE(STR({a[0]}))"),
    "lowerCase": (1, 1, lambda a: f"LCASE(STR({a[0]}))"),
    "substring": (2, 3, lambda a: f"SUBSTR({', '.join([f'STR({a[0]})', *a[1:]])})"),
}

_TESTS: dict[str, tuple[int, int, Callable[[list[str]], str]]] = {
    "contains": (2, 2, lambda a: f"CONTAINS(STR({a[0]}), STR({a[1]}))"),
    "containsIgnoreCase": (2, 2, lambda a: f"CONTAINS(LCASE(STR({a[0]})), LCASE(STR({a[1]})))"),
    "startsWith": (2, 2, lambda a: f"STRSTARTS(STR({a[0]}), STR({a[1]}))"),
    "endsWith": (2, 2, lambda a: f"STRENDS(STR({a[0]}), STR({a[1]}))"),
    "matches": (2, 3, lambda a: f"REGEX(STR({a[0]}), {_whole(a[1])})"),
}

_PLAIN_STRING = re.compile(r'"((?:[^"\\\n\r]|\\.)*)"')


def _whole(pattern: str) -> str:
    """swrlb:matches as Pellet evaluates it: the pattern matches the whole string (Java's
    ``Pattern.matches``), and a flags argument is ignored.  SPARQL's REGEX searches, so the pattern is
    anchored as a group: ``a|b`` stays ``^(?:a|b)$``, and a pattern's own ``^``/``$`` still hold."""
    plain = _PLAIN_STRING.fullmatch(pattern)
    if plain is not None:
        return f'"^(?:{plain.group(1)})$"'
    return f'CONCAT("^(?:", STR({pattern}), ")$")'


SUPPORTED = sorted(set(_COMPARISONS) | set(_FUNCTIONS) | set(_TESTS) | calendar_builtins.NAMES)
#: the SWRL built-ins of the submission Pellet 2.3.1 does not register (its ``BuiltInRegistry``): a rule using one
#: draws nothing there, as here, where it is set aside; the date and duration arithmetic among them
NOT_IN_PELLET = frozenset({
    "addYearMonthDurations", "subtractYearMonthDurations", "multiplyYearMonthDuration", "divideYearMonthDurations",
    "addDayTimeDurations", "subtractDayTimeDurations", "multiplyDayTimeDurations", "divideDayTimeDuration",
    "subtractDates", "subtractTimes", "addYearMonthDurationToDateTime", "addDayTimeDurationToDateTime",
    "subtractYearMonthDurationFromDateTime", "subtractDayTimeDurationFromDateTime", "addYearMonthDurationToDate",
    "addDayTimeDurationToDate", "subtractYearMonthDurationFromDate", "subtractDayTimeDurationFromDate",
    "addDayTimeDurationToTime", "subtractDayTimeDurationFromTime", "subtractDateTimesYieldingYearMonthDuration",
    "subtractDateTimesYieldingDayTimeDuration", "listConcat", "listIntersection", "listSubtraction", "member",
    "length", "first", "rest", "sublist", "empty"})


def conditions(name: str, args: list[str], bound: set[str],
               numbers: Collection[str] = ()) -> tuple[Condition, ...] | None:
    """The conditions for built-in ``name`` with argument texts ``args``: :func:`translate`'s one, or for
    ``swrlb:date`` and ``swrlb:dateTime`` a test and a BIND or comparison per part (:mod:`.calendar_builtins`);
    None when it cannot run yet."""
    local = name.removeprefix(SWRLB)
    if name.startswith(SWRLB) and local in calendar_builtins.NAMES:
        return calendar_builtins.translate(local, args, bound, numbers)
    one = translate(name, args, bound, numbers)
    return None if one is None else (one,)


def translate(name: str, args: list[str], bound: set[str], numbers: Collection[str] = ()) -> Condition | None:
    """The condition for built-in ``name`` with argument texts ``args`` (``numbers``: the variables known to hold
    a number, :func:`gives_number`).

    Returns a test (``FILTER(...)``), a BIND of the first argument (``?r``,
    :attr:`Condition.binds`) when it is still unbound, or None when it cannot run yet (some input
    argument is still unbound; the caller retries after other built-ins).
    Raises :class:`RuleCompileError` for unknown built-ins or wrong arity, and for the built-ins of several
    conditions (:func:`conditions` gives them).
    """
    local = name[len(SWRLB):] if name.startswith(SWRLB) else None
    if local is None or local not in set(SUPPORTED):
        unknown = " (Pellet does not evaluate it either, and ignores the rule)" if local in NOT_IN_PELLET else ""
        raise RuleCompileError(f"unsupported built-in {name}{unknown}; supported: swrlb:{', swrlb:'.join(SUPPORTED)}")

    def is_bound(a: str) -> bool:
        return not a.startswith("?") or a in bound

    if local in calendar_builtins.NAMES:
        raise RuleCompileError(f"swrlb:{local} is several conditions: see conditions()")
    if local in _COMPARISONS:
        if len(args) != 2:
            raise RuleCompileError(f"swrlb:{local} takes 2 arguments, got {len(args)}")
        if all(is_bound(a) for a in args):
            return test(comparison(local, args[0], args[1], numbers))
        if local == "equal" and is_bound(args[1]):
            return bind(args[1], args[0])
        return None
    if local in _TESTS:
        lo, hi, build = _TESTS[local]
        if not lo <= len(args) <= hi:
            raise RuleCompileError(f"swrlb:{local} takes {lo}..{hi} arguments, got {len(args)}")
        return test(build(args)) if all(is_bound(a) for a in args) else None
    lo, hi, build = _FUNCTIONS[local]
    inputs = args[1:]
    if len(args) < 1 or len(inputs) < lo or (hi is not None and len(inputs) > hi):
        raise RuleCompileError(f"swrlb:{local} takes a result and {lo}..{hi or 'n'} arguments, got {len(args)} in all")
    if not all(is_bound(a) for a in inputs):
        return None
    expr = build(inputs)
    if is_bound(args[0]):
        return test(f"{args[0]} = {expr}")
    return bind(expr, args[0])


#: built-ins false (a SPARQL error) on any argument that is not a data value: an IRI has no number,
#: and ``<``/``>`` compare no IRIs; ``=``, ``<=`` and the string functions (``STR``) do take one
_STRICT = frozenset(_FUNCTIONS) - {"stringConcat", "stringLength", "upperCase", "lowerCase", "substring"} \
    | {"lessThan", "greaterThan"} | calendar_builtins.NAMES


#: the functions whose result is a number (the arithmetic ones, and a string's length)
_NUMBER_RESULTS = frozenset(_FUNCTIONS) - {"stringConcat", "upperCase", "lowerCase", "substring"}


def gives_number(name: str, args: list[str], variable: str) -> bool:
    """Whether built-in ``name`` (full IRI) on argument texts ``args`` binds ``variable`` to a number."""
    local = name.removeprefix(SWRLB)
    if local in calendar_builtins.NAMES:
        return calendar_builtins.number_part(local, args, variable)
    return local in _NUMBER_RESULTS


def is_strict(name: str) -> bool:
    """Whether built-in ``name`` (full IRI) already fails where an argument is not a data value."""
    return name.removeprefix(SWRLB) in _STRICT


def defined(variable: str) -> Condition:
    """The test that a built-in's computed result, or an argument it reads, is a data value.

    Pellet's built-ins take data values only: on an individual (its IRI) they are false, where
    SPARQL's functions would read the IRI's text (``STR``) or compare IRIs (``=``).

    A SPARQL error in ``BIND(expr AS ?r)`` leaves ``?r`` unbound and keeps the row, so without it a
    rule whose built-in cannot be computed (``"abc" + 1``, a division by zero) would still fire; Pellet's
    built-in then fails.  ``isLiteral`` of an unbound variable is an error, hence false.
    """
    return test(f"isLiteral({variable})")


# --------------------------------------------------------------------------- run time
#: largest integer result swrlb:pow computes (bits); beyond it the built-in gives no value
POW_MAX_BITS = 4096


def pow_value(base: Term, exponent: Term) -> Literal | None:
    """swrlb:pow for a non-constant exponent, as the store evaluates ``POW_FUNCTION``.

    Integers with a non-negative integer exponent stay integers; anything else
    is computed as a double.  Non-numbers give no value (the rule does not fire),
    and so does an integer result past ``POW_MAX_BITS``: a number that large is no
    measurement, and computing it would freeze the service.
    """
    if not isinstance(base, Literal) or not isinstance(exponent, Literal):
        return None
    try:
        if base.datatype.value.startswith(XSD) and "." not in base.value \
                and "e" not in base.value.lower() and exponent.value.lstrip("+").isdigit():
            b, e = int(base.value), int(exponent.value)
            if abs(b) > 1 and e * abs(b).bit_length() > POW_MAX_BITS:
                return None
            return Literal(str(b ** e), datatype=xsd("integer"))
        return Literal(repr(float(base.value) ** float(exponent.value)), datatype=xsd("double"))
    except (ValueError, OverflowError, ZeroDivisionError):
        return None


#: The extension functions compiled rules call, handed to the store that runs them
#: (:meth:`topostore.stores.base.Store.use_functions`); the store itself knows nothing of rules.
FUNCTIONS: Mapping[NamedNode, Callable[..., Term | None]] = {POW_FUNCTION: pow_value}
