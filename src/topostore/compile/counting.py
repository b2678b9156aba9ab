"""Cardinalities by counting: the compiled form of ``≥ n`` / ``≤ n`` that does not grow with n.

A minimum cardinality holds when an individual has n values that are pairwise
different; a maximum is violated when it has n + 1 of them.  Asking for n
values as an n-way self-join with n(n-1)/2 difference tests costs about kⁿ for
k values and makes a query text that grows as n², which the store's parser
cannot even take past a few hundred (the process dies).  A set of values is
also pairwise different, without any pairwise test, when

* they are literals with different values: the number of different values is
  ``COUNT(DISTINCT key)`` over a canonical key of each literal's value
  (:func:`literal_key`); this is exact for data properties;
* they are individuals holding keys of one ``owl:AllDifferent`` group, each key
  naming another member: ``COUNT(DISTINCT key)`` per group.  Two keys of one
  group on one individual (or on two individuals that are the same) make the
  ontology inconsistent by eq-diff2, so counting keys never counts one
  individual twice in a consistent ontology.

For individuals declared different in other ways (``owl:differentFrom``,
disjoint classes, two values of a functional data property) a count needs the
largest set of pairwise-different values, a clique in the difference graph:
no fixed query computes it.  The compiler keeps the exact pairwise form for
small n (:data:`PAIRWISE_MAX`, data values included) and, above it, counts:
exactly for literals, only group members for individuals, which it says with
the warning :data:`COUNTED_ONLY` (:func:`counting_warning`).
"""

from __future__ import annotations

import re

from ..rdf.vocab import AUX, DIFFERENT_KEY_OF, KEY_PREFIX, XSD
from . import condition as cond
from .condition import Condition
from .notices import INCOMPLETE, Notice
from .rule import Atom
from .snippets import STRINGS

#: up to this n, cardinalities keep the pairwise form (exact for every kind of difference);
#: its cost grows as C(k, n) for k values, so it stays small
PAIRWISE_MAX = 3
#: a cardinality at or above this can never be reached by a store (counts are 64-bit integers)
UNREACHABLE = 2 ** 62
#: name of the warning for cardinalities above PAIRWISE_MAX on object properties
COUNTED_ONLY = "cardinality-counted-by-group"

_EPOCH = f'"1970-01-01T00:00:00Z"^^<{XSD}dateTime>'


def literal_key(var: str) -> str:
    """A SPARQL expression naming the value of literal ``var``: equal values, equal keys.

    Numbers of the decimal types and doubles/floats that are whole or decimal
    map to their decimal value (``1``, ``"01"^^xsd:int`` and ``1.0e0`` are one
    value, as SPARQL's ``=`` says); NaN and the infinities keep their double form;
    a dateTime with a timezone maps to its distance from the epoch (one instant
    in two timezones is one value); any other literal is its datatype (one for xsd:string and the
    types derived from it), lower-case language tag and lexical form.  One difference from the pairwise test's
    ``!=``: a float whose decimal expansion is not the decimal it was written as
    (``"0.1"^^xsd:float`` against ``0.1``) is a second value here, as OWL's disjoint
    value spaces say, where ``!=`` compares both as floats and finds them equal.
    """
    kind = f'IF(DATATYPE({var}) IN ({STRINGS}), "s", STR(DATATYPE({var})))'  # "a" is "a"^^xsd:token
    term = f'CONCAT("l:", {kind}, "|", LCASE(LANG({var})), "|", STR({var}))'
    number = f'COALESCE(CONCAT("n:", STR(<{XSD}decimal>({var}))), CONCAT("d:", STR({var})))'
    instant = f'COALESCE(CONCAT("t:", STR({var} - {_EPOCH})), {term})'
    return (f"IF(isNumeric({var}), {number}, "
            f"IF(DATATYPE({var}) = <{XSD}dateTime> && TZ({var}) != \"\", {instant}, {term}))")


def group_of(key: str) -> str:
    """The AllDifferent group part of a key ``urn:topostore:key:<group>:<member>``."""
    return f'STRBEFORE(STRAFTER(STR({key}), "{KEY_PREFIX}"), ":")'


def key_atom(individual: str, key: str) -> Atom:
    """Body atom: ``individual`` holds the AllDifferent key ``key`` (helper graph; the key is the subject)."""
    return Atom(key, f"<{DIFFERENT_KEY_OF.value}>", individual, aux=True)


def _pattern_text(atoms: list[Atom], conditions: list[Condition]) -> str:
    lines = [f"GRAPH <{AUX.value}> {{ {a.text()} }}" if a.aux else a.text() for a in atoms]
    return " ".join(lines + [c.text for c in conditions])


def count_at_least(x: str, values: list[Atom], tests: list[Condition], value: str, n: int,
                   data: bool) -> tuple[list[Atom], list[Condition]]:
    """(extra body atoms, conditions) requiring ``x`` to have at least ``n`` values known different.

    ``values`` and ``tests`` say that ``value`` is a value of ``x`` (the rule body
    has them too, so that a new value triggers the rule); for object values the
    body also gets the value's group key, so that new keys trigger it as well.
    The count is one grouped subquery joined on ``x`` (and the group): its text
    is the same for every n.
    """
    inner = value + "_c"
    rename = {value: inner}
    inner_atoms = [Atom(*(rename.get(t, t) for t in (a.s, a.p, a.o)), aux=a.aux) for a in values]
    same = re.compile(re.escape(value) + r"(?!\w)")
    inner_tests = [cond.test(same.sub(inner, t.expression)) for t in tests]
    if data:
        inner_tests.append(cond.bind(literal_key(inner), "?count_key"))
        group = f"{{ SELECT {x} WHERE {{ {_pattern_text(inner_atoms, inner_tests)} }} GROUP BY {x} " \
                f"HAVING (COUNT(DISTINCT ?count_key) >= {n}) }}"
        return [], [Condition(cond.PATTERN, group, reads_graph=True, written=group)]
    key, inner_key = "?count_key", "?count_key_c"
    inner_atoms.append(key_atom(inner, inner_key))
    inner_tests.append(cond.bind(group_of(inner_key), "?count_group"))
    group = f"{{ SELECT {x} ?count_group WHERE {{ {_pattern_text(inner_atoms, inner_tests)} }} " \
            f"GROUP BY {x} ?count_group HAVING (COUNT(DISTINCT {inner_key}) >= {n}) }}"
    return [key_atom(value, key)], [cond.bind(group_of(key), "?count_group"),
                                    Condition(cond.PATTERN, group, reads_graph=True, written=group)]


def counting_notice(restriction: str) -> Notice:
    """The notice of an object cardinality above :data:`PAIRWISE_MAX` (one per restriction), kind
    :data:`COUNTED_ONLY`: what it does not reason completely."""
    return Notice(INCOMPLETE, restriction,
                  f"more than {PAIRWISE_MAX} values are counted only among members of one owl:AllDifferent; "
                  "individuals different only by owl:differentFrom, disjoint classes or functional values are "
                  "not counted", axiom_kind=COUNTED_ONLY)


__all__ = ["COUNTED_ONLY", "PAIRWISE_MAX", "UNREACHABLE", "count_at_least", "counting_notice", "group_of",
           "key_atom", "literal_key"]
