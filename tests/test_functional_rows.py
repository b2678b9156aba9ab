"""Functional and inverse-functional object properties as rows of ``rules/owl/prp-fp.rq`` and ``prp-ifp.rq``.

The sameAs rule of such a property (its two values, or two subjects, are one individual unless known
different) is the file's rule with the property as its row: the rule set holds a table, not a rule per
property, and a full REASON runs the generic rule over the table when it is large.  The checks (two values
known different, two distinct values of a functional data property) stay a rule per property.  Generic
equals instantiated, closure and violations; incremental equals from scratch.
"""

from __future__ import annotations

import sys
from pathlib import Path

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
    checks = [r for r in rules.rules if r.name in ("prp-fp", "prp-ifp") and r.is_check]
    assert len(checks) == 60  # two values known different (f, g), two distinct data values (d)
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


@settings(max_examples=property_examples(30), deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.lists(st.tuples(st.lists(_fact, max_size=3), st.lists(st.integers(0, 20), max_size=2)), min_size=1,
                max_size=5))
def test_incremental_equals_from_scratch(steps: list) -> None:
    """Each step adds facts and removes facts added before (by index): merges made and undone, values
    made known different and no longer."""
    onto = _loaded(_TBOX)
    onto.max_change_share = 1.0
    assert_same_as_scratch(onto)
    added: list[Triple] = []
    for facts, removed in steps:
        triples = [_triple(f) for f in facts]
        onto.add(*triples)
        added += triples
        gone = list(dict.fromkeys(added[i] for i in removed if i < len(added)))
        if gone:
            onto.remove(*gone)
            added = [t for t in added if t not in gone]
        assert_same_as_scratch(onto)


def test_the_files_filters_are_the_compilers_texts() -> None:
    """A store with graphs of its own (a remote store's prefix) renames the helper graph's full IRI in a
    rule's text: the files write the filter as the compiler does, not with a prefixed name it would miss."""
    from topostore.compile.snippets import not_different

    for name in ("prp-fp", "prp-ifp"):
        tests, negated = schema_rule(name).rule.conditions
        assert negated.text == not_different("?y1", "?y2").text
        assert tests.text == "FILTER(!sameTerm(?y1, ?y2) && isIRI(?y1) && isIRI(?y2))"
