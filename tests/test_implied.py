"""Implied body atoms (topostore.compile.implied): dropped only where the rule set itself implies them."""

from __future__ import annotations

from topostore import Ontology
from topostore.compile import condition
from topostore.compile.implied import simplify
from topostore.compile.rule import Atom, Rule
from topostore.rdf.vocab import TYPE
from topostore.resources import default_ontology_files

T = str(TYPE)


def copy(name: str, body: Atom, head: Atom) -> Rule:
    """A single-atom, condition-free rule (what domain, range and subclass axioms compile to)."""
    return Rule(name, name, (body,), head)


DOMAIN = copy("dom", Atom("?x", "<urn:p>", "?y"), Atom("?x", T, "<urn:A>"))
RANGE = copy("rng", Atom("?x", "<urn:p>", "?y"), Atom("?y", T, "<urn:B>"))
SUB = copy("sub", Atom("?x", T, "<urn:A>"), Atom("?x", T, "<urn:Top>"))
INVERSE = copy("inv", Atom("?x", "<urn:q>", "?y"), Atom("?y", "<urn:p>", "?x"))


def user_rule(*atoms: Atom) -> Rule:
    return Rule("swrl:r", "SWRL rule r", atoms, Atom("?x", "<urn:out>", "?y"))


def simplified(rule: Rule, *axioms: Rule) -> Rule:
    return simplify([*axioms, rule])[-1]


def test_a_domain_implies_the_subject_type_and_keeps_the_written_body() -> None:
    rule = user_rule(Atom("?x", "<urn:p>", "?y"), Atom("?x", T, "<urn:A>"))
    out = simplified(rule, DOMAIN)
    assert out.body == (Atom("?x", "<urn:p>", "?y"),)
    assert out.premises == rule.body  # explanations show the rule as written
    assert out.conditions == ()  # a subject is never a literal: no filter needed


def test_a_range_leaves_a_not_literal_filter() -> None:
    rule = user_rule(Atom("?x", "<urn:p>", "?y"), Atom("?y", T, "<urn:B>"))
    out = simplified(rule, RANGE)
    assert out.body == (Atom("?x", "<urn:p>", "?y"),)
    assert [c.text for c in out.conditions] == ["FILTER(!isLiteral(?y))"]
    assert out.written_filters == ""  # as written: no filter


def test_superclasses_and_inverse_properties_chain() -> None:
    rule = user_rule(Atom("?y", "<urn:q>", "?x"), Atom("?x", T, "<urn:Top>"))
    out = simplified(rule, DOMAIN, SUB, INVERSE)  # q(y, x) ⟹ p(x, y) ⟹ A(x) ⟹ Top(x)
    assert out.body == (Atom("?y", "<urn:q>", "?x"),)


def test_nothing_is_dropped_without_an_implying_rule() -> None:
    rule = user_rule(Atom("?x", "<urn:p>", "?y"), Atom("?x", T, "<urn:Other>"))
    assert simplified(rule, DOMAIN, RANGE) is rule


def test_a_rule_with_conditions_implies_nothing() -> None:
    guarded = Rule("dom", "dom", (Atom("?x", "<urn:p>", "?y"),), Atom("?x", T, "<urn:A>"), (condition.test("?y > 0"),))
    rule = user_rule(Atom("?x", "<urn:p>", "?y"), Atom("?x", T, "<urn:A>"))
    assert simplified(rule, guarded) is rule


def test_equivalent_classes_keep_one_of_the_two_atoms() -> None:
    a_to_b = copy("eq1", Atom("?x", T, "<urn:A>"), Atom("?x", T, "<urn:B>"))
    b_to_a = copy("eq2", Atom("?x", T, "<urn:B>"), Atom("?x", T, "<urn:A>"))
    out = simplified(user_rule(Atom("?x", T, "<urn:A>"), Atom("?x", T, "<urn:B>"), Atom("?x", "<urn:z>", "?y")),
                     a_to_b, b_to_a)
    assert len([a for a in out.body if a.p == T]) == 1


def test_a_constant_object_implies_nothing_about_the_property_in_general() -> None:
    has_value = copy("hv", Atom("?x", "<urn:p>", "<urn:v>"), Atom("?x", T, "<urn:A>"))
    rule = user_rule(Atom("?x", "<urn:p>", "?y"), Atom("?x", T, "<urn:A>"))
    assert simplified(rule, has_value) is rule


def test_the_tutorial_rules_read_no_implied_class() -> None:
    """Reachability and Urgency keep only what the axioms do not already say."""
    rules = [r for r in Ontology.from_file(*default_ontology_files()).rules.inference_rules if r.name.startswith("swrl:")]
    urgency = next(r for r in rules if r.name == "swrl:Urgency")
    assert {a.p.rsplit("#", 1)[-1] for a in urgency.body} == {"now>", "urgencyThreshold>", "visitedAt>"}
    reachability = [r for r in rules if r.name == "swrl:Reachability"]
    # the conclusion joined with each way of being declared different (AllDifferent keys, differentFrom
    # either way); the entailed-only one and the pairs it asks about by values (compile/inline_difference.py)
    assert len(reachability) == 5 and all(a.p != T for r in reachability for a in r.body)
    assert all(len(r.premises) > len(r.body) for r in reachability)
