"""One value in two spellings is one fact, whatever the calls: ``"1"^^xsd:int`` and ``"1.0"^^xsd:decimal``.

Oxigraph keeps every integer type as one ``xsd:integer`` term but a decimal as a term of its own, so a
presence look-up of the quad as written missed a value held in the other; and a change naming one value
twice on one side started a fresh pending write after cancelling the first, so it reported (and an undo
took back) a change that never happened.
"""

from __future__ import annotations

import time
import warnings

import pytest
from pyoxigraph import Literal, NamedNode, Quad, Triple
from test_value_spellings import N, assert_same_as_scratch
from test_value_spellings import ontology as rule_ontology

from topostore import Ontology, SpellingKeptWarning
from topostore.armor.reference import Reference
from topostore.rdf.vocab import ASSERTED, XSD
from topostore.sparql.execute import Job, run_update
from topostore.stores import memory_store

NS = "http://example.org/onefact#"
S, P = NamedNode(NS + "s"), NamedNode(NS + "p")
HEAD = f"@prefix : <{NS}> . @prefix owl: <http://www.w3.org/2002/07/owl#> . @prefix xsd: <{XSD}> .\n"
HELD = "is the same value, already in the graph"


def fact(lexical: str, datatype: str) -> Triple:
    return Triple(S, P, Literal(lexical, datatype=NamedNode(XSD + datatype)))


INT, INTEGER, DECIMAL = fact("1", "int"), fact("1", "integer"), fact("1.0", "decimal")


def holding(first: Triple, reasoned: bool = True) -> Ontology:
    """An ontology whose asserted graph holds ``first`` (:p functional), reasoned when asked."""
    o = Ontology()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        o.load_data(HEAD + ":p a owl:DatatypeProperty , owl:FunctionalProperty .", "turtle")
    o.add(first)
    if reasoned:
        o.reason()
    return o


def stored(o: Ontology) -> list[str]:
    """The store's quads of (:s :p), as held (Oxigraph's terms)."""
    return sorted(str(q.object) for q in o.store.triples(S, P, None, ASSERTED))


def shown(o: Ontology) -> list[Literal]:
    """What the ontology shows of (:s :p), as written."""
    return [t.object for t in o.triples() if t.predicate == P]


def by_load(o: Ontology, t: Triple) -> int:
    return o.load_data(HEAD + f"{t.subject} {t.predicate} {t.object} .", "turtle")


def by_add(o: Ontology, t: Triple) -> int:
    return o.add(t)


def by_change(o: Ontology, t: Triple) -> int:
    return len(o.change([t], [])[0])


PATHS = {"load": by_load, "add": by_add, "change": by_change}


@pytest.mark.parametrize("reasoned", [False, True])
@pytest.mark.parametrize("path", sorted(PATHS))
def test_a_decimal_beside_a_held_integer_is_not_stored_and_is_said(path: str, reasoned: bool) -> None:
    o = holding(INT, reasoned)
    with pytest.warns(SpellingKeptWarning, match=HELD) as said:
        assert PATHS[path](o, DECIMAL) == 0
    (note,) = [w for w in said if HELD in str(w.message)]  # said once, not by the load and its change too
    assert str(INT.object) in str(note.message) and str(DECIMAL.object) in str(note.message)
    assert note.filename == __file__  # it points at the caller
    assert stored(o) == [str(INTEGER.object)]
    assert shown(o) == [INT.object]


def test_an_integer_beside_a_held_decimal_is_not_stored() -> None:
    o = holding(DECIMAL)
    with pytest.warns(SpellingKeptWarning, match=HELD):
        assert o.add(INT) == 0
    assert shown(o) == [DECIMAL.object]


def test_a_sparql_update_inserting_a_held_value_in_another_spelling_stores_nothing_and_says_so() -> None:
    o = holding(INT)
    outcome = run_update(Reference("ref", o, NS), f"INSERT DATA {{ {S} {P} {DECIMAL.object} }}",
                         Job(time.monotonic() + 60), 60.0)
    assert stored(o) == [str(INTEGER.object)]
    assert any(HELD in w for w in outcome.warnings)


def test_two_calls_store_what_one_call_stores() -> None:
    one, two = holding(INT, reasoned=False), holding(INT, reasoned=False)
    one.remove(INT)
    one.add(INT, DECIMAL)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", SpellingKeptWarning)
        two.add(DECIMAL)
    assert stored(one) == stored(two) == [str(INTEGER.object)]


@pytest.mark.parametrize(("held", "named"), [(INT, DECIMAL), (DECIMAL, INT), (INT, INTEGER)])
def test_removing_either_spelling_removes_the_fact(held: Triple, named: Triple) -> None:
    o = holding(held)
    assert o.remove(named) == 1
    assert stored(o) == [] and shown(o) == []


def test_a_value_held_in_either_spelling_keeps_a_functional_property_consistent() -> None:
    o = holding(INT)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", SpellingKeptWarning)
        o.add(DECIMAL)
    assert o.reason().consistent


class Failed(Exception):
    """Raised inside a unit of work to have it undone."""


@pytest.mark.parametrize(("add", "remove"), [
    ([INTEGER], [INT, DECIMAL]),
    ([INT, INTEGER], [INT]),
    ([INTEGER, DECIMAL], [INT]),
    ([DECIMAL, INTEGER], [INT]),
    ([INTEGER, DECIMAL], []),
])
def test_a_change_naming_a_held_value_twice_on_one_side_changes_nothing_and_undoes_to_it(
        add: list[Triple], remove: list[Triple]) -> None:
    o = holding(INT)
    with pytest.raises(Failed), warnings.catch_warnings():
        warnings.simplefilter("ignore", SpellingKeptWarning)
        with o.ledger.undoable(o):
            added, removed = o.change(add, remove)
            assert shown(o) == [INT.object]
            raise Failed
    assert [t for t in added if t not in removed] == []  # nothing reported that the graph did not gain
    assert shown(o) == [INT.object] and stored(o) == [str(INTEGER.object)]


def test_a_value_removed_and_added_in_another_spelling_by_two_changes_of_one_transaction_is_no_change() -> None:
    """The store nets the two changes out (its pending write is keyed by value): the ledger does too, so an
    incremental REASON derives nothing from the decimal the graph never held."""
    o = rule_ontology()
    eight = Literal("8", datatype=NamedNode(XSD + "integer"))
    old = Triple(N("x"), N("score"), eight)
    o.add(old, Triple(N("x"), N("limit"), Literal(5)))
    o.reason()
    new = Triple(N("x"), N("score"), Literal("8.0", datatype=NamedNode(XSD + "decimal")))
    with o.store.transaction():
        o.change([], [old])
        o.change([new], [])
    assert o.ledger.net_changes() == ([], [])
    assert_same_as_scratch(o)


GRAPH = NamedNode(NS + "graph")


def test_the_store_removes_a_value_held_as_the_other_term() -> None:
    store = memory_store()
    store.add([INT], GRAPH)
    assert store.add([DECIMAL], GRAPH) == 0
    assert store.remove([DECIMAL], GRAPH) == 1
    assert list(store.triples(S, P, None, GRAPH)) == []


def test_a_graph_holding_both_terms_loses_only_the_one_removed() -> None:
    """A reasoner's graph keeps each spelling a rule derived: a removal there takes its own term only."""
    store = memory_store()
    store.add([INT], GRAPH)
    store._write([Quad(S, P, DECIMAL.object, GRAPH)], [])
    assert store.remove([DECIMAL], GRAPH) == 1
    assert [str(t.object) for t in store.triples(S, P, None, GRAPH)] == [str(INTEGER.object)]
