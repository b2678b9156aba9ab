"""DRed with a rule whose head value a built-in BINDs (``swrlb:lowerCase``, ``swrlb:add``).

Such a head variable cannot be bound before its BIND, so the evaluations that
start from a graph of heads (DRed's proofs and subgoals, rederivation, the
candidates kept) match the head under a name of its own and require the bound
value to be the same term.  Without that restriction a proof ranged over every
derivation of the rule, kept finding "new" proofs and never ended.
"""

from __future__ import annotations

import pytest
from pyoxigraph import Literal, NamedNode, Quad, Store, Triple
from test_incremental import assert_same_as_scratch

from topostore import Ontology
from topostore.rdf.vocab import INFERRED
from topostore.reason import limits
from topostore.reason.limits import ReasonLimitExceeded, ReasonLimits
from topostore.reason.plan import goal_match, plan_where

NS = "http://example.org/fz#"
XSD = "http://www.w3.org/2001/XMLSchema#"
GOALS = NamedNode("urn:test:goals")

PREFIXES = """@prefix : <http://example.org/fz#> . @prefix owl: <http://www.w3.org/2002/07/owl#> .
@prefix xsd: <http://www.w3.org/2001/XMLSchema#> .
@prefix swrl: <http://www.w3.org/2003/11/swrl#> . @prefix swrlb: <http://www.w3.org/2003/11/swrlb#> .
"""

#: d0(x, w) ^ builtin(u, w, ...) -> d1(x, u): the head's value ?u is bound by the built-in
RULE = """:d0 a owl:DatatypeProperty . :d1 a owl:DatatypeProperty .
:a1 a owl:NamedIndividual . :a5 a owl:NamedIndividual .
:x a swrl:Variable . :w a swrl:Variable . :u a swrl:Variable .
[ a swrl:Imp ;
  swrl:body ( [ a swrl:DatavaluedPropertyAtom ; swrl:propertyPredicate :d0 ; swrl:argument1 :x ; swrl:argument2 :w ]
              [ a swrl:BuiltinAtom ; swrl:builtin swrlb:%s ; swrl:arguments ( :u :w %s ) ] ) ;
  swrl:head ( [ a swrl:DatavaluedPropertyAtom ; swrl:propertyPredicate :d1 ; swrl:argument1 :x ;
                swrl:argument2 :u ] ) ] .
"""

BUILTINS = {"lowerCase": ("lowerCase", ""), "add": ("add", "1")}
VALUES = ['"2020-01-01T12:00:00Z"^^xsd:dateTime', '"Hello"', "5", '"7"^^xsd:integer']


def N(name: str) -> NamedNode:
    return NamedNode(NS + name)


def ontology(builtin: str, value: str, same_as: bool) -> Ontology:
    onto = Ontology()
    data = PREFIXES + RULE % BUILTINS[builtin] + f":a1 :d0 {value} .\n:a5 :d1 \"X\" .\n"
    onto.load_data(data + (":a1 owl:sameAs :a5 .\n" if same_as else ""), "turtle")
    # the normal kind of limit, far above what the step needs: a proof that never ends hits it
    onto.limits = ReasonLimits(max_seconds=30)
    onto.reason()
    return onto


@pytest.mark.parametrize("same_as", [True, False])
@pytest.mark.parametrize("value", VALUES)
@pytest.mark.parametrize("builtin", sorted(BUILTINS))
def test_step_after_deletion_with_a_bound_head_ends_and_equals_scratch(builtin: str, value: str,
                                                                        same_as: bool) -> None:
    onto = ontology(builtin, value, same_as)
    onto.change([Triple(N("a5"), N("d1"), Literal("Y"))], [Triple(N("a5"), N("d1"), Literal("X"))])
    report = onto.reason()
    assert report.stats.mode == "incremental"
    assert_same_as_scratch(onto)


@pytest.mark.parametrize("builtin", sorted(BUILTINS))
def test_removing_the_premise_of_a_bound_head_retracts_it(builtin: str) -> None:
    onto = ontology(builtin, '"7"^^xsd:integer', True)
    derived = Triple(N("a1"), N("d1"), Literal("8" if builtin == "add" else "7",
                                                datatype=NamedNode(XSD + ("integer" if builtin == "add" else "string"))))
    assert derived in set(onto.store.triples())
    onto.change([], [Triple(N("a1"), N("d0"), Literal("7", datatype=NamedNode(XSD + "integer")))])
    assert onto.reason().stats.mode == "incremental"
    assert derived not in set(onto.store.triples())
    assert_same_as_scratch(onto)


def bound_head_rule(builtin: str):
    onto = Ontology()
    onto.load_data(PREFIXES + RULE % BUILTINS[builtin], "turtle")
    rules = [r for r in onto.rules.inference_rules if r.head is not None and r.head.p == f"<{NS}d1>"]
    assert len(rules) == 1 and rules[0].binds & rules[0].head.variables()
    return rules[0]


@pytest.mark.parametrize("lateral", [True, False])
@pytest.mark.parametrize("builtin", sorted(BUILTINS))
def test_plan_from_the_heads_yields_only_the_heads_of_that_graph(builtin: str, lateral: bool) -> None:
    """Two derivations of the rule, one of them a goal: the plan from the goals finds that one only."""
    rule = bound_head_rule(builtin)
    store = Store()
    for name, value in (("a1", 3), ("a2", 4)):
        store.add(Quad(N(name), N("d0"), Literal(str(value), datatype=NamedNode(XSD + "integer"))))
    goal = Literal("4", datatype=NamedNode(XSD + "integer")) if builtin == "add" else Literal("3")
    store.add(Quad(N("a1"), N("d1"), goal, GOALS))
    where = plan_where(rule, head_graph=GOALS, lateral=lateral)
    vars_ = " ".join(sorted(rule.head.variables()))
    rows = list(store.query(f"SELECT {vars_} WHERE {{ {where} }}"))
    assert len(rows) == 1, where
    assert rows[0]["x"] == N("a1")
    assert rows[0]["u"] == goal


def test_goal_match_renames_only_the_bound_variable() -> None:
    rule = bound_head_rule("add")
    pattern, same = goal_match(rule, GOALS)
    assert pattern == f"GRAPH {GOALS} {{ ?x <{NS}d1> ?u_goal . }}"
    assert same == "FILTER(sameTerm(?u, ?u_goal))"


def test_a_limit_names_what_was_running() -> None:
    with limits.budget(ReasonLimits(max_seconds=1e-9)) as budget:
        budget.deadline = 0.0
        with limits.doing("DRed's proof of the over-deletion candidates"):
            with pytest.raises(ReasonLimitExceeded) as info:
                limits.check()
        message = str(info.value)
        assert "while running DRed's proof of the over-deletion candidates" in message
        assert "creates new values" not in message  # nothing was deriving: no rule to blame
        with pytest.raises(ReasonLimitExceeded) as info:
            limits.tick(3, ["Runaway"])
        assert "while running semi-naive rounds" in str(info.value)
        assert "creates new values" in str(info.value)


#: d0(x, w) ^ add(u, w, 1) -> d1(x, u) and d2(x, w) ^ add(u, w, 1.5) -> d1(x, u): one value, two spellings
TWO_SPELLINGS = """:d2 a owl:DatatypeProperty .
[ a swrl:Imp ;
  swrl:body ( [ a swrl:DatavaluedPropertyAtom ; swrl:propertyPredicate :d2 ; swrl:argument1 :x ; swrl:argument2 :w ]
              [ a swrl:BuiltinAtom ; swrl:builtin swrlb:add ; swrl:arguments ( :u :w "1.5"^^xsd:decimal ) ] ) ;
  swrl:head ( [ a swrl:DatavaluedPropertyAtom ; swrl:propertyPredicate :d1 ; swrl:argument1 :x ;
                swrl:argument2 :u ] ) ] .
:a1 :d0 "7"^^xsd:integer ; :d2 "6.5"^^xsd:decimal .
"""
INTEGER_8 = Literal("8", datatype=NamedNode(XSD + "integer"))
DECIMAL_8 = Literal("8", datatype=NamedNode(XSD + "decimal"))
PREMISES = {"integer": Triple(N("a1"), N("d0"), Literal("7", datatype=NamedNode(XSD + "integer"))),
            "decimal": Triple(N("a1"), N("d2"), Literal("6.5", datatype=NamedNode(XSD + "decimal")))}


@pytest.mark.parametrize("path", ["staged", "whole", "general"])
@pytest.mark.parametrize("removed", sorted(PREMISES))
def test_a_value_derived_in_another_spelling_does_not_keep_the_lost_one(removed: str, path: str) -> None:
    """Two rules derive ``"8"^^xsd:integer`` and ``"8"^^xsd:decimal`` (one value, two stored terms);
    removing the premise of one retracts that term, though the other still holds the same value."""
    onto = Ontology()
    onto.load_data(PREFIXES + RULE % BUILTINS["add"] + TWO_SPELLINGS, "turtle")
    onto.limits = ReasonLimits(max_seconds=30)
    onto.reason()
    heads = {t.object for t in onto.store.triples(graph=INFERRED) if t.predicate == N("d1")}
    assert heads == {INTEGER_8, DECIMAL_8}
    reasoner = onto._reasoner
    saved = reasoner.store.round_trips
    reasoner.store.round_trips = path == "whole"  # one request, as on a remote store
    reasoner.step.enabled = path != "general"
    try:
        onto.change([], [PREMISES[removed]])
        report = onto.reason()
        assert report.stats.mode == "incremental"
        expected = "general" if path == "general" else "compiled"
        assert report.stats.program.startswith(expected), report.stats.program
        kept = DECIMAL_8 if removed == "integer" else INTEGER_8
        heads = {t.object for t in onto.store.triples(graph=INFERRED) if t.predicate == N("d1")}
        assert heads == {kept}, report.stats
        assert_same_as_scratch(onto)
    finally:
        reasoner.store.round_trips = saved
