"""SWRL compiler: every atom kind, every supported built-in, disabled and refused rules.

Each test writes a small Turtle ontology with one rule.  Expected values come
from the SWRL submission (W3C Member Submission 2004, §8 "Built-Ins", whose
functions follow XPath/XQuery Functions and Operators) unless a comment says
otherwise.
"""

from __future__ import annotations

from decimal import Decimal

import pytest
from pyoxigraph import Literal
from swrl_support import NS, PREFIXES, arg, builtin, cls, data, data_range, diff, obj, rule, same

from topostore import Ontology, RuleCompileError
from topostore.rdf.vocab import ASSERTED, INFERRED


def ontology(rules: str, facts: str = "", schema: str = "") -> Ontology:
    o = Ontology()
    o.load_data(PREFIXES + schema + facts + rules, "turtle")
    report = o.reason()
    assert report.consistent, report.explain()
    return o


def names(o: Ontology, cls_name: str) -> set[str]:
    return {o.short(i) for i in o.instances(cls_name)}


def values(o: Ontology, prop: str, ind: str) -> list[Literal]:
    return o.data_values(prop, ind)


def number(lit: Literal) -> Decimal:
    return Decimal(lit.value)


# ---------------------------------------------------------------- atom kinds

def test_class_atom_with_variable_and_individual():
    # SWRL semantics: A(?x) -> B(?x); A(:a) -> C(:b) (individual arguments)
    o = ontology(
        rule([cls(":A", "?x")], [cls(":B", "?x")], "vars")
        + rule([cls(":A", ":a")], [cls(":C", ":b")], "inds"),
        ":a a :A . :z a :Z .",
    )
    assert names(o, "B") == {"a"}
    assert names(o, "C") == {"b"}


def test_individual_property_atom_with_variables_and_individuals():
    # p(?x, ?y) -> q(?y, ?x); p(?x, :c) -> Hit(?x); Hit(?x) -> q(:c, ?x)
    o = ontology(
        rule([obj(":p", "?x", "?y")], [obj(":q", "?y", "?x")], "swap")
        + rule([obj(":p", "?x", ":c")], [cls(":Hit", "?x")], "const")
        + rule([cls(":Hit", "?x")], [obj(":r", ":c", "?x")], "head-ind"),
        ":a :p :b . :d :p :c .",
    )
    assert set(o.object_values("q", "b")) == {"a"}
    assert set(o.object_values("q", "c")) == {"d"}
    assert names(o, "Hit") == {"d"}
    assert set(o.object_values("r", "c")) == {"d"}


def test_datavalued_property_atom_with_variable_and_literal():
    # v(?x, 5) matches the value 5 (also as another integer type: one data value);
    # head with a literal argument asserts that literal
    o = ontology(
        rule([data(":v", "?x", 5)], [cls(":Five", "?x")], "lit")
        + rule([data(":v", "?x", "?y")], [data(":w", "?x", "?y")], "copy")
        + rule([cls(":Five", "?x")], [data(":tag", "?x", '"five"')], "head-lit"),
        ':a :v 5 . :b :v 6 . :c :v "5"^^xsd:long .',
    )
    assert names(o, "Five") == {"a", "c"}
    assert [v.value for v in values(o, "w", "b")] == ["6"]
    assert [v.value for v in values(o, "tag", "a")] == ["five"]


def test_same_individual_atom_body_and_head():
    # SameAs(?x, ?y) in a body holds for x = y and for declared owl:sameAs; in a head it asserts owl:sameAs
    o = ontology(
        rule([obj(":p", "?x", "?y"), same("?x", "?y")], [cls(":SelfOrSame", "?x")], "body")
        + rule([obj(":twin", "?x", "?y")], [same("?x", "?y")], "head"),
        ":a :p :a . :b :p :c . :d :p :e . :d owl:sameAs :e . :m :twin :n . :m a :M .",
    )
    assert names(o, "SelfOrSame") >= {"a", "d"}
    assert "b" not in names(o, "SelfOrSame")
    assert o.sparql(f"ASK {{ <{NS}m> <http://www.w3.org/2002/07/owl#sameAs> <{NS}n> }}")
    assert names(o, "M") == {"m", "n"}  # OWL 2 RL eq-rep-s


def test_different_individuals_atom_needs_declared_difference():
    # No unique name assumption: DifferentFrom(?x, ?y) holds only when declared (differentFrom or AllDifferent)
    o = ontology(
        rule([obj(":p", "?x", "?y"), diff("?x", "?y")], [cls(":Diff", "?x")], "body"),
        ":a :p :b . :c :p :d . :e :p :f . :a owl:differentFrom :b . "
        "[] a owl:AllDifferent ; owl:distinctMembers ( :e :f :g ) .",
    )
    assert names(o, "Diff") == {"a", "e"}


def test_different_individuals_atom_in_a_head():
    # DifferentFrom in a head asserts owl:differentFrom, which a later DifferentFrom body atom sees
    o = ontology(
        rule([obj(":apart", "?x", "?y")], [diff("?x", "?y")], "head")
        + rule([obj(":apart", "?x", "?y"), diff("?x", "?y")], [cls(":Apart", "?x")], "body"),
        ":a :apart :b .",
    )
    assert o.sparql(f"ASK {{ <{NS}a> <http://www.w3.org/2002/07/owl#differentFrom> <{NS}b> }}")
    assert names(o, "Apart") == {"a"}


def test_data_range_atom():
    # xsd:integer(?v) holds for integer values only (SWRL DataRangeAtom)
    o = ontology(
        rule([data(":v", "?x", "?y"), data_range("xsd:integer", "?y")], [cls(":Int", "?x")], "dr")
        + rule([data(":v", "?x", "?y"), data_range("xsd:string", "?y")], [cls(":Str", "?x")], "dr2"),
        ':a :v 5 . :b :v "x" . :c :v 2.5 . :d :v "7"^^xsd:long .',
    )
    assert names(o, "Int") == {"a", "d"}
    assert names(o, "Str") == {"b"}


def test_builtin_with_individual_literal_and_variable_arguments():
    # swrlb:equal with literal arguments on both sides of variables
    o = ontology(
        rule([data(":v", "?x", "?y"), builtin("equal", "?y", 3)], [cls(":Three", "?x")], "eq")
        + rule([data(":v", "?x", "?y"), builtin("notEqual", 3, "?y")], [cls(":NotThree", "?x")], "ne"),
        ":a :v 3 . :b :v 4 . :c :v 3.0 .",
    )
    assert names(o, "Three") == {"a", "c"}  # 3.0 = 3 (numeric equality)
    assert names(o, "NotThree") == {"b"}


# ---------------------------------------------------------------- comparisons

@pytest.mark.parametrize("name,expected", [
    ("equal", {"b"}), ("notEqual", {"a", "c"}), ("lessThan", {"a"}),
    ("lessThanOrEqual", {"a", "b"}), ("greaterThan", {"c"}), ("greaterThanOrEqual", {"b", "c"}),
])
def test_comparison_builtins(name, expected):
    # swrlb comparisons (op:numeric-equal / less-than / greater-than) of ?y against 5
    o = ontology(
        rule([data(":v", "?x", "?y"), builtin(name, "?y", 5)], [cls(":Hit", "?x")], name),
        ":a :v 4 . :b :v 5 . :c :v 6 .",
    )
    assert names(o, "Hit") == expected


def test_comparison_of_strings():
    # swrlb comparisons also order strings (fn:compare)
    o = ontology(
        rule([data(":s", "?x", "?y"), builtin("lessThan", "?y", '"m"')], [cls(":Early", "?x")], "str"),
        ':a :s "apple" . :b :s "zebra" .',
    )
    assert names(o, "Early") == {"a"}


# ---------------------------------------------------------------- arithmetic

def _compute(name: str, inputs: list[object]) -> Ontology:
    args = ["?r"] + [f"?i{k}" if not isinstance(v, str) else v for k, v in enumerate(inputs)]
    body = [data(f":in{k}", "?x", f"?i{k}") for k, v in enumerate(inputs) if not isinstance(v, str)]
    facts = " ".join(f":a :in{k} {arg(v)} ." for k, v in enumerate(inputs) if not isinstance(v, str))
    return ontology(rule(body + [builtin(name, *args)], [data(":out", "?x", "?r")], name), facts)


@pytest.mark.parametrize("name,inputs,expected", [
    ("add", [2, 3], Decimal(5)),
    ("add", [1, 2, 3, 4], Decimal(10)),
    ("subtract", [10, 4], Decimal(6)),
    ("subtract", [4, 10], Decimal(-6)),
    ("multiply", [6, 7], Decimal(42)),
    ("multiply", [2, 3, 4], Decimal(24)),
    ("divide", [7, 2], Decimal("3.5")),
    ("integerDivide", [7, 2], Decimal(3)),
    ("integerDivide", [-7, 2], Decimal(-3)),  # op:numeric-integer-divide truncates toward zero
    ("mod", [7, 3], Decimal(1)),
    ("mod", [-7, 3], Decimal(-1)),  # op:numeric-mod: the sign of the dividend
    ("pow", [2, 10], Decimal(1024)),
    ("pow", [3, 0], Decimal(1)),
    ("unaryMinus", [5], Decimal(-5)),
    ("unaryMinus", [-5], Decimal(5)),
    ("abs", [-8], Decimal(8)),
    ("round", [Decimal("2.5")], Decimal(3)),
    ("round", [Decimal("2.4")], Decimal(2)),
    ("round", [Decimal("-2.5")], Decimal(-2)),  # fn:round: halves toward positive infinity
    ("floor", [Decimal("2.7")], Decimal(2)),
    ("floor", [Decimal("-2.2")], Decimal(-3)),
    ("ceiling", [Decimal("2.2")], Decimal(3)),
    ("ceiling", [Decimal("-2.7")], Decimal(-2)),
], ids=lambda v: str(v))
def test_arithmetic_binds_an_unbound_result(name, inputs, expected):
    # the first argument is unbound: the built-in binds it to the result
    o = _compute(name, inputs)
    out = values(o, "out", "a")
    assert len(out) == 1, out
    assert number(out[0]) == expected


def test_pow_with_literal_exponent():
    # swrlb:pow (op:numeric pow): ?r = 4^3
    o = ontology(
        rule([data(":v", "?x", "?y"), builtin("pow", "?r", "?y", 3)], [data(":cube", "?x", "?r")], "cube"),
        ":a :v 4 .",
    )
    assert number(values(o, "cube", "a")[0]) == 64


@pytest.mark.parametrize("name,result,inputs,holds", [
    ("add", 5, [2, 3], True), ("add", 6, [2, 3], False),
    ("subtract", 6, [10, 4], True), ("subtract", 7, [10, 4], False),
    ("multiply", 42, [6, 7], True), ("divide", Decimal("3.5"), [7, 2], True),
    ("integerDivide", 3, [7, 2], True), ("mod", 1, [7, 3], True), ("mod", 2, [7, 3], False),
    ("pow", 8, [2, 3], True), ("unaryMinus", -5, [5], True), ("abs", 8, [-8], True),
    ("round", 3, [Decimal("2.5")], True), ("floor", 2, [Decimal("2.7")], True),
    ("ceiling", 3, [Decimal("2.2")], True), ("ceiling", 2, [Decimal("2.2")], False),
], ids=lambda v: str(v))
def test_arithmetic_compares_a_bound_result(name, result, inputs, holds):
    # the first argument is bound: the built-in is true iff it equals the result
    body = [data(":res", "?x", "?r")] + [data(f":in{k}", "?x", f"?i{k}") for k in range(len(inputs))]
    facts = f":a :res {arg(result)} . " + " ".join(f":a :in{k} {arg(v)} ." for k, v in enumerate(inputs))
    o = ontology(rule(body + [builtin(name, "?r", *[f"?i{k}" for k in range(len(inputs))])],
                      [cls(":Holds", "?x")], name), facts)
    assert names(o, "Holds") == ({"a"} if holds else set())


def test_arithmetic_with_literal_arguments():
    # arguments may be literals: ?r = ?v + 10, and 15 = ?v + 10 as a test
    o = ontology(
        rule([data(":v", "?x", "?y"), builtin("add", "?r", "?y", 10)], [data(":plus10", "?x", "?r")], "bind")
        + rule([data(":v", "?x", "?y"), builtin("add", 15, "?y", 10)], [cls(":Five", "?x")], "test"),
        ":a :v 5 . :b :v 6 .",
    )
    assert number(values(o, "plus10", "b")[0]) == 16
    assert names(o, "Five") == {"a"}


# ---------------------------------------------------------------- strings

@pytest.mark.parametrize("name,inputs,expected", [
    ("stringConcat", ['"ab"', '"cd"', '"e"'], "abcde"),
    ("upperCase", ['"Robot"'], "ROBOT"),
    ("lowerCase", ['"Robot"'], "robot"),
    ("substring", ['"corridor"', 2, 3], "orr"),  # fn:substring is 1-based
    ("substring", ['"corridor"', 5], "idor"),
], ids=lambda v: str(v))
def test_string_functions(name, inputs, expected):
    # swrlb string functions = fn:concat, fn:upper-case, fn:lower-case, fn:substring (result bound first)
    body = [data(f":in{k}", "?x", f"?i{k}") for k in range(len(inputs))]
    facts = " ".join(f":a :in{k} {arg(v)} ." for k, v in enumerate(inputs))
    o = ontology(rule(body + [builtin(name, "?r", *[f"?i{k}" for k in range(len(inputs))])],
                      [data(":out", "?x", "?r")], name), facts)
    assert [v.value for v in values(o, "out", "a")] == [expected]


def test_string_length_binds_and_compares():
    # swrlb:stringLength = fn:string-length; binds when unbound, compares when bound
    o = ontology(
        rule([data(":s", "?x", "?y"), builtin("stringLength", "?n", "?y")], [data(":len", "?x", "?n")], "bind")
        + rule([data(":s", "?x", "?y"), builtin("stringLength", 4, "?y")], [cls(":Four", "?x")], "test"),
        ':a :s "door" . :b :s "corridor" .',
    )
    assert number(values(o, "len", "b")[0]) == 8
    assert names(o, "Four") == {"a"}


@pytest.mark.parametrize("name,pattern,expected", [
    ("contains", '"rid"', {"corridor"}),
    ("containsIgnoreCase", '"RID"', {"corridor", "RIDGE"}),
    ("startsWith", '"cor"', {"corridor"}),
    ("endsWith", '"dor"', {"corridor"}),
    ("matches", '"^[A-Z]+$"', {"RIDGE"}),
    ("matches", '"co(r+i)+dor"', {"corridor"}),
    ("matches", '"r+i"', set()),  # the whole string, as Pellet matches
])
def test_string_tests(name, pattern, expected):
    # swrlb:contains/containsIgnoreCase/startsWith/endsWith/matches = fn:contains, fn:starts-with,
    # fn:ends-with, fn:matches (containsIgnoreCase compares lower-cased strings)
    o = ontology(
        rule([data(":s", "?x", "?y"), builtin(name, "?y", pattern)], [cls(":Hit", "?x")], name),
        ':corridor :s "corridor" . :RIDGE :s "RIDGE" . :room :s "room" .',
    )
    assert names(o, "Hit") == expected


# ---------------------------------------------------------------- the topological map rules

def test_urgency_rule_shape_from_the_reference_uses_subtract_then_greater_than():
    # the reference Urgency rule: subtract(?d, ?t, ?v) ^ greaterThan(?d, ?h)
    o = ontology(
        rule([data(":now", "?r", "?t"), data(":visitedAt", "?l", "?v"), builtin("subtract", "?d", "?t", "?v"),
              data(":threshold", "?r", "?h"), builtin("greaterThan", "?d", "?h")], [cls(":URGENT", "?l")], "Urgency"),
        ":robot :now 100 ; :threshold 7 . :l1 :visitedAt 92 . :l2 :visitedAt 93 . :l3 :visitedAt 150 .",
    )
    assert names(o, "URGENT") == {"l1"}


def test_builtin_order_does_not_matter():
    # SWRL semantics: a body is a conjunction, so atom order cannot change the result
    # greaterThan written before the subtract that binds its argument
    o = ontology(
        rule([data(":now", "?r", "?t"), builtin("greaterThan", "?d", 7), data(":visitedAt", "?l", "?v"),
              builtin("subtract", "?d", "?t", "?v")], [cls(":URGENT", "?l")], "reordered"),
        ":robot :now 100 . :l1 :visitedAt 92 . :l2 :visitedAt 93 .",
    )
    assert names(o, "URGENT") == {"l1"}


# ---------------------------------------------------------------- enabled / refused rules

def test_disabled_rule_is_skipped_and_unannotated_rule_runs():
    # Protégé/SWRLAPI: swrla:isRuleEnabled false disables a rule; absent means enabled
    o = ontology(
        rule([cls(":A", "?x")], [cls(":Off", "?x")], "off", enabled=False)
        + rule([cls(":A", "?x")], [cls(":On", "?x")], "on", enabled=True)
        + rule([cls(":A", "?x")], [cls(":Plain", "?x")], "plain", enabled=None),
        ":a a :A .",
    )
    assert names(o, "Off") == set()
    assert names(o, "On") == {"a"}
    assert names(o, "Plain") == {"a"}
    assert not any(r.name == "swrl:off" for r in o.rules.rules)


def _refused(text: str) -> str:
    """Loading ``text`` raises RuleCompileError and leaves the ontology as it was (all or nothing)."""
    o = Ontology()
    o.load_data(PREFIXES + ":a a :A . :a :v 5 .", "turtle")
    o.reason()
    before = (o.store.count(ASSERTED), o.store.count(INFERRED))
    with pytest.raises(RuleCompileError) as info:
        o.load_data(PREFIXES + text, "turtle")
    assert (o.store.count(ASSERTED), o.store.count(INFERRED)) == before
    assert o.reason().consistent
    assert names(o, "A") == {"a"}
    assert not o.sparql("ASK { ?r a <http://www.w3.org/2003/11/swrl#Imp> }")
    return str(info.value)


def test_unknown_builtin_is_refused_naming_rule_and_atom():
    message = _refused(rule([data(":v", "?x", "?y"), builtin("tan", "?r", "?y")], [data(":t", "?x", "?r")], "Trig"))
    assert "Trig" in message
    assert "tan" in message and "BuiltinAtom" in message


def test_unbound_head_variable_is_refused_naming_rule_and_atom():
    message = _refused(rule([cls(":A", "?x")], [obj(":p", "?x", "?z")], "Unsafe"))
    assert "Unsafe" in message
    assert "?z" in message and "IndividualPropertyAtom" in message


def test_builtin_with_inputs_never_bound_is_refused():
    message = _refused(rule([cls(":A", "?x"), builtin("greaterThan", "?y", 3)], [cls(":B", "?x")], "Unbound"))
    assert "Unbound" in message and "greaterThan" in message


def test_unsupported_atom_is_refused_naming_rule_and_atom():
    bad = "[ a swrl:WeirdAtom ; swrl:argument1 var:x ]"
    message = _refused(rule([cls(":A", "?x"), bad], [cls(":B", "?x")], "Strange"))
    assert "Strange" in message and "WeirdAtom" in message


def test_data_range_atom_in_a_head_is_refused():
    message = _refused(rule([data(":v", "?x", "?y")], [data_range("xsd:integer", "?y")], "HeadRange"))
    assert "HeadRange" in message and "DataRangeAtom" in message
