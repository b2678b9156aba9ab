"""Cardinalities by counting (compile/counting.py) and the size guard on compiled rules (compile/guard.py).

The shapes of the W3C OWL 2 test cases that used to kill the process (``owl:cardinality 257`` and
``600``, ``maxQualifiedCardinality 300``, ``minCardinality 128``) are reasoned with the answers
right on both sides of n; literal values are counted by value, individuals by AllDifferent key;
what counting cannot see is said with the named warning; a rule too large to evaluate is
refused and leaves the ontology as it was.
"""

from __future__ import annotations

import subprocess
import sys
import textwrap
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from profiles import property_examples

from topostore import Ontology, OntologyWarning
from topostore.compile.counting import COUNTED_ONLY, PAIRWISE_MAX
from topostore.errors import RuleCompileError

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))  # the benchmarks package lives beside src/
from benchmarks.cardinality import PREFIXES, cardinality_ttl  # noqa: E402


def reasoned(text: str) -> Ontology:
    onto = Ontology()
    onto.load_data(text, "turtle")
    onto.reason()
    return onto


def x_in_c(onto: Ontology) -> bool:
    return "x" in {onto.short(i) for i in onto.instances("C")}


# ---------------------------------------------------------------- the W3C shapes, both sides of n

@pytest.mark.parametrize(("kind", "n", "qualified"), [
    ("cardinality", 600, False), ("cardinality", 257, False), ("maxCardinality", 300, True),
    ("cardinality", 40, True), ("maxCardinality", PAIRWISE_MAX + 1, False),
])
def test_a_maximum_holds_at_n_and_is_violated_at_n_plus_one(kind: str, n: int, qualified: bool) -> None:
    assert reasoned(cardinality_ttl(kind, n, n, qualified)).report.consistent
    report = reasoned(cardinality_ttl(kind, n, n + 1, qualified)).report
    assert not report.consistent
    assert f"more than {n} different values of p" in report.explain()


@pytest.mark.parametrize(("n", "qualified", "data"), [
    (128, False, False), (128, True, False), (600, True, False), (300, True, True), (PAIRWISE_MAX + 1, False, True),
])
def test_a_minimum_needs_n_different_values(n: int, qualified: bool, data: bool) -> None:
    assert x_in_c(reasoned(cardinality_ttl("minCardinality", n, n, qualified, data)))
    assert not x_in_c(reasoned(cardinality_ttl("minCardinality", n, n - 1, qualified, data)))


def test_an_exact_cardinality_with_no_values_is_consistent_and_named_in_the_warning() -> None:
    report = reasoned(cardinality_ttl("cardinality", 600, 0)).report
    assert report.consistent
    assert [n.subject for n in counted(report)] == ["(p exact 600 Thing)"]


def test_the_cardinality_600_shape_does_not_kill_a_process() -> None:
    """The crash was native (SIGSEGV): only a child process can show that it is gone."""
    code = textwrap.dedent(f"""
        import sys; sys.path.insert(0, {str(ROOT)!r})
        from benchmarks.cardinality import cardinality_ttl
        from topostore import Ontology
        for kind, q in (("cardinality", False), ("maxCardinality", True), ("minCardinality", False)):
            o = Ontology(); o.load_data(cardinality_ttl(kind, 600, 0, q), "turtle"); assert o.reason().consistent
        print("alive")
    """)
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert (done.returncode, done.stdout.strip()) == (0, "alive"), done.stderr[-2000:]


# ---------------------------------------------------------------- what counts as different

def restriction(kind: str, n: int, data: bool = False) -> str:
    prop = "owl:DatatypeProperty" if data else "owl:ObjectProperty"
    return PREFIXES + f":p a {prop} .\n:C owl:equivalentClass [ a owl:Restriction ; owl:onProperty :p ; owl:{kind} {n} ] .\n"


def test_literals_are_counted_by_value_not_by_spelling() -> None:
    values = ('1, "01"^^xsd:int, "1.0e0"^^xsd:double, "1.0"^^xsd:decimal, '
              '"2020-01-01T00:00:00Z"^^xsd:dateTime, "2020-01-01T01:00:00+01:00"^^xsd:dateTime, '
              '"a"@en, "a"@EN, "a", "a"^^xsd:string, true, "1"^^xsd:boolean')
    # four values: 1, one instant, "a"@en, "a" (and the boolean true: five)
    assert x_in_c(reasoned(restriction("minCardinality", 5, data=True) + f":x :p {values} ."))
    assert not x_in_c(reasoned(restriction("minCardinality", 6, data=True) + f":x :p {values} ."))
    onto = reasoned(restriction("maxCardinality", 5, data=True) + f":x a :C ; :p {values} .")
    assert onto.report.consistent
    assert counted(onto.report) == []  # data values are counted exactly


def group(members: str) -> str:
    return f"[] a owl:AllDifferent ; owl:distinctMembers ({members}) .\n"


def test_individuals_count_once_per_key_even_under_several_names() -> None:
    text = restriction("minCardinality", 5) + group(":a :b :c :d :e") + ":x :p :a, :b, :c, :d, :a2 .\n:a2 owl:sameAs :a .\n"
    assert not x_in_c(reasoned(text))  # :a2 is :a: four different values
    assert x_in_c(reasoned(text + ":x :p :e ."))


def test_individuals_of_two_groups_are_not_counted_together_and_the_warning_says_so() -> None:
    text = restriction("minCardinality", 5) + group(":a :b :c") + group(":d :e") + ":x :p :a, :b, :c, :d, :e .\n"
    onto = reasoned(text)
    assert not x_in_c(onto)  # :a and :d may be the same individual as far as the groups say
    assert counted(onto.report)


def test_small_cardinalities_stay_pairwise_and_see_differentfrom() -> None:
    n = PAIRWISE_MAX
    names = [f":y{i}" for i in range(n)]
    different = " ".join(f"{a} owl:differentFrom {b} ." for i, a in enumerate(names) for b in names[i + 1:])
    onto = reasoned(restriction("minCardinality", n) + f":x :p {', '.join(names)} .\n{different}\n")
    assert x_in_c(onto)
    assert counted(onto.report) == []


def test_incremental_reasoning_follows_values_added_and_removed() -> None:
    onto = reasoned(cardinality_ttl("minCardinality", 10, 9))
    assert not x_in_c(onto)
    onto.load_data(PREFIXES + ":x :p :z . :z a :D . [] a owl:AllDifferent ; owl:distinctMembers (:y0 :z) .", "turtle")
    onto.reason()
    assert not x_in_c(onto)  # :z is only known different from :y0: nine values of one group
    onto.load_data(cardinality_ttl("minCardinality", 10, 10), "turtle")  # :y9 joins :x and the group
    onto.reason()
    assert x_in_c(onto)
    onto.remove_fact("x", "p", "y3")
    onto.reason()
    assert not x_in_c(onto)
    onto.add_fact("x", "p", "y3")
    assert onto.reason().stats.mode != "full" and x_in_c(onto)
    assert onto.reason(mode="full") and x_in_c(onto)  # the same closure from scratch


# ---------------------------------------------------------------- rules too large to evaluate

@pytest.mark.parametrize("axiom", [
    ":C owl:equivalentClass [ a owl:Class ; owl:intersectionOf ({}) ] .".format(" ".join(f":A{i}" for i in range(300))),
    ":q owl:propertyChainAxiom ({}) .".format(" ".join(f":p{i}" for i in range(300))),
])
def test_a_rule_too_large_is_refused_and_nothing_changes(axiom: str) -> None:
    onto = reasoned(cardinality_ttl("minCardinality", 3, 3))
    triples = len(list(onto.sparql("SELECT * WHERE { ?s ?p ?o }")))
    with pytest.raises(RuleCompileError, match="too large to evaluate safely"):
        onto.load_data(PREFIXES + axiom, "turtle")
    assert len(list(onto.sparql("SELECT * WHERE { ?s ?p ?o }"))) == triples
    assert onto.reason().consistent and x_in_c(onto)


def test_a_class_expression_nested_too_deep_is_set_aside_and_named() -> None:
    """Read by recursion, 150 nested complements would overflow the stack: the axiom is set aside,
    the load says so, and the rest of the ontology is reasoned."""
    onto = reasoned(cardinality_ttl("minCardinality", 3, 3))
    with pytest.warns(OntologyWarning, match="nested more than"):
        onto.load_data(PREFIXES + ":C owl:equivalentClass " + "[ owl:complementOf " * 150 + ":A" + " ]" * 150
                       + " .", "turtle")
    report = onto.reason()
    assert report.consistent and x_in_c(onto)
    assert any("nested more than" in n.reason for n in report.incomplete)


def test_the_benchmark_row_runs_in_a_child_and_reports_the_answer() -> None:
    from benchmarks.cardinality import cases, run_child

    row = run_child(None, "maxCardinality", 5, 6, True, False, timeout=120)
    assert row["outcome"].endswith(" s") and row["consistent"] is False
    assert len(cases([40, 600])) == 7 and all(f == 0 for _, _, f, _, _ in cases([40], empty=True))
    with pytest.raises(ValueError, match="kind must be one of"):
        cardinality_ttl("someCardinality", 3, 3)


def test_the_cli_prints_the_named_warning(tmp_path: Path) -> None:
    from click.testing import CliRunner

    from topostore.cli.group import cli

    path = tmp_path / "card.ttl"
    path.write_text(cardinality_ttl("minCardinality", 10, 10))
    result = CliRunner().invoke(cli, ["reason", str(path)])
    assert result.exit_code == 0, result.output
    assert f"{COUNTED_ONLY}: (p min 10 Thing)" in result.output


# ---------------------------------------------------------------- incremental = full, on random changes

COUNTED_TBOX = PREFIXES + """:p a owl:ObjectProperty . :d a owl:DatatypeProperty . :D a owl:Class .
:C owl:equivalentClass [ a owl:Restriction ; owl:onProperty :p ; owl:minQualifiedCardinality 4 ; owl:onClass :D ] .
:M owl:equivalentClass [ a owl:Restriction ; owl:onProperty :p ; owl:maxCardinality 5 ] .
:V owl:equivalentClass [ a owl:Restriction ; owl:onProperty :d ; owl:minCardinality 4 ] .
[] a owl:AllDifferent ; owl:distinctMembers (:y0 :y1 :y2 :y3 :y4 :y5) .
"""
CHANGES = st.lists(st.tuples(st.booleans(), st.sampled_from(["x", "z"]),
                             st.sampled_from(["p y0", "p y1", "p y2", "p y3", "p y4", "p y5", "p w", "d 1", "d 2",
                                              "d 3", "d 4", "d 5", "type D y0", "type D y1", "type D w",
                                              "same w y0", "type M"])), min_size=1, max_size=8)


def _triple(onto: Ontology, subject: str, change: str):
    from pyoxigraph import Literal, NamedNode, Triple

    from topostore.rdf.vocab import SAME_AS, TYPE

    ns = "http://example.org/card#"
    kind, *rest = change.split()
    if kind == "p":
        return Triple(NamedNode(ns + subject), NamedNode(ns + "p"), NamedNode(ns + rest[0]))
    if kind == "d":
        return Triple(NamedNode(ns + subject), NamedNode(ns + "d"), Literal(rest[0], datatype=NamedNode(
            "http://www.w3.org/2001/XMLSchema#integer")))
    if kind == "same":
        return Triple(NamedNode(ns + rest[0]), SAME_AS, NamedNode(ns + rest[1]))
    target = rest[1] if len(rest) > 1 else subject
    return Triple(NamedNode(ns + target), TYPE, NamedNode(ns + rest[0]))


def _closure(onto: Ontology) -> tuple[bool, set]:
    report = onto.report
    rows = onto.sparql("SELECT ?s ?c WHERE { ?s a ?c FILTER(STRSTARTS(STR(?c), 'http://example.org/card#')) }")
    return report.consistent, {(r["s"].value, r["c"].value) for r in rows}




@settings(max_examples=property_examples(40), deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(changes=CHANGES)
def test_incremental_counting_equals_a_full_reason(changes: list) -> None:
    onto = Ontology()
    onto.load_data(COUNTED_TBOX + ":x :p :y0, :y1, :y2 ; :d 7 . :y0 a :D . :y1 a :D . :y2 a :D . :y3 a :D .",
                   "turtle")
    onto.reason()
    for add, subject, change in changes:
        triple = _triple(onto, subject, change)
        (onto.add if add else onto.remove)(triple)
        onto.reason(mode="incremental")
        incremental = _closure(onto)
        onto.reason(mode="full")
        assert _closure(onto) == incremental, (add, subject, change)


def test_the_guard_measures_each_limit() -> None:
    from topostore.compile import condition as cond
    from topostore.compile.guard import RuleLimits, check_rule, measure
    from topostore.compile.rule import Atom, Rule

    atoms = tuple(Atom(f"?v{i}", "<urn:p>", f"?v{i + 1}") for i in range(5))
    rule = Rule("r", "a test", atoms, Atom("?v0", "<urn:q>", "?v5"),
                (cond.test("(((?v0 != ?v1)))"), cond.test("?v1 != ?v2")))
    check_rule(rule, RuleLimits())
    for limits, words in ((RuleLimits(max_atoms=4), "5 body atoms"), (RuleLimits(max_conditions=1), "2 filters"),
                          (RuleLimits(max_tokens=20, lex_above=0), "more than 20 tokens"),
                          (RuleLimits(max_depth=3, lex_above=0), "nesting 5 deep")):
        with pytest.raises(RuleCompileError, match=words):
            check_rule(rule, limits)
    assert measure("SELECT * WHERE { ?s ?p ?o # a comment ((((\n }", 100) == (8, 1)


def counted(report) -> list:
    """The report's notices of cardinalities counted by AllDifferent group only."""
    return [n for n in report.incomplete if n.axiom_kind == COUNTED_ONLY]
