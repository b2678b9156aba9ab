"""A rule's conditions on the look-up path keep their answers by the terms they read (reason/look_join.Conditions).

A kept answer must be the one the evaluator gives for those terms: the same terms answer alike whatever
else the solution holds, other terms are evaluated again, the three-valued answer (``holds``) and the
one that needs every test to be a boolean (``strict``) are kept apart, and an unbound variable is never
confused with a bound one.
"""

from __future__ import annotations

from pyoxigraph import Literal, NamedNode

from topostore.compile import condition
from topostore.compile.rule import Atom, Rule
from topostore.reason import look_join
from topostore.reason.look_join import Conditions
from topostore.reason.look_values import UNKNOWN

XSD = "http://www.w3.org/2001/XMLSchema#"
R, L = NamedNode("urn:x:r"), NamedNode("urn:x:l")


def num(n: int | str) -> Literal:
    return Literal(str(n), datatype=NamedNode(XSD + "integer"))


def _rule(*conditions) -> Rule:
    body = (Atom("?r", "<urn:x:now>", "?t"), Atom("?l", "<urn:x:at>", "?v"), Atom("?r", "<urn:x:h>", "?h"))
    return Rule("urgent", "test", body, Atom("?l", "<urn:x:p>", "?r"), conditions=tuple(conditions))


def test_the_same_terms_answer_alike_and_other_terms_are_evaluated() -> None:
    c = Conditions(_rule(condition.bind("(?t - ?v)", "?d"), condition.test("?d > ?h")))
    base = {"?r": R, "?l": L, "?h": num(10)}
    assert c.holds({**base, "?t": num(100), "?v": num(80)}) is True
    assert c.holds({**base, "?t": num(100), "?v": num(95)}) is False
    # another location with the same values: the answer kept for those values
    assert c.holds({**base, "?l": NamedNode("urn:x:m"), "?t": num(100), "?v": num(95)}) is False
    assert c.strict({**base, "?t": num(100), "?v": num(80)}) is True
    # a value the evaluator does not model (not canonical): UNKNOWN, kept as such, never another's answer
    assert c.holds({**base, "?t": num("0100"), "?v": num(80)}) is UNKNOWN
    assert c.holds({**base, "?t": num(100), "?v": num(80)}) is True


def test_three_valued_and_strict_answers_are_kept_apart() -> None:
    """``false && error`` is false in SPARQL, yet not a boolean for every test (``strict``)."""
    c = Conditions(_rule(condition.test("?t > 5"), condition.test("?v > 5")))
    s = {"?r": R, "?l": L, "?h": num(1), "?t": num(1), "?v": Literal("x", datatype=NamedNode(XSD + "date"))}
    assert c.holds(s) is False
    assert c.strict(s) is UNKNOWN
    assert c.holds(s) is False


def test_an_unbound_variable_is_evaluated_not_kept() -> None:
    c = Conditions(_rule(condition.test("?t > ?w")))
    assert c.holds({"?t": num(3)}) is UNKNOWN
    assert c.holds({"?t": num(3), "?w": num(2)}) is True


def test_past_the_limit_the_answers_are_forgotten_not_mixed(monkeypatch) -> None:
    monkeypatch.setattr(look_join, "_ANSWERS_MAX", 4)
    c = Conditions(_rule(condition.test("?t > ?h")))
    for n in range(20):
        assert c.holds({"?t": num(n), "?h": num(10)}) is (n > 10)
    for n in range(20):
        assert c.strict({"?t": num(n), "?h": num(10)}) is (n > 10)
