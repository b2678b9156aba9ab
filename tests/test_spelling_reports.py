"""What a change reports is what the store took, and every spelling it wrote and did not store is said.

One value is one fact, kept in the spelling written first (``"1"^^xsd:int``, ``"1"^^xsd:integer`` and
``"1.0"^^xsd:decimal`` are one value).  A call naming a value twice, a SPARQL update inserting a value held
in another spelling and a change removing and adding one value each used to report (or leave unsaid) what
the store never did.  The property test runs random sequences of calls against a model of values.
"""

from __future__ import annotations

import time
import warnings
from contextlib import nullcontext

import pytest
from hypothesis import HealthCheck, example, given, settings
from hypothesis import strategies as st
from pyoxigraph import Literal, NamedNode, Triple
from test_one_fact_per_value import DECIMAL, HEAD, INT, INTEGER, NS, P, S, holding, shown, stored
from test_value_spellings import N, assert_same_as_scratch
from test_value_spellings import ontology as rule_ontology

from topostore import Ontology, SpellingKeptWarning
from topostore.armor.reference import Reference
from topostore.rdf.terms import value_key
from topostore.rdf.vocab import ASSERTED, XSD
from topostore.sparql.execute import Job, run_update
from topostore.stores import open_store

SAID = "stays as written"


def said(caught: list[warnings.WarningMessage]) -> list[str]:
    """The texts of the SpellingKeptWarnings caught."""
    return [str(w.message) for w in caught if issubclass(w.category, SpellingKeptWarning)]


def fresh(reasoned: bool) -> Ontology:
    """An ontology with :p declared and nothing of (:s :p), reasoned (its changes recorded) when asked."""
    o = Ontology()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        o.load_data(HEAD + ":p a owl:DatatypeProperty .", "turtle")
    if reasoned:
        o.reason()
    return o


def by_add(o: Ontology, *ts: Triple) -> int:
    return o.add(*ts)


def by_add_new(o: Ontology, *ts: Triple) -> int:
    return len(o.add_new(*ts))


def by_change(o: Ontology, *ts: Triple) -> int:
    return len(o.change(list(ts), [])[0])


PATHS = {"add": by_add, "add_new": by_add_new, "change": by_change}


@pytest.mark.parametrize("reasoned", [False, True])
@pytest.mark.parametrize("path", sorted(PATHS))
def test_two_spellings_of_one_value_in_one_call_store_the_first_and_say_the_second(path: str, reasoned: bool) -> None:
    o = fresh(reasoned)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        assert PATHS[path](o, INT, DECIMAL) == 1
    (note,) = said(caught)
    assert note.startswith(f"{S} {P} {INT.object} {SAID}") and str(DECIMAL.object) in note
    assert [w.filename for w in caught if issubclass(w.category, SpellingKeptWarning)] == [__file__]
    assert shown(o) == [INT.object]


@pytest.mark.parametrize("reasoned", [False, True])
def test_add_data_says_a_spelling_held_already(reasoned: bool) -> None:
    o = holding(INT, reasoned)
    with pytest.warns(SpellingKeptWarning, match="already in the graph") as caught:
        assert o.add_data(f"<{NS}p>", f"<{NS}s>", "1.0", XSD + "decimal") == 0
    assert [w.filename for w in caught] == [__file__]
    assert shown(o) == [INT.object]


def test_add_fact_says_a_spelling_held_already() -> None:
    o = holding(INT)
    with pytest.warns(SpellingKeptWarning, match="already in the graph"):
        assert o.add_fact(f"<{NS}s>", f"<{NS}p>", DECIMAL.object) == 0
    assert shown(o) == [INT.object]


def test_a_replace_by_the_value_held_in_another_spelling_replaces_nothing_and_says_so() -> None:
    o = holding(INT)
    with pytest.warns(SpellingKeptWarning, match=SAID):
        assert o.replace(f"<{NS}s>", f"<{NS}p>", DECIMAL.object) == 0
    assert shown(o) == [INT.object]
    assert o.ledger.net_changes() == ([], [])


def update(o: Ontology, text: str) -> tuple[int, int, list[str]]:
    """A SPARQL update's reported counts and warnings."""
    outcome = run_update(Reference("ref", o, NS), text, Job(time.monotonic() + 60), 60.0)
    return outcome.added, outcome.removed, outcome.warnings


def test_a_sparql_update_inserting_a_held_value_in_another_spelling_counts_nothing_added() -> None:
    o = holding(INT)
    added, removed, notes = update(o, f"INSERT DATA {{ {S} {P} {DECIMAL.object} }}")
    assert (added, removed) == (0, 0)
    assert any("already in the graph" in n for n in notes)
    assert stored(o) == [str(INTEGER.object)]


def test_a_sparql_update_respelling_a_value_counts_neither_side() -> None:
    o = holding(INT)
    added, removed, notes = update(o, f"DELETE DATA {{ {S} {P} {INT.object} }} ; "
                                      f"INSERT DATA {{ {S} {P} {DECIMAL.object} }}")
    assert (added, removed) == (0, 0)
    assert any(SAID in n for n in notes)
    assert shown(o) == [INT.object]


def test_a_sparql_update_counts_what_it_stored() -> None:
    o = holding(INT)
    two = Literal("2", datatype=NamedNode(XSD + "integer"))
    assert update(o, f"DELETE DATA {{ {S} {P} {INT.object} }} ; INSERT DATA {{ {S} {P} {two} }}")[:2] == (1, 1)


class Failed(Exception):
    """Raised inside a unit of work to have it undone."""


def test_a_value_removed_and_added_in_two_spellings_is_no_change_and_says_the_spelling_not_stored() -> None:
    o = holding(INT)
    with pytest.raises(Failed), pytest.warns(SpellingKeptWarning, match=SAID) as caught:
        with o.ledger.undoable(o):
            assert o.change([INT, INTEGER], [INT]) == ([], [])
            assert o.ledger.net_changes() == ([], [])
            assert o.ledger._steps == []
            raise Failed
    assert any(str(INTEGER.object) in str(w.message) for w in caught)
    assert shown(o) == [INT.object]


def test_a_value_removed_and_added_in_one_spelling_is_no_change() -> None:
    o = holding(INT)
    assert o.change([INT], [INT]) == ([], [])
    assert o.ledger.net_changes() == ([], [])
    assert shown(o) == [INT.object]


def test_a_value_written_earlier_in_the_transaction_is_respelled_by_a_change_and_reported_so() -> None:
    """Added by one change and removed and added in another spelling by the next, in one transaction: the
    graph never held the first spelling, so the store writes the second, and the report and the ledger say
    the second change removed one and added the other (an incremental REASON reads the decimal)."""
    o = rule_ontology()
    o.add(Triple(N("x"), N("limit"), Literal(5)))
    o.reason()
    eight = Triple(N("x"), N("score"), Literal("8", datatype=NamedNode(XSD + "integer")))
    decimal = Triple(N("x"), N("score"), Literal("8.0", datatype=NamedNode(XSD + "decimal")))
    with warnings.catch_warnings():
        warnings.simplefilter("error", SpellingKeptWarning)
        with o.store.transaction():
            o.change([eight], [])
            assert o.change([decimal], [eight]) == ([decimal], [eight])
    assert [t.object for t in o.triples() if t.predicate == N("score")] == [decimal.object]
    assert [value_key(t.object) for t in o.ledger.net_changes()[0] if t.predicate == N("score")] == \
        [value_key(decimal.object)]
    assert_same_as_scratch(o)


# ---------------------------------------------------------------------------------------------- the model
ONE = [INT, INTEGER, DECIMAL, Triple(S, P, Literal("01", datatype=NamedNode(XSD + "int")))]
TWO = [Triple(S, P, Literal(lexical, datatype=NamedNode(XSD + datatype)))
       for lexical, datatype in (("2", "integer"), ("2.0", "decimal"), ("2", "long"))]
SPELLINGS = st.sampled_from(ONE + TWO)
SIDE = st.lists(SPELLINGS, max_size=3)
CALLS = st.lists(st.one_of(
    st.tuples(st.just("add"), SIDE, st.just([])),
    st.tuples(st.just("add_new"), SIDE, st.just([])),
    st.tuples(st.just("remove"), st.just([]), SIDE),
    st.tuples(st.just("change"), SIDE, SIDE),
    st.tuples(st.just("replace"), SPELLINGS.map(lambda t: [t]), st.just([])),
), max_size=6)


def value(t: Triple) -> tuple:
    return value_key(t.object)


def model_call(kept: dict[tuple, Literal], committed: dict[tuple, Literal] | None, call: str, add: list[Triple],
               remove: list[Triple]) -> tuple[dict[tuple, Literal], set[tuple], set[tuple], set[Literal]]:
    """The values after ``call`` (value → spelling), those it added and removed (a value whose spelling
    changed counts as both), and the spellings it wrote and did not store.

    A call is one transaction unless ``committed`` gives the values the graph held when the open one began.
    A value removed and added again in one transaction keeps the spelling the graph held when it began (the
    store's pending write of it is taken back); a value added twice keeps the spelling written first."""
    before = dict(kept)
    after = dict(kept)
    held = before if committed is None else committed
    if call == "replace":
        remove = [Triple(S, P, o) for o in kept.values()]
    for t in remove:
        after.pop(value(t), None)
    for t in add:
        v = value(t)
        if v not in after:
            after[v] = held[v] if v in held and (call in ("change", "replace") or committed is not None) else t.object
    respelled = {v for v in before.keys() & after.keys() if before[v] != after[v]}
    not_stored = {t.object for t in add if after[value(t)] != t.object}
    return after, (after.keys() - before.keys()) | respelled, (before.keys() - after.keys()) | respelled, not_stored


def run_call(o: Ontology, call: str, add: list[Triple], remove: list[Triple]) -> tuple[list | None, list]:
    """The call on the ontology: the values it reports added and removed (a count as that many Nones; None:
    not reported)."""
    if call == "add":
        return [None] * o.add(*add), []
    if call == "add_new":
        return [value(t) for t in o.add_new(*add)], []
    if call == "remove":
        return [], [None] * o.remove(*remove)
    if call == "change":
        added, removed = o.change(add, remove)
        return [value(t) for t in added], [value(t) for t in removed]
    return None, [None] * o.replace(f"<{NS}s>", f"<{NS}p>", add[0].object)  # how many removed only


def spellings(o: Ontology) -> dict[tuple, Literal]:
    return {value_key(lit): lit for lit in shown(o)}


def run_calls(o: Ontology, calls: list, start: dict[tuple, Literal], one_transaction: bool) -> dict[tuple, Literal]:
    """The calls on the ontology, each checked against the model (what it reports, stores and says); the
    values left (value → spelling)."""
    kept = dict(start)
    with o.store.transaction() if one_transaction else nullcontext():
        for call, add, remove in calls:
            after, gained, lost, not_stored = model_call(kept, start if one_transaction else None, call, add, remove)
            with warnings.catch_warnings(record=True) as caught:
                warnings.simplefilter("always")
                added, removed = run_call(o, call, add, remove)
            where = (call, add, remove)
            assert added is None or len(added) == len(gained), where
            assert len(removed) == len(lost), where
            if call in ("add_new", "change"):
                assert set(added) == gained, where
            if call == "change":
                assert set(removed) == lost, where
            assert spellings(o) == after, where
            notes = said(caught)
            for lit in not_stored:
                assert any(str(lit) in n for n in notes), (*where, lit, notes)
            assert bool(notes) == bool(not_stored), (*where, notes)
            kept = after
    return kept


@settings(max_examples=300, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(initial=st.lists(SPELLINGS, max_size=3), calls=CALLS, reasoned=st.booleans(), one_transaction=st.booleans(),
       revert=st.booleans())
@example(initial=[INT], calls=[("replace", [TWO[0]], []), ("add", [INTEGER], [])], reasoned=True,
         one_transaction=False, revert=True)  # the value back in another spelling of its stored term
@example(initial=[INT], calls=[("replace", [TWO[0]], []), ("replace", [ONE[3]], []), ("replace", [TWO[2]], [])],
         reasoned=True, one_transaction=False, revert=True)  # ... and removed again in that spelling
def test_reports_store_ledger_and_undo_agree_with_a_model_of_values(initial: list[Triple], calls: list,
                                                                     reasoned: bool, one_transaction: bool,
                                                                     revert: bool) -> None:
    """Each call agrees with the model; then the calls are undone, by the unit of work they ran in failing or
    (reasoned) by a revert of the ledger (a failed REASON's), and every value is back in the spelling held
    before them, the one the store held at the last REASON."""
    o = fresh(False)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", SpellingKeptWarning)
        o.add(*initial)
    if reasoned:
        o.reason()
    start = spellings(o)
    revert = revert and reasoned
    with nullcontext() if revert else pytest.raises(Failed), o.ledger.undoable(o):
        kept = run_calls(o, calls, start, one_transaction)
        if reasoned:
            net_added, net_removed = o.ledger.net_changes()
            was = {o.store.stored_form(Triple(S, P, lit)) for lit in start.values()}
            now = {o.store.stored_form(Triple(S, P, lit)) for lit in kept.values()}
            assert (set(net_added), set(net_removed)) == (now - was, was - now)
        if not revert:
            raise Failed
    if revert:
        o.ledger.revert(o.store)
    assert spellings(o) == start  # the values come back, each in the spelling it was held in
    if reasoned:
        assert o.ledger.net_changes() == ([], [])


@pytest.mark.parametrize("later", [DECIMAL, ONE[3]], ids=["a decimal", "one Oxigraph term"])
@pytest.mark.parametrize("reasoned", [False, True])
def test_an_undo_restores_the_spelling_a_value_was_held_in(reasoned: bool, later: Triple) -> None:
    """Undone, a removal of ``"1"^^xsd:int`` and an addition of ``"1.0"^^xsd:decimal`` (or ``"01"^^xsd:int``,
    the same term in Oxigraph) give the integer back: the undo's removal and addition of the value, in one
    transaction, are a respelling the store writes."""
    o = holding(INT, reasoned=reasoned)
    with pytest.raises(Failed), o.ledger.undoable(o):
        o.remove(INT)
        o.add(later)
        raise Failed
    assert shown(o) == [INT.object]
    assert stored(o) == [str(INTEGER.object)]
    assert o.ledger.net_changes() == ([], [])


def _undo_a_respelling(o: Ontology) -> None:
    """``o`` holds INT, REASONed; a unit of undo replaces it by DECIMAL (the same value) and fails."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        o.load_data(HEAD + ":p a owl:DatatypeProperty .", "turtle")
    o.add(INT)
    o.reason()
    with pytest.raises(Failed), o.ledger.undoable(o):
        o.remove(INT)
        o.add(DECIMAL)
        raise Failed


def test_an_undo_on_a_durable_store_keeps_the_restored_spelling_when_reopened(tmp_path) -> None:
    """The respelling's forms are persisted with it: reopened, the store shows the spelling held."""
    o = Ontology(store=str(tmp_path))
    _undo_a_respelling(o)
    o.store.close()
    again = Ontology(store=str(tmp_path))
    try:
        assert (shown(again), stored(again)) == ([INT.object], [str(INTEGER.object)])
    finally:
        again.store.close()


def test_an_undo_on_a_remote_store_restores_the_spelling_on_the_server(oxigraph_url: str) -> None:
    """A store that keeps literals as written (a remote one) is sent the respelling as one update."""
    o = Ontology(store=open_store(oxigraph_url, reference="undo-respelled"))
    try:
        _undo_a_respelling(o)
        o.store.send_writes()
        assert shown(o) == [INT.object]
    finally:
        o.store.close()
    server = open_store(oxigraph_url, reference="undo-respelled")  # what the server holds, nothing cached
    try:
        assert [t.object.datatype for t in server.triples(S, P, None, ASSERTED)] == [INTEGER.object.datatype]
    finally:
        server.close()


def undone_in_open_transaction(o: Ontology) -> None:
    """Inside an open transaction, a unit of work that removed :s :p 1 and added it as a decimal, each change
    committed (as a SPARQL query inside the transaction would), is undone."""
    with pytest.raises(Failed), o.ledger.undoable(o):
        o.remove(INT)
        o.store._flush_open()
        o.add(DECIMAL)
        o.store._flush_open()
        raise Failed


def test_an_undo_joining_an_open_transaction_restores_the_spelling_when_it_commits() -> None:
    o = holding(INT)
    with o.store.transaction():
        undone_in_open_transaction(o)
        assert [t.object for t in o.store.triples(S, P, None, ASSERTED)] == [INT.object]  # the held one hidden
    assert shown(o) == [INT.object]
    assert o.ledger.net_changes() == ([], [])


def test_a_value_respelled_by_an_undo_and_removed_in_its_transaction_is_removed_as_held() -> None:
    """The respelling an undo left pending is taken back by a removal of the value: the held spelling goes."""
    o = holding(INT)
    with o.store.transaction():
        undone_in_open_transaction(o)
        assert o.remove(INTEGER) == 1
        assert list(o.store.triples(S, P, None, ASSERTED)) == []
        assert o.add(DECIMAL) == 1
    assert shown(o) == [DECIMAL.object]
    assert_same_as_scratch(o)


def test_an_incremental_reason_after_an_undo_that_respelled_a_value_equals_one_from_scratch() -> None:
    """The undo's respelling is recorded as the change it is (the decimal removed, the integer added), so an
    incremental REASON after it derives from the spelling the graph holds."""
    o = rule_ontology()
    eight = Triple(N("x"), N("score"), Literal("8", datatype=NamedNode(XSD + "int")))
    decimal = Triple(N("x"), N("score"), Literal("8.0", datatype=NamedNode(XSD + "decimal")))
    o.add(Triple(N("x"), N("limit"), Literal(5)), eight)
    o.reason()
    with pytest.raises(Failed), o.ledger.undoable(o):
        o.remove(eight)
        o.add(decimal)
        o.reason()
        raise Failed
    assert [t.object for t in o.triples() if t.predicate == N("score")] == [eight.object]
    assert_same_as_scratch(o)


def test_a_failed_reason_reverts_a_value_to_the_spelling_it_was_held_in() -> None:
    """A REASON that fails reverts the asserted changes since the last good one, in the spellings held."""
    o = holding(INT, reasoned=True)
    o.remove(INT)
    o.add(DECIMAL)
    reverted = o.ledger.revert(o.store)
    assert reverted == 2
    assert shown(o) == [INT.object]


def double(lexical: str) -> Literal:
    return Literal(lexical, datatype=NamedNode(XSD + "double"))


@pytest.mark.parametrize("steps", [
    [Literal(3), double("1.5E0"), Literal("03", datatype=NamedNode(XSD + "int"))],
    [Literal(3), double("1.5E0")],
], ids=["removed again in the other spelling", "held in the other spelling"])
def test_a_revert_gives_back_the_spelling_held_at_the_last_reason(steps: list[Literal]) -> None:
    """``"1.5"`` replaced by 3, then by ``"1.5E0"`` (the stored term of ``"1.5"``: its addition cancels the
    removal in the ledger), then by 03: the revert (a failed REASON's) gives back ``"1.5"``, not the spelling
    of the later removal, nor the one the graph holds."""
    o = holding(Triple(S, P, double("1.5")), reasoned=True)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", SpellingKeptWarning)
        for lit in steps:
            o.replace(f"<{NS}s>", f"<{NS}p>", lit)
    o.ledger.revert(o.store)
    assert shown(o) == [double("1.5")]
    assert o.ledger.net_changes() == ([], [])


def test_inside_an_open_transaction_a_respelled_value_shows_the_spelling_written() -> None:
    """Read-your-writes: the undo's respelling pending in the open transaction is what the ontology shows
    before the commit, not the spelling the committed store holds."""
    o = holding(INT)
    with o.store.transaction():
        undone_in_open_transaction(o)
        assert shown(o) == [INT.object]
        assert o.data_values(P, S) == [INT.object]
    assert shown(o) == [INT.object]


@pytest.mark.parametrize("reasoned", [False, True], ids=["bulk add before the first REASON", "recorded add"])
def test_inside_an_open_transaction_a_spelling_not_stored_is_said_beside_the_one_pending(reasoned: bool) -> None:
    """A value added earlier in the open transaction and added again in another spelling: the warning names the
    spelling the transaction wrote (pending, not committed yet), and the ontology shows it."""
    o = fresh(reasoned)
    with o.store.transaction():
        assert o.add(INT) == 1
        with pytest.warns(SpellingKeptWarning, match=SAID) as caught:
            assert o.add(DECIMAL) == 0
        assert [str(INT.object) in str(w.message) for w in caught if w.category is SpellingKeptWarning] == [True]
        assert shown(o) == [INT.object]
    assert shown(o) == [INT.object]


def test_inside_an_open_transaction_a_respelled_value_written_again_is_said_beside_the_pending_spelling() -> None:
    """The committed store holds the decimal; the undo's respelling pending gives the integer back: adding the
    value in a third spelling names the integer as the one kept."""
    o = holding(INT)
    with o.store.transaction():
        undone_in_open_transaction(o)
        with pytest.warns(SpellingKeptWarning, match=SAID) as caught:
            assert o.add(INTEGER) == 0
        texts = [str(w.message) for w in caught if w.category is SpellingKeptWarning]
        assert len(texts) == 1 and texts[0].startswith(f"{S} {P} {INT.object}"), texts
    assert shown(o) == [INT.object]
