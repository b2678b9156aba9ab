"""Functional and inverse-functional object properties as rows of ``rules/owl/prp-fp.rq`` and ``prp-ifp.rq``.

The sameAs rule of such a property (its two values, or two subjects, are one individual unless known
different) is the file's rule with the property as its row: the rule set holds a table, not a rule per
property, and a full REASON runs the generic rule over the table when it is large.  The checks (two values
known different, two distinct values of a functional data property), the candidate rules asking whether two
values differ and the rules finding two individuals different by their values are rows of their files too.
Generic equals instantiated, closure and violations; incremental equals from scratch.
"""

from __future__ import annotations

import sys
from collections.abc import Callable
from pathlib import Path
from typing import Any

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from profiles import property_examples
from pyoxigraph import NamedNode, Triple
from test_incremental import assert_same_as_scratch
from test_schema_rules import _materialize

from topostore import Ontology
from topostore.compile.generic import parse_rule_text
from topostore.compile.schema import schema_rule
from topostore.compile.schema_program import full_program
from topostore.errors import RuleCompileError
from topostore.rdf.vocab import SAME_AS
from topostore.reason.consistency import check_consistency

NS = "http://example.org/functional#"
PREFIXES = f"""\
@prefix : <{NS}> .
@prefix owl: <http://www.w3.org/2002/07/owl#> .
@prefix xsd: <http://www.w3.org/2001/XMLSchema#> .
"""


def functional_tbox(n: int) -> str:
    """``n`` functional object properties, ``n`` inverse-functional ones and ``n`` functional data properties,
    each with values that merge (two values, two subjects), one pair known different and two distinct data
    values (violations)."""
    lines = [PREFIXES]
    for i in range(n):
        lines += [f":f{i} a owl:ObjectProperty, owl:FunctionalProperty .",
                  f":g{i} a owl:ObjectProperty, owl:InverseFunctionalProperty .",
                  f":d{i} a owl:DatatypeProperty, owl:FunctionalProperty .",
                  f":a{i} :f{i} :u{i}, :v{i} . :v{i} :q :w{i} .",
                  f":m{i} :g{i} :o{i} . :n{i} :g{i} :o{i} .",
                  f":b{i} :d{i} 5 ."]
    lines += [":q a owl:ObjectProperty .",
              ":k :f0 :x1, :x2 . :x1 owl:differentFrom :x2 .",  # two values known different
              ":s1 :g0 :t . :s2 :g0 :t . :s1 owl:differentFrom :s2 .",  # two subjects known different
              ":c :d0 5, 6 ."]  # two distinct values of a functional data property
    return "\n".join(lines) + "\n"


def _loaded(text: str) -> Ontology:
    onto = Ontology()
    onto.load_data(text, "turtle")
    return onto


def _violations(onto: Ontology) -> set[tuple[str, tuple]]:
    return {(v.rule, v.axiom, tuple(sorted(str(t) for t in v.individuals.values())))
            for v in check_consistency(onto.store, onto.rules)}


def test_the_same_as_rules_are_rows_of_their_files() -> None:
    onto = _loaded(functional_tbox(20))
    rules = onto.rules
    fp, ifp = schema_rule("prp-fp"), schema_rule("prp-ifp")
    assert fp.rule.stratum == ifp.rule.stratum == 1
    assert rules.tables is not None
    assert sorted(rules.tables.rows("prp-fp")) == sorted((f"<{NS}f{i}>",) for i in range(20))
    assert sorted(rules.tables.rows("prp-ifp")) == sorted((f"<{NS}g{i}>",) for i in range(20))
    same_as = [r for r in rules.rules if r.head is not None and r.head.p == str(SAME_AS) and r.name in ("prp-fp", "prp-ifp")]
    assert same_as == []  # held as rows, not rules of their own
    assert [r for r in rules.rules if r.name in ("prp-fp", "prp-ifp")] == []  # the checks too: rows
    checks = [r for r in rules.checks if r.name in ("prp-fp", "prp-ifp")]
    assert len(checks) == 60  # two values known different (f, g), two distinct data values (d), bound back
    for key, prop in (("prp-fp-3", "f"), ("prp-ifp-3", "g"), ("prp-fp-2-data", "d")):
        assert sorted(rules.tables.rows(key)) == sorted((f"<{NS}{prop}{i}>",) for i in range(20)), key
    kinds = {"prp-fp-3": "functional", "prp-ifp-3": "inverse functional", "prp-fp-2-data": "functional"}
    for key, kind in kinds.items():  # the message names the property as the compiler's did
        check = rules.tables.held[key][0]
        assert check.is_check and check.violation == ("?x", "?y1", "?y2")
        assert check.message.endswith(f"of the {kind} property {check.origin.split()[0]}"), check.message
    instance = rules.tables.held["prp-fp"][0]
    assert instance.stratum == 1 and not instance.is_check and fp.row_of(instance) in rules.tables.rows("prp-fp")


def test_generic_equals_instantiated_closure_and_violations() -> None:
    onto = _loaded(functional_tbox(20))
    program = full_program(onto.rules, 0)
    assert {"prp-fp", "prp-ifp"} <= set(program.rows)
    instantiated = _materialize(onto, sys.maxsize)
    broken = _violations(onto)
    generic = _materialize(onto, 0)
    assert generic == instantiated and _violations(onto) == broken
    inferred = instantiated[0]
    same = NamedNode(str(SAME_AS)[1:-1])
    for i in range(20):
        assert (NamedNode(f"{NS}u{i}"), same, NamedNode(f"{NS}v{i}")) in inferred
        assert (NamedNode(f"{NS}m{i}"), same, NamedNode(f"{NS}n{i}")) in inferred
        assert (NamedNode(f"{NS}u{i}"), NamedNode(NS + "q"), NamedNode(f"{NS}w{i}")) in inferred  # through sameAs
    for a, b in (("x1", "x2"), ("s1", "s2")):
        assert (NamedNode(NS + a), same, NamedNode(NS + b)) not in inferred  # known different: not merged
    assert {v[0] for v in broken} == {"prp-fp", "prp-ifp"}, broken
    assert len(broken) == 3  # :k with x1, x2; :c with 5, 6; :t with s1, s2 (each pair once, either order)


def test_a_full_reason_agrees_with_the_instantiated_rules() -> None:
    onto = _loaded(functional_tbox(20))
    report = onto.reason(mode="full")
    assert not report.consistent
    assert {v.rule for v in report.violations} == {"prp-fp", "prp-ifp"}


def test_the_stratum_header_is_read_and_checked(tmp_path: Path) -> None:
    body = "CONSTRUCT { ?x <urn:q> ?y }\nWHERE {\n  ?x <urn:p> ?y .\n}\n"
    (tmp_path / "r.rq").write_text("# name: r\n# stratum: 2\n" + body)
    assert parse_rule_text(tmp_path / "r.rq")[0].stratum == 2
    (tmp_path / "plain.rq").write_text("# name: plain\n" + body)
    assert parse_rule_text(tmp_path / "plain.rq")[0].stratum == 0
    (tmp_path / "bad.rq").write_text("# name: bad\n# stratum: high\n" + body)
    with pytest.raises(RuleCompileError, match="stratum"):
        parse_rule_text(tmp_path / "bad.rq")


# ---------------------------------------------------------------- incremental = from scratch
_TBOX = PREFIXES + """\
:f a owl:ObjectProperty, owl:FunctionalProperty . :g a owl:ObjectProperty, owl:InverseFunctionalProperty .
:d a owl:DatatypeProperty, owl:FunctionalProperty . :q a owl:ObjectProperty .
"""
_ind = st.sampled_from([f"i{i}" for i in range(4)])
_fact = st.one_of(st.builds(lambda s, p, o: (s, p, o), _ind, st.sampled_from(["f", "g", "q"]), _ind),
                  st.builds(lambda s, v: (s, "d", v), _ind, st.integers(1, 3)),
                  st.builds(lambda s, o: (s, "differentFrom", o), _ind, _ind))


def _triple(fact: tuple) -> Triple:
    from pyoxigraph import Literal

    s, p, o = fact
    pred = NamedNode("http://www.w3.org/2002/07/owl#differentFrom") if p == "differentFrom" else NamedNode(NS + p)
    obj = Literal(str(o), datatype=NamedNode("http://www.w3.org/2001/XMLSchema#integer")) if p == "d" \
        else NamedNode(NS + o)
    return Triple(NamedNode(NS + s), pred, obj)


def _walk(onto: Ontology, steps: list, triple: Callable[[Any], Triple]) -> None:
    """Add each step's facts, remove facts added before (by index), and hold the closure against a
    REASON from scratch after each step."""
    onto.max_change_share = 1.0
    assert_same_as_scratch(onto)
    added: list[Triple] = []
    for facts, removed in steps:
        triples = [triple(f) for f in facts]
        onto.add(*triples)
        added += triples
        gone = list(dict.fromkeys(added[i] for i in removed if i < len(added)))
        if gone:
            onto.remove(*gone)
            added = [t for t in added if t not in gone]
        assert_same_as_scratch(onto)


@settings(max_examples=property_examples(30), deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.lists(st.tuples(st.lists(_fact, max_size=3), st.lists(st.integers(0, 20), max_size=2)), min_size=1,
                max_size=5))
def test_incremental_equals_from_scratch(steps: list) -> None:
    """Each step adds facts and removes facts added before (by index): merges made and undone, values
    made known different and no longer."""
    onto = _loaded(_TBOX)
    _walk(onto, steps, _triple)


def test_the_files_filters_are_the_compilers_texts() -> None:
    """A store with graphs of its own (a remote store's prefix) renames the helper graph's full IRI in a
    rule's text: the files write the filter as the compiler does, not with a prefixed name it would miss."""
    from topostore.compile.snippets import not_different

    for name in ("prp-fp", "prp-ifp"):
        tests, negated = schema_rule(name).rule.conditions
        assert negated.text == not_different("?y1", "?y2").text
        assert tests.text == "FILTER(!sameTerm(?y1, ?y2) && isIRI(?y1) && isIRI(?y2))"


# ---------------------------------------------------------------- the difference rules as rows
def difference_tbox(n: int) -> str:
    """:func:`functional_tbox` with two values of each functional object property made different by their
    values of a functional data property (:y, :z) and by a class allowing one value of a data property (:r,
    :s): every such pair a violation of the property's check, found through the difference rules."""
    lines = [functional_tbox(n), ":xsdint a owl:Class ."]
    for i in range(n):
        lines += [f":e{i} a owl:DatatypeProperty .",
                  f":One{i} owl:equivalentClass [ a owl:Restriction ; owl:onProperty :e{i} ; "
                  f'owl:maxCardinality "1"^^xsd:nonNegativeInteger ] .',
                  f":h{i} :f{i} :y{i}, :z{i} . :y{i} :d{i} 1 . :z{i} :d{i} 2 .",
                  f":j{i} :g{i} :w{i} . :k{i} :g{i} :w{i} . :j{i} :d{i} 3 . :k{i} :d{i} 4 .",
                  f":r{i} :f{i} :p{i}, :q{i} . :p{i} a :One{i} ; :e{i} 1 . :q{i} :e{i} 2 ."]
    return "\n".join(lines) + "\n"


def test_the_difference_rules_are_rows_of_their_files() -> None:
    onto = _loaded(difference_tbox(20))
    tables = onto.rules.tables
    assert tables is not None
    props = {"f": "different-candidate-2-fp", "g": "different-candidate-2-ifp", "d": "different-values-3"}
    for prop, key in props.items():
        assert sorted(tables.rows(key)) == sorted((f"<{NS}{prop}{i}>",) for i in range(20)), key
    for key in ("different-values-4-a", "different-values-4-b"):
        assert len(tables.rows(key)) == 20 and {row[1] for row in tables.rows(key)} == {f"<{NS}e{i}>" for i in range(20)}
    own = [r for r in onto.rules.rules if r.name in ("different-candidate", "different-values")
           and r.origin.endswith(("is functional", "is inverse functional", "allows one value"))]
    assert own == []  # held as rows, not a rule per property


def test_the_difference_rules_generic_equal_instantiated() -> None:
    onto = _loaded(difference_tbox(20))
    program = full_program(onto.rules, 0)
    assert {"different-candidate-2-fp", "different-candidate-2-ifp", "different-values-3",
            "different-values-4-a", "different-values-4-b"} <= set(program.rows)
    instantiated = _materialize(onto, sys.maxsize)
    broken = _violations(onto)
    generic = _materialize(onto, 0)
    assert generic == instantiated and _violations(onto) == broken
    found = {v[2] for v in broken}
    for i in range(20):  # different by values: each pair reported by its property's check
        for pair in (("y", "z"), ("j", "k"), ("p", "q")):
            assert any(f"{NS}{pair[0]}{i}>" in " ".join(t) and f"{NS}{pair[1]}{i}>" in " ".join(t) for t in found), pair
    assert onto.reason(mode="full").consistent is False


def test_a_datatype_the_ranges_do_not_keep_stays_a_rule_of_its_own() -> None:
    """A max 1 restriction on a datatype tests each value's datatype, a filter naming the datatype: the
    files' filters read no schema term, so its rules are the compiler's, not rows."""
    onto = _loaded(PREFIXES + """:e a owl:DatatypeProperty .
:One owl:equivalentClass [ a owl:Restriction ; owl:onProperty :e ;
  owl:maxQualifiedCardinality "1"^^xsd:nonNegativeInteger ; owl:onDataRange xsd:integer ] .
:x a :One ; :e 1 . :y :e 2 . :x owl:sameAs :y .
""")
    own = [r for r in onto.rules.rules if r.name == "different-values"]
    assert len(own) == 2
    assert onto.rules.tables is None or "different-values-4-a" not in onto.rules.tables.held
    assert not onto.reason(mode="full").consistent


_ONE_TBOX = _TBOX + """:e a owl:DatatypeProperty . :One owl:equivalentClass [ a owl:Restriction ; owl:onProperty :e ;
  owl:maxCardinality "1"^^xsd:nonNegativeInteger ] .
"""
_one_fact = st.one_of(_fact, st.builds(lambda s, v: (s, "e", v), _ind, st.integers(1, 3)),
                      st.builds(lambda s: (s, "type", "One"), _ind))


def _one_triple(fact: tuple) -> Triple:
    from pyoxigraph import Literal

    s, p, o = fact
    if p == "type":
        return Triple(NamedNode(NS + s), NamedNode("http://www.w3.org/1999/02/22-rdf-syntax-ns#type"), NamedNode(NS + o))
    if p == "e":
        return Triple(NamedNode(NS + s), NamedNode(NS + p),
                      Literal(str(o), datatype=NamedNode("http://www.w3.org/2001/XMLSchema#integer")))
    return _triple(fact)


@settings(max_examples=property_examples(30), deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.lists(st.tuples(st.lists(_one_fact, max_size=3), st.lists(st.integers(0, 20), max_size=2)), min_size=1,
                max_size=5))
def test_incremental_equals_from_scratch_with_one_value_classes(steps: list) -> None:
    """As :func:`test_incremental_equals_from_scratch`, with a class allowing one value of ``e``: two
    individuals asked about (two values of ``f``, two subjects of ``g``) made different by their values."""
    onto = _loaded(_ONE_TBOX)
    assert {"different-values-4-a", "different-values-4-b", "different-values-3"} <= set(onto.rules.tables.held)
    _walk(onto, steps, _one_triple)
