"""The data values Pellet 2.3.1 tells apart, and the warning where an inconsistency rests on two it does not.

OWL 2 (Direct Semantics) makes ``5`` and ``"five"`` two values, so a functional data property (or a maximum of
one) holding both is inconsistent; topostore says so.  Pellet 2.3.1 finds two literal values different only
when its datatype reasoner holds them as values of one class and unequal; its classes, as measured through
Owlready2 (``tests/test_functional_values_pellet.py``):

* an integer, or a decimal with no fraction (``"2.0"^^xsd:decimal``), by magnitude: a byte (-128..127), a
  short, an int, a long, a bigger integer (``5`` and ``300`` are never found different, ``300`` and ``400``
  are);
* a decimal with a fraction; a float; a double; a boolean; a date or time of any XSD date/time type;
* a string (plain, ``xsd:string`` and its derived types, ``xsd:anyURI``), compared by its lexical form, but an
  ``xsd:anyURI`` is never a string's value (``"a"^^xsd:anyURI`` and ``"a"`` are two values, as in OWL 2);
* a string of one language tag (``"a"@en`` and ``"b"@en`` are two values; ``"a"@en`` and ``"b"@fr``, or
  ``"a"@en`` and ``"b"``, are never found different).

Two values in different classes are taken as possibly equal: Pellet merges them, keeps one (which one depends
on the order it reads them in) and misses the clash, unless another axiom (a range) rules the kept one out.
That departs from OWL 2, and a robot does not write it in a day's work (it writes one datatype per property,
and a REPLACE leaves one value), so topostore follows OWL 2 and says where it answers otherwise than Pellet:
a :class:`PelletDifferenceWarning` naming the inconsistency, said once the REASON has completed (by
:func:`topostore.ontology.ledger.all_or_nothing`: a warning turned into an error must not undo a good REASON).
It names an inconsistency resting on the two values themselves (the violation holds both), and one resting on
them after equality: two individuals of the violation held different only by entailment (not declared
different) whose values of a functional data property differ, none of them told apart by Pellet (a functional
object property, an inverse-functional one or ``owl:sameAs`` merging individuals whose values tell them
apart in OWL 2 alone).  The values are those topostore holds of each individual, its equals' included.
"""

from __future__ import annotations

import logging
from collections.abc import Iterable
from decimal import Decimal, InvalidOperation
from itertools import combinations
from typing import TYPE_CHECKING

from pyoxigraph import Literal, NamedNode

from ..compile.notices import OntologyWarning, warn
from ..compile.snippets import distinct_values, zoned
from ..rdf.terms import CALENDAR_TYPES, REAL_TYPES, sparql
from ..rdf.vocab import ASSERTED, AUX, DECLARED_DIFFERENT, DIFFERENT, INFERRED, TYPE, XSD, owl
from ..reason import Violation
from ..reason.consistency import short, spelled

if TYPE_CHECKING:  # pragma: no cover
    from ..stores.base import Store

logger = logging.getLogger("topostore.reason")

#: the integer classes of Pellet's datatype reasoner, by magnitude (Java's byte, short, int and long)
_INTEGER_BOUNDS = (("byte", 2 ** 7), ("short", 2 ** 15), ("int", 2 ** 31), ("long", 2 ** 63))
_NUMBERS = {XSD + n for n in REAL_TYPES}
_CALENDAR = {XSD + n for n in CALENDAR_TYPES}
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
    return not kind.startswith("string") or a.value != b.value or _uri(a) != _uri(b)


def _uri(lit: Literal) -> bool:
    return lit.datatype.value == XSD + "anyURI"


def not_told_apart(violation: Violation) -> bool:
    """Whether ``violation`` rests on two literal values Pellet 2.3.1 does not tell apart."""
    values = [v for v in violation.individuals.values() if isinstance(v, Literal)]
    return len(values) == 2 and not told_apart(*values)


def missed_by_pellet(store: Store, violations: Iterable[Violation]) -> list[str]:
    """What to say of each inconsistency Pellet 2.3.1 would miss (a REASON's ``violations``, read on ``store``
    as the REASON left it): resting on two values it does not tell apart, directly or after equality.

    Each such violation is named, even beside another that rests on no such values: Pellet finds that other
    one, but it may rest on a value Pellet dropped when it merged two (a range the dropped value is outside)."""
    texts = []
    for v in violations:
        if not_told_apart(v):
            texts.append(_said(v))
        elif unzoned_stamp(v):
            texts.append(f"{v.message} [{v.rule}]: inconsistent in OWL 2 (an xsd:dateTimeStamp is an xsd:dateTime "
                         "with a time zone); Pellet 2.3.1 takes every xsd:dateTime for an xsd:dateTimeStamp and finds "
                         "the ontology consistent unless another axiom rules the value out")
        elif (merged := _merged_values(store, v)) is not None:
            a, b, p, one, other = merged
            texts.append(_said(v, f", resting on the values {spelled(store.restore(one))} of {short(a)} and "
                                  f"{spelled(store.restore(other))} of {short(b)} of the functional property {short(p)}, "
                                  "which alone make them different",
                               "; or unless another axiom makes the two individuals clash once merged"))
    return texts


def unzoned_stamp(violation: Violation) -> bool:
    """Whether ``violation`` rests on an xsd:dateTime without a time zone being outside xsd:dateTimeStamp (a
    range, a universal, a functional property's existential into it), which Pellet 2.3.1 takes it to be in."""
    values = [v for v in violation.individuals.values() if isinstance(v, Literal)]
    return ("dateTimeStamp" in violation.axiom and len(values) == 1 and values[0].datatype.value == XSD + "dateTime"
            and not zoned(values[0].value))


def _said(v: Violation, resting: str = "", unless: str = "") -> str:
    return (f"{v.message} [{v.rule}]{resting}: inconsistent in OWL 2; Pellet 2.3.1 does not tell these two values "
            f"apart and finds the ontology consistent unless another axiom rules out the one it keeps{unless} (its "
            "datatype reasoner compares values only within one of its classes: integers of one magnitude, decimals, "
            "floats, doubles, booleans, dates and times, strings, strings of one language tag)")


#: the values of a functional data property two individuals hold, distinct in OWL 2, where the individuals are
#: held different by entailment only (not declared different, nor linked by an irreflexive or asymmetric
#: property, which clashes in Pellet once it merges them): asked of two individuals of a violation
_APART_BY_VALUES = f"PREFIX xsd: <{XSD}> " + """SELECT ?p ?v1 ?v2 WHERE {{
  GRAPH {aux} {{ {{ {a} {different} {b} }} UNION {{ {b} {different} {a} }}
    FILTER NOT EXISTS {{ {{ {a} {declared} {b} }} UNION {{ {b} {declared} {a} }} }} }}
  {a} ?p ?v1 . {b} ?p ?v2 . ?p {type} {functional} .
  FILTER NOT EXISTS {{ {{ {a} ?q {b} }} UNION {{ {b} ?q {a} }} ?q {type} ?kind . VALUES ?kind {{ {linked} }} }}
  FILTER(isLiteral(?v1) && isLiteral(?v2) && {distinct})
}}"""


#: the violations that rest on two individuals being different (a functional or inverse-functional property's
#: two values, a maximum cardinality's, sameAs against a difference): only those can rest on a merge
_RESTS_ON_DIFFERENCE = ("prp-fp", "prp-ifp", "cls-maxc", "cls-maxqc", "eq-diff")
_LINKED = f"{sparql(owl('IrreflexiveProperty'))} {sparql(owl('AsymmetricProperty'))}"


def _merged_values(store: Store, v: Violation) -> tuple[NamedNode, NamedNode, NamedNode, Literal, Literal] | None:
    """Two individuals of ``v`` that only values Pellet 2.3.1 does not tell apart hold different, with a
    property and the two values: (a, b, property, a's value, b's value); None where there are none."""
    terms = list(v.individuals.values())
    if not v.rule.startswith(_RESTS_ON_DIFFERENCE) or any(isinstance(t, Literal) for t in terms):
        return None
    for a, b in combinations(dict.fromkeys(t for t in terms if isinstance(t, NamedNode)), 2):
        rows = list(store.query(_APART_BY_VALUES.format(
            aux=AUX, a=sparql(a), b=sparql(b), different=DIFFERENT, declared=DECLARED_DIFFERENT, type=TYPE,
            functional=sparql(owl("FunctionalProperty")), linked=_LINKED,
            distinct=distinct_values("?v1", "?v2")), graphs=[ASSERTED, INFERRED], named=[AUX]))
        pairs = [(r["p"], r["v1"], r["v2"]) for r in rows]
        if pairs and not any(told_apart(one, other) for _, one, other in pairs):
            p, one, other = pairs[0]
            return a, b, p, one, other
    return None


def warn_pellet_differences(texts: Iterable[str]) -> None:
    """Say (a :class:`PelletDifferenceWarning`, and the log) each inconsistency Pellet 2.3.1 would miss, as
    :func:`missed_by_pellet` wrote it."""
    for text in texts:
        logger.warning(text)
        warn(text, PelletDifferenceWarning, stacklevel=3)


__all__ = ["PelletDifferenceWarning", "missed_by_pellet", "not_told_apart", "told_apart", "unzoned_stamp", "value_class",
           "warn_pellet_differences"]
