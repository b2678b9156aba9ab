"""Scratch graphs held in Python on the in-memory store (stores/held.py) answer as the store's index would."""

from __future__ import annotations

from hypothesis import given, settings
from hypothesis import strategies as st
from pyoxigraph import Literal, NamedNode, Quad, Triple

from topostore.rdf.vocab import ASSERTED, XSD
from topostore.stores import reads
from topostore.stores.held import HELD_MAX
from topostore.stores.oxigraph import OxigraphStore
from topostore.stores.work import transaction

S = [NamedNode(f"urn:x:s{i}") for i in range(3)]
P = [NamedNode(f"urn:x:p{i}") for i in range(2)]
INTEGER, LONG = NamedNode(XSD + "integer"), NamedNode(XSD + "long")
#: objects: IRIs and literals in several spellings of one value
O = [*S, Literal("5", datatype=INTEGER), Literal("05", datatype=INTEGER), Literal("5", datatype=LONG),
     Literal("7", datatype=INTEGER)]
SCRATCH = [NamedNode(f"urn:x:scratch{i}") for i in range(3)]
OTHER = NamedNode("urn:x:other")
GRAPHS = [*SCRATCH, OTHER, ASSERTED]

triples = st.lists(st.builds(Triple, st.sampled_from(S), st.sampled_from(P), st.sampled_from(O)), max_size=4)
patterns = st.tuples(st.sampled_from([None, *S]), st.sampled_from([None, *P]), st.sampled_from([None, *O]),
                     st.sampled_from([None, *GRAPHS]))
operations = st.one_of(
    st.tuples(st.just("add_scratch"), triples, st.sampled_from(GRAPHS)),
    st.tuples(st.just("discard"), triples, st.sampled_from(GRAPHS)),
    st.tuples(st.just("add"), triples, st.sampled_from(GRAPHS)),
    st.tuples(st.just("read"), patterns),
    st.tuples(st.just("few"), patterns, st.lists(st.sampled_from(GRAPHS), max_size=3), st.integers(0, 3)),
    st.tuples(st.just("pending"), triples, st.sampled_from(GRAPHS), patterns),
    st.tuples(st.just("has"), patterns),
    st.tuples(st.just("contains"), triples, st.sampled_from(GRAPHS)),
    st.tuples(st.just("small"), st.sampled_from(GRAPHS)),
    st.tuples(st.just("copy"), st.sampled_from(SCRATCH), st.sampled_from(GRAPHS)),
    st.tuples(st.just("count"), st.sampled_from(GRAPHS)),
    st.tuples(st.just("drop"), st.lists(st.sampled_from(GRAPHS), min_size=1, max_size=3)),
)


def _terms(fact) -> str:
    """A fact's subject, predicate and object (a triple's, or a quad's as :meth:`.OxigraphStore.matches` gives it)."""
    return f"{fact.subject} {fact.predicate} {fact.object}"


def _run(store: OxigraphStore, op: tuple):
    """One operation; what it answers, comparable between stores."""
    kind = op[0]
    if kind == "add_scratch":
        store.add_scratch(op[1], op[2])
    elif kind == "discard":
        store.discard(op[1], (op[2],))
    elif kind == "add":
        store.add(op[1], op[2])
    elif kind == "read":
        found = sorted(map(str, store.triples(*op[1])))
        assert found == sorted(map(str, reads.triples(store, *op[1])))  # the direct read is the general one
        return found
    elif kind == "few":
        (s, p, o, _), graphs, limit = op[1:]
        found = store.few_facts(s, p, o, graphs, limit)
        general = reads.few_facts(store, s, p, o, graphs, limit)
        assert (found is None) == (general is None) and sorted(map(str, found or [])) == sorted(map(str, general or []))
        if len(graphs) == 1:  # one graph's facts as a look-up join reads them (quads from the index): their terms
            one = store.matches(s, p, o, graphs[0], limit)
            assert (one is None) == (general is None)
            assert sorted(map(_terms, one or [])) == sorted(map(_terms, general or []))
        return None if found is None else sorted(map(str, found))
    elif kind == "has":
        s, p, o, g = op[1]
        found = store.has_match(s, p, o, g)
        assert found == bool(list(reads.triples(store, s, p, o, g)))
        return found
    elif kind == "pending":  # a read inside a transaction sees its pending writes
        with transaction(store):
            store.add(op[1], op[2])
            s, p, o, _ = op[3]
            return sorted(map(str, store.triples(*op[3]))), store.few_facts(s, p, o, (op[2],), 2) is None, \
                sorted(map(_terms, store.matches(s, p, o, op[2], 2) or [])), store.has_match(*op[3])
    elif kind == "contains":
        return store.contains_each(op[1], op[2]), [store.contains(t, op[2]) for t in op[1]]
    elif kind == "small":
        quads = store.small_graph(op[1])
        return (sorted(map(str, quads)), store.is_empty(op[1]))
    elif kind == "copy":  # SPARQL reading a scratch graph and writing one
        store.update(f"INSERT {{ GRAPH {op[2]} {{ ?s ?p ?o }} }} WHERE {{ GRAPH {op[1]} {{ ?s ?p ?o }} }}")
    elif kind == "count":
        return store.count(op[1])
    elif kind == "drop":
        store.drop_graphs(op[1])
    return None


@settings(max_examples=300, deadline=None)
@given(st.lists(operations, max_size=14))
def test_held_scratch_graphs_answer_as_the_index(ops: list[tuple]) -> None:
    held, plain = OxigraphStore(), OxigraphStore()
    held.hold_scratch(SCRATCH)
    for op in ops:
        assert _run(held, op) == _run(plain, op), op
    for g in GRAPHS:
        assert sorted(map(str, held.triples(graph=g))) == sorted(map(str, plain.triples(graph=g)))


def test_a_held_graph_costs_the_store_nothing_until_sparql_needs_it() -> None:
    store = OxigraphStore()
    store.hold_scratch(SCRATCH)
    g = SCRATCH[0]
    store.add_scratch([Triple(S[0], P[0], O[4])], g)
    assert len(store._ox) == 0 and store.contains(Triple(S[0], P[0], O[5]), g)  # "05" is the stored "5"
    store.update(f"INSERT {{ GRAPH {OTHER} {{ ?s ?p ?o }} }} WHERE {{ GRAPH {g} {{ ?s ?p ?o }} }}")
    assert len(store._ox) == 2  # the held fact moved to the store before the update read it
    store.add_scratch([Triple(S[1], P[0], S[2])], g)  # the graph stays in the store until dropped
    assert len(store._ox) == 3
    store.drop_graphs(SCRATCH)
    assert len(store._ox) == 1


def test_a_held_graph_past_its_limit_goes_to_the_store() -> None:
    store = OxigraphStore()
    store.hold_scratch(SCRATCH)
    facts = [Triple(NamedNode(f"urn:x:n{i}"), P[0], S[0]) for i in range(HELD_MAX + 1)]
    store.add_scratch(facts[:HELD_MAX], SCRATCH[0])
    assert len(store._ox) == 0
    store.add_scratch(facts[HELD_MAX:], SCRATCH[0])
    assert len(store._ox) == HELD_MAX + 1
    assert len(list(store.triples(None, P[0], None, SCRATCH[0]))) == HELD_MAX + 1


def test_a_held_literal_is_found_in_any_spelling_as_the_index_finds_it() -> None:
    held, plain = OxigraphStore(), OxigraphStore()
    held.hold_scratch(SCRATCH)
    g = SCRATCH[0]
    for store in (held, plain):
        store.add_scratch([Triple(S[0], P[0], O[5])], g)  # "05"
    for o in O[3:]:
        for s in (None, S[0]):
            assert list(held.triples(s, P[0], o, g)) == list(plain.triples(s, P[0], o, g)), o
            assert list(held.triples(s, P[0], o, None)) == list(plain.triples(s, P[0], o, None)), o
        assert held.contains(Triple(S[0], P[0], o), g) == plain.contains(Triple(S[0], P[0], o), g), o
    assert list(held.triples(graph=g)) == list(plain.triples(graph=g))
    held.discard([Triple(S[0], P[0], O[3])], (g,))  # "5": the same value, the same stored term
    assert held.is_empty(g) and len(held._ox) == 0


def test_after_a_reason_whose_sparql_needed_its_scratch_graphs_the_next_one_writes_to_the_store() -> None:
    store = OxigraphStore()
    store.hold_scratch(SCRATCH)
    g, fact = SCRATCH[0], Triple(S[0], P[0], S[1])
    store.add_scratch([fact], g)
    store.update(f"INSERT {{ GRAPH {OTHER} {{ ?s ?p ?o }} }} WHERE {{ GRAPH {g} {{ ?s ?p ?o }} }}")
    store.drop_graphs(SCRATCH)  # the end of a REASON that ran SPARQL
    store.add_scratch([fact], g)
    assert len(store._ox) == 2 and store.contains(fact, g)  # written to the store at once
    store.drop_graphs(SCRATCH)  # a REASON without SPARQL
    assert len(store._ox) == 1
    store.add_scratch([fact], g)
    assert len(store._ox) == 1 and store.contains(fact, g)  # held again
    store.query(f"ASK {{ GRAPH {OTHER} {{ ?s ?p ?o }} }}")
    store.drop_graphs(SCRATCH)
    store.add_scratch([fact], g)
    assert len(store._ox) == 2


def test_an_empty_scratch_write_writes_nothing_and_marks_no_graph() -> None:
    store = OxigraphStore()
    store.hold_scratch(SCRATCH)
    store.add_scratch([Triple(S[0], P[0], S[1])], SCRATCH[0])
    store.update(f"INSERT {{ GRAPH {OTHER} {{ ?s ?p ?o }} }} WHERE {{ GRAPH {SCRATCH[0]} {{ ?s ?p ?o }} }}")
    store.drop_graphs(SCRATCH)  # the end of a REASON that ran SPARQL: the next one writes to the store
    writes = store._writes
    store.add_scratch([], SCRATCH[1])  # a recheck that kept no candidate
    assert store._writes == writes and not store._held.in_store and not store._held.reasoning


def test_a_read_of_every_graph_lists_the_held_facts_when_asked() -> None:
    """A scratch write made while a read over every graph is iterated neither shows up in it nor breaks it
    (the held graphs' matches are listed when the read is asked, as the general read does)."""
    store = OxigraphStore()
    first, second = NamedNode("urn:scratch:1"), NamedNode("urn:scratch:2")
    store.hold_scratch([first, second])

    def fact(i: int) -> Triple:
        return Triple(NamedNode(f"http://e/s{i}"), NamedNode("http://e/p"), NamedNode("http://e/o"))

    store.add_scratch([fact(1)], first)
    read = store.triples(None, None, None)
    store.add_scratch([fact(2)], second)
    assert [t.subject.value for t in read] == ["http://e/s1"]
    read = store.triples(None, None, None)
    assert next(read).subject.value in {"http://e/s1", "http://e/s2"}
    store.add_scratch([fact(3)], second)
    assert len(list(read)) == 1


def test_a_drop_of_the_same_graphs_again_answers_for_the_graphs_as_they_are_now() -> None:
    """What a drop finds of its list of graphs is kept for the next drop of the same list: the graphs in
    the store are still those of this drop, and a grown set of eligible graphs is no longer covered."""
    from topostore.stores.held import HeldGraphs

    held = HeldGraphs()
    held.eligible = frozenset(SCRATCH[:2])
    names = [*SCRATCH[:2], OTHER]
    assert held.drop(names) == [OTHER]
    held.in_store.add(SCRATCH[1])
    held.graphs[SCRATCH[0]] = {(S[0], P[0], S[1]): None}
    held.reasoning = True
    assert sorted(held.drop(list(names)), key=str) == sorted([OTHER, SCRATCH[1]], key=str)
    assert not held.graphs and not held.in_store and not held.reasoning  # every eligible graph dropped: settled
    held.eligible = held.eligible | {SCRATCH[2]}
    held.reasoning = True
    assert held.drop(names) == [OTHER]
    assert held.reasoning  # SCRATCH[2] is eligible and not dropped: the REASON is not over


def test_a_fact_known_in_some_graphs_is_answered_as_the_presence_batch_answers() -> None:
    """``known_in`` (one read per fact over every graph) answers as the presence look-ups per graph: a
    fact only in another graph is not known; a literal, or a held graph asked about, is left to them."""
    store = OxigraphStore()
    store.hold_scratch(SCRATCH)
    state = frozenset([ASSERTED, OTHER])
    facts = [Triple(S[0], P[0], S[1]), Triple(S[1], P[0], S[2]), Triple(S[2], P[1], S[0]), Triple(S[0], P[1], S[0])]
    store._ox.extend([Quad(*facts[0], ASSERTED), Quad(*facts[1], SCRATCH[1]), Quad(*facts[2], OTHER),
                      Quad(*facts[2], SCRATCH[2]), Quad(*facts[3], SCRATCH[1])])
    by_quads = [any(store.contains_quads([Quad(*t, g) for g in state])) for t in facts]
    batches: list[int] = []
    present = store._present
    store._present = lambda quads: batches.append(len(quads)) or present(quads)  # type: ignore[method-assign]
    assert store.known_in(facts, state) == by_quads == [True, False, True, False]
    assert not batches  # one index read per fact
    assert store.known_in([Triple(S[0], P[0], O[4])], state) == [False]
    assert batches == [2]  # by value: the presence batch, a quad per graph
    store.add_scratch([facts[1]], SCRATCH[0])
    assert store.known_in(facts, state | {SCRATCH[0]}) == [True, True, True, False]
    assert batches == [2, 12]  # a held graph: its facts are not in the index, the batch answers


def test_a_subjects_values_by_graph_in_one_read_answer_as_each_graphs_read() -> None:
    """``objects_by_graph`` (one index read over every graph) answers as one read per graph: a value in
    a graph not asked about is left out, each graph keeps its own values; an open transaction or a held
    graph asked about is read graph by graph."""
    store = OxigraphStore()
    store.hold_scratch(SCRATCH)
    asked = [ASSERTED, OTHER]
    store._ox.extend([Quad(S[0], P[0], S[1], ASSERTED), Quad(S[0], P[0], S[2], OTHER),
                      Quad(S[0], P[0], O[3], SCRATCH[1]), Quad(S[0], P[1], S[2], ASSERTED)])
    each = {g: store.objects(S[0], P[0], g) for g in asked}
    assert store.objects_by_graph(S[0], P[0], asked) == each == {ASSERTED: [S[1]], OTHER: [S[2]]}
    assert store.objects_by_graph(S[0], P[0], [OTHER]) == {OTHER: [S[2]]}
    store.add_scratch([Triple(S[0], P[0], S[0])], SCRATCH[0])
    assert store.objects_by_graph(S[0], P[0], [SCRATCH[0], ASSERTED]) == {SCRATCH[0]: [S[0]], ASSERTED: [S[1]]}
    with transaction(store):
        store.add([Triple(S[0], P[0], S[0])], ASSERTED)
        found = store.objects_by_graph(S[0], P[0], asked)
        assert {g: sorted(v, key=str) for g, v in found.items()} == {ASSERTED: [S[0], S[1]], OTHER: [S[2]]}


def test_a_fact_in_one_graph_is_answered_by_one_test_as_the_presence_batch_answers() -> None:
    """``contains_each`` tests each fact of IRIs in the held graph or the index, answering as the presence
    batch; a literal (presence by value) or an open transaction is left to that batch."""
    store = OxigraphStore()
    store.hold_scratch(SCRATCH)
    facts = [Triple(S[0], P[0], S[1]), Triple(S[1], P[0], S[2]), Triple(S[2], P[1], S[0])]
    store._ox.extend([Quad(*facts[0], ASSERTED), Quad(*facts[1], OTHER)])
    store.add_scratch([facts[2]], SCRATCH[0])
    batches: list[int] = []
    present = store._present
    store._present = lambda quads, *keys: batches.append(len(quads)) or present(quads, *keys)  # type: ignore[method-assign]
    assert store.contains_each(facts, ASSERTED) == [True, False, False]
    assert store.contains_each(facts, SCRATCH[0]) == [False, False, True]
    assert not batches  # one test per fact
    assert store.contains_each([facts[0], Triple(S[0], P[0], O[4])], ASSERTED) == [True, False]
    assert batches == [2]  # a literal: the presence batch
    with transaction(store):
        store.add([facts[1]], ASSERTED)
        batches.clear()
        assert store.contains_each(facts, ASSERTED) == [True, True, False]
        assert batches == [3]  # an open transaction: the batch sees its pending writes


def test_a_presence_test_and_a_join_read_answer_as_the_general_read_held_or_not() -> None:
    """``has_match`` (a staged run's presence test) and ``matches`` (a look-up join's read of one graph) answer
    what the general read finds: in a held graph, in the index, over every graph (held facts included) and
    inside a transaction (its pending writes)."""
    store = OxigraphStore()
    store.hold_scratch(SCRATCH)
    fact, other = Triple(S[0], P[0], O[3]), Triple(S[1], P[0], S[2])
    store.add_scratch([fact], SCRATCH[0])
    store.add([other], ASSERTED)
    assert store.has_match(None, P[0], None, SCRATCH[0]) and store.has_match(S[0], None, O[4], SCRATCH[0])
    assert store.has_match(None, None, None, None)  # only the held graph holds S[0]'s fact
    assert store.has_match(S[0], None, None, None) and not store.has_match(S[2], None, None, None)
    assert not store.has_match(S[1], None, None, SCRATCH[0]) and store.has_match(S[1], P[0], S[2], ASSERTED)
    assert [_terms(f) for f in store.matches(S[1], None, None, ASSERTED, 3)] == [_terms(other)]
    assert [_terms(f) for f in store.matches(None, P[0], None, SCRATCH[0], 3)] == [_terms(fact)]
    assert store.matches(None, P[0], None, ASSERTED, 0) is None and store.matches(S[2], None, None, ASSERTED, 0) == []
    with transaction(store):
        store.add([Triple(S[2], P[1], S[0])], ASSERTED)
        assert store.has_match(S[2], None, None, ASSERTED)
        assert [_terms(f) for f in store.matches(S[2], None, None, ASSERTED, 3)] == [f"{S[2]} {P[1]} {S[0]}"]
