"""A deferred ask left out where a census of the AllDifferent keys shows every body pair's conclusion
known (reason/keyed_asks.py): the same closure, and the ask evaluated wherever a pair may be unkeyed,
share a key, or belong to another group."""

from __future__ import annotations

import pytest
from support import closure, map_or_text, quiet_turtle
from test_inline_difference import BORN, entailed_siblings
from test_swrl_difference import PREFIXES

from topostore import Ontology
from topostore.compile.rule import Atom, Rule
from topostore.rdf.vocab import DIFFERENT_KEY_OF
from topostore.reason import early_reads, keyed_asks
from topostore.reason.keyed_asks import KeyCensus, key_censuses

SIBLINGS = ":c :hasParent :t . "
CASES = {
    # every sibling a member of one AllDifferent: every pair's conclusion is known by the keys
    "one group": (BORN + SIBLINGS + ":a :born 1990 . :b :born 1992 . [] a owl:AllDifferent ; owl:distinctMembers (:a :b :c) .", set()),
    # b is outside the AllDifferent: a and b are different by their birth years alone
    "a sibling outside": (BORN + SIBLINGS + ":a :born 1990 . :b :born 1992 . "
                          "[] a owl:AllDifferent ; owl:distinctMembers (:a :c) .", {("a", "b"), ("b", "a")}),
    "two groups": (BORN + SIBLINGS + ":a :born 1990 . :b :born 1992 . "
                   "[] a owl:AllDifferent ; owl:distinctMembers (:a :c) . "
                   "[] a owl:AllDifferent ; owl:distinctMembers (:b :t) .", {("a", "b"), ("b", "a")}),
    # e holds b's key (eq-rep-s) and no other: b and e share their one key, so are not different by it
    "a key shared by sameAs": (BORN + SIBLINGS + ":e :hasParent :t ; owl:sameAs :b . :a :born 1990 . "
                               "[] a owl:AllDifferent ; owl:distinctMembers (:a :b :c) .", set()),
}
#: more disjoint classes than joins allowed (compile/inline_difference.py MAX_JOINED): candidates stay
MANY_DISJOINT = "[] a owl:AllDisjointClasses ; owl:members (:K1 :K2 :K3 :K4 :K5 :K6) . "


def family(case: str) -> Ontology:
    return quiet_turtle(PREFIXES + CASES[case][0])


def census(onto: Ontology) -> KeyCensus:
    (found,) = key_censuses(onto.rules.inference_rules).values()
    return found


@pytest.mark.parametrize("case", CASES)
def test_the_answers_are_published_whatever_the_census(case: str) -> None:
    onto = family(case)
    assert onto.reason(mode="full").consistent
    assert entailed_siblings(onto) == CASES[case][1]


@pytest.mark.parametrize("case", CASES)
def test_the_census_covers_only_one_group_of_keyed_unshared_individuals(case: str) -> None:
    onto = family(case)
    onto.reason(mode="full")
    assert keyed_asks.covered(onto.store, census(onto), ()) == (case == "one group")


@pytest.mark.parametrize("case", ["map", *CASES])
def test_a_full_reason_reaches_the_same_closure_with_and_without_the_census(
        case: str, monkeypatch: pytest.MonkeyPatch) -> None:
    onto = map_or_text() if case == "map" else family(case)
    first = onto.reason(mode="full")
    kept = closure(onto)
    monkeypatch.setattr(KeyCensus, "covers", lambda self, store, graphs=None: False)
    again = onto.reason(mode="full")
    assert closure(onto) == kept and first.consistent == again.consistent


def test_a_census_wrongly_covering_loses_an_answer(monkeypatch: pytest.MonkeyPatch) -> None:
    """What the answer tests above guard: where a pair is unkeyed, leaving the ask out loses its twin."""
    monkeypatch.setattr(KeyCensus, "covers", lambda self, store, graphs=None: True)
    onto = family("a sibling outside")
    onto.reason(mode="full")
    assert entailed_siblings(onto) != CASES["a sibling outside"][1]


@pytest.mark.parametrize("early", [True, False], ids=["asked early", "asked at its turn"])
@pytest.mark.parametrize("case", ["map", "one group"])
def test_a_covered_ask_never_reads_its_body(case: str, early: bool, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(early_reads, "ENABLED", early and early_reads.ENABLED)
    onto = map_or_text() if case == "map" else family(case)
    onto.reason()
    minus = f"MINUS {{ {onto.rules.inference_rules[_deferred(onto)].unless_known.text()} }}"
    sent: list[str] = []
    update, query = onto.store.update, onto.store.query
    monkeypatch.setattr(onto.store, "update", lambda text, *a, **k: (sent.append(text), update(text, *a, **k))[1])
    monkeypatch.setattr(onto.store, "query", lambda text, *a, **k: (sent.append(text), query(text, *a, **k))[1])
    onto.reason(mode="full")
    assert any("COUNT(DISTINCT" in t and str(DIFFERENT_KEY_OF) in t for t in sent)
    assert not any(minus in t for t in sent)


def test_no_census_where_another_rule_writes_keys() -> None:
    onto = family("one group")
    rules = list(onto.rules.inference_rules)
    assert key_censuses(rules)
    writer = Rule("mine", "a rule writing keys", (Atom("?x", "<http://e.org/f#p>", "?k"),),
                  Atom("?k", f"<{DIFFERENT_KEY_OF.value}>", "?x", aux=True))
    assert key_censuses([*rules, writer]) == {}


def test_no_census_without_the_keyed_conclusion() -> None:
    """Past MAX_JOINED the conclusion is not joined with the keys: nothing tells that a keyed pair's
    conclusion is known, and no census is taken."""
    onto = quiet_turtle(PREFIXES + MANY_DISJOINT + CASES["a sibling outside"][0])
    assert key_censuses(onto.rules.inference_rules) == {}
    assert onto.reason(mode="full").consistent
    assert entailed_siblings(onto) == CASES["a sibling outside"][1]
    rules = onto.rules.inference_rules
    one = family("one group").rules.inference_rules
    assert key_censuses([r for r in one if not any(a.p == f"<{DIFFERENT_KEY_OF.value}>" and a.aux
                                                   for a in r.body)]) == {}
    assert rules


def _deferred(onto: Ontology) -> int:
    (index,) = key_censuses(onto.rules.inference_rules)
    return index
