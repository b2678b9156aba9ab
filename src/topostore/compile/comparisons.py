"""The SWRL comparison built-ins (``swrlb:equal``, ``notEqual``, ``lessThan`` …) as Pellet 2.3.1 evaluates them.

Why not SPARQL's operators alone: SPARQL compares values of one kind and makes every other comparison an error
(false in a FILTER), where Pellet's testers (``ComparisonTesters``) answer otherwise on values of different kinds:

* ``equal``: numbers by value across their types; the strings (``xsd:string`` and the types derived from it
  Pellet knows: ``normalizedString``, ``token``, ``language``, ``Name``, ``NCName``) by their characters,
  whatever the type (``"ab"^^xsd:token`` equals ``"ab"``); any other value only a value of its own kind (two
  booleans by value, two instants by time line, two literals of one other datatype as written);
* ``notEqual``: exactly where ``equal`` is false, between any two data values (``"5"^^xsd:token`` is not
  equal to 5, a boolean to a date, ``"a"@en`` to ``"a"``);
* NaN (float or double) as Java's ``compareTo`` has it: equal to a NaN, above every other number (``NaN > INF``);
* the orderings: numbers by value; the strings above by their characters, across those types; two instants
  of comparable types by time line; two literals of one datatype and language tag Pellet does not order by
  value (``xsd:anyURI``, ``xsd:hexBinary``, a tagged string, a datatype of the ontology's own) by their
  characters; booleans never (not even ``<=`` two equal ones); any two values of different kinds never.

A comparison with a number known to be one (a numeric constant, or the result of an arithmetic built-in) is
SPARQL's operator itself, which already answers so: the form a robot step's rules take
(``swrlb:greaterThan(?elapsed, ?threshold)`` after a ``swrlb:subtract``), kept as the look-up path
evaluates it (:mod:`topostore.reason.look_filters`).
"""

from __future__ import annotations

from collections.abc import Collection

from pyoxigraph import Literal

from ..rdf.terms import CALENDAR_TYPES, NUMERIC_TYPES, parse_term
from ..rdf.vocab import XSD
from .snippets import STRING_TYPES

OPERATORS = {
    "equal": "=", "notEqual": "!=", "lessThan": "<", "lessThanOrEqual": "<=",
    "greaterThan": ">", "greaterThanOrEqual": ">=",
}
#: the string datatypes Pellet compares by their characters, across the types: OWL 2's, NMTOKEN left out
_STRINGS = ", ".join(f"<{XSD}{t}>" for t in STRING_TYPES if t != "NMTOKEN")
#: the datatypes of instants and dates, compared on the time line (SPARQL's operators, as Pellet's facets do)
_TEMPORAL = ", ".join(f"<{XSD}{t}>" for t in sorted(CALENDAR_TYPES))
#: the datatypes whose values are not ordered by their characters (strings, instants, booleans)
_BY_VALUE = f"{_STRINGS}, {_TEMPORAL}, <{XSD}boolean>"


def comparison(name: str, a: str, b: str, numbers: Collection[str]) -> str:
    """The SPARQL test of comparison built-in ``name`` (local name) on argument texts ``a`` and ``b``, both
    bound; ``numbers``: the variables known to hold a number."""
    op = OPERATORS[name]
    if (_number(a, numbers) or _number(b, numbers)) and not (_nan_constant(a) or _nan_constant(b)):
        if name == "notEqual":
            return f"COALESCE({a} != {b}, true)"
        # NaN above every number: a value read from the graph may be NaN; a number computed by an arithmetic
        # built-in is taken as none (a NaN result is not followed), so a robot's greaterThan(?elapsed,
        # ?threshold) keeps its plain form (a NaN threshold answers false there, as Pellet does)
        above = b if name in ("lessThan", "lessThanOrEqual") else a if name.startswith("greater") else None
        if above is not None and above.startswith("?") and not _number(above, numbers):
            return f"({a} {op} {b} || {_nan(above)})"
        return f"{a} {op} {b}"
    if name == "equal":
        return _equal(a, b)
    if name == "notEqual":
        return f"(isLiteral({a}) && isLiteral({b}) && !{_equal(a, b)})"
    return (f"COALESCE(IF({_nan(a)} || {_nan(b)}, {_nan_order(name, a, b)}, "
            f"IF({_string(a)} && {_string(b)}, STR({a}) {op} STR({b}), "
            f"IF({_by_characters(a)} && sameTerm(datatype({a}), datatype({b})) && lang({a}) = lang({b}), "
            f"STR({a}) {op} STR({b}), (isNumeric({a}) || datatype({a}) IN ({_TEMPORAL})) && {a} {op} {b}))), false)")


def _nan(v: str) -> str:
    """``v`` is a NaN (float or double): the one number SPARQL finds unequal to itself."""
    return f"COALESCE(isNumeric({v}) && {v} != {v}, false)"


def _nan_order(name: str, a: str, b: str) -> str:
    """An ordering with a NaN, as Java's ``compareTo`` in Pellet's testers: NaN equals NaN and is above every
    other number (never comparable with a value of another kind)."""
    a_above = f"({_nan(a)} && isNumeric({b}))"  # a >= b
    b_above = f"({_nan(b)} && isNumeric({a}))"  # a <= b
    return {"lessThan": f"(!{_nan(a)} && {b_above})", "lessThanOrEqual": b_above,
            "greaterThan": f"(!{_nan(b)} && {a_above})", "greaterThanOrEqual": a_above}[name]


def _equal(a: str, b: str) -> str:
    """Pellet's equality: SPARQL's, two strings of the string types by their characters, and two NaNs (float
    or double: Java's ``compareTo``, where SPARQL's ``=`` follows IEEE 754)."""
    return (f"(COALESCE({a} = {b}, false) || "
            f"COALESCE({_string(a)} && {_string(b)} && STR({a}) = STR({b}), false) || ({_nan(a)} && {_nan(b)}))")


def _string(v: str) -> str:
    return f"(isLiteral({v}) && datatype({v}) IN ({_STRINGS}))"


def _by_characters(v: str) -> str:
    """A literal Pellet orders by its characters against one of its own datatype and tag (no number, no
    string type, no instant, no boolean)."""
    return f"(isLiteral({v}) && !isNumeric({v}) && !(datatype({v}) IN ({_BY_VALUE})))"


def _nan_constant(text: str) -> bool:
    """Whether argument ``text`` is a NaN written as a constant: it takes the general forms, which order and
    equate NaNs as Pellet's testers do (the plain number forms follow IEEE 754)."""
    if text.startswith("?"):
        return False
    term = parse_term(text)
    return isinstance(term, Literal) and term.value == "NaN" and term.datatype.value in (XSD + "float", XSD + "double")


def _number(text: str, numbers: Collection[str]) -> bool:
    """Whether argument ``text`` is surely a number: a variable of ``numbers`` or a numeric constant."""
    if text.startswith("?"):
        return text in numbers
    term = parse_term(text)
    return isinstance(term, Literal) and term.datatype.value.startswith(XSD) \
        and term.datatype.value[len(XSD):] in NUMERIC_TYPES


__all__ = ["OPERATORS", "comparison"]
