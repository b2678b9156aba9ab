"""SWRL compiler: every atom kind, every supported built-in, disabled rules and rules set aside.

Each test writes a small Turtle ontology with one rule.  Expected values come
from the SWRL submission (W3C Member Submission 2004, §8 "Built-Ins", whose
functions follow XPath/XQuery Functions and Operators) unless a comment says
otherwise.
"""

from __future__ import annotations

from decimal import Decimal

import pytest
from pyoxigraph import Literal, NamedNode
from swrl_support import NS, PREFIXES, arg, builtin, cls, data, data_range, diff, obj, rule, same

from topostore import IncompleteOntologyError, Ontology, OntologyWarning
from topostore.compile.notices import RULE_SET_ASIDE
from topostore.rdf.vocab import ASSERTED


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


SMALL = ("[ a rdfs:Datatype ; owl:onDatatype xsd:integer ; owl:withRestrictions ( [ xsd:minInclusive 1 ] "
         "[ xsd:maxExclusive 10 ] ) ]")


@pytest.mark.parametrize("data_range_node", [":Small", ":Tiny", SMALL])
def test_a_data_range_atom_on_a_datatype_defined_by_facets_tests_the_facets(data_range_node: str) -> None:
    """A datatype defined by numeric facets (named by a definition, a chain of two, or written in the atom) is
    tested as a range or a restriction of it is: an integer in [1, 10) (Pellet evaluates it so)."""
    o = ontology(
        rule([data(":v", "?x", "?y"), data_range(data_range_node, "?y")], [cls(":In", "?x")], "dr"),
        ':a :v 5 . :b :v 50 . :c :v "5" . :d :v "7"^^xsd:long . :e :v 0 . :f :v 9.5 .',
        f":Small a rdfs:Datatype ; owl:equivalentClass {SMALL} . :Tiny a rdfs:Datatype ; owl:equivalentClass :Small .",
    )
    assert names(o, "In") == {"a", "d"}
    assert not o.notices


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


def _set_aside(text: str) -> str:
    """Loading ``text`` (a rule that cannot be compiled) beside a rule that can: the document is loaded, the rule
    kept in the graph and set aside with a warning naming it, the other rule reasoned, as Pellet ignores a rule it
    cannot handle and reasons with the rest (its log: "Ignoring rule ..."); the notice is the REASON's too.
    Returns the notice's text."""
    o = Ontology()
    good = rule([cls(":A", "?x")], [cls(":Good", "?x")], "Good")
    with pytest.warns(OntologyWarning, match="SWRL rule set aside") as said:
        o.load_data(PREFIXES + ":a a :A . :a :v 5 . " + text + good, "turtle")
    report = o.reason()
    assert report.consistent and names(o, "Good") == {"a"}
    assert len(list(o.sparql("SELECT ?r WHERE { ?r a <http://www.w3.org/2003/11/swrl#Imp> }"))) == 2
    aside = [n for n in report.incomplete if n.axiom_kind == RULE_SET_ASIDE]
    assert len(aside) == 1 and str(aside[0]) in str(said[0].message)
    return str(aside[0])


def _refused_when_strict(text: str) -> None:
    """Strict loading refuses the document naming the rule, and the ontology is as it was."""
    o = Ontology(strict=True)
    o.load_data(PREFIXES + ":a a :A .", "turtle")
    before = o.store.count(ASSERTED)
    with pytest.raises(IncompleteOntologyError, match="SWRL rule set aside"):
        o.load_data(PREFIXES + text, "turtle")
    assert o.store.count(ASSERTED) == before


def test_unknown_builtin_is_set_aside_naming_rule_and_atom():
    text = rule([data(":v", "?x", "?y"), builtin("tan", "?r", "?y")], [data(":t", "?x", "?r")], "Trig")
    message = _set_aside(text)
    assert "Trig" in message
    assert "tan" in message and "BuiltinAtom" in message
    _refused_when_strict(text)


def test_unbound_head_variable_is_set_aside_naming_rule_and_atom():
    message = _set_aside(rule([cls(":A", "?x")], [obj(":p", "?x", "?z")], "Unsafe"))
    assert "Unsafe" in message
    assert "?z" in message and "IndividualPropertyAtom" in message


def test_builtin_with_inputs_never_bound_is_set_aside():
    message = _set_aside(rule([cls(":A", "?x"), builtin("greaterThan", "?y", 3)], [cls(":B", "?x")], "Unbound"))
    assert "Unbound" in message and "greaterThan" in message


def test_unsupported_atom_is_set_aside_naming_rule_and_atom():
    bad = "[ a swrl:WeirdAtom ; swrl:argument1 var:x ]"
    message = _set_aside(rule([cls(":A", "?x"), bad], [cls(":B", "?x")], "Strange"))
    assert "Strange" in message and "WeirdAtom" in message


def test_data_range_atom_in_a_head_is_set_aside():
    message = _set_aside(rule([data(":v", "?x", "?y")], [data_range("xsd:integer", "?y")], "HeadRange"))
    assert "HeadRange" in message and "DataRangeAtom" in message


@pytest.mark.parametrize("atom,why", [
    ("[ a swrl:ClassAtom ; swrl:classPredicate :A ]", "expects 1 argument"),
    ("[ a swrl:IndividualPropertyAtom ; swrl:argument1 var:x ; swrl:argument2 var:y ]", "missing property predicate"),
    ("[ swrl:classPredicate :A ; swrl:argument1 var:x ]", "unsupported atom type"),
    (builtin("equal", "?x", 5, 6), "takes 2 arguments, got 3"),
    (data_range(":A", "?x"), "neither a datatype"),
])
def test_a_malformed_atom_sets_its_rule_aside(atom: str, why: str) -> None:
    assert why in _set_aside(rule([cls(":A", "?x"), atom], [cls(":B", "?x")], "Malformed"))


def test_a_rule_with_no_head_is_set_aside() -> None:
    text = "var:x a swrl:Variable . [] a swrl:Imp ; rdfs:label \"Headless\" ; swrl:body ( " + cls(":A", "?x") + " ) ."
    assert "Headless (has no head atom)" in _set_aside(text)


def test_a_rule_set_aside_by_a_change_is_named_by_the_reason() -> None:
    """A rule broken by a change of the graph (here: its head taken away) is set aside at the next REASON, which
    names it; the REASON does not fail."""
    o = ontology(rule([cls(":A", "?x")], [cls(":B", "?x")], "Broken"), ":a a :A .")
    assert names(o, "B") == {"a"}
    o.remove(*o.store.triples(None, NamedNode("http://www.w3.org/2003/11/swrl#head"), None, ASSERTED))
    report = o.reason()
    assert report.consistent and names(o, "B") == set()
    assert [n.subject for n in report.incomplete if n.axiom_kind == RULE_SET_ASIDE] == ["Broken"]


# ---------------------------------------------------------------- comparisons across kinds of values, as Pellet

#: (first value, second value) of each individual, in Turtle
PAIRS = {
    "token_number": ('"5"^^xsd:token', "5"), "string_token": ('"ab"', '"ab"^^xsd:token'),
    "token_string": ('"abc"^^xsd:token', '"abd"'), "booleans": ("true", '"1"^^xsd:boolean'),
    "date_string": ('"2020-01-01"^^xsd:date', '"2020-01-01"'),
    "uris": ('"http://a10"^^xsd:anyURI', '"http://a2"^^xsd:anyURI'),
    "tagged_plain": ('"a"@en', '"a"'), "numbers": ("5", '"5.0"^^xsd:decimal'), "boolean_number": ("true", "1"),
}
#: comparison -> the individuals it holds of, Pellet 2.3.1's answers (ComparisonTesters; tests/test_fidelity_pellet.py
#: runs the same document through Pellet)
COMPARED = {
    "equal": {"string_token", "booleans", "numbers"},
    "notEqual": {"token_number", "token_string", "date_string", "uris", "tagged_plain", "boolean_number"},
    "lessThan": {"token_string", "uris"},
    "lessThanOrEqual": {"string_token", "token_string", "uris", "numbers"},  # two equal booleans are not ordered
    "greaterThan": set(),
    "greaterThanOrEqual": {"string_token", "numbers"},
}


def test_comparisons_across_kinds_of_values_are_pellets() -> None:
    facts = " ".join(f":{name} :d {a} ; :e {b} ." for name, (a, b) in PAIRS.items())
    rules = "".join(rule([data(":d", "?x", "?v"), data(":e", "?x", "?w"), builtin(op, "?v", "?w")],
                         [cls(f":{op}", "?x")], op) for op in COMPARED)
    o = ontology(rules, facts)
    assert {op: names(o, op) for op in COMPARED} == COMPARED


def test_a_comparison_with_an_arithmetic_result_stays_sparqls_operator() -> None:
    """A number known to be one (a subtraction's result) is compared by SPARQL's operator itself, the text the
    look-up path of a robot step evaluates (the tutorial's Urgency rule)."""
    o = ontology(rule([data(":now", "?r", "?t"), data(":visitedAt", "?l", "?v"), builtin("subtract", "?d", "?t", "?v"),
                       data(":threshold", "?r", "?h"), builtin("greaterThan", "?d", "?h")], [cls(":URGENT", "?l")],
                      "Urgency"), ":robot :now 100 ; :threshold 7 . :l1 :visitedAt 92 .")
    (urgency,) = [r for r in o.rules.rules if r.name == "swrl:Urgency"]
    assert "FILTER(?d > ?h)" in [c.text for c in urgency.conditions]


def test_a_built_in_with_an_individual_as_argument_is_false() -> None:
    """An individual given as a built-in's argument (``:a``): false, as on an individual variable, as in Pellet."""
    o = ontology(
        rule([cls(":D", "?x"), builtin("equal", "?x", ":a")], [cls(":Same", "?x")], "same")
        + rule([data(":d", "?x", "?v"), builtin("notEqual", "?v", ":a")], [cls(":Other", "?x")], "other")
        + rule([data(":n", "?x", "?v"), builtin("add", "?s", "?v", 1), builtin("notEqual", "?s", ":a")],
               [cls(":OtherNumber", "?x")], "number")
        + rule([cls(":D", "?x"), builtin("contains", ":a", '"swrltest"')], [cls(":Named", "?x")], "named")
        + rule([data(":n", "?x", "?v"), builtin("add", "?r", "?v", ":a")], [data(":sum", "?x", "?r")], "sum"),
        ':a a :D ; :d "x" ; :n 5 . :b a :D .',
    )
    assert all(names(o, c) == set() for c in ("Same", "Other", "OtherNumber", "Named"))
    assert values(o, "sum", "a") == []
