"""A look-up join compiled into a flat function (reason/join_code.py) gives the interpreted join's
solutions, in the same order, with the same reads: random bodies (variables repeated within and
across atoms, constants, a variable predicate) over random facts in two graphs."""

from __future__ import annotations

from itertools import islice

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from profiles import property_examples
from pyoxigraph import Literal, NamedNode, Triple

from topostore.reason.atom_shape import Shape
from topostore.reason.join_code import compile_join, interpreted
from topostore.stores import memory_store

G1, G2 = NamedNode("urn:g:1"), NamedNode("urn:g:2")
NODES = [NamedNode(f"urn:n:{k}") for k in range(3)]
PREDS = [NamedNode(f"urn:p:{k}") for k in range(2)]
VARS = ["?a", "?b", "?c"]

node = st.sampled_from(NODES)
facts = st.lists(st.tuples(node, st.sampled_from(PREDS), st.one_of(node, st.just(Literal("7"))),
                           st.sampled_from([G1, G2])), min_size=4, max_size=16)
subject = st.one_of(st.sampled_from(VARS), node)
predicate = st.one_of(st.sampled_from(PREDS), st.just("?p"))
obj = st.one_of(st.sampled_from(VARS), node)
atoms = st.lists(st.tuples(subject, predicate, obj), min_size=1, max_size=3)


def reader(log: list):
    """A read as :func:`topostore.reason.look_join._read` does it (distinct facts of the graphs), logged."""

    def read(store, pattern, graphs, graph_set):
        log.append((pattern, graphs))
        found: dict = {}
        for g in graphs:
            found.update(dict.fromkeys(islice(store.triples(*pattern, g), 64)))
        return list(found)

    return read


@settings(max_examples=property_examples(300), deadline=None)
@given(quads=facts, body=atoms, start=st.integers(0, 2), data=st.data())
def test_the_compiled_join_is_the_interpreted_one(quads: list, body: list, start: int, data) -> None:
    store = memory_store()
    for s, p, o, g in quads:
        store.add([Triple(s, p, o)], g)
    start = min(start, len(body) - 1)
    shapes = [Shape(terms) for terms in body]
    order = [start] + data.draw(st.permutations([k for k in range(len(body)) if k != start]))
    graphs = [((G1, G2), frozenset((G1, G2)))] * len(body)
    given_vars = {x for x in body[start] if isinstance(x, str)}
    first = shapes[start]
    seeds = [b for t in store.triples(*first.free, None) if (b := first.bind(t)) is not None]
    interpreted_log: list = []
    compiled_log: list = []
    reference = interpreted(shapes, order[1:], graphs, reader(interpreted_log))
    compiled = compile_join(body, order[1:], given_vars, graphs, reader(compiled_log))
    for bound in seeds:
        assert outcome(compiled, store, bound) == outcome(reference, store, bound)
    assert compiled_log == interpreted_log


def outcome(join, store, bound: dict) -> list | str:
    """The solutions, or the error's type (a literal read as a subject is refused by the store alike)."""
    try:
        return list(join(store, bound))
    except TypeError as exc:
        return type(exc).__name__


def test_a_read_that_refuses_stops_the_compiled_join() -> None:
    """The read's exception (too many matches: the SPARQL text runs) goes through the generated loops."""

    class Many(Exception):
        pass

    def read(store, pattern, graphs, graph_set):
        raise Many

    join = compile_join([("?a", PREDS[0], "?b"), ("?b", PREDS[1], "?c")], [1], {"?a", "?b"},
                        [((G1,), frozenset((G1,)))] * 2, read)
    with pytest.raises(Many):
        list(join(memory_store(), {"?a": NODES[0], "?b": NODES[1]}))


def test_the_generated_text_names_no_term() -> None:
    """Constants reach the function through its namespace, never as text, and a variable's name only
    as a string literal (a literal constant and a name may hold any character)."""
    odd = Literal('"), __import__("os").system("false"), ("')
    name = "?a'\"\n)"
    join = compile_join([(name, PREDS[0], odd)], [0], set(), [((G1,), frozenset((G1,)))], reader([]))
    store = memory_store()
    store.add([Triple(NODES[0], PREDS[0], odd)], G1)
    assert list(join(store, {})) == [{name: NODES[0]}]
