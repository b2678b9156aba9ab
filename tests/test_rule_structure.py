"""Rules stay structured until they become text: conditions, the shared tokenizer, the rule index.

The compilers record on each :class:`Condition` whether it negates, reads the graph and what it
binds; these tests pin those records against what the SPARQL text says (read back with the one
tokenizer), and the pieces of the reasoner that used to scan text (the rule dependency order,
the feasibility index) against their definitions.
"""

from __future__ import annotations

from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from topostore import Ontology
from topostore.compile import condition as cond
from topostore.compile.rule import Atom, Rule
from topostore.rdf.lexer import COMMENT, IRI, KEYWORD, NAME, PUNCT, STRING, VARIABLE, negates_exists, tokens, variables
from topostore.rdf.vocab import ASSERTED, AUX, INFERRED, TYPE
from topostore.reason import full_passes, materialize
from topostore.reason.order import reachable, single_graphs, strongly_connected, within
from topostore.reason.triggers import Triggers, matches

ROOT = Path(__file__).resolve().parent.parent
EXAMPLE = ROOT / "ontology" / "topological_map.ttl"


@pytest.fixture(scope="module")
def example_rules() -> list[Rule]:
    onto = Ontology()
    onto.load(EXAMPLE)
    return onto.rules.rules


# ---------------------------------------------------------------- tokenizer

def test_tokens_kinds_and_texts() -> None:
    text = 'SELECT ?x WHERE { ?x ex:LOAD "a { b" . <urn:x?y> $z } # FILTER EXISTS\nLIMIT 1'
    got = [(t.kind, t.text) for t in tokens(text)]
    assert got == [
        (KEYWORD, "SELECT"), (VARIABLE, "?x"), (KEYWORD, "WHERE"), (PUNCT, "{"), (VARIABLE, "?x"),
        (NAME, "ex:LOAD"), (STRING, '"a { b"'), (PUNCT, "."), (IRI, "<urn:x?y>"), (VARIABLE, "$z"),
        (PUNCT, "}"), (COMMENT, "# FILTER EXISTS\n"), (KEYWORD, "LIMIT"), (PUNCT, "1"),
    ]


def test_variables_skip_strings_and_iris() -> None:
    assert variables('FILTER(?a - ?b_2 > 3 && STR(?c) != "?d" && ?e = <urn:x?f>)') == {"?a", "?b_2", "?c", "?e"}
    assert variables("BIND(($t-?v) AS ?d)") == {"?t", "?v", "?d"}


@pytest.mark.parametrize(("text", "negated"), [
    ("FILTER NOT EXISTS { ?x ?p ?y }", True),
    ("FILTER(!(?a && EXISTS { ?x ?p ?y }))", True),
    ("FILTER(!EXISTS { ?x ?p ?y })", True),
    ("FILTER(!sameTerm(?a, ?b) && EXISTS { ?x ?p ?y })", False),
    ("BIND((?t - ?v) AS ?d)\n  FILTER(?d > ?h)", False),
    ('FILTER(?x != "NOT EXISTS")', False),
    ("FILTER(?p != <urn:not#exists>)", False),
])
def test_negates_exists(text: str, negated: bool) -> None:
    assert negates_exists(text) is negated


# ---------------------------------------------------------------- conditions

def test_condition_renderings() -> None:
    assert cond.test("?d > ?h").text == "FILTER(?d > ?h)"
    assert cond.bind("(?t - ?v)", "?d").text == "BIND((?t - ?v) AS ?d)"
    assert cond.exists("?a <urn:p> ?b", negated=True).text == "FILTER NOT EXISTS { ?a <urn:p> ?b }"
    assert cond.exists("?a <urn:p> ?b").text == "FILTER EXISTS { ?a <urn:p> ?b }"


def test_parse_reads_rule_file_lines() -> None:
    b = cond.parse('BIND(IRI(CONCAT("urn:k:", MD5(STR(?x)))) AS ?key)')
    assert (b.kind, b.binds, b.expression, b.negated, b.reads_graph) == (
        cond.BIND, "?key", 'IRI(CONCAT("urn:k:", MD5(STR(?x))))', False, False)
    f = cond.parse("FILTER(!sameTerm(?x, ?y))")
    assert (f.kind, f.expression, f.plain, f.variables) == (cond.TEST, "!sameTerm(?x, ?y)", True, {"?x", "?y"})
    n = cond.parse("FILTER NOT EXISTS { GRAPH <urn:g> { ?a <urn:p> ?b } }")
    assert (n.kind, n.negated, n.reads_graph, n.plain, n.expression) == (
        cond.EXISTS, True, True, False, "GRAPH <urn:g> { ?a <urn:p> ?b }")
    o = cond.parse("OPTIONAL { ?a <urn:p> ?b }")
    assert (o.kind, o.negated, o.reads_graph, o.plain) == (cond.PATTERN, False, True, False)


def test_compiled_conditions_agree_with_their_text(example_rules: list[Rule]) -> None:
    """What each compiler recorded is what its SPARQL says, read back by the tokenizer."""
    seen = 0
    for rule in example_rules:
        for c in rule.conditions:
            back = cond.parse(c.text)
            assert (back.kind, back.binds, back.negated, back.reads_graph, back.variables) == \
                (c.kind, c.binds, c.negated, c.reads_graph, c.variables), c.text
            seen += 1
    assert seen > 0 and any(r.negates for r in example_rules) and any(r.binds for r in example_rules)


def test_urgency_rule_is_structured(example_rules: list[Rule]) -> None:
    urgency = [r for r in example_rules if r.name == "swrl:Urgency" and r.head is not None
               and "entailment" not in r.origin]
    assert len(urgency) == 1
    (rule,) = urgency
    assert [c.kind for c in rule.conditions] == [cond.BIND, cond.TEST]
    assert rule.binds == {"?d"}
    assert not rule.negates and not rule.conditions_read_graph
    assert rule.filters == "\n  ".join(c.text for c in rule.conditions)


def test_rule_flags() -> None:
    body = (Atom("?x", "<urn:p>", "?y"),)
    plain = Rule("r", "o", body, Atom("?x", "<urn:q>", "?d"), (cond.bind("(?y + 1)", "?d"),))
    negating = Rule("n", "o", body, Atom("?x", "<urn:q>", "?y"), (cond.exists("?y <urn:r> ?x", negated=True),))
    assert (plain.negates, plain.binds, plain.conditions_read_graph) == (False, {"?d"}, False)
    assert (negating.negates, negating.binds, negating.conditions_read_graph) == (True, frozenset(), True)
    assert negating.where() == "?x <urn:p> ?y .\n  FILTER NOT EXISTS { ?y <urn:r> ?x }"


# ---------------------------------------------------------------- rule index

def test_unknown_atoms_and_feasible() -> None:
    rule = Rule("r", "o", (Atom("?x", "<urn:p>", "?y"), Atom("?y", "<http://www.w3.org/1999/02/22-rdf-syntax-ns#type>",
                                                                 "<urn:C>"), Atom("?y", "?any", "?z")),
                Atom("?x", "<urn:q>", "?z"))
    index = Triggers([rule])
    assert index.unknown_atoms(0, ({"<urn:p>"}, set())) == [1]
    assert index.unknown_atoms(0, (set(), {"<urn:C>"})) == [0]
    assert index.unknown_atoms(0, ({"<urn:p>"}, {"<urn:C>"})) == []
    assert index.feasible(0, ({"<urn:p>"}, set())) is False
    assert index.feasible(0, ({"<urn:p>"}, set()), skip=1) is True
    assert index.feasible(0, None) is True
    assert matches(("*",), {"<urn:p>"}, set()) and not matches(("*",), set(), {"<urn:C>"})
    assert matches(("t", "<urn:C>"), set(), {"<urn:C>"}) and not matches(("p", "<urn:C>"), set(), {"<urn:C>"})


# ---------------------------------------------------------------- rule dependency order

def _reach(succ: dict[int, list[int]], a: int) -> set[int]:
    seen, todo = {a}, [a]
    while todo:
        for w in succ[todo.pop()]:
            if w not in seen:
                seen.add(w)
                todo.append(w)
    return seen


graphs = st.integers(1, 9).flatmap(lambda n: st.lists(
    st.tuples(st.integers(0, n - 1), st.integers(0, n - 1)), max_size=n * 3).map(lambda edges: (n, edges)))


@settings(max_examples=200, deadline=None)
@given(graphs)
def test_strongly_connected_is_mutual_reachability_in_topological_order(graph: tuple[int, list]) -> None:
    n, edges = graph
    succ: dict[int, list[int]] = {i: [] for i in range(n)}
    for a, b in edges:
        if b not in succ[a]:
            succ[a].append(b)
    components = strongly_connected(list(range(n)), succ)
    reach = {v: _reach(succ, v) for v in range(n)}
    expected = {frozenset(w for w in range(n) if w in reach[v] and v in reach[w]) for v in range(n)}
    assert {frozenset(c) for c in components} == expected
    assert sorted(v for c in components for v in c) == list(range(n))
    assert all(c == sorted(c) for c in components)
    position = {v: k for k, c in enumerate(components) for v in c}
    assert all(position[a] <= position[b] for a, b in edges)


@settings(max_examples=200, deadline=None)
@given(graphs)
def test_within_a_component_writers_come_first_unless_a_cycle_forbids(graph: tuple[int, list]) -> None:
    """:func:`within` orders a set of rules so that an edge goes backwards only on a cycle: on an
    acyclic graph every writer comes before its readers (no rule needs a delta), on any graph each
    backward edge closes a cycle (its reader reaches its writer)."""
    n, edges = graph
    succ: dict[int, list[int]] = {i: [] for i in range(n)}
    for a, b in edges:
        if b not in succ[a]:
            succ[a].append(b)
    order = within(list(range(n)), succ)
    assert sorted(order) == list(range(n))
    at = {v: k for k, v in enumerate(order)}
    for a, b in edges:
        if at[b] <= at[a]:
            assert a in _reach(succ, b)  # a backward edge lies on a cycle


def _type(x: str, c: str) -> Atom:
    return Atom(x, str(TYPE), f"<http://e.org/{c}>")


def test_reachable_keys_follow_the_rules_that_can_fire() -> None:
    """A rule whose body needs a key no asserted fact and no firing rule gives stays out of the
    first stratum's order; a head of any class makes every class possible."""
    chain = [Rule("r0", "A => B", (_type("?x", "A"),), _type("?x", "B")),
             Rule("r1", "B => C", (_type("?x", "B"),), _type("?x", "C")),
             Rule("r2", "D => E", (_type("?x", "D"),), _type("?x", "E")),
             Rule("r3", "E and p => F", (_type("?x", "E"), Atom("?x", "<http://e.org/p>", "?y")), _type("?x", "F"))]
    triggers = Triggers(chain)
    preds, classes = reachable(triggers, [0, 1, 2, 3], ({str(TYPE)}, {"<http://e.org/A>"}))
    assert classes == {"<http://e.org/A>", "<http://e.org/B>", "<http://e.org/C>"}
    assert [i for i in range(4) if triggers.feasible(i, (preds, classes))] == [0, 1]
    any_class = [*chain, Rule("r4", "q => any", (Atom("?x", "<http://e.org/q>", "?c"),), Atom("?x", str(TYPE), "?c"))]
    triggers = Triggers(any_class)
    possible = reachable(triggers, list(range(5)), ({str(TYPE), "<http://e.org/q>"}, {"<http://e.org/A>"}))
    assert [i for i in range(5) if triggers.feasible(i, possible)] == [0, 1, 2, 4]  # r3 also needs p


def test_single_graphs_name_a_graph_only_where_every_fact_of_a_key_lies() -> None:
    """A key is read in one graph when its asserted facts and its writers all put it there; an
    asserted key that a rule also writes, and every class once a rule writes ``?x rdf:type ?c``,
    stay on the default dataset."""
    hidden = "<urn:topostore:bnode:x>"
    rules = [Rule("r0", "A => B", (_type("?x", "A"),), _type("?x", "B")),
             Rule("r1", "q => hidden", (Atom("?x", "<http://e.org/q>", "?y"),), Atom("?x", str(TYPE), hidden)),
             Rule("r2", "B and hidden => C", (_type("?x", "B"), Atom("?x", str(TYPE), hidden)), _type("?x", "C"))]
    needed = Triggers(rules).needed_keys()
    asserted = ({str(TYPE), "<http://e.org/q>"}, {"<http://e.org/A>", "<http://e.org/B>"})

    def graph_of(rule: Rule) -> object:
        return AUX if rule.head_aux() else INFERRED

    found = single_graphs(rules, [0, 1, 2], needed, asserted, graph_of, ASSERTED)
    assert found == {("t", "<http://e.org/A>"): ASSERTED, ("p", "<http://e.org/q>"): ASSERTED, ("t", hidden): AUX}
    any_class = [*rules, Rule("r3", "q => any", (Atom("?x", "<http://e.org/q>", "?c"),), Atom("?x", str(TYPE), "?c"))]
    found = single_graphs(any_class, [0, 1, 2, 3], Triggers(any_class).needed_keys(), asserted, graph_of, ASSERTED)
    assert found == {("p", "<http://e.org/q>"): ASSERTED}
    assert single_graphs(rules, [1, 2], needed, asserted, graph_of, ASSERTED)[("t", "<http://e.org/B>")] == ASSERTED


def test_full_reason_reading_single_graphs_finds_the_closure_of_the_default_dataset(monkeypatch) -> None:
    """owl:sameAs (an upper stratum) copies hasDoor, asserted only until then, into the inferred graph:
    the rounds after the ordered first stratum read it there, and the closure is the one found with
    every atom read on the default dataset."""
    onto = Ontology()
    onto.load(EXAMPLE)
    onto.load_data("""@prefix : <http://bnc/exp-rob-lab/2022-23#> . @prefix owl: <http://www.w3.org/2002/07/owl#> .
        :R1 :isIn :A , :B .
        :A :hasDoor :D1 . :C :hasDoor :D1 . :B :hasDoor :D2 . :E :hasDoor :D2 .
        [] a owl:AllDifferent ; owl:distinctMembers ( :A :C :E :D1 :D2 ) .
        [] a owl:AllDifferent ; owl:distinctMembers ( :B :C :E ) .""")

    def closure() -> set[str]:
        assert onto.reason(mode="full").consistent
        return {f"{t} {g}" for g in (INFERRED, AUX) for t in onto.store.triples(graph=g)}

    read_apart = closure()
    ns = "http://bnc/exp-rob-lab/2022-23#"
    assert f"<{ns}A> <{ns}connectedTo> <{ns}E> {INFERRED}" in read_apart  # by A sameAs B
    monkeypatch.setattr(full_passes, "single_graphs", lambda *args: {})
    assert closure() == read_apart


def test_rules_after_the_ordered_pass_read_the_default_dataset() -> None:
    """An upper stratum writes p and q, asserted only until then, into the inferred graph: the join of
    the two (each atom once on the delta) reads the other atom in every graph again."""
    from pyoxigraph import NamedNode, Triple

    from topostore.compile.rule import RuleSet
    from topostore.stores import memory_store

    def atom(s: str, p: str, o: str) -> Atom:
        return Atom(s, f"<http://e.org/{p}>", o)

    rules = [Rule("join", "p then q", (atom("?x", "p", "?y"), atom("?y", "q", "?z")), atom("?x", "r", "?z")),
             Rule("to-p", "s gives p", (atom("?x", "s", "?y"),), atom("?x", "p", "?y"), stratum=1),
             Rule("to-q", "t gives q", (atom("?x", "t", "?y"),), atom("?x", "q", "?y"), stratum=1)]
    store = memory_store()
    e = {n: NamedNode(f"http://e.org/{n}") for n in ("a", "b", "c", "d", "p", "q", "r", "s", "t")}
    store.add([Triple(e["a"], e["s"], e["b"]), Triple(e["b"], e["t"], e["c"]),
               Triple(e["d"], e["p"], e["d"]), Triple(e["d"], e["q"], e["d"])], ASSERTED)
    materialize.Materializer(store, RuleSet(rules)).run()
    assert set(store.triples(None, e["r"], None, INFERRED)) == {Triple(e["a"], e["r"], e["c"]),
                                                                Triple(e["d"], e["r"], e["d"])}
