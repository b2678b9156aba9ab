"""Flip windows (topostore.reason.window): the interval holds every value whose test answer flips."""

from __future__ import annotations

import operator
from fractions import Fraction

from hypothesis import given, settings
from hypothesis import strategies as st
from profiles import property_examples
from pyoxigraph import Literal, NamedNode, Triple

from topostore.compile import condition
from topostore.compile.rule import Atom, Rule
from topostore.rdf.vocab import xsd
from topostore.reason import window

OPS = {">": operator.gt, ">=": operator.ge, "<": operator.lt, "<=": operator.le, "=": operator.eq,
       "!=": operator.ne}


def rule_with(*conditions) -> Rule:
    body = (Atom("?r", "<urn:x:now>", "?t"), Atom("?r", "<urn:x:limit>", "?h"), Atom("?l", "<urn:x:at>", "?v"))
    return Rule("r", "test", body, Atom("?l", "<urn:x:p>", "<urn:x:o>"), tuple(conditions))


def test_builtin_chain_is_read_as_one_linear_test() -> None:
    found = window.tests(rule_with(condition.bind("(?t - ?v)", "?d"), condition.test("?d > ?h")))
    assert found == [window.Test(({"t": 1, "v": -1, "h": -1}, Fraction(0)), frozenset({"t", "v", "h"}))]


def test_a_non_linear_test_gives_no_form() -> None:
    found = window.tests(rule_with(condition.bind("(?t * ?v)", "?d"), condition.test("?d > ?h"), condition.test("isLiteral(?v)")))
    assert [f.form for f in found] == [None, None]
    assert found[0].variables == frozenset({"t", "v", "h"})
    rows = window.interval(found, "v", "t", Fraction(1), Fraction(2), {"h": Fraction(0)}, Fraction(0))
    assert rows is None  # a test on t that is not linear: no window


def test_tests_that_do_not_read_the_seed_never_flip() -> None:
    found = window.tests(rule_with(condition.test("?v > ?h")))
    assert window.interval(found, "v", "t", Fraction(1), Fraction(9), {"h": Fraction(0)}, Fraction(0)) is False


coef = st.integers(-3, 3)
small = st.integers(-40, 40)


@settings(max_examples=property_examples(300), deadline=None)
@given(a=coef, c=coef, e=coef, k=small, op=st.sampled_from(sorted(OPS)), old=small, new=small, h=small)
def test_every_flipping_value_lies_in_the_window(a: int, c: int, e: int, k: int, op: str, old: int, new: int,
                                                 h: int) -> None:
    """Brute force over integer values of v: a test ``a·v + c·t + e·h + k op 0`` that answers differently
    for t = old and t = new does so only inside the interval."""
    text = f"({_sum(a, 'v')} + {_sum(c, 't')} + {_sum(e, 'h')} + {k}) {op} 0"
    found = window.tests(rule_with(condition.test(text)))
    span = window.interval(found, "v", "t", Fraction(old), Fraction(new), {"h": Fraction(h)}, Fraction(0))
    flipping = [v for v in range(-200, 201)
                if OPS[op](a * v + c * old + e * h + k, 0) != OPS[op](a * v + c * new + e * h + k, 0)]
    if span is None:  # only a test that reads t but not v, and whose value changed, gives no window
        assert a == 0 and c != 0 and old != new
        return
    if span is False:
        assert flipping == []
        return
    assert all(span[0] <= v <= span[1] for v in flipping), (span, flipping)


def _sum(n: int, var: str) -> str:
    """``n·?var`` written with + and - only (the form the swrlb arithmetic compiles to)."""
    if n == 0:
        return "0"
    return "(" + " + ".join([f"?{var}"] * n) + ")" if n > 0 else "(0 - " + " - ".join([f"?{var}"] * -n) + ")"


def test_multiplication_by_a_constant_is_not_linear_here() -> None:
    """Only + and - are read: a product gives no window (the flip query scans), never a wrong one."""
    assert window.tests(rule_with(condition.test("(2 * ?v) > ?t")))[0].form is None


def fact(s: str, value: str, datatype: str = "integer") -> Triple:
    return Triple(NamedNode(f"urn:x:{s}"), NamedNode("urn:x:at"), Literal(value, datatype=xsd(datatype)))


def test_value_index_finds_the_facts_between_two_values() -> None:
    facts = [fact(f"l{i}", str(i * 10)) for i in range(10)] + [fact("d", "25.5", "decimal"), fact("x", "abc", "string")]
    index = window.ValueIndex(facts)
    assert len(index) == 11  # the string is no number
    assert set(index.between(Fraction(20), Fraction(30), 100)) == {facts[2], facts[3], facts[10]}
    assert index.between(Fraction(0), Fraction(90), 5) is None  # more than the limit: scan instead
    index.discard(facts[3])
    index.add(fact("new", "29"))
    assert set(index.between(Fraction(20), Fraction(30), 100)) == {facts[2], facts[10], fact("new", "29")}


def test_numbers_are_read_exactly() -> None:
    assert window.number(Literal("7", datatype=xsd("long"))) == 7
    assert window.number(Literal("0.1", datatype=xsd("decimal"))) == Fraction(1, 10)
    assert window.number(Literal("NaN", datatype=xsd("double"))) is None
    assert window.number(Literal("seven", datatype=xsd("integer"))) is None
    assert window.number(Literal("7")) is None
