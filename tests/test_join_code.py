"""A look-up join compiled into a flat function (reason/join_code.py) gives the interpreted join's
solutions, in the same order, with the same reads but for the repeats of a read the inner loops do
not change: random bodies (variables repeated within and across atoms, constants, a variable
predicate) over random facts in two graphs; and a flip's compiled branches write what its
interpreted ones write."""

from __future__ import annotations

from itertools import islice
from unittest import mock

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from profiles import property_examples
from pyoxigraph import Literal, NamedNode, Triple
from swrl_support import NS, PREFIXES, builtin, cls, data, rule

from topostore import Ontology
from topostore.rdf.vocab import ASSERTED
from topostore.reason import look_flip, look_join
from topostore.reason.atom_shape import Shape
from topostore.reason.delta_texts import FLIP_LOST
from topostore.reason.flip import CHANGE_OLD
from topostore.reason.join_code import compile_join, interpreted
from topostore.reason.scratch import FLIP_GAINED
from topostore.stores import memory_store

#: every test twice: the compiled step's staged runs generated and interpreted (reason/staged_code.py)
pytestmark = pytest.mark.usefixtures("staged_form")

XSD_INTEGER = NamedNode("http://www.w3.org/2001/XMLSchema#integer")

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
    assert_fewer_of_the_same(compiled_log, interpreted_log)


def assert_fewer_of_the_same(compiled: list, reference: list) -> None:
    """``compiled`` is ``reference`` with some reads left out, each of them a read made before."""
    it = iter(reference)
    made: set = set()
    for read in compiled:
        for expected in it:
            if expected == read:
                break
            assert expected in made, f"{expected} left out but never read before"
        else:
            raise AssertionError(f"{read} read by the compiled join only, or out of order")
        made.add(read)
    assert all(rest in made for rest in it)


def test_a_read_the_inner_loops_do_not_change_is_made_once_per_turn_of_its_own() -> None:
    """canReach's shape: the key of the robot's location is read once, not once per connected location;
    the key of each connected location once per location."""
    a, b = NamedNode("urn:p:connected"), NamedNode("urn:p:key")
    body = [("?l1", a, "?l2"), ("?k1", b, "?l1"), ("?k2", b, "?l2")]
    store = memory_store()
    here, keys = NODES[0], [NamedNode(f"urn:k:{k}") for k in range(3)]
    store.add([Triple(here, a, NODES[1]), Triple(here, a, NODES[2])]
              + [Triple(keys[k], b, NODES[k]) for k in range(3)], G1)
    graphs = [((G1,), frozenset((G1,)))] * 3
    log: list = []
    join = compile_join(body, [0, 1, 2], {"?l1"}, graphs, reader(log))
    reference: list = []
    assert list(join(store, {"?l1": here})) == list(interpreted([Shape(t) for t in body], [0, 1, 2], graphs,
                                                                reader(reference))(store, {"?l1": here}))
    patterns = [pattern for pattern, _ in log]
    assert patterns[:2] == [(here, a, None), (None, b, here)]
    assert sorted(str(p[2]) for p in patterns[2:]) == [str(NODES[1]), str(NODES[2])]
    assert len(reference) == 5  # the key of l1 read again for the second connected location


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


CLOCK = PREFIXES + f"""
:now a owl:DatatypeProperty . :seen a owl:DatatypeProperty . :limit a owl:DatatypeProperty . :Hot a owl:Class .
{rule([data(':now', '?c', '?t'), data(':seen', '?l', '?v'), data(':limit', '?c', '?h'),
       builtin('subtract', '?d', '?t', '?v'), builtin('greaterThan', '?d', '?h')], [cls(':Hot', '?l')], 'Clock')}
"""
CLOCKS, PLACES = [NamedNode(NS + f"c{k}") for k in range(2)], [NamedNode(NS + f"l{k}") for k in range(3)]
number = st.sampled_from([0, 4, 15, 30]).map(lambda n: Literal(str(n), datatype=XSD_INTEGER))
values = st.lists(st.tuples(st.sampled_from(["now", "seen", "limit"]), st.integers(0, 2), number), min_size=3,
                  max_size=10)


@settings(max_examples=property_examples(200), deadline=None)
@given(new=values, replaced=st.lists(st.tuples(st.integers(0, 9), number), max_size=4),
       order=st.sampled_from([(0,), (1,), (0, 1), (1, 0), (1, 0, 2)]))
def test_the_compiled_flip_is_the_interpreted_one(new: list, replaced: list, order: tuple) -> None:
    """A flip (reason/look_flip.py) by its compiled branches writes what the interpreted branches write,
    or falls back alike: random new values, and old values of some of those facts in CHANGE_OLD."""
    old = [(new[i % len(new)][0], new[i % len(new)][1], value) for i, value in replaced]
    onto = Ontology()
    onto.load_data(CLOCK)
    clock = next(r for r in onto.rules.inference_rules if r.name == "swrl:Clock" or r.name.endswith("Clock"))
    results = []
    for compiled in (True, False):
        store = memory_store()
        for graph, facts in ((ASSERTED, new), (CHANGE_OLD, old)):
            store.add([Triple((CLOCKS + PLACES)[k] if p == "seen" else CLOCKS[k % 2], NamedNode(NS + p), v)
                       for p, k, v in facts], graph)
        with mock.patch.object(look_join, "COMPILED_JOINS", compiled), mock.patch.object(look_join, "COMPILE_AFTER", 1):
            flipped = look_flip.Flipped(clock, order)
        answer = flipped.run(store)  # compiled at its first run (COMPILE_AFTER 1)
        assert (flipped._branches is not None) == compiled
        results.append((answer, set(store.triples(graph=FLIP_GAINED)), set(store.triples(graph=FLIP_LOST))))
    assert results[0] == results[1]


@settings(max_examples=property_examples(200), deadline=None)
@given(new=st.lists(st.tuples(st.sampled_from(["now", "seen", "limit"]), st.integers(0, 2),
                              st.one_of(number, st.just(Literal("soon")))), min_size=3, max_size=10),
       hot=st.lists(st.integers(0, 4), max_size=4), delta=st.integers(0, 2), many=st.booleans())
def test_the_deciding_joins_are_the_interpreted_recheck_and_additions(new: list, hot: list, delta: int,
                                                                      many: bool) -> None:
    """A look-up rule's recheck and additions (reason/look_join.py) through its compiled joins deciding
    each solution where they find it (the conditions called with the loops' locals) keep, delete and add
    what the interpreted joins do, or give up alike: random clock values (a string among them, which no
    comparison decides), candidates and new facts (and more new facts than a look-up writes, which it
    leaves to the text)."""
    from topostore.rdf.vocab import INFERRED, TYPE
    from topostore.reason.delta_texts import KEEP
    from topostore.reason.scratch import CANDIDATES, NEW_FACTS, OVERDELETED

    onto = Ontology()
    onto.load_data(CLOCK)
    clock = next(r for r in onto.rules.inference_rules if r.name == "swrl:Clock" or r.name.endswith("Clock"))
    facts = [Triple((CLOCKS + PLACES)[k] if p == "seen" else CLOCKS[k % 2], NamedNode(NS + p), v) for p, k, v in new]
    hot_facts = [Triple((CLOCKS + PLACES)[k], TYPE, NamedNode(NS + "Hot")) for k in hot]
    delta_pred = NamedNode(NS + ("now", "seen", "limit")[delta])
    extra = [Triple(NamedNode(f"{NS}x{k}"), delta_pred, Literal("1", datatype=XSD_INTEGER)) for k in range(20)] \
        if many else []
    results = []
    for compiled in (True, False):
        store = memory_store()
        store.add(facts, ASSERTED)
        store.add(hot_facts, INFERRED)
        store.add(hot_facts, CANDIDATES)
        store.add([t for t in facts if t.predicate == delta_pred] + extra, NEW_FACTS)
        with mock.patch.object(look_join, "COMPILED_JOINS", compiled), mock.patch.object(look_join, "COMPILE_AFTER", 1):
            atom = next(j for j, a in enumerate(clock.body) if a.p == f"<{delta_pred.value}>")
            joined = look_join.Joined(clock, INFERRED, atom)
            answers = [joined.keep(store), joined.additions(store), joined.delete(store), joined.additions(store)]
        if compiled and hot:  # a candidate was rechecked: its join compiled at its first run
            assert joined._prove_decided is not None
        if not compiled:
            assert joined._prove_decided is None and joined._derive_decided is None
        results.append((answers, *(sorted(map(str, store.triples(graph=g)))
                                   for g in (KEEP, INFERRED, NEW_FACTS, OVERDELETED))))
    assert results[0] == results[1]


def test_a_rule_longer_than_python_nests_is_interpreted_and_reasons_incrementally() -> None:
    """A SWRL chain of 24 atoms: Python refuses a function of more than 20 nested blocks, so its join
    is interpreted, and a step after a change still equals a REASON from scratch (it once failed and
    rolled back every REASON)."""
    from swrl_support import obj
    from test_incremental import from_scratch

    from topostore.rdf.vocab import INFERRED
    from topostore.reason.join_code import MAX_LOOPS

    n = 24
    assert compile_join([("?a", PREDS[0], "?b")] * n, list(range(n)), set(),
                        [((G1,), frozenset((G1,)))] * n, reader([])) is None
    assert n > MAX_LOOPS
    text = (PREFIXES + ":p a owl:ObjectProperty . :End a owl:Class .\n"
            + "".join(f":n{i} a owl:NamedIndividual ; :p :n{i + 1} .\n" for i in range(n))
            + f":n{n} a owl:NamedIndividual .\n"
            + rule([obj(":p", f"?x{i}", f"?x{i + 1}") for i in range(n)], [cls(":End", "?x0")], "Long"))
    onto = Ontology()
    onto.load_data(text)
    onto.reason()
    onto.add(onto.fact(NamedNode(NS + "m"), NamedNode(NS + "p"), NamedNode(NS + "n1")))
    assert onto.reason().consistent
    inferred = {t for t in onto.store.triples(graph=INFERRED) if t.object == NamedNode(NS + "End")}
    scratch = {t for t in from_scratch(onto)[0] if t.object == NamedNode(NS + "End")}
    assert inferred == scratch and {t.subject for t in inferred} == {NamedNode(NS + "n0"), NamedNode(NS + "m")}
