"""The reads after an incremental maintenance: the entailed-only refresh of touched triples, the shape
decisions are kept by, and the completion's watched keys (see topostore.reason.changed, .entailed and
.negation)."""

from __future__ import annotations

import itertools
import random

from pyoxigraph import NamedNode, Quad, Triple
from test_incremental import assert_same_as_scratch, new_map, robot_step

from topostore.rdf.vocab import ASSERTED, AUX, ENTAILED, INFERRED
from topostore.reason.changed import shape
from topostore.reason.entailed import _publish, _standings, internal, refresh_touched
from topostore.reason.negation import Completion, lost_any
from topostore.reason.triggers import matches
from topostore.stores.oxigraph import OxigraphStore

EX = "http://example.org/"
P = NamedNode(EX + "reaches")


def _state(store: OxigraphStore, t: Triple, twin: bool, inferred: bool, asserted: bool, shown: bool) -> None:
    s, p, o = t.subject, t.predicate, t.object
    quads = [q for flag, q in ((twin, Quad(s, internal(p), o, AUX)), (inferred, Quad(s, p, o, INFERRED)),
                               (asserted, Quad(s, p, o, ASSERTED)), (shown, Quad(s, p, o, ENTAILED))) if flag]
    if quads:
        store._ox.extend(quads)


def test_a_touched_triple_is_decided_as_by_its_four_look_ups() -> None:
    """Every standing a touched triple can have (its twin changed or not), decided by the twin's look-up
    first: the same ENTAILED graph as the four look-ups of every triple.  A triple whose twin did not
    change and is absent was not shown before (ENTAILED holds only triples with a twin)."""
    cases = [c for c in itertools.product([False, True], repeat=5) if c[4] or not c[3] or c[0]]
    touched = [Triple(NamedNode(f"{EX}s{k}"), P, NamedNode(f"{EX}o{k}")) for k in range(len(cases))]
    fast, four = OxigraphStore(), OxigraphStore()
    twin_changed = set()
    for t, (twin, inferred, asserted, shown, changed) in zip(touched, cases, strict=True):
        for store in (fast, four):
            _state(store, t, twin, inferred, asserted, shown)
        if changed:
            twin_changed.add(t)
    refresh_touched(fast, touched, twin_changed)
    _publish(four, touched, _standings(four, touched))
    assert set(fast.triples(graph=ENTAILED)) == set(four.triples(graph=ENTAILED))
    wanted = {t for t, (twin, inferred, asserted, _, _) in zip(touched, cases, strict=True)
              if twin and not inferred and not asserted}
    assert set(fast.triples(graph=ENTAILED)) == wanted


def test_the_shape_of_a_change_keeps_its_graphs_apart() -> None:
    """A key gained in one step and lost in another is a different shape (the negated premises read the
    gained facts only): the decisions kept by shape must not mix them up."""
    gained_p = [({"<p>": 1}, {}), ({"<q>": 1}, {})]
    gained_q = [({"<q>": 1}, {}), ({"<p>": 1}, {})]
    present = (set(), set())
    assert shape(gained_p, frozenset(), present) != shape(gained_q, frozenset(), present)
    many = [({"<p>": 1}, {}), ({"<q>": 500}, {})]
    few = [({"<p>": 1}, {}), ({"<q>": 1}, {})]
    assert shape(many, frozenset(), present) != shape(few, frozenset(), present)


def _needed(completion: Completion, present, lost, asserted: bool) -> bool:
    """What :meth:`Completion.needed` answers, decided from its writers afresh."""
    if asserted and lost_any(completion.heads, *lost):
        return True
    return any(lost_any(keys, *lost) for needs, keys in completion.writers
               if all(matches(k, *present) for k in needs))


def test_the_watched_keys_follow_the_keys_with_facts() -> None:
    """The completion's watched keys are made once per keys-with-facts; a key gaining facts, or a
    forgotten state (the general phases may drop keys), is decided afresh."""
    onto = new_map(10, 4, False)
    onto.reason()
    completion = onto._reasoner._completion
    assert completion.writers
    reads = sorted({k for needs, keys in completion.writers for k in needs | keys if k[0] != "*"} | completion.heads)
    rng = random.Random(7)
    present: tuple[set[str], set[str]] = (set(), set())
    for step in range(200):
        if step % 17 == 16:  # the keys with facts shrink (the general phases): the reasoner forgets
            present[0].clear()
            present[1].clear()
            completion.forget()
        elif rng.random() < 0.3:
            kind, key = rng.choice(reads)
            present[0 if kind == "p" else 1].add(key)
        lost = ({k for kind, k in rng.sample(reads, 2) if kind == "p"}, {k for kind, k in reads[:1] if kind == "t"})
        asserted = rng.random() < 0.5
        assert completion.needed(present, lost, asserted) == _needed(completion, present, lost, asserted)


def test_robot_steps_with_entailed_conclusions_stay_exact() -> None:
    """Undeclared places publish entailed-only conclusions: the refresh of the touched triples keeps
    ENTAILED equal to a from-scratch run step after step."""
    onto = new_map(10, 4, False)
    onto.reason()
    for k, where in enumerate(["R3", "C2", "R7", "C1", "R3"]):
        robot_step(onto, where, 1665579750 + 400 * k)
        assert_same_as_scratch(onto)


def test_a_touched_triple_whose_twin_did_not_change_is_still_shown_where_its_twin_is() -> None:
    """No twin among the changed facts: the helper graph is read once per predicate, and a predicate
    with a twin there decides its triples one by one (another predicate's lack of twins decides nothing)."""
    other = NamedNode(EX + "sees")
    shown = Triple(NamedNode(EX + "s1"), P, NamedNode(EX + "o1"))
    touched = [Triple(NamedNode(EX + "s0"), other, NamedNode(EX + "o0")), shown,
               Triple(NamedNode(EX + "s2"), P, NamedNode(EX + "o2"))]
    store = OxigraphStore()
    _state(store, shown, True, False, False, False)
    refresh_touched(store, touched, set())
    assert set(store.triples(graph=ENTAILED)) == {shown}
    refresh_touched(store, touched[:1], set())  # no twin of `sees` anywhere: nothing to decide
    assert set(store.triples(graph=ENTAILED)) == {shown}
