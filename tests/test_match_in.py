"""``OxigraphStore.match_in``: one index read over several graphs answers what one read per graph does."""

from __future__ import annotations

from itertools import product

from pyoxigraph import NamedNode, Triple

from topostore.rdf.vocab import ASSERTED, AUX, INFERRED
from topostore.stores.oxigraph import OxigraphStore

EX = "http://example.org/"
STATE = frozenset((ASSERTED, INFERRED, AUX))
OTHER = NamedNode(EX + "scratch")


def _n(name: str) -> NamedNode:
    return NamedNode(EX + name)


def _store() -> OxigraphStore:
    store = OxigraphStore()
    p, q = _n("p"), _n("q")
    store.add_scratch([Triple(_n("a"), p, _n("b")), Triple(_n("a"), p, _n("c"))], ASSERTED)
    store.add_scratch([Triple(_n("a"), p, _n("b")), Triple(_n("a"), q, _n("b"))], INFERRED)  # b twice
    store.add_scratch([Triple(_n("a"), p, _n("d"))], OTHER)  # a graph the look-up does not read
    store.add_scratch([Triple(_n("c"), p, _n("b"))], AUX)
    return store


def _per_graph(store: OxigraphStore, s, p, o) -> set[Triple]:
    return {t for g in STATE for t in store.triples(s, p, o, g)}


def test_same_facts_as_one_read_per_graph() -> None:
    store = _store()
    terms = [None, _n("a"), _n("b"), _n("c"), _n("d")]
    for s, p, o in product(terms, [None, _n("p"), _n("q")], terms):
        found = store.match_in(s, p, o, STATE, 16)
        if s is None and o is None:
            assert found is None  # unbound: read each graph
            continue
        assert found is not None
        assert len(found) == len(set(found))  # each fact once, whichever graphs hold it
        assert set(found) == _per_graph(store, s, p, o)


def test_stops_past_the_limit() -> None:
    store = OxigraphStore()
    store.add_scratch([Triple(_n("a"), _n("p"), _n(f"o{i}")) for i in range(10)], ASSERTED)
    found = store.match_in(_n("a"), _n("p"), None, STATE, 3)
    assert found is not None and len(found) == 4  # limit + 1: the caller knows there are more


def test_many_quads_of_other_graphs_give_up() -> None:
    store = OxigraphStore()
    store.add_scratch([Triple(_n("a"), _n("p"), _n(f"o{i}")) for i in range(40)], OTHER)
    store.add_scratch([Triple(_n("a"), _n("p"), _n("o1"))], ASSERTED)
    assert store.match_in(_n("a"), _n("p"), None, STATE, 4) is None
    # 40 quads elsewhere stay under 4 x 16: read once, filtered
    assert store.match_in(_n("a"), _n("p"), None, STATE, 16) == [Triple(_n("a"), _n("p"), _n("o1"))]
