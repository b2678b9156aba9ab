"""A full REASON's first pass of ``A ⟹ C`` reads the asserted A facts alone where every writer of A implies
C through a one-atom rule with a non-literal guard (reason/guarded.py), or only returns A facts already held
(reason/order.py ``_returns``): the closure is the same as with every fact read, and as an incremental
REASON's."""

from __future__ import annotations

import sys
import tempfile
import warnings
from pathlib import Path

import pytest
from support import closure

from topostore import Ontology, OntologyWarning
from topostore.compile.condition import test as guard
from topostore.compile.rule import Atom, Rule
from topostore.reason import full_passes
from topostore.reason.guarded import guarded_classes, guarded_rules
from topostore.reason.implied_passes import implied_first_passes

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))  # the benchmarks package lives beside src/
from benchmarks import maps  # noqa: E402
from benchmarks.cardinality import PREFIXES  # noqa: E402

TYPE = "<http://www.w3.org/1999/02/22-rdf-syntax-ns#type>"
P, Q, E = "<urn:p>", "<urn:q>", "<urn:E>"
#: p(x, y) ∧ !isLiteral(y) ⟹ E(x): the existential's rule once its filler atom, implied by a range, is dropped
SOME = Rule("cls-svf1", "", (Atom("?x", P, "?y"),), Atom("?x", TYPE, E), conditions=(guard("!isLiteral(?y)"),))


def writer(*atoms: Atom, conditions=()) -> Rule:
    return Rule("w", "", atoms, Atom("?s", TYPE, "<urn:A>"), conditions=tuple(conditions))


@pytest.mark.parametrize(("rule", "implies"), [
    (writer(Atom("?s", P, "?v")), False),  # ?v may be a literal: the guarded rule does not fire there
    (writer(Atom("?s", P, "?v"), Atom("?v", Q, "?w")), True),  # a subject is never a literal
    (writer(Atom("?s", P, "?v"), conditions=[guard("!isLiteral(?v)")]), True),
    (writer(Atom("?s", P, "<urn:b>")), True),
    (writer(Atom("?s", P, '"1"')), False),
    (writer(Atom("?v", P, "?s"), Atom("?s", Q, "?w")), False),  # the term at the other place
    (writer(Atom("?s", Q, "?v"), Atom("?v", Q, "?w")), False),  # another predicate
])
def test_a_writer_implies_a_guarded_head_where_the_guard_holds(rule: Rule, implies: bool) -> None:
    rules = guarded_rules([SOME])
    assert len(rules) == 1
    assert (E in guarded_classes("?s", rule, rules, {})) is implies


def test_a_rule_with_another_condition_is_no_guarded_rule() -> None:
    other = Rule("r", "", SOME.body, SOME.head, conditions=(guard("isLiteral(?y)"),))
    assert guarded_rules([other]) == []


MIN = PREFIXES + """:p a owl:ObjectProperty ; rdfs:range :D . :D a owl:Class .
:Some owl:equivalentClass [ a owl:Restriction ; owl:onProperty :p ; owl:someValuesFrom :D ] .
:Two owl:equivalentClass [ a owl:Class ; owl:intersectionOf ( :L
    [ a owl:Restriction ; owl:onProperty :p ; owl:minQualifiedCardinality 2 ; owl:onClass :D ] ) ] .
"""


@pytest.mark.parametrize(("data", "some"), [
    (":x :p :a, :b . :x a :L . [] a owl:AllDifferent ; owl:distinctMembers (:a :b) .", {"x"}),
    (":x a :Two .", {"x"}),  # asserted: the minimum holds with no value known, and so does the existential
    (":x a :L . :y :p :a . [] a owl:AllDifferent ; owl:distinctMembers (:a :b) .", {"y"}),
    (':x :p "v" .', set()),
])
def test_a_minimum_implies_the_existential_in_both_modes(data: str, some: set) -> None:
    onto = Ontology()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", OntologyWarning)
        onto.load_data(MIN + data, "turtle")
        onto.reason(mode="full")
    assert {onto.short(i) for i in onto.instances("Some")} == some
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", OntologyWarning)
        onto.reason(mode="incremental")
    assert {onto.short(i) for i in onto.instances("Some")} == some


def test_on_the_map_the_minimum_s_subsumption_is_left_to_the_existential(monkeypatch: pytest.MonkeyPatch) -> None:
    """ext-card-sub (≥2 hasDoor.DOOR ⊑ ∃hasDoor.DOOR, now CORRIDOR ⊑ ROOM) has nothing asserted to read on
    the map: not evaluated, with the closure unchanged against a run whose one-atom first passes read
    every member."""
    onto, report = _map_reasoned()
    assert "ext-card-sub" not in report.stats.per_rule
    shortened = closure(onto)
    real = full_passes.implied_first_passes
    monkeypatch.setattr(full_passes, "implied_first_passes", lambda rules, ordered, asserted=None: real(rules, ordered))
    onto.reason(mode="full", profile=True)
    assert closure(onto) == shortened


def _class_rule(name: str, body: tuple[Atom, ...], cls: str) -> Rule:
    return Rule(name, "", body, Atom("?x", TYPE, cls))


L, R, CO = "<urn:L>", "<urn:R>", "<urn:Co>"
#: p's domain L, ∃p ⊑ R, ≥2 p ⊑ Co, Co ⊑ R and R ⊑ L: every R stands on a p link, whose domain is L
CHAIN = [
    _class_rule("prp-dom", (Atom("?x", P, "?y"),), L),
    _class_rule("cls-svf1", (Atom("?x", P, "?y"),), R),
    _class_rule("ext-min-card", (Atom("?x", P, "?y1"), Atom("?x", P, "?y2")), CO),
    _class_rule("ext-card-sub", (Atom("?x", TYPE, CO),), R),
    _class_rule("cls-int2", (Atom("?x", TYPE, R),), L),
]


@pytest.mark.parametrize(("rules", "asserted", "chosen"), [
    (CHAIN, (set(), set()), True),
    (CHAIN, (set(), {CO}), False),  # an asserted Co need not be L
    (CHAIN, None, False),  # the asserted keys unknown
    # Co's writer reads q, which says nothing of L
    ([*CHAIN[:2], _class_rule("ext-min-card", (Atom("?x", Q, "?y"),), CO), *CHAIN[3:]], (set(), set()), False),
])
def test_a_subclass_copy_reads_the_asserted_facts_alone_where_its_writer_s_writers_imply_it(
        rules: list[Rule], asserted, chosen: bool) -> None:
    """R ⊑ L, R written by ∃p (p's domain is L) and by Co ⊑ R, Co written by ≥2 p alone: every R fact
    the pass can find is of a term L holds of already (two steps back: the Co fact's own writer)."""
    assert (4 in implied_first_passes(rules, list(range(len(rules))), asserted)) is chosen


def test_on_the_map_the_rooms_are_not_copied_into_locations(monkeypatch: pytest.MonkeyPatch) -> None:
    """ROOM ⊑ LOCATION (cls-int2) finds no ROOM that is not a LOCATION on the map: its writers are ∃hasDoor
    and CORRIDOR ⊑ ROOM, and CORRIDOR's writer reads hasDoor, whose domain is LOCATION.  Not evaluated,
    the closure the same as a run whose one-atom first passes read every member."""
    onto, report = _map_reasoned()
    assert "cls-int2" not in report.stats.per_rule
    shortened = closure(onto)
    monkeypatch.setattr(full_passes, "implied_first_passes", lambda rules, ordered, asserted=None: set())
    onto.reason(mode="full", profile=True)
    assert closure(onto) == shortened


def _map_reasoned() -> tuple[Ontology, object]:
    """The 200-location bench map loaded and reasoned in full, with its per-rule profile."""
    onto = Ontology()
    with tempfile.TemporaryDirectory() as tmp, warnings.catch_warnings():
        warnings.simplefilter("ignore", OntologyWarning)
        path, _ = maps.write("200", Path(tmp))
        onto.load(path)
    return onto, onto.reason(mode="full", profile=True)
