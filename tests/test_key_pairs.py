"""A full run asks a pair of values different by AllDifferent keys as one count per group
(reason/key_pairs.py): the same matches as the pairwise rule, which stays as written."""

from __future__ import annotations

import itertools
import sys
from pathlib import Path

import pytest
from support import closure, map_or_text

from topostore import Ontology
from topostore.compile.rule import Atom, Rule
from topostore.reason import insert_text
from topostore.reason.key_pairs import grouped_form
from topostore.resources import default_ontology_files

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))  # the benchmarks package lives beside src/
from benchmarks.cardinality import PREFIXES  # noqa: E402


def example() -> Ontology:
    onto = Ontology()
    for path in default_ontology_files():
        onto.load(path)
    return onto


def test_the_maps_minimum_of_two_by_keys_has_a_count_form_and_nothing_else_does() -> None:
    rules = example().rules.inference_rules
    grouped = [r for r in rules if grouped_form(r) is not None]
    assert [(r.name, r.origin) for r in grouped] == [("ext-min-card", "class expression (hasDoor min 2 DOOR)")]
    pair = grouped_form(grouped[0])
    assert pair.shared == ("?x",) and len(pair.rule.body) == 2  # one door and its key
    assert grouped[0].body != pair.rule.body  # the rule itself keeps both doors (explanations show them)


def test_a_rule_that_is_not_symmetric_in_its_two_values_keeps_its_text() -> None:
    rule = next(r for r in example().rules.inference_rules if grouped_form(r) is not None)
    # the second door must also be a DOOR, the first need not: the count would ask it of both
    lopsided = Rule(rule.name, rule.origin, rule.body + (Atom("?y2", "<urn:t:type>", "<urn:t:D>"),), rule.head,
                    rule.conditions)
    assert grouped_form(lopsided) is None
    without_difference = Rule(rule.name, rule.origin, rule.body, rule.head,
                              tuple(c for c in rule.conditions if "k1_d" not in c.text))
    assert grouped_form(without_difference) is None


@pytest.mark.parametrize("size", [2, 3])
def test_two_values_and_two_keys_of_a_group_are_a_pair_different_in_both(size: int) -> None:
    """Every relation between ``size`` values and ``size`` keys: some two pairs differ in value and
    in key exactly when the pairs hold two values and two keys (the count's question)."""
    cells = list(itertools.product(range(size), range(size)))
    for n in range(len(cells) + 1):
        for pairs in itertools.combinations(cells, n):
            pairwise = any(a[0] != b[0] and a[1] != b[1] for a in pairs for b in pairs)
            counted = len({v for v, _ in pairs}) > 1 and len({k for _, k in pairs}) > 1
            assert pairwise == counted, pairs


MIN2 = PREFIXES + """:p a owl:ObjectProperty . :D a owl:Class .
:C owl:equivalentClass [ a owl:Restriction ; owl:onProperty :p ; owl:minQualifiedCardinality 2 ; owl:onClass :D ] .
"""
CASES = [
    ":x :p :a, :b . :a a :D . :b a :D . [] a owl:AllDifferent ; owl:distinctMembers (:a :b) .",
    ":x :p :a, :a2 . :a a :D . :a2 a :D . :a2 owl:sameAs :a . [] a owl:AllDifferent ; owl:distinctMembers (:a :b) .",
    ":x :p :a, :b . :a a :D . :b a :D . [] a owl:AllDifferent ; owl:distinctMembers (:a :c) . "
    "[] a owl:AllDifferent ; owl:distinctMembers (:b :c) .",
    ":x :p :a, :b . :a a :D . [] a owl:AllDifferent ; owl:distinctMembers (:a :b) .",
    ":x :p :a, :b2 . :a a :D . :b a :D . :b2 owl:sameAs :b . [] a owl:AllDifferent ; owl:distinctMembers (:a :b) .",
    ":x :p :a, :b . :y :p :b, :c . :a a :D . :b a :D . :c a :D . [] a owl:AllDifferent ; owl:distinctMembers (:a :c) . "
    "[] a owl:AllDifferent ; owl:distinctMembers (:b :c) .",
]


def loaded(source: str) -> Ontology:
    if source == "example":
        return example()
    return map_or_text(None if source == "map" else MIN2 + CASES[int(source)])


@pytest.mark.parametrize("source", ["example", "map"] + [str(i) for i in range(len(CASES))])
def test_a_full_reason_reaches_the_same_closure_with_and_without_the_count(
        source: str, monkeypatch: pytest.MonkeyPatch) -> None:
    onto = loaded(source)
    first = onto.reason(mode="full")
    counted = closure(onto)
    monkeypatch.setattr(insert_text, "grouped_form", lambda rule: None)
    again = onto.reason(mode="full")
    assert closure(onto) == counted
    assert first.consistent == again.consistent
