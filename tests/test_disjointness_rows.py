"""Pairs of disjoint classes held as rows (compile/disjointness.py): the rule set does not grow with the
pairs, and what the pairs conclude (difference, inconsistency) is the same through the generic rule and
check of a full REASON as through the per-pair rules a robot step maintains."""

from __future__ import annotations

import warnings

import pytest

from topostore import Ontology
from topostore.compile.schema_program import GENERIC_ROWS

NS = "http://example.org/d#"
PREFIXES = f"""@prefix : <{NS}> .
@prefix owl: <http://www.w3.org/2002/07/owl#> .
@prefix rdf: <http://www.w3.org/1999/02/22-rdf-syntax-ns#> .
@prefix rdfs: <http://www.w3.org/2000/01/rdf-schema#> .
"""


def siblings(k: int) -> str:
    """``k`` sibling classes made pairwise disjoint (one axiom per pair), a functional property."""
    lines = [":Thing0 a owl:Class .", ":owner a owl:ObjectProperty , owl:FunctionalProperty ."]
    lines += [f":S{i} a owl:Class ; rdfs:subClassOf :Thing0 ." for i in range(k)]
    lines += [f":S{i} owl:disjointWith :S{j} ." for i in range(k) for j in range(i + 1, k)]
    return PREFIXES + "\n".join(lines) + "\n"


def loaded(text: str) -> Ontology:
    onto = Ontology(prefix=NS)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        onto.load_data(text, "turtle")
    return onto


@pytest.mark.parametrize("k", [10, 40])
def test_the_rule_set_does_not_grow_with_the_pairs(k: int) -> None:
    onto = loaded(siblings(k))
    pairs = k * (k - 1) // 2
    rules = onto.rules
    names = [r.name for r in rules.rules]
    assert "different-disjoint" not in names and "cax-dw" not in names
    assert len(rules.rules) <= 60 + 2 * k  # the subclass axioms and the fixed rules: linear in the classes
    assert len(rules.disjointness.different) == 2 * pairs and len(rules.disjointness.told) == pairs
    # the maintained rules and checks have one per row, as a robot step needs them
    assert sum(r.name == "different-disjoint" for r in rules.inference_rules) == 2 * pairs
    assert sum(r.name == "cax-dw" for r in rules.checks) == pairs


def test_an_inconsistency_found_by_the_generic_check_names_the_axiom() -> None:
    k = 12  # 66 told pairs: more than a full REASON keeps instantiated
    assert k * (k - 1) // 2 > GENERIC_ROWS
    onto = loaded(siblings(k) + ":x a :S3 , :S7 .\n:y a :S1 .\n")
    report = onto.reason(mode="full")
    assert not report.consistent
    assert [(v.rule, v.axiom, v.message) for v in report.violations] == [
        ("cax-dw", "S3 DisjointWith S7", "x is in the disjoint classes S3 and S7")]


def test_a_step_reaching_a_pair_equals_a_reason_from_scratch() -> None:
    onto = loaded(siblings(12) + ":x a :S1 .\n:y a :S2 .\n:z a :S5 .\n")
    assert onto.reason(mode="full").consistent
    # a step: x becomes a member of S4 as well, an inconsistency found by a per-pair check
    onto.add_type("x", "S4")
    step = onto.reason()
    assert step.stats.mode == "incremental"
    fresh = loaded(siblings(12) + ":x a :S1 , :S4 .\n:y a :S2 .\n:z a :S5 .\n").reason(mode="full")
    assert [(v.rule, v.axiom, v.message) for v in step.violations] == \
        [(v.rule, v.axiom, v.message) for v in fresh.violations] == [
            ("cax-dw", "S1 DisjointWith S4", "x is in the disjoint classes S1 and S4")]
    onto.remove_type("x", "S4")
    assert onto.reason().consistent


def test_members_of_disjoint_classes_are_different_in_a_full_reason_and_a_step() -> None:
    # a functional property with two values of disjoint classes: they cannot be one individual
    text = siblings(12) + ":x :owner :a , :b .\n:a a :S2 .\n"
    onto = loaded(text + ":b a :S9 .\n")
    report = onto.reason(mode="full")
    assert not report.consistent and {v.rule for v in report.violations} == {"prp-fp"}
    onto.remove_type("b", "S9")
    assert onto.reason().consistent  # a and b may be one individual now
    onto.add_type("b", "S9")
    step = onto.reason()
    fresh = loaded(text + ":b a :S9 .\n").reason(mode="full")
    assert [str(v) for v in step.violations] == [str(v) for v in fresh.violations]
    assert not step.consistent


@pytest.mark.parametrize(("busy", "other"), [((0, 1), (10, 11)), ((5, 6), (2, 9))])
def test_a_busy_violated_pair_does_not_hide_another(busy: tuple[int, int], other: tuple[int, int]) -> None:
    """The one-query check's LIMIT counts rows: 400 individuals in one pair once took every row, and the
    other violated pair went unnamed."""
    lines = [f":x{n} a :S{busy[0]} , :S{busy[1]} ." for n in range(400)]
    lines.append(f":y a :S{other[0]} , :S{other[1]} .")
    onto = loaded(siblings(12) + "\n".join(lines) + "\n")
    report = onto.reason(mode="full")
    assert not report.consistent
    named = {v.axiom for v in report.violations}
    assert named == {f"S{busy[0]} DisjointWith S{busy[1]}", f"S{other[0]} DisjointWith S{other[1]}"}


def test_a_class_expression_disjoint_with_itself_and_folded_into_its_name() -> None:
    """``N ≡ ∃p.B`` with ``∃p.B`` disjoint with itself: the fold renames the expression N, and the told
    row (never among the ordered ones, which leave a class with itself out) must be renamed too."""
    onto = loaded(PREFIXES + """:p a owl:ObjectProperty . :B a owl:Class . :N a owl:Class .
:N owl:equivalentClass _:r . _:r a owl:Restriction ; owl:onProperty :p ; owl:someValuesFrom :B .
_:r owl:disjointWith _:r .
:x :p :y . :y a :B .
""")
    report = onto.reason(mode="full")
    assert not report.consistent
    assert [v.rule for v in report.violations] == ["cax-dw"]


@pytest.mark.parametrize(("first", "second"), [(25, 30), (30, 25)])
def test_each_violated_pair_lists_as_many_individuals_as_its_own_check(first: int, second: int) -> None:
    """A pair that got a few rows before the shared LIMIT was reached is asked again: each pair lists
    MAX_REPORTED individuals, as its own per-pair check does."""
    from topostore.reason.consistency import MAX_REPORTED

    lines = [f":S{i} a owl:Class ." for i in range(5)] + [":S0 owl:disjointWith :S1 . :S2 owl:disjointWith :S3 ."]
    lines += [f":a{n} a :S0 , :S1 ." for n in range(first)] + [f":b{n} a :S2 , :S3 ." for n in range(second)]
    onto = loaded(PREFIXES + "\n".join(lines) + "\n")
    full = onto.reason(mode="full")
    onto.add_type("w", "S4")  # an unrelated change: the step's check runs over the told pairs in one query
    step = onto.reason(mode="incremental")
    for report in (full, step):
        counts: dict[str, int] = {}
        for v in report.violations:
            counts[v.axiom] = counts.get(v.axiom, 0) + 1
        assert counts == {"S0 DisjointWith S1": MAX_REPORTED, "S2 DisjointWith S3": MAX_REPORTED}
