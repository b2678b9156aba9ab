"""The data values Pellet 2.3.1 tells apart, and the warning where an inconsistency rests on two it does not.

OWL 2 (Direct Semantics) makes ``5`` and ``"five"`` two values, so a functional data property (or a maximum of
one) holding both is inconsistent; topostore says so.  Pellet 2.3.1 finds two literal values different only
when its datatype reasoner holds them as values of one class and unequal; its classes, as measured through
Owlready2 (``tests/test_functional_values_pellet.py``):

* an integer, or a decimal with no fraction (``"2.0"^^xsd:decimal``), by magnitude: a byte (-128..127), a
  short, an int, a long, a bigger integer (``5`` and ``300`` are never found different, ``300`` and ``400``
  are);
* a decimal with a fraction; a float; a double; a boolean; a date or time of any XSD date/time type;
* a string (plain, ``xsd:string`` and its derived types, ``xsd:anyURI``), compared by its lexical form;
* a string of one language tag (``"a"@en`` and ``"b"@en`` are two values; ``"a"@en`` and ``"b"@fr``, or
  ``"a"@en`` and ``"b"``, are never found different).

Two values in different classes are taken as possibly equal: Pellet merges them, keeps one (which one depends
on the order it reads them in) and misses the clash, unless another axiom (a range) rules the kept one out.
That departs from OWL 2, and a robot does not write it in a day's work (it writes one datatype per property,
and a REPLACE leaves one value), so topostore follows OWL 2 and says where it answers otherwise than Pellet:
a :class:`PelletDifferenceWarning` naming the inconsistency, said once the REASON has completed (by
:func:`topostore.ontology.ledger.all_or_nothing`: a warning turned into an error must not undo a good REASON).
It names an inconsistency resting on the two values themselves (the violation holds both); one resting on them
only indirectly (two individuals told different by such values, then merged by a functional object property)
is reported without it: telling that apart would mean tracing why the individuals differ.
"""

from __future__ import annotations

import logging
import warnings
from collections.abc import Iterable
from decimal import Decimal, InvalidOperation

from pyoxigraph import Literal

from ..compile.notices import OntologyWarning
from ..rdf.vocab import XSD
from ..reason import Violation

logger = logging.getLogger("topostore.reason")

#: the integer classes of Pellet's datatype reasoner, by magnitude (Java's byte, short, int and long)
_INTEGER_BOUNDS = (("byte", 2 ** 7), ("short", 2 ** 15), ("int", 2 ** 31), ("long", 2 ** 63))
_NUMBERS = {XSD + n for n in ("decimal", "integer", "nonNegativeInteger", "nonPositiveInteger", "negativeInteger",
                              "positiveInteger", "long", "int", "short", "byte", "unsignedLong", "unsignedInt",
                              "unsignedShort", "unsignedByte")}
_CALENDAR = {XSD + n for n in ("dateTime", "dateTimeStamp", "date", "time", "gYear", "gYearMonth", "gMonth",
                               "gMonthDay", "gDay")}
_STRINGS = {XSD + n for n in ("string", "normalizedString", "token", "language", "Name", "NCName", "NMTOKEN",
                              "anyURI")}
_SINGLE = {XSD + "float": "float", XSD + "double": "double", XSD + "boolean": "boolean"}


class PelletDifferenceWarning(OntologyWarning):
    """topostore knowingly answers otherwise than Pellet 2.3.1: an inconsistency rests on two data values that
    OWL 2 makes different and Pellet 2.3.1 does not tell apart (see :mod:`topostore.ontology.pellet_values`)."""


def value_class(lit: Literal) -> str:
    """The class of Pellet's datatype reasoner that holds ``lit``'s value (its datatype where none is known)."""
    if lit.language is not None:
        return "string@" + lit.language.lower()
    dt = lit.datatype.value
    if dt in _NUMBERS:
        return _number_class(lit.value)
    if dt in _STRINGS:
        return "string"
    if dt in _CALENDAR:
        return "calendar"
    return _SINGLE.get(dt, dt)


def _number_class(lexical: str) -> str:
    try:
        number = Decimal(lexical.strip())
    except InvalidOperation:
        return "ill-typed"
    if number != number.to_integral_value():
        return "decimal"
    whole = int(number)
    return next((name for name, bound in _INTEGER_BOUNDS if -bound <= whole < bound), "big integer")


def told_apart(a: Literal, b: Literal) -> bool:
    """Whether Pellet 2.3.1 finds ``a`` and ``b`` different values (both known different in OWL 2)."""
    kind = value_class(a)
    if kind != value_class(b):
        return False
    return not kind.startswith("string") or a.value != b.value


def not_told_apart(violation: Violation) -> bool:
    """Whether ``violation`` rests on two literal values Pellet 2.3.1 does not tell apart."""
    values = [v for v in violation.individuals.values() if isinstance(v, Literal)]
    return len(values) == 2 and not told_apart(*values)


def warn_pellet_differences(violations: Iterable[Violation]) -> list[Violation]:
    """Say (a :class:`PelletDifferenceWarning`, and the log) which inconsistencies Pellet 2.3.1 would miss;
    returns them."""
    missed = [v for v in violations if not_told_apart(v)]
    for v in missed:
        text = (f"{v.message} [{v.rule}]: inconsistent in OWL 2; Pellet 2.3.1 does not tell these two values apart "
                "and finds the ontology consistent unless another axiom rules out the one it keeps (its datatype "
                "reasoner compares values only within one of its classes: integers of one magnitude, decimals, floats, "
                "doubles, booleans, dates and times, strings, strings of one language tag)")
        logger.warning(text)
        warnings.warn(text, PelletDifferenceWarning, stacklevel=3)
    return missed


__all__ = ["PelletDifferenceWarning", "not_told_apart", "told_apart", "value_class", "warn_pellet_differences"]
