"""A keyed conclusion's first pass without its key atoms (topostore.reason.keyed_first_pass): taken only where
the census shows the keys one to one with their holders in one group, and the same closure as the pass
with its keys wherever they are not."""

from __future__ import annotations

import pytest
from support import closure, map_or_text, quiet_turtle
from test_inline_difference import BORN
from test_swrl_difference import PREFIXES

from topostore import Ontology
from topostore.rdf.vocab import DIFFERENT_KEY_OF
from topostore.reason import early_reads, early_rules
from topostore.reason.early_rules import EarlyRules
from topostore.reason.keyed_asks import KeyCensus

SIBLINGS = ":c :hasParent :t . :a :born 1990 . :b :born 1992 . "
#: case -> (Turtle, whether the census covers at the keyed conclusion's turn)
CASES = {
    "one group": ("[] a owl:AllDifferent ; owl:distinctMembers (:a :b :c) .", True),
    # d holds a key and no parent: a key whose holder the body never binds
    "a member outside the body": ("[] a owl:AllDifferent ; owl:distinctMembers (:a :b :c :d) .", True),
    # b holds no key: a and b are not different by the keys
    "a holder without a key": ("[] a owl:AllDifferent ; owl:distinctMembers (:a :c) .", False),
    "a group of one": ("[] a owl:AllDifferent ; owl:distinctMembers (:a) .", False),
    "two groups": ("[] a owl:AllDifferent ; owl:distinctMembers (:a :c) . "
                   "[] a owl:AllDifferent ; owl:distinctMembers (:b :t) .", False),
    # a in both: b and c are in no group together
    "a member of two groups": ("[] a owl:AllDifferent ; owl:distinctMembers (:a :c) . "
                               "[] a owl:AllDifferent ; owl:distinctMembers (:a :b) .", False),
    # e holds b's key alone (eq-rep-s): b and e share their one key
    "two holders sharing a key": (":e :hasParent :t ; owl:sameAs :b . "
                                  "[] a owl:AllDifferent ; owl:distinctMembers (:a :b :c) .", False),
    # a and b each hold both keys: two keys per holder (inconsistent, as Pellet finds)
    "sameAs between members": (":a owl:sameAs :b . [] a owl:AllDifferent ; owl:distinctMembers (:a :b :c) .", False),
}
#: the cases where the keyed conclusion without its keys would add what the keys do not allow
WRONG_WITHOUT_KEYS = ["a holder without a key", "a group of one", "two groups", "a member of two groups",
                      "two holders sharing a key"]


def family(case: str) -> Ontology:
    return quiet_turtle(PREFIXES + BORN + SIBLINGS + CASES[case][0])


def _keyless(monkeypatch: pytest.MonkeyPatch) -> list[tuple[str, bool]]:
    """(rule name, whether its first pass left its keys out) of every keyed conclusion's first pass."""
    log: list[tuple[str, bool]] = []
    keyless = EarlyRules.keyless

    def logged(self, i):
        found = keyless(self, i)
        if i in self.run.keyed:
            log.append((self.run.rules[i].name, found))
        return found

    monkeypatch.setattr(EarlyRules, "keyless", logged)
    return log


def _with_keys(onto: Ontology, monkeypatch: pytest.MonkeyPatch) -> tuple[dict, bool]:
    """The closure and consistency of a full REASON of ``onto`` whose first pass keeps every key atom."""
    with monkeypatch.context() as m:
        m.setattr(EarlyRules, "keyless", lambda self, i: False)
        report = onto.reason(mode="full")
        return closure(onto), report.consistent


@pytest.mark.skipif(not early_reads.ENABLED, reason="the census is taken in the worker thread")
@pytest.mark.parametrize("case", ["map", *CASES])
def test_the_keys_are_left_out_only_where_the_census_covers_and_the_closure_is_the_same(
        case: str, monkeypatch: pytest.MonkeyPatch) -> None:
    onto = map_or_text() if case == "map" else family(case)
    kept, consistent = _with_keys(onto, monkeypatch)
    log = _keyless(monkeypatch)
    report = onto.reason(mode="full")
    assert log and all(name in ("swrl:Connectability", "swrl:siblings") for name, _ in log)
    assert all(used == (case == "map" or CASES[case][1]) for _, used in log), log
    assert closure(onto) == kept and report.consistent == consistent


@pytest.mark.skipif(not early_reads.ENABLED, reason="the census is taken in the worker thread")
@pytest.mark.parametrize("case", WRONG_WITHOUT_KEYS)
def test_leaving_the_keys_out_where_the_census_does_not_cover_changes_the_closure(
        case: str, monkeypatch: pytest.MonkeyPatch) -> None:
    """What the test above guards: in these cases the lean text, used wrongly, derives more."""
    onto = family(case)
    kept, _ = _with_keys(onto, monkeypatch)
    monkeypatch.setattr(EarlyRules, "keyless", lambda self, i: i in self.run.keyed)
    onto.reason(mode="full")
    assert closure(onto) != kept


@pytest.mark.skipif(not early_reads.ENABLED, reason="the census is taken in the worker thread")
@pytest.mark.parametrize("read", ["a body key", "the keys", "the group"])
def test_a_census_is_dropped_once_a_key_it_reads_is_written(read: str, monkeypatch: pytest.MonkeyPatch) -> None:
    """A write of a key the census reads between its start and the keyed conclusion's turn: the keys are kept."""
    log: list[bool] = []
    keyless = EarlyRules.keyless
    written = {"a body key": ("p", "<http://e.org/f#hasParent>"), "the keys": ("p", f"<{DIFFERENT_KEY_OF.value}>"),
               "the group": ("t", "<http://www.w3.org/2002/07/owl#AllDifferent>")}[read]

    def late(self, i):
        if i not in self.run.keyed:
            return keyless(self, i)
        self.wrote(written)  # as an evaluation sent just before the turn
        log.append(keyless(self, i))
        return log[-1]

    monkeypatch.setattr(EarlyRules, "keyless", late)
    onto = family("one group")
    onto.reason(mode="full")
    assert log == [False]


def test_without_the_worker_the_keys_stay(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(early_reads, "ENABLED", False)
    log = _keyless(monkeypatch)
    onto = family("one group")
    assert onto.reason(mode="full").consistent
    assert not log


@pytest.mark.skipif(not early_reads.ENABLED, reason="the census is taken in the worker thread")
def test_the_census_is_queued_after_the_keys_and_before_the_count(monkeypatch: pytest.MonkeyPatch) -> None:
    """The census starts at the same point as the minimum's count (right after the keys) but is awaited
    sooner, at Connectability's turn: the worker runs it before the count, not behind it."""
    ran: list[str] = []
    evaluate, covers = early_rules._evaluate, KeyCensus.covers

    def logged(store, query, graph):
        ran.append("keys" if "rdf:rest*" in query else "count" if "HAVING" in query else query)
        return evaluate(store, query, graph)

    def census(self, store, graphs=None):
        ran.append("census")
        return covers(self, store, graphs)

    monkeypatch.setattr(early_rules, "_evaluate", logged)
    monkeypatch.setattr(KeyCensus, "covers", census)
    log = _keyless(monkeypatch)
    onto = map_or_text()
    onto.reason(mode="full")
    assert ran[:3] == ["keys", "census", "count"], ran
    assert log == [("swrl:Connectability", True)]


def _censuses(monkeypatch: pytest.MonkeyPatch) -> list[bool]:
    """The answers of every census counted (a census answered by one taken before is not counted)."""
    counted: list[bool] = []
    covers = KeyCensus.covers

    def logged(self, store, graphs=None):
        counted.append(covers(self, store, graphs))
        return counted[-1]

    monkeypatch.setattr(KeyCensus, "covers", logged)
    return counted


@pytest.mark.skipif(not early_reads.ENABLED, reason="the census is taken in the worker thread")
@pytest.mark.parametrize("case", ["map", "one group"])
def test_the_deferred_ask_reads_the_census_taken_at_the_conclusions_turn(
        case: str, monkeypatch: pytest.MonkeyPatch) -> None:
    """The deferred ask's census counts what the keyed conclusion's did (nothing it reads written since):
    counted once, and the closure the same as with the keys kept."""
    onto = map_or_text() if case == "map" else family(case)
    kept, consistent = _with_keys(onto, monkeypatch)
    counted = _censuses(monkeypatch)
    report = onto.reason(mode="full")
    assert counted == [True]
    assert closure(onto) == kept and report.consistent == consistent


@pytest.mark.skipif(not early_reads.ENABLED, reason="the census is taken in the worker thread")
@pytest.mark.parametrize("read", ["a body key", "the keys", "the group"])
def test_a_census_written_since_its_conclusions_turn_is_counted_again(
        read: str, monkeypatch: pytest.MonkeyPatch) -> None:
    """A write of a key the census reads after the keyed conclusion's turn: the deferred ask counts again."""
    written = {"a body key": ("p", "<http://e.org/f#hasParent>"), "the keys": ("p", f"<{DIFFERENT_KEY_OF.value}>"),
               "the group": ("t", "<http://www.w3.org/2002/07/owl#AllDifferent>")}[read]
    keyless = EarlyRules.keyless

    def written_after(self, i):
        found = keyless(self, i)
        if i in self.run.keyed:
            self.wrote(written)  # as an evaluation sent right after the conclusion
        return found

    monkeypatch.setattr(EarlyRules, "keyless", written_after)
    counted = _censuses(monkeypatch)
    assert family("one group").reason(mode="full").consistent
    assert counted == [True, True]
