"""A difference-by-values flip left out when no partner value may equal a replaced value (reason/equal_values.py).

The keys must never be finer than SPARQL's equality (a pair SPARQL calls equal that the keys keep
apart would leave out a flip that happens); the step with a partner of equal value, written in another
lexical form or datatype, must still lose and regain the difference, as reasoning from scratch does.
"""

from __future__ import annotations

import pytest
from pyoxigraph import Literal, NamedNode, Store, Triple
from test_incremental import N, assert_same_as_scratch, new_map, revisit

from topostore.rdf.vocab import AUX, DIFFERENT, XSD
from topostore.reason.equal_values import EqualityIndex, difference_pairs, may_equal

A, B, P = NamedNode("urn:a"), NamedNode("urn:b"), NamedNode("urn:p")


def lit(value: str, local: str) -> Literal:
    return Literal(value, datatype=NamedNode(XSD + local))


def sparql_equal(a: Literal, b: Literal) -> bool:
    """What pyoxigraph answers for ``!distinct_values(a, b)`` (sameTerm or =, an error counting as unequal)."""
    text = f"ASK {{ FILTER(sameTerm({a}, {b}) || COALESCE({a} = {b}, false)) }}"
    return bool(Store().query(text))


VALUES = [lit("1", "integer"), lit("01", "integer"), lit("1", "int"), lit("1", "long"), lit("1.0", "decimal"),
          lit("1.0E0", "double"), lit("1", "float"), lit("1.1", "float"), lit("1.100000023841858", "double"),
          lit("1.1", "double"), lit("1.1", "decimal"), lit("NaN", "double"), lit("INF", "double"),
          lit("INF", "float"), lit("abc", "integer"), lit("abc", "string"), lit("ABC", "string"),
          lit("true", "boolean"), lit("1", "boolean"), lit("2022-01-01T00:00:00Z", "dateTime"),
          lit("2022-01-01T01:00:00+01:00", "dateTime"), Literal("abc", language="en"), Literal("abc", language="EN"),
          lit("-0", "integer"), lit("0.0", "double"), lit("-0.0E0", "double")]


@pytest.mark.parametrize("a", VALUES, ids=str)
def test_values_sparql_calls_equal_are_found(a: Literal) -> None:
    for b in VALUES:
        if sparql_equal(a, b):
            assert EqualityIndex([Triple(B, P, b)]).other_subject(a, str(A)), (a, b)
            assert may_equal(a, b), (a, b)


def test_distinct_values_do_not_meet() -> None:
    """Visit times a second apart stay apart (no float literal: the single-precision keys never meet)."""
    pairs = [(lit("1665579750", "integer"), lit("1665579751", "long")), (lit("a", "string"), lit("b", "string")),
             (NamedNode("urn:a"), NamedNode("urn:b"))]
    for a, b in pairs:
        assert not EqualityIndex([Triple(B, P, b)]).other_subject(a, str(A)), (a, b)
        assert not may_equal(a, b), (a, b)
    assert not EqualityIndex([Triple(B, P, lit("1.5", "float"))]).other_subject(lit("2", "integer"), str(A))


def test_the_index_knows_other_subjects_only() -> None:
    a, b, p = NamedNode("urn:a"), NamedNode("urn:b"), NamedNode("urn:p")
    index = EqualityIndex([Triple(a, p, lit("5", "integer"))])
    assert not index.other_subject(lit("5", "long"), str(a))
    assert index.other_subject(lit("5", "long"), str(b)) and index.other_subject(lit("5.0", "decimal"), None)
    index.add(Triple(b, p, lit("05", "integer")))
    assert index.other_subject(lit("5", "integer"), str(a))
    index.discard(Triple(b, p, lit("05", "integer")))
    assert not index.other_subject(lit("5", "integer"), str(a))


@pytest.mark.parametrize("a", VALUES, ids=str)
def test_values_added_later_are_found_as_from_the_start(a: Literal) -> None:
    """An index that held no xsd:float probes numbers in double precision only; a float added later
    (and one added then removed, then added again for another subject) is still met in single precision."""
    for b in VALUES:
        if not sparql_equal(a, b):
            continue
        index = EqualityIndex([Triple(B, P, lit("7", "integer"))])
        index.add(Triple(B, P, b))
        assert index.other_subject(a, str(A)), (a, b)
        index.discard(Triple(B, P, b))
        index.add(Triple(NamedNode("urn:c"), P, b))
        assert index.other_subject(a, str(A)), (a, b)


def test_an_integer_meets_a_float_equal_only_in_single_precision() -> None:
    """16777217 is no xsd:float; compared with the float 16777216 it is promoted, and then equal."""
    a, f = lit("16777217", "integer"), lit("16777216", "float")
    assert sparql_equal(a, f)
    index = EqualityIndex([Triple(B, P, lit("3", "integer"))])
    assert not index.other_subject(a, str(A))
    index.add(Triple(B, P, f))
    assert index.other_subject(a, str(A))


def _difference_rule(onto):
    rules = onto.rules.inference_rules
    found = [r for r in rules if r.head.p == f"<{DIFFERENT.value}>" and len(r.conditions) == 1
             and any("visitedAt" in a.p for a in r.body)]
    assert found, "the map's TBox gives a difference by visitedAt values"
    return found[0]


def test_the_difference_rule_is_decided_by_equality() -> None:
    rule = _difference_rule(new_map(3, 0, False))
    changed = [j for j, a in enumerate(rule.body) if "visitedAt" in a.p]
    assert difference_pairs(rule, changed) == [tuple(changed)]


@pytest.mark.parametrize("form", ["integer", "long", "decimal"])
def test_a_partner_of_equal_value_flips_the_difference(form: str) -> None:
    """R1 takes C1's visit time (in another lexical form or datatype): their difference by values is
    lost, then regained when R1 moves on; an unrelated visit in between leaves it alone."""
    onto = new_map(3, 0, False)
    revisit(onto, "C1", 1665579750)
    revisit(onto, "R1", 1665579760)
    assert_same_as_scratch(onto)
    pair = Triple(N("R1"), DIFFERENT, N("C1"))
    assert pair in set(onto.store.triples(graph=AUX))
    same = "1665579750.0" if form == "decimal" else "01665579750"
    onto.replace(N("R1"), N("visitedAt"), onto.value(same, form))
    assert_same_as_scratch(onto)
    assert pair not in set(onto.store.triples(graph=AUX))
    revisit(onto, "R2", 1665579770)
    assert_same_as_scratch(onto)
    revisit(onto, "R1", 1665579790)
    assert_same_as_scratch(onto)
    assert pair in set(onto.store.triples(graph=AUX))
