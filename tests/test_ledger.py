"""The change ledger: one record of asserted changes since the last successful REASON.

Incremental REASON reads its net changes, a failed REASON is rolled back from it, and a unit of
work (an aRMOR manipulation) is undone through it; these tests drive each reader on a small
ontology and check the asserted graph afterwards.
"""

from __future__ import annotations

import pytest
from pyoxigraph import NamedNode, Triple
from support import names, too_large_axiom, typed

from topostore import Ontology, RuleCompileError
from topostore.ontology.ledger import check_mode
from topostore.rdf.vocab import ASSERTED, TYPE

EX = "http://example.org/ledger#"
n = names(EX)
TBOX = f"""@prefix : <{EX}> . @prefix owl: <http://www.w3.org/2002/07/owl#> .
@prefix rdfs: <http://www.w3.org/2000/01/rdf-schema#> .
:Robot a owl:Class . :Thing2 a owl:Class . :Robot rdfs:subClassOf :Thing2 .
:speed a owl:DatatypeProperty .
"""


@pytest.fixture
def onto() -> Ontology:
    o = Ontology(prefix=EX)
    o.load_data(TBOX)
    o.add(Triple(n("r1"), TYPE, n("Robot")), Triple(n("r1"), n("speed"), typed("7", "long")))
    o.reason()
    return o


def asserted(o: Ontology) -> set[Triple]:
    return set(o.store.triples(graph=ASSERTED))


def test_nothing_is_recorded_before_the_first_successful_reason() -> None:
    o = Ontology(prefix=EX)
    o.add(Triple(n("r1"), TYPE, n("Robot")))
    assert not o.ledger.recording and o.ledger.added == {} and o.ledger.removed == {}


def test_adding_then_removing_cancels_even_in_another_spelling_of_the_value(onto: Ontology) -> None:
    fact = Triple(n("r2"), n("speed"), typed("8", "long"))
    onto.add(fact)
    assert list(onto.ledger.added.values()) == [fact]
    onto.remove(Triple(n("r2"), n("speed"), typed("8", "integer")))  # the same value, written otherwise
    assert onto.ledger.added == {} and onto.ledger.removed == {}
    assert onto.ledger.net_changes() == ([], [])


def test_incremental_reason_reads_the_net_changes_and_a_success_empties_them(onto: Ontology) -> None:
    onto.add(Triple(n("r2"), TYPE, n("Robot")))
    added, removed = onto.ledger.net_changes()
    assert added == [Triple(n("r2"), TYPE, n("Robot"))] and removed == []
    report = onto.reason(mode="incremental")  # "auto" recomputes a graph this small in full
    assert report.stats.mode == "incremental", report.stats.reason
    assert onto.ledger.net_changes() == ([], []) and n("r2") in onto.instances("Thing2")


def test_a_schema_change_keeps_the_record_for_rollback_but_not_for_incremental_reason(onto: Ontology) -> None:
    onto.add(Triple(n("r2"), TYPE, n("Robot")))
    onto.load_data(f"@prefix : <{EX}> . @prefix owl: <http://www.w3.org/2002/07/owl#> . :Other a owl:Class .")
    assert onto.ledger.net_changes() == ([], [])
    assert Triple(n("r2"), TYPE, n("Robot")) in onto.ledger.added.values()


def test_a_failed_reason_restores_every_change_since_the_last_success_as_written(onto: Ontology) -> None:
    before = asserted(onto)
    onto.remove(Triple(n("r1"), n("speed"), typed("7", "integer")))  # asserted as xsd:long
    onto.add(Triple(n("r2"), TYPE, n("Robot")), *too_large_axiom(EX))
    with pytest.raises(RuleCompileError, match="too large"):
        onto.reason()
    assert asserted(onto) == before
    assert onto.data_values("speed", "r1") == [typed("7", "long")]
    assert onto.ledger.added == {} and onto.ledger.removed == {}
    assert onto.reason().consistent and n("r1") in onto.instances("Thing2")


def test_a_unit_of_work_is_undone_newest_first_when_it_fails(onto: Ontology) -> None:
    before = asserted(onto)
    with pytest.raises(KeyError), onto.ledger.undoable(onto):
        onto.remove(Triple(n("r1"), n("speed"), typed("7", "long")))
        onto.add(Triple(n("r1"), n("speed"), typed("9", "long")), Triple(n("r3"), TYPE, n("Robot")))
        raise KeyError("a later step failed")
    assert asserted(onto) == before
    assert onto.ledger.added == {} and onto.ledger.removed == {}  # the undo cancelled the net record too


def test_a_change_is_one_step_of_a_unit_of_work_and_is_undone_whole(onto: Ontology) -> None:
    """A REPLACE's removal and addition are recorded by one call: one step, undone addition first."""
    before = asserted(onto)
    old, new = Triple(n("r1"), n("speed"), typed("7", "long")), Triple(n("r1"), n("speed"), typed("9", "long"))
    with pytest.raises(KeyError), onto.ledger.undoable(onto):
        onto.change([new], [old])
        assert onto.ledger._steps == [([new], [old])]
        onto.change([Triple(n("r3"), TYPE, n("Robot"))], [new])
        assert len(onto.ledger._steps) == 2
        raise KeyError("a later step failed")
    assert asserted(onto) == before
    assert onto.data_values("speed", "r1") == [typed("7", "long")]
    assert onto.ledger.added == {} and onto.ledger.removed == {} and onto.ledger._steps == []


def test_a_unit_of_work_that_succeeds_keeps_its_changes_and_works_before_any_reason() -> None:
    o = Ontology(prefix=EX)
    with o.ledger.undoable(o):
        o.add(Triple(n("r1"), TYPE, n("Robot")))
    assert Triple(n("r1"), TYPE, n("Robot")) in asserted(o)
    with pytest.raises(ValueError), o.ledger.undoable(o):
        o.add(Triple(n("r2"), TYPE, n("Robot")))
        raise ValueError("refused")
    assert Triple(n("r2"), TYPE, n("Robot")) not in asserted(o)


def test_a_wrong_mode_is_refused_once_and_undoes_nothing(onto: Ontology) -> None:
    onto.add(Triple(n("r2"), TYPE, n("Robot")))
    with pytest.raises(ValueError, match="unknown reasoning mode 'sometimes'"):
        onto.reason(mode="sometimes")
    assert Triple(n("r2"), TYPE, n("Robot")) in asserted(onto)
    with pytest.raises(ValueError):
        check_mode("")
    check_mode("full")


def test_add_new_and_remove_present_return_and_record_what_changed(onto: Ontology) -> None:
    """The one presence look-up of a change decides both what it returns and what the ledger records;
    a triple already there (or absent) is neither returned nor recorded, in any spelling of its value."""
    known, fresh = Triple(n("r1"), TYPE, n("Robot")), Triple(n("r2"), n("speed"), typed("9", "int"))
    assert onto.add_new(known, fresh, fresh) == [fresh]
    assert list(onto.ledger.added.values()) == [fresh]
    assert onto.add_new(Triple(n("r2"), n("speed"), typed("09", "integer"))) == []
    gone = onto.remove_present(Triple(n("r1"), n("speed"), typed("7", "integer")), Triple(n("r3"), TYPE, n("Robot")))
    assert gone == [Triple(n("r1"), n("speed"), typed("7", "integer"))]
    assert list(onto.ledger.removed.values()) == [Triple(n("r1"), n("speed"), typed("7", "long"))]  # as written
    assert onto.remove_present(*gone) == [] and onto.add(known) == 0 and onto.remove(fresh) == 1
    assert onto.ledger.added == {}
    assert {t for t in asserted(onto) if t.subject in (n("r1"), n("r2"))} == {known}


@pytest.mark.parametrize("kind", ["add", "remove", "replace"])
def test_a_unit_of_work_around_a_store_transaction_that_fails_leaves_nothing_in_the_record(
        onto: Ontology, kind: str) -> None:
    """The transaction rolls the store back before the unit of work undoes its steps: the steps whose
    change never landed are taken out of the record too, so the next REASON is not told of them."""
    before = asserted(onto)
    old = Triple(n("r1"), n("speed"), typed("7", "long"))
    new = Triple(n("r1"), n("speed"), typed("9", "long"))
    with pytest.raises(RuntimeError), onto.ledger.undoable(onto), onto.store.transaction():
        if kind != "add":
            onto.changes.remove(old)
        if kind != "remove":
            onto.changes.add(new)
        onto.changes.add(Triple(n("r3"), TYPE, n("Robot")))
        raise RuntimeError("the caller's own failure")
    assert asserted(onto) == before
    assert onto.ledger.added == {} and onto.ledger.removed == {}
    onto.add(Triple(n("r4"), TYPE, n("Robot")))  # a later change is recorded as itself alone
    assert onto.ledger.net_changes() == ([Triple(n("r4"), TYPE, n("Robot"))], [])
    onto.reason()
    assert n("Thing2") in set(onto.types("r4")) and n("Thing2") not in set(onto.types("r3"))


def test_a_change_made_again_after_a_failed_transaction_inside_one_unit_is_undone_exactly(onto: Ontology) -> None:
    """Inside one unit: a store transaction adds a fact and fails, the caller adds it again (it lands), then
    the unit fails: the record holds nothing (the fact was never there before the unit)."""
    before = asserted(onto)
    t = Triple(n("r3"), TYPE, n("Robot"))
    with pytest.raises(KeyError), onto.ledger.undoable(onto):
        with pytest.raises(RuntimeError), onto.store.transaction():
            onto.changes.add(t)
            raise RuntimeError("the transaction's own failure")
        assert onto.ledger.added == {}  # rolled back: never made
        onto.changes.add(t)
        raise KeyError("the unit's failure")
    assert asserted(onto) == before
    assert onto.ledger.added == {} and onto.ledger.removed == {}


def test_a_schema_change_a_failed_transaction_rolled_back_leaves_no_rule_compiled_from_it(onto: Ontology) -> None:
    subclass = NamedNode("http://www.w3.org/2000/01/rdf-schema#subClassOf")
    with pytest.raises(RuntimeError), onto.store.transaction():
        onto.changes.add(Triple(n("Robot"), subclass, n("Thing3")))
        assert onto.rules is not None  # compiled while the axiom was pending
        raise RuntimeError("the transaction's own failure")
    onto.add(Triple(n("r2"), TYPE, n("Robot")))
    onto.reason(mode="full")
    assert set(onto.types("r2")) == {n("Robot"), n("Thing2")}


def test_a_commit_that_fails_while_writing_leaves_nothing_in_the_record(
        onto: Ontology, monkeypatch: pytest.MonkeyPatch) -> None:
    t = Triple(n("r2"), TYPE, n("Robot"))

    def full_disk(*_args, **_kwargs) -> None:
        raise OSError("no space left on the device")

    with monkeypatch.context() as patched:
        patched.setattr(onto.store, "_write", full_disk)
        with pytest.raises(OSError):
            onto.add(t)
    assert t not in asserted(onto)
    assert onto.ledger.added == {} and onto.ledger.removed == {}
    onto.reason(mode="incremental")
    assert onto.types("r2") == []
