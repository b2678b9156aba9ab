"""The compiled step (:mod:`topostore.reason.program`) gives exactly what reasoning from scratch gives.

The ontology has no recursive component (domain, range, subclasses, a SWRL join and a SWRL clock
comparison), so every change is maintained by the compiled program; random batches of additions,
removals and value replacements are compared with a from-scratch materialisation after every
REASON, on both ways of running it (key by key, and as one request).
"""

from __future__ import annotations

from unittest import mock

import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st
from profiles import property_examples
from pyoxigraph import Literal, NamedNode, Triple
from swrl_support import NS, PREFIXES, builtin, cls, data, diff, obj, rule

from topostore import Ontology
from topostore.rdf.vocab import ASSERTED, AUX, INFERRED, TYPE
from topostore.reason import Materializer, check_consistency, direct, look_flip, look_join, staged_code
from topostore.reason.program import Refused, check_pair_atom, describe, pair_atom, signature
from topostore.reason.step_compiler import StepCompiler, _Writers
from topostore.stores import memory_store

#: every test twice: the compiled step's staged runs generated and interpreted (reason/staged_code.py)
pytestmark = pytest.mark.usefixtures("staged_form")

TBOX = PREFIXES + f"""
:A a owl:Class . :B a owl:Class . :C a owl:Class ; rdfs:subClassOf :A . :Hot a owl:Class ; rdfs:subClassOf :C .
:p a owl:ObjectProperty ; rdfs:domain :A ; rdfs:range :B .
:q a owl:ObjectProperty . :r a owl:ObjectProperty ; rdfs:range :C . :s a owl:ObjectProperty .
:now a owl:DatatypeProperty ; rdfs:domain :A . :seen a owl:DatatypeProperty .
{rule([obj(':p', '?x', '?y'), obj(':q', '?y', '?z')], [obj(':r', '?x', '?z')], 'Join')}
{rule([obj(':p', '?x', '?y'), obj(':q', '?y', '?z'), builtin('notEqual', '?x', '?z')], [obj(':s', '?x', '?z')], 'Apart')}
{rule([data(':now', '?c', '?t'), data(':seen', '?l', '?v'), builtin('subtract', '?d', '?t', '?v'),
       builtin('greaterThan', '?d', 10)], [cls(':Hot', '?l')], 'Clock')}
"""

PEOPLE = [f"i{k}" for k in range(5)]


def N(name: str) -> NamedNode:
    return NamedNode(NS + name)


def from_scratch(onto: Ontology) -> tuple[set, set, bool]:
    store = memory_store()
    store.add(onto.store.triples(graph=ASSERTED), ASSERTED)
    Materializer(store, onto.rules).run()
    return set(store.triples(graph=INFERRED)), set(store.triples(graph=AUX)), not check_consistency(store, onto.rules)


def toggle(onto: Ontology, fact: Triple) -> None:
    """Remove an asserted fact, or assert it."""
    onto.remove(fact) if fact in set(onto.store.triples(graph=ASSERTED)) else onto.add(fact)


def assert_as_from_scratch(onto: Ontology, report, consistency: bool = True) -> None:
    """The inferred and helper graphs (and the consistency) are those of a from-scratch run."""
    inferred, aux, consistent = from_scratch(onto)
    assert set(onto.store.triples(graph=INFERRED)) == inferred, report.stats
    assert set(onto.store.triples(graph=AUX)) == aux, report.stats
    if consistency:
        assert report.consistent == consistent


def walk(onto: Ontology, batches: list, classes: str, compiled: bool) -> None:
    """Toggle each batch's facts (a class membership for the names in ``classes``, else a property
    value), REASON incrementally and compare with from scratch; ``compiled``: every change compiles."""
    onto.reason()
    for batch in batches:
        for p, a, b in batch:
            toggle(onto, Triple(N(a), TYPE, N(p)) if p in classes else Triple(N(a), N(p), N(b)))
        report = onto.reason(mode="incremental")
        assert_as_from_scratch(onto, report, consistency=False)
        if compiled and report.stats.reason != "no asserted change" and report.stats.mode == "incremental":
            assert report.stats.program == "compiled", report.stats.program


def turtle(text: str) -> Ontology:
    onto = Ontology()
    onto.load_data(text)
    return onto


def new_ontology() -> Ontology:
    onto = turtle(TBOX)
    onto.add(Triple(N("clock"), N("now"), Literal("100", datatype=NamedNode("http://www.w3.org/2001/XMLSchema#long"))))
    onto.reason()
    return onto


def apply(onto: Ontology, op: tuple) -> None:
    kind, a, b, n = op
    if kind in ("p", "q"):
        fact = Triple(N(a), N(kind), N(b))
        toggle(onto, fact)
    elif kind == "type":
        fact = Triple(N(a), TYPE, N("B"))
        toggle(onto, fact)
    elif kind == "seen":
        onto.replace(N(a), N("seen"), n)
    else:
        onto.replace(N("clock"), N("now"), n if isinstance(n, str) or n > 40 else 100 + n)


#: visit times: small, and at the ends of 64 bits or not a number, where ``now - seen`` is no value the
#: look-up path models exactly (its SPARQL text then runs)
VALUES = st.one_of(st.integers(0, 40), st.sampled_from([2 ** 63 - 1, -(2 ** 63), "x"]))
ops = st.tuples(st.sampled_from(["p", "q", "type", "seen", "tick"]), st.sampled_from(PEOPLE),
                st.sampled_from(PEOPLE), VALUES)


@settings(max_examples=property_examples(60), deadline=None)
@given(batches=st.lists(st.lists(ops, min_size=1, max_size=4), min_size=1, max_size=6), whole=st.booleans(),
       few=st.sampled_from([0, 1, direct.FEW]))
def test_compiled_step_equals_from_scratch(batches: list, whole: bool, few: int) -> None:
    """``whole``: the program as one request; ``few``: up to how many facts an operation with an
    equivalent through look-ups uses it (0: never, its SPARQL text runs; see reason/direct.py)."""
    onto = new_ontology()
    reasoner = onto._reasoner
    reasoner.store.round_trips, saved = whole, reasoner.store.round_trips  # one request, as on a remote store
    try:
        with mock.patch.object(direct, "FEW", few):
            for batch in batches:
                for op in batch:
                    apply(onto, op)
                report = onto.reason(mode="incremental")
                assert_as_from_scratch(onto, report)
                if report.stats.reason != "no asserted change":
                    assert report.stats.program == "compiled", report.stats.program
    finally:
        reasoner.store.round_trips = saved


@settings(max_examples=property_examples(40), deadline=None)
@given(batches=st.lists(st.lists(ops, min_size=1, max_size=4), min_size=1, max_size=6))
def test_compiled_joins_leave_the_store_of_interpreted_ones(batches: list) -> None:
    """The look-up joins and flips compiled into flat functions (reason/join_code.py) and the same joins
    interpreted atom by atom: after every REASON of random steps the two stores hold the same quads."""
    told = "\n".join(f"{t} ." for t in new_ontology().store.triples(graph=ASSERTED))  # one set of blank node names
    stores = []
    for compiled in (True, False):
        with mock.patch.object(look_join, "COMPILED_JOINS", compiled), mock.patch.object(look_join, "COMPILE_AFTER", 1):
            onto = turtle(told)
            onto.reason()
            states = []
            for batch in batches:
                for op in batch:
                    apply(onto, op)
                onto.reason(mode="incremental")
                states.append({g: set(onto.store.triples(graph=g)) for g in (ASSERTED, INFERRED, AUX)})
        stores.append(states)
    assert stores[0] == stores[1]


def test_joins_with_conditions_run_by_look_ups_and_fall_back_where_not_exact() -> None:
    """The Join, Apart and Clock rules' rechecks and additions run through look-ups (reason/look_join.py)
    while their values are small integers and IRIs; a visit time at the end of 64 bits (``now - seen``
    overflows) or a string makes the look-up decline, and its SPARQL text gives the answer."""
    calls: list[tuple[str, bool]] = []
    originals = {name: getattr(look_join.Joined, name) for name in ("keep", "delete", "additions")}

    def counted(name):
        def run(self, store, *given):
            answer = originals[name](self, store, *given)
            calls.append((name, answer))
            return answer
        return run

    onto = new_ontology()
    long = NamedNode("http://www.w3.org/2001/XMLSchema#long")
    late = Triple(N("clock2"), N("now"), Literal(str(-(2 ** 63)), datatype=long))  # minus a visit time overflows
    with mock.patch.multiple(look_join.Joined, **{name: counted(name) for name in originals}):
        for batch in ([("p", "i0", "i1", 0), ("q", "i1", "i2", 0)], [("seen", "i3", "", 3)], [("tick", "", "", 30)],
                      [("p", "i0", "i1", 0)], [("seen", "i3", "", 2 ** 63 - 1)], [("seen", "i4", "", "x")],
                      [("seen", "i4", "", 5)], [("add", late)], [("remove", Triple(N("clock"), N("now"),
                                                                                      Literal(130)))]):
            seen = len(calls)
            for op in batch:
                getattr(onto, op[0])(op[1]) if op[0] in ("add", "remove") else apply(onto, op)
            report = onto.reason(mode="incremental")
            assert_as_from_scratch(onto, report)
            assert report.stats.program == "compiled", report.stats.program
        # the removed clock made Hot(i3), Hot(i4) candidates; clock2's derivation overflows: the text decided
        assert ("delete", False) in calls[seen:] or ("keep", False) in calls[seen:], calls[seen:]
    assert ("additions", True) in calls and ("delete", True) in calls


def test_clock_tick_is_compiled_as_a_flip() -> None:
    onto = new_ontology()
    for k, v in enumerate([99, 80, 60]):
        onto.replace(N(PEOPLE[k]), N("seen"), v)
    onto.reason()
    assert {onto.short(i) for i in onto.instances(N("Hot"))} == {"i1", "i2"}
    onto.replace(N("clock"), N("now"), 115)
    report = onto.reason()
    assert report.stats.program == "compiled" and report.stats.flipped == 1
    assert {onto.short(i) for i in onto.instances(N("Hot"))} == {"i0", "i1", "i2"}
    onto.replace(N("clock"), N("now"), 70)  # back in time: all cool down
    onto.reason()
    assert set(onto.instances(N("Hot"))) == set()


def _clock_walk(onto: Ontology) -> None:
    """Three visit times, then the clock moved forward, back and forward again, each move one compiled flip whose
    Hot individuals equal a REASON from scratch's."""
    for k, v in enumerate([99, 80, 60]):
        onto.replace(N(PEOPLE[k]), N("seen"), v)
    onto.reason()
    for now, hot in ((115, {"i0", "i1", "i2"}), (70, set()), (100, {"i1", "i2"})):
        onto.replace(N("clock"), N("now"), now)
        report = onto.reason(mode="incremental")
        assert report.stats.program == "compiled" and report.stats.flipped == 1
        assert {onto.short(i) for i in onto.instances(N("Hot"))} == hot
        assert_as_from_scratch(onto, report)


def test_flipped_heads_a_lost_or_gained_operation_cannot_take_reach_its_text() -> None:
    """A staged run hands a flip's heads to its part's lost and gained operations instead of writing them
    to FLIP_LOST / FLIP_GAINED (reason/staged.py); where such an operation cannot take them (too many, a
    literal) its text runs, and reads them from the graph they are written to first."""
    refused: list[int] = []

    def refuse(facts):
        refused.append(len(facts))
        return None

    onto = new_ontology()
    handed = mock.Mock(wraps=look_flip.Flipped.heads)
    with mock.patch.object(look_flip.Flipped, "heads", lambda self, store: handed(self, store)), \
            mock.patch.object(direct, "_movable", refuse):
        _clock_walk(onto)
    assert handed.call_count >= 3 and sum(refused) >= 5


TWO_CLOCKS = TBOX + rule([data(':now', '?c', '?t'), data(':seen', '?l', '?v'), builtin('subtract', '?d', '?v', '?t'),
                          builtin('greaterThan', '?d', 50)], [cls(':Hot', '?l')], 'Ahead')


@pytest.mark.parametrize("by_text", [0, 1])
def test_flipped_heads_kept_in_python_join_those_of_a_flip_run_as_text(by_text: int) -> None:
    """Two flips in one part (two clock rules concluding Hot), one of them run as its text: the heads the
    other found by look-ups are written where the part's lost and gained operations read them (the text's
    beside them), whichever of the two runs first.  ``by_text``: the position of the one sent as text."""
    original, by_look_ups, refused = look_flip.Flipped.heads, [], []

    def heads(self, store):
        found = None if self in refused else original(self, store)
        by_look_ups.append(found is not None)
        return found

    onto = turtle(TWO_CLOCKS)
    onto.add(Triple(N("clock"), N("now"), Literal("100", datatype=NamedNode("http://www.w3.org/2001/XMLSchema#long"))))
    for person, seen in (("i0", 80), ("i1", 95), ("i2", 200), ("i3", 170)):
        onto.replace(N(person), N("seen"), seen)
    onto.reason()
    with mock.patch.object(look_flip.Flipped, "heads", heads):  # bound when the program is
        onto.replace(N("clock"), N("now"), 101)
        onto.reason(mode="incremental")  # compiles the clock's program
        flips = [op.direct.__self__ for program in onto._reasoner.step.programs.values()
                 if not isinstance(program, str) for part in program.segments or () for op in part.ops
                 if op.flip is not None and op.hand is not None]
        assert len(flips) == 2, "both clock rules flip by look-ups in the clock's part"
        refused.append(flips[by_text])
        by_look_ups.clear()
        # i1 becomes Hot by the clock rule, i2 stops being Hot by the other; then back
        for now, hot in ((160, {"i0", "i1"}), (100, {"i0", "i2", "i3"}), (90, {"i2", "i3"})):
            onto.replace(N("clock"), N("now"), now)
            report = onto.reason(mode="incremental")
            assert report.stats.program == "compiled", report.stats.program
            assert {onto.short(i) for i in onto.instances(N("Hot"))} == hot
            assert_as_from_scratch(onto, report)
    assert True in by_look_ups and False in by_look_ups


GUARDED = PREFIXES + f"""
:B a owl:Class . :p a owl:ObjectProperty . :q a owl:ObjectProperty . :r a owl:ObjectProperty .
:s a owl:ObjectProperty .
{rule([obj(':s', '?y', '?z'), cls(':B', '?z')], [obj(':q', '?y', '?z')], 'Writer')}
{rule([obj(':p', '?x', '?y'), obj(':q', '?y', '?z')], [obj(':r', '?x', '?z')], 'Joiner')}
:h a :B . :x a :B .
"""


def _walk_skips(onto: Ontology, steps: list) -> list[bool]:
    """Run each step (triples added, triples removed, the ``r`` facts expected after it) as an incremental
    REASON checked against a REASON from scratch; per step, whether the staged run left out an operation that
    joins a key without facts (reason/staged.py ``_without_facts``)."""
    from topostore.reason import staged

    skipped: list[bool] = []
    original = staged.StagedRun._without_facts

    def counted(run, keys):
        skipped.append(original(run, keys))
        return skipped[-1]

    left_out = []
    with mock.patch.object(staged.StagedRun, "_without_facts", counted):
        for added, removed, r in steps:
            for a, p, b in added:
                onto.add(Triple(N(a), N(p), N(b)))
            for a, p, b in removed:
                onto.remove(Triple(N(a), N(p), N(b)))
            skipped.clear()
            report = onto.reason(mode="incremental")
            left_out.append(True in skipped)
            assert report.stats.program == "compiled", report.stats.program
            assert_as_from_scratch(onto, report)
            found = {(onto.short(t.subject), onto.short(t.object)) for t in onto.store.triples(None, N("r"), None)}
            assert found == r
    return left_out


def test_additions_joining_a_premise_without_facts_are_left_out_until_it_has_some() -> None:
    """A staged run leaves out the additions that join a premise without facts (no facts before the run,
    none written by it so far: reason/staged.py ``needs``); the keys with facts grow by what each run
    wrote.  The same kind of change three times: q has no facts (the Joiner's additions left out), q
    gains its first fact in the run that joins it, then q has facts from the run before."""
    onto = turtle(GUARDED)
    onto.max_change_share = 1.0
    onto.reason()
    left_out = _walk_skips(onto, [([(a, "p", b), (c, "s", d)], [], r) for (a, b), (c, d), r in (
        (("a", "b"), ("e", "f"), set()), (("c", "g"), ("g", "h"), {("c", "h")}),
        (("k", "g"), ("m", "n"), {("c", "h"), ("k", "h")}))])
    assert left_out == [True, False, False]


def test_candidates_through_a_premise_without_facts_are_left_out() -> None:
    """The candidates of a lost fact are the heads derived through it before the change: where another
    premise of the rule had no facts then, there are none, and the operation is left out
    (reason/staged.py); once it has facts, losing the fact loses the head."""
    onto = turtle(GUARDED)
    onto.max_change_share = 1.0
    onto.add(Triple(N("a"), N("p"), N("b")))
    onto.reason()
    # s added beside: q is a key the program may write (its Joiner is in the program), without facts
    left_out = _walk_skips(onto, [([("e", "s", "f")], [("a", "p", "b")], set()),
                                  ([("c", "p", "g"), ("g", "s", "h")], [], {("c", "h")}),
                                  ([("m", "s", "n")], [("c", "p", "g")], set())])
    assert left_out[0] is True and left_out[2] is False


TAGGED_CLOCK = PREFIXES + f"""
:B a owl:Class . :Hot a owl:Class . :s a owl:ObjectProperty . :tagged a owl:ObjectProperty .
:now a owl:DatatypeProperty . :seen a owl:DatatypeProperty .
{rule([obj(':s', '?y', '?z'), cls(':B', '?z')], [obj(':tagged', '?y', '?z')], 'Writer')}
{rule([data(':now', '?c', '?t'), obj(':tagged', '?l', '?g'), data(':seen', '?l', '?v'),
       builtin('subtract', '?d', '?t', '?v'), builtin('greaterThan', '?d', 10)], [cls(':Hot', '?l')], 'Clock')}
:h a :B .
"""


def test_a_flip_joining_a_premise_without_facts_is_left_out_until_it_has_some() -> None:
    """A clock's flip reads its other atoms from the new state: where one has no facts (none before the
    run, none gained in it) nothing can flip and the flip is left out (reason/staged.py); once the premise
    has facts, from this run or an earlier one, the flip runs."""
    from topostore.reason import staged

    skipped: list[bool] = []
    original = staged.StagedRun._without_facts

    def counted(run, keys):
        skipped.append(original(run, keys))
        return skipped[-1]

    onto = turtle(TAGGED_CLOCK)
    onto.max_change_share = 1.0
    long = NamedNode("http://www.w3.org/2001/XMLSchema#long")
    onto.add(Triple(N("clock"), N("now"), Literal("100", datatype=long)))
    for person in PEOPLE[:3]:
        onto.replace(N(person), N("seen"), 95)
    onto.reason()
    left_out = []
    with mock.patch.object(staged.StagedRun, "_without_facts", counted):
        # i0 tagged with no B (tagged still without facts), i1 with one; then i1 is hot by the clock alone
        for now, (subject, tag), hot in ((101, ("i0", "f"), set()), (102, ("i1", "h"), set()),
                                         (110, ("i2", "n"), {"i1"})):
            onto.replace(N("clock"), N("now"), Literal(str(now), datatype=long))
            onto.add(Triple(N(subject), N("s"), N(tag)))
            skipped.clear()
            report = onto.reason(mode="incremental")
            left_out.append(True in skipped)
            assert report.stats.program == "compiled", report.stats.program
            assert {onto.short(i) for i in onto.instances(N("Hot"))} == hot
            assert_as_from_scratch(onto, report)
    assert left_out == [True, False, False]


def test_a_flip_runs_by_look_ups_and_falls_back_on_an_overflow() -> None:
    """The clock's flip through look-ups (reason/look_flip.py) gives the text's heads; a visit time whose
    difference from the clock overflows 64 bits is no boolean the evaluator decides: the text runs."""
    answers: list[bool] = []
    original = look_flip.Flipped.heads

    def counted(self, store):
        found = original(self, store)
        answers.append(found is not None)
        return found

    onto = new_ontology()
    with mock.patch.object(look_flip.Flipped, "heads", counted):
        _clock_walk(onto)
        assert answers[-1] is True
        onto.replace(N(PEOPLE[3]), N("seen"), -(2 ** 63))
        onto.reason(mode="incremental")
        onto.replace(N("clock"), N("now"), 101)
        report = onto.reason(mode="incremental")
        assert answers[-1] is False
        assert_as_from_scratch(onto, report)

RESTATED = PREFIXES + f"""
:A a owl:Class . :B a owl:Class . :p a owl:ObjectProperty ; rdfs:range :A . :q a owl:ObjectProperty ; rdfs:domain :B .
:r a owl:ObjectProperty ; rdfs:range :A ; rdfs:domain :B .
{rule([cls(':A', '?y'), cls(':B', '?x'), obj(':q', '?x', '?y')], [obj(':r', '?x', '?y')], 'Restating')}
"""


@settings(max_examples=property_examples(60), deadline=None)
@given(batches=st.lists(st.lists(st.tuples(st.sampled_from(["p", "q", "r", "A", "B"]), st.sampled_from(PEOPLE),
                                           st.sampled_from(PEOPLE)), min_size=1, max_size=3), min_size=1, max_size=6))
def test_a_rule_restating_a_premise_equals_from_scratch(batches: list) -> None:
    """r's range and domain restate premises of the only rule deriving r: maintenance leaves them out for
    derived r facts (see reason/restate.py), not for asserted ones."""
    walk(turtle(RESTATED), batches, "AB", compiled=False)


THROUGH = PREFIXES + f"""
:A a owl:Class . :B a owl:Class . :K owl:equivalentClass [ a owl:Class ; owl:intersectionOf ( :A :B ) ] .
:q a owl:ObjectProperty ; rdfs:domain :A . :r a owl:ObjectProperty ; rdfs:domain :K ; rdfs:range :B .
{rule([cls(':K', '?x'), obj(':q', '?x', '?y'), cls(':B', '?y')], [obj(':r', '?x', '?y')], 'Through')}
"""


@settings(max_examples=property_examples(60), deadline=None)
@given(batches=st.lists(st.lists(st.tuples(st.sampled_from(["q", "r", "A", "B", "K"]), st.sampled_from(PEOPLE),
                                           st.sampled_from(PEOPLE)), min_size=1, max_size=3), min_size=1, max_size=6))
def test_restating_through_an_equivalence_equals_from_scratch(batches: list) -> None:
    """K is A and B, written as an equivalence with an anonymous intersection: the intersection's way
    back to A and B, and r's domain and range, restate premises of every derivation, through the
    equivalence's two directions (see reason/restate.py); asserted K, A, B and r facts keep them needed."""
    walk(turtle(THROUGH), batches, "ABK", compiled=True)


def test_restating_rules_leave_no_recursive_component() -> None:
    """A change of q reaches A, the intersection, K, r and B; with the restating edges left out no key is
    derived from itself, so every key is rechecked once, in order (no DRed).  (With r's domain K, K is
    derived from r, which a rule derives from K: a cycle the compiler keeps.)"""
    onto = turtle(THROUGH.replace("rdfs:domain :K ; ", ""))
    for a, b in (("i0", "i1"), ("i1", "i2")):
        onto.add(Triple(N(a), N("q"), N(b)), Triple(N(b), TYPE, N("B")))
    onto.reason()
    reasoner = onto._reasoner
    key = f"<{NS}q>"
    program = reasoner.step.compiler.compile(signature(({key: 1}, {}), ({key: 1}, {}), ()), reasoner.state.present,
                                        reasoner.state.asserted)
    assert program.whole, describe(program)
    assert f"<{NS}r>" in describe(program)
    # an asserted K fact changes: the equivalence's way back is needed again, and the two form a cycle
    cls_key = f"<{NS}K>"
    program = reasoner.step.compiler.compile(signature(({key: 1}, {cls_key: 1}), ({}, {}), ()), reasoner.state.present,
                                        reasoner.state.asserted)
    assert not program.whole


NEGATED = PREFIXES + """
:f a owl:ObjectProperty, owl:FunctionalProperty . :d a owl:DatatypeProperty, owl:FunctionalProperty .
"""


@settings(max_examples=property_examples(60), deadline=None)
@given(batches=st.lists(st.lists(st.tuples(st.sampled_from(["f", "d"]), st.sampled_from(PEOPLE[:3]),
                                           st.sampled_from(PEOPLE[:3]), st.integers(1, 3)),
                                 min_size=1, max_size=3), min_size=1, max_size=6))
def test_negated_premise_check_is_semi_naive_and_exact(batches: list) -> None:
    """Two values of a functional property are the same individual unless known different (a rule
    with a negated premise, stratum 1); distinct values of a functional data property make them
    different.  After each step the check asks only what gained facts (or lost a difference) may
    make match, and a match makes the run full: equal to from scratch either way."""
    onto = turtle(NEGATED)
    onto.reason()
    for batch in batches:
        for p, a, b, n in batch:
            if p == "d":
                onto.replace(N(b), N("d"), n)
                continue
            fact = Triple(N(a), N("f"), N(b))
            toggle(onto, fact)
        report = onto.reason(mode="incremental")
        assert_as_from_scratch(onto, report)


def test_a_lost_difference_makes_the_negated_premise_match() -> None:
    """i1 and i2 are different while their d values differ; when they become equal nothing new is
    derived, but the difference is lost: the negated-premise rule matches (owl:sameAs)."""
    onto = turtle(NEGATED)
    onto.replace(N("i1"), N("d"), 1)
    onto.replace(N("i2"), N("d"), 2)
    onto.add(Triple(N("i0"), N("f"), N("i1")), Triple(N("i0"), N("f"), N("i2")))
    onto.reason()
    same = Triple(N("i1"), NamedNode("http://www.w3.org/2002/07/owl#sameAs"), N("i2"))
    assert same not in set(onto.store.triples(graph=INFERRED))
    onto.replace(N("i2"), N("d"), 1)
    report = onto.reason(mode="incremental")
    assert report.stats.mode == "full" and "negated premise" in report.stats.reason
    assert same in set(onto.store.triples(graph=INFERRED))


MAP = PREFIXES + f"""
:L a owl:Class . :Room a owl:Class ; rdfs:subClassOf :L . :Hall a owl:Class ; rdfs:subClassOf :L .
:Room owl:disjointWith :Hall .
:door a owl:ObjectProperty ; rdfs:domain :L . :at a owl:ObjectProperty, owl:FunctionalProperty ; rdfs:range :L .
:link a owl:ObjectProperty ; rdfs:domain :L ; rdfs:range :L . :reach a owl:ObjectProperty ; rdfs:range :L .
{rule([obj(':door', '?a', '?d'), obj(':door', '?b', '?d'), diff('?a', '?b')], [obj(':link', '?a', '?b')], 'Link')}
{rule([obj(':at', '?r', '?a'), obj(':link', '?a', '?b'), diff('?a', '?b')], [obj(':reach', '?r', '?b')], 'Reach')}
"""
PLACES = ["p0", "p1", "p2", "p3"]


@settings(max_examples=property_examples(60), deadline=None)
@given(batches=st.lists(st.lists(st.tuples(st.sampled_from(["door", "at", "link", "Room", "Hall"]),
                                           st.sampled_from(PLACES), st.sampled_from(["d0", "d1", *PLACES])),
                                 min_size=1, max_size=3), min_size=1, max_size=6))
def test_a_covered_rule_left_out_equals_from_scratch(batches: list) -> None:
    """Every derived link had two places with a door each, so link's domain and range (and, where a
    difference is asked by candidate facts, Reach's question) add nothing the doors did not: while no
    link is asserted, the compiled step leaves them out (reason/restate.py covering).  Asserted links,
    moves and disjoint classes are mixed in."""
    onto = turtle(MAP)
    onto.add(Triple(N("bot"), N("at"), N("p0")))
    onto.reason()
    for batch in batches:
        for p, a, b in batch:
            if p == "at":
                onto.replace(N("bot"), N("at"), N(a))
                continue
            fact = Triple(N(a), TYPE, N(p)) if p in ("Room", "Hall") else Triple(N(a), N(p), N(b))
            toggle(onto, fact)
        report = onto.reason(mode="incremental")
        assert_as_from_scratch(onto, report)


def test_the_covered_rule_is_left_out_until_a_fact_of_its_atom_is_asserted() -> None:
    onto = turtle(MAP)
    onto.add(Triple(N("bot"), N("at"), N("p0")), Triple(N("p0"), N("door"), N("d0")),
             Triple(N("p1"), N("door"), N("d0")))
    onto.reason()
    reasoner = onto._reasoner
    # link's domain and range: every derived link had two places with doors, whose domain says as much
    assert {key for key in reasoner.step.compiler.covered.values()} == {("p", f"<{NS}link>")}
    # a change of Link's premises reaches the links and their domain and range (a covered rule the
    # change does not reach is not asked about, and names nothing: see step_compiler._LeftOut)
    different = "<http://www.w3.org/2002/07/owl#differentFrom>"
    sig = signature(({f"<{NS}door>": 1, different: 1}, {}), ({}, {}), ())
    program = reasoner.step.compiler.compile(sig, reasoner.state.present, reasoner.state.asserted)
    assert ("p", f"<{NS}link>") in program.needs_unasserted
    onto.add(Triple(N("p2"), N("link"), N("p3")))
    onto.reason(mode="incremental")
    program = reasoner.step.compiler.compile(sig, reasoner.state.present, reasoner.state.asserted)
    assert ("p", f"<{NS}link>") not in program.needs_unasserted


def test_a_kind_of_change_run_again_is_checked_again_once_a_key_gains_facts() -> None:
    """A program run again with no new key with facts reuses what its last run noted (the keys it left
    out have none still); once a key gains facts, it is checked again, and the general phases forget
    every such record."""
    onto = turtle(MAP)
    onto.add(Triple(N("bot"), N("at"), N("p0")), Triple(N("p0"), N("door"), N("d0")),
             Triple(N("p1"), N("door"), N("d0")))
    onto.reason()
    step = onto._reasoner.step
    for place in ("p5", "p6"):  # one kind of change twice: the second run takes what the first noted
        onto.add(Triple(N(place), N("door"), N("d1")))
        report = onto.reason(mode="incremental")
        assert report.stats.program == "compiled", report.stats.program
        assert_as_from_scratch(onto, report)
    (sig, ran), = step._ran.items()
    assert step._unchanged(sig, onto._reasoner.state) is ran
    onto.add(Triple(N("p2"), N("link"), N("p3")))  # link: a key with no asserted fact until now
    onto.reason(mode="incremental")
    assert step._unchanged(sig, onto._reasoner.state) is None  # the asserted keys grew
    onto.add(Triple(N("p7"), N("door"), N("d1")))
    report = onto.reason(mode="incremental")
    assert report.stats.program == "compiled", report.stats.program
    assert_as_from_scratch(onto, report)
    assert step._unchanged(sig, onto._reasoner.state) is step._ran[sig]
    with mock.patch.object(step, "enabled", False):  # the general phases forget every record
        onto.add(Triple(N("p8"), N("door"), N("d1")))
        assert_as_from_scratch(onto, onto.reason(mode="incremental"))
    assert not step._ran


def test_a_check_pair_kept_apart_by_difference_is_skipped_after_a_clean_replacement() -> None:
    """prp-fp (two values of a functional property known different) pairs the values of one subject
    through its difference atom: after a clean replacement it cannot match anew (a value different
    from itself is the different-self check's violation), but an added second value does."""
    onto = turtle(NEGATED)
    for name, value in (("i1", 1), ("i2", 2)):
        onto.replace(N(name), N("d"), value)
    onto.add(Triple(N("i0"), N("f"), N("i1")))
    onto.reason()
    reasoner = onto._reasoner
    assert "different-self" in {c.name for c in reasoner.checks}
    fp = next(c for c in reasoner.checks if c.name == "prp-fp" and c.body[0].p == f"<{NS}f>")
    assert check_pair_atom(fp, 0) and check_pair_atom(fp, 1) and not pair_atom(fp, 0)
    onto.replace(N("i0"), N("f"), N("i2"))
    report = onto.reason(mode="incremental")
    assert report.consistent and report.stats.program == "compiled"
    onto.add(Triple(N("i0"), N("f"), N("i1")))
    report = onto.reason(mode="incremental")
    assert not report.consistent and [v.rule for v in report.violations] == ["prp-fp"]


TRANSITIVE = PREFIXES + """
:t a owl:TransitiveProperty . :s a owl:ObjectProperty ; rdfs:subPropertyOf :t .
:t rdfs:domain :A . :A owl:equivalentClass [ a owl:Restriction ; owl:onProperty :t ; owl:someValuesFrom :A ] .
"""


@settings(max_examples=property_examples(60), deadline=None)
@given(batches=st.lists(st.lists(st.tuples(st.sampled_from(["t", "s"]), st.sampled_from(PEOPLE),
                                           st.sampled_from(PEOPLE)), min_size=1, max_size=3), min_size=1, max_size=6),
       whole=st.booleans())
def test_recursive_component_equals_from_scratch(batches: list, whole: bool) -> None:
    """A transitive property, a subproperty and a class defined through the property itself: every change
    reaches recursive components, maintained with DRed inside them (see reason/component.py), round by
    round or with its rounds unrolled in one request (``whole``; a full run when they were not enough)."""
    onto = turtle(TRANSITIVE)
    onto.reason()
    onto._reasoner.store.round_trips = whole
    for batch in batches:
        for p, a, b in batch:
            fact = Triple(N(a), N(p), N(b))
            toggle(onto, fact)
        report = onto.reason(mode="incremental")
        assert_as_from_scratch(onto, report, consistency=False)
        if report.stats.reason != "no asserted change" and report.stats.mode == "incremental":
            assert report.stats.program == "compiled" or (
                whole and report.stats.program.startswith("general: a recursive component needed more")), \
                report.stats.program
        elif report.stats.mode == "full":
            assert whole and "rounds of a recursive component were not enough" in report.stats.reason


def test_recursive_component_runs_key_by_key_or_unrolled() -> None:
    onto = turtle(PREFIXES + ":t a owl:TransitiveProperty .")
    onto.add(Triple(N("a"), N("t"), N("b")))
    onto.reason()
    onto.add(Triple(N("b"), N("t"), N("c")))
    assert onto.reason(mode="incremental").stats.program == "compiled"
    assert Triple(N("a"), N("t"), N("c")) in set(onto.store.triples(graph=INFERRED))
    compiler = StepCompiler(onto._reasoner.rules, onto._reasoner.monotone, lambda i, atoms: atoms, True)
    key = f"<{NS}t>"
    program = compiler.compile(signature(({key: 1}, {}), ({}, {}), ()), onto._reasoner.state.present)
    assert not program.whole  # a component runs in rounds
    reasoner = onto._reasoner
    reasoner.store.round_trips = True  # as on a remote store: one request, the rounds unrolled
    try:
        onto.add(Triple(N("c"), N("t"), N("d")))
        report = onto.reason(mode="incremental")
        assert report.stats.program == "compiled"
        assert Triple(N("a"), N("t"), N("d")) in set(onto.store.triples(graph=INFERRED))
        chain = [Triple(N(f"n{k}"), N("t"), N(f"n{k + 1}")) for k in range(64)]
        onto.add(*chain)  # closing a long chain needs more rounds than one request has
        report = onto.reason(mode="incremental")
        assert report.stats.mode == "full" and "rounds of a recursive component were not enough" in report.stats.reason
        assert Triple(N("n0"), N("t"), N("n64")) in set(onto.store.triples(graph=INFERRED))
        onto.add(Triple(N("n64"), N("t"), N("n65")))  # the same kind of change: no second full run
        report = onto.reason(mode="incremental")
        assert report.stats.program.startswith("general: a recursive component needed more than"), report.stats
        assert Triple(N("n0"), N("t"), N("n65")) in set(onto.store.triples(graph=INFERRED))
    finally:
        reasoner.store.round_trips = False


def test_rules_over_any_predicate_are_refused() -> None:
    onto = turtle(PREFIXES + ":p a owl:ObjectProperty .")
    onto.add(Triple(N("a"), NamedNode("http://www.w3.org/2002/07/owl#sameAs"), N("b")))
    onto.add(Triple(N("a"), N("p"), N("c")))
    onto.reason()
    onto.add(Triple(N("b"), N("p"), N("d")))
    report = onto.reason(mode="incremental")
    assert report.stats.program.startswith("general: ") and "any predicate" in report.stats.program
    try:
        StepCompiler(onto._reasoner.rules, onto._reasoner.monotone, lambda i, a: a, True).compile(
            signature(({f"<{NS}p>": 1}, {}), ({}, {}), ()), onto._reasoner.state.present)
    except Refused:
        pass
    else:
        raise AssertionError("a rule over any predicate was compiled")


def test_a_rule_copying_a_literal_equals_from_scratch() -> None:
    """A sub-property of a data property copies literals: its operations leave their spelling to the
    store (the look-up equivalents of reason/direct.py decline them), in every form the value takes."""
    onto = turtle(PREFIXES + ":seen a owl:DatatypeProperty ; rdfs:subPropertyOf :noted . "
                             ":noted a owl:DatatypeProperty . :i0 :seen 5 .")
    onto.max_change_share = 1.0
    onto.reason()
    for value in [6, onto.value("07", "integer"), onto.value(7, "long"), "text", 5]:
        onto.replace(N("i0"), N("seen"), value)
        report = onto.reason(mode="incremental")
        assert_as_from_scratch(onto, report)
        assert report.stats.program == "compiled" or report.stats.reason == "no asserted change", report.stats
        assert [t.object for t in onto.store.triples(N("i0"), N("noted"), None, INFERRED)] == \
            [t.object for t in onto.store.triples(N("i0"), N("seen"), None, ASSERTED)]


def test_a_flip_seeded_by_a_clock_needs_every_clock_replaced() -> None:
    """The clock rule's flip runs as the one branch seeded by ``now`` only when every ``now`` fact was
    replaced: with a second clock left alone, a visit compared with that clock must still flip."""
    onto = new_ontology()
    onto.max_change_share = 1.0
    onto.add(Triple(N("clock2"), N("now"), Literal("200", datatype=NamedNode("http://www.w3.org/2001/XMLSchema#long"))))
    onto.replace(N("i1"), N("seen"), 195)
    assert_as_from_scratch(onto, onto.reason())
    steps = [[("i1", "seen", 150), ("clock", "now", 101)],  # i1 becomes Hot by clock2 (the clock left alone)
             [("i1", "seen", 195), ("clock", "now", 102), ("clock2", "now", 201)],  # both clocks: one branch
             [("i2", "seen", 90), ("clock", "now", 103), ("clock2", "now", 202)],
             [("i2", "seen", 100), ("clock2", "now", 150)]]
    for batch in steps:
        for a, p, v in batch:
            onto.replace(N(a), N(p), v)
        report = onto.reason(mode="incremental")
        assert_as_from_scratch(onto, report)
        assert report.stats.program == "compiled", report.stats.program
    assert {onto.short(i) for i in onto.instances(N("Hot"))} == {"i2"}


def test_a_flip_run_by_look_ups_reads_no_clock_for_a_text_it_does_not_send() -> None:
    """Whether every ``now`` fact was replaced only picks the text a flip queues: the flip's look-ups
    read no asserted facts for it, and a flip whose look-ups give way sends the one seeded branch."""
    from topostore.reason.staged import StagedRun

    asked: list[str] = []
    all_replaced = StagedRun._all_replaced

    def counted(run, p):
        asked.append(p)
        return all_replaced(run, p)

    def ticks(onto: Ontology) -> None:
        onto.max_change_share = 1.0
        onto.replace(N("i1"), N("seen"), 95)
        assert_as_from_scratch(onto, onto.reason())
        for tick in (105, 111, 100):
            onto.replace(N("i1"), N("seen"), tick - 1 if tick > 100 else 80)
            onto.replace(N("clock"), N("now"), tick)
            report = onto.reason(mode="incremental")
            assert report.stats.program == "compiled", report.stats.program
            assert_as_from_scratch(onto, report)
        assert {onto.short(i) for i in onto.instances(N("Hot"))} == {"i1"}

    with mock.patch.object(StagedRun, "_all_replaced", counted):
        ticks(new_ontology())
        assert asked == []
        with mock.patch.object(look_flip.Flipped, "heads", lambda self, store: None):  # the text runs
            ticks(new_ontology())
    assert asked, "the queued flip chose its text"


def test_a_step_run_by_look_ups_copies_no_change_for_text() -> None:
    """The asserted changes go to the scratch graphs SPARQL text reads them from (ADDED, REMOVED) only
    where a text is sent: not in the clock's steps once every operation runs by look-ups (the first
    sends a text), and before the first text of steps whose operations run as text (as from scratch)."""
    from topostore.reason.scratch import ADDED, REMOVED
    from topostore.reason.staged import StagedRun

    def steps(onto: Ontology, joined: bool) -> list[set]:
        """The scratch graphs each step wrote."""
        written: list[set] = []
        add_scratch = onto.store.add_scratch

        def spied(triples, graph):
            written[-1].add(graph)
            return add_scratch(triples, graph)

        onto.max_change_share = 1.0
        with mock.patch.object(onto.store, "add_scratch", spied):
            for tick, (a, b) in enumerate([("i1", "i2"), ("i2", "i3"), ("i3", "i1"), ("i1", "i2")]):
                written.append(set())
                if joined:  # the join rules' operations: sent as text
                    toggle(onto, Triple(N(a), N("p"), N(b)))
                onto.replace(N("i1"), N("seen"), 90 + tick)
                onto.replace(N("clock"), N("now"), 101 + tick)
                report = onto.reason(mode="incremental")
                assert report.stats.program == "compiled", report.stats.program
                assert_as_from_scratch(onto, report)
        return written

    copies = {ADDED, REMOVED}
    assert [copies & graphs for graphs in steps(new_ontology(), False)[1:]] == [set()] * 3
    assert any(copies <= graphs for graphs in steps(new_ontology(), True))
    init = StagedRun.__init__

    def as_text(run, *args, **kwargs):
        init(run, *args, **kwargs)
        run.direct = {}  # every operation sent as its text

    with mock.patch.object(StagedRun, "__init__", as_text):
        assert all(copies <= graphs for graphs in steps(new_ontology(), False))


def test_a_look_up_waits_for_the_queued_deletion_of_a_key_it_reads() -> None:
    """Hot's deletion is queued when the clock goes back; C's candidates and rechecks, made by look-ups
    (C ⊑ A, Hot ⊑ C: one-atom rules), read Hot: the deletion is sent before them, and C and A of the
    individual that cooled down go too."""
    onto = new_ontology()
    onto.replace(N("i0"), N("seen"), 80)
    onto.reason()
    assert {onto.short(i) for i in onto.instances(N("C"))} == {"i0"}
    onto.replace(N("clock"), N("now"), 85)
    report = onto.reason(mode="incremental")
    assert report.stats.program == "compiled", report.stats.program
    assert_as_from_scratch(onto, report)
    assert set(onto.instances(N("C"))) == set()
    assert N("i0") not in set(onto.instances(N("A")))


def test_parts_reading_apart_share_one_request(tmp_path) -> None:
    """The example map's robot step: the clock's flip is sent alone (its flipped facts are read by
    look-ups), every operation after it in one request (no look-up reads a key they write)."""
    import sys
    from pathlib import Path

    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # the benchmarks package lives beside src/
    from benchmarks import maps
    from benchmarks.armor_robot import ArmorRobot
    from benchmarks.walk import plan

    path, bench = maps.write("example", tmp_path)
    moves = plan(bench, 12)
    robot = ArmorRobot(path)
    for move in moves[:10]:
        robot.step(move)
    store = robot.ontology.store
    sent: list[str] = []
    update = store.update
    with mock.patch.object(store, "update", lambda text, *a, **k: (sent.append(text), update(text, *a, **k))[1]):
        for move in moves[10:]:
            sent.clear()
            robot.step(move)
            assert len(sent) <= 2, sent


def test_a_recheck_keeping_every_candidate_by_look_ups_reads_none_back(tmp_path, staged_form: str) -> None:
    """The example map's robot step: the old location's LOCATION is a candidate, rechecked by one-atom
    look-ups; one that keeps every candidate of the key answers so (direct.ALL_KEPT), and the generated run
    reads neither the candidates nor the kept facts back to learn it (the interpreted run still does, as
    both do after a recheck that kept only some)."""
    import sys
    from pathlib import Path

    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # the benchmarks package lives beside src/
    from benchmarks import maps
    from benchmarks.armor_robot import ArmorRobot
    from benchmarks.walk import plan
    from topostore.reason.delta_texts import KEEP

    kept_reads, answers = [], []
    keep = direct.OneAtom.keep

    def counted(self, store):
        answers.append(keep(self, store))
        return answers[-1]

    path, bench = maps.write("example", tmp_path)
    moves = plan(bench, 30)
    with mock.patch.object(direct.OneAtom, "keep", counted):  # bound when the program is
        robot = ArmorRobot(path)
        for move in moves[:10]:
            robot.step(move)
        store = robot.ontology.store
        triples = store.triples
        answers.clear()
        with mock.patch.object(store, "triples", lambda *a, **k: (
                kept_reads.append(a) if KEEP in (*a, k.get("graph")) else None, triples(*a, **k))[1]):
            for move in moves[10:]:
                robot.step(move)
    assert direct.ALL_KEPT in answers and True in answers
    # one read of the kept facts after each recheck, but (generated) after one that kept every candidate
    assert len(kept_reads) == (answers.count(True) if staged_form == "generated" else len(answers)), \
        (staged_form, answers, len(kept_reads))


def test_covering_finds_by_index_what_trying_every_writer_finds() -> None:
    """reason/restate.py looks the rules that may derive a conclusion up by the keys they read; trying
    every rule that writes the key must give the same covered rules, on the tutorial map and a TBox of
    restrictions and disjointness (where thousands of rules write types)."""
    import tempfile
    from pathlib import Path

    from benchmarks import tbox
    from topostore.reason import restate
    from topostore.resources import default_ontology_files

    def every_writer(self, written, premises):
        return [n for n, r in enumerate(self.rules) if r.head is not None and r.writes() == written]

    with tempfile.TemporaryDirectory() as tmp:
        sources = [default_ontology_files(), [tbox.write(60, Path(tmp))]]
        covered = []
        for files in sources:
            onto = Ontology.from_file(*files)
            rules = list(onto.rules.inference_rules)
            asking = [i for i, r in enumerate(rules) if r.head is not None and r.head_aux()]
            indexed = restate.covering(rules, asking)
            with mock.patch.object(restate._Readers, "within", every_writer), \
                    mock.patch.object(restate._Readers, "rules", rules, create=True):
                tried = restate.covering(rules, asking)
            assert indexed == tried
            covered.append(indexed)
    assert covered[0], "the tutorial's Reachability is covered by Connectability"


def test_a_part_nothing_starts_is_passed_by_its_keys() -> None:
    """The staged run groups the program by part once (reason/staged.segments): every operation in
    order, a part with a flip or seeds always runs, and a part whose operations start only from keys
    no part before it touched is not entered; where the tick flips something, it runs."""
    from topostore.reason import staged

    onto = new_ontology()
    onto.replace(N("i3"), N("seen"), 95)
    onto.reason()
    reasoner = onto._reasoner
    sig = signature(({f"<{NS}now>": 1}, {}), ({f"<{NS}now>": 1}, {}), (f"<{NS}now>",))
    program = reasoner.step.compiler.compile(sig, reasoner.state.present, reasoner.state.asserted)
    parts = staged.segments(program)
    assert [index for part in parts for index, *_ in part.ops] == [
        i for i, (tag, _) in enumerate(program.ops) if tag[0] != "component"]
    for part in parts:
        kinds = {op[1] for op in part.ops}
        if any(op[4] is not None for op in part.ops) or kinds & {"seeds", "always", "changes"}:
            assert part.always
        assert part.minus == {op[2] for op in part.ops if op[1] == "minus"}
        assert part.plus == {op[2] for op in part.ops if op[1] == "plus"}
        for index, _, _, text, _, key, found, reads, seeded, _, _, _, _, _ in part.ops:  # bound once per program
            assert (text, key, found, seeded) == (program.ops[index][1], program.part[index],
                                                   program.direct.get(index), index in program.seeded)
            assert reads == (program.reads[index] if found is not None else None)
    # the subclasses of Hot (C, then A): only Hot's changes start C's part, only C's start A's
    idle = [part.ops[0][0] for part in parts if not part.always]
    assert len(idle) == 2, describe(program)
    entered: list[int] = []
    original = staged.StagedRun._part

    def part_run(self, ops):
        entered.append(ops[0][0])
        return original(self, ops)

    with mock.patch.object(staged.StagedRun, "_part", part_run), mock.patch.object(staged_code, "GENERATED", False):
        for now, hot, runs in ((101, set(), False), (110, {"i3"}, True), (104, set(), True), (102, set(), False)):
            entered.clear()
            onto.replace(N("clock"), N("now"), now)
            report = onto.reason(mode="incremental")
            assert report.stats.program == "compiled", report.stats.program
            assert {onto.short(i) for i in onto.instances(N("Hot"))} == hot
            assert_as_from_scratch(onto, report)
            # C's part is entered to look up whether Hot changed (its flip ran); A's only after C's ran
            assert idle[0] in entered and (idle[1] in entered) == runs, (now, entered)


def _every_rule(compiler: StepCompiler, sig, present) -> tuple[set, set, dict]:
    """What the step compiler finds by its indexes, found by trying every maintained rule until nothing
    changes: (active rules, affected keys, the rules that can fire by written key)."""
    affected, active = set(sig.added | sig.removed), set()
    grew = True
    while grew:
        grew = False
        for i in compiler.monotone:
            rule = compiler.rules[i]
            reads = rule.reads()
            wild = ("*",) in reads or ("p", str(TYPE)) in reads
            if i in active or not (bool(affected) if wild else reads & affected):
                continue
            if compiler._missing(i, present, affected):
                continue
            active.add(i)
            if rule.writes() not in affected:
                affected.add(rule.writes())
                grew = True
    writers: dict = {}
    for i in compiler.monotone:
        if not compiler._missing(i, present, affected):
            writers.setdefault(compiler.rules[i].writes(), []).append(i)
    return active, affected, writers


def test_the_step_compiler_finds_by_index_what_trying_every_rule_finds() -> None:
    """reason/step_compiler.py visits the readers of each key as it joins, and leaves a rule out by a
    guard without facts: on a TBox of disjoint classes (thousands of rules on classes without members)
    the rules, keys and writers must be those of trying every rule, and every rule left out must name
    a key without facts that is in the program's ``needs_absent`` (else the program would be reused
    after that key gets facts)."""
    import tempfile
    from pathlib import Path

    from benchmarks import tbox, tbox_steps

    with tempfile.TemporaryDirectory() as tmp:
        onto = Ontology.from_file(tbox.write(60, Path(tmp)))
    onto.reason(mode="full")
    reasoner = onto._reasoner
    compiler = StepCompiler(reasoner.rules, reasoner.monotone, lambda i, atoms: atoms, True, cover=False)
    present = reasoner.state.present
    for step in tbox_steps.plan(60, 4):
        classes = {f"<{tbox.NS}{c}>": 1 for _, c in step.types if c != "NamedIndividual"}
        preds = {f"<{tbox.NS}{p}>": 1 for _, p, _ in step.add}
        sig = signature((preds, classes), ({f"<{tbox.NS}hasTopping>": 1}, {}), ())
        active, affected, absent, _ = compiler._affected(sig, present, set())
        want_active, want_affected, want_writers = _every_rule(compiler, sig, present)
        assert (set(active), affected) == (want_active, want_affected)
        program = compiler.compile(sig, present)
        found = _Writers(compiler, present, affected, set(absent), set(), active, {})
        for key in affected:
            assert found.get(key, []) == want_writers.get(key, [])
        for i in compiler.monotone:
            missing = compiler._missing(i, present, want_affected)
            if missing and compiler.rules[i].reads() & want_affected:
                assert missing & program.needs_absent, compiler.rules[i]


def test_run_records_are_dropped_with_their_evicted_programs() -> None:
    """The record of a kind of change's last run names its program: when the program is evicted the record
    goes too (else every evicted kind of change kept one alive until the next full run)."""
    from topostore.reason import compiled_step

    onto = new_ontology()
    kinds = [Triple(N("i0"), N("p"), N("i1")), Triple(N("i1"), N("q"), N("i2")), Triple(N("i2"), N("r"), N("i3")),
             Triple(N("i3"), N("s"), N("i4")), Triple(N("i4"), TYPE, N("B"))]
    with mock.patch.object(compiled_step, "MAX_PROGRAMS", 2):
        for triple in kinds:
            onto.add(triple)
            onto.reason(mode="incremental")
            step = onto._reasoner.step
            assert len(step._ran) <= len(step.programs) <= 2


def test_only_a_change_a_rule_may_have_inferred_is_discarded_from_the_inferred_graphs() -> None:
    """A clock tick or a visit time (no rule writes :now or :seen) discards nothing from the inferred and
    helper graphs; a type fact a rule inferred, once asserted, leaves the inferred graph (as from scratch)."""
    onto = new_ontology()
    onto.max_change_share = 1.0
    onto.add(Triple(N("i1"), N("p"), N("i2")))
    onto.reason(mode="incremental")
    inferred = Triple(N("i1"), TYPE, N("A"))
    assert inferred in set(onto.store.triples(graph=INFERRED))
    discarded: list[list] = []
    discard = onto.store.discard

    def spied(triples, graphs):
        discarded.append(list(triples))
        return discard(triples, graphs)

    with mock.patch.object(onto.store, "discard", spied):
        onto.replace(N("clock"), N("now"), 120)
        onto.replace(N("i1"), N("seen"), 95)
        assert_as_from_scratch(onto, onto.reason(mode="incremental"))
        assert discarded == []
        onto.add(inferred)
        assert_as_from_scratch(onto, onto.reason(mode="incremental"))
    assert [inferred] in discarded
    assert inferred not in set(onto.store.triples(graph=INFERRED))


_terms = st.sampled_from(["i1", "i2", "i3"])
_facts = st.lists(st.tuples(_terms, st.sampled_from(["p", "q", "type"]), _terms), max_size=6)


@settings(max_examples=property_examples(100), deadline=None)
@given(held=_facts, added=_facts, removed=_facts)
def test_the_clean_replacements_read_here_are_those_of_the_definition(held: list, added: list, removed: list) -> None:
    """:func:`.kinds.replaced_in` in memory (one pass, a look-up per pair replaced once) gives what
    :func:`.flip.clean_replacements` defines, on any change: pairs with several triples added or removed,
    additions or removals alone, type facts, several values held."""
    from topostore.reason import flip, kinds

    def triples(facts: list) -> list[Triple]:
        return list(dict.fromkeys(Triple(N(s), TYPE if p == "type" else N(p), N(o)) for s, p, o in facts))

    store = memory_store()
    store.add(triples(held + added), ASSERTED)
    store.remove(triples(removed), ASSERTED)
    change = triples(added), triples(removed)
    definition = flip.clean_replacements(*change, lambda s, pred: store.objects(s, pred, ASSERTED))
    assert kinds.replaced_in(store, *change, ASSERTED) == definition
    # where a read is a round trip the same pass asks the pairs' values in one batch, and keeps no pair
    single: set = set()
    with mock.patch.object(type(store), "round_trips", True):
        assert kinds.replaced_in(store, *change, ASSERTED, single) == definition
    assert not single


_few = st.lists(st.tuples(st.sampled_from(["i1", "i2"]), st.sampled_from(["p", "type"]), _terms), max_size=3)


@settings(max_examples=property_examples(200), deadline=None)
@given(held=_few, batches=st.lists(st.tuples(_few, _few), max_size=8))
# a pair replaced cleanly, given a second value, then one of its two values replaced
@example(held=[("i1", "p", "i1")], batches=[([("i1", "p", "i2")], [("i1", "p", "i1")]), ([("i1", "p", "i3")], []),
                                            ([("i1", "p", "i1")], [("i1", "p", "i2")])])
# a pair replaced cleanly, its value removed, then one given and replaced
@example(held=[("i1", "p", "i1")], batches=[([("i1", "p", "i2")], [("i1", "p", "i1")]), ([], [("i1", "p", "i2")]),
                                            ([("i1", "p", "i1"), ("i1", "p", "i3")], []),
                                            ([("i1", "p", "i2")], [("i1", "p", "i1")])])
def test_the_pairs_known_single_valued_are_carried_exactly_from_change_to_change(held: list, batches: list) -> None:
    """The pairs :func:`.kinds.replaced_in` keeps as holding one value (no look-up for them at the next
    change) give, change after change, what :func:`.flip.clean_replacements` defines from the values read:
    each change is the net one (added: absent before and present after; removed: the reverse)."""
    from topostore.reason import flip, kinds

    def triples(facts: list) -> list[Triple]:
        return list(dict.fromkeys(Triple(N(s), TYPE if p == "type" else N(p), N(o)) for s, p, o in facts))

    store = memory_store()
    store.add(triples(held), ASSERTED)
    single: set = set()
    for adds, removes in batches:
        before = set(store.triples(graph=ASSERTED))
        store.remove(triples(removes), ASSERTED)
        store.add(triples(adds), ASSERTED)
        after = set(store.triples(graph=ASSERTED))
        change = sorted(after - before, key=str), sorted(before - after, key=str)
        assert kinds.replaced_in(store, *change, ASSERTED, single) == flip.clean_replacements(
            *change, lambda s, pred: store.objects(s, pred, ASSERTED))


def test_the_clean_replacements_of_a_change_read_only_the_pairs_replaced_once() -> None:
    """A change's clean replacements (:func:`.kinds.replaced_in`) read the asserted values of the pairs
    with one triple added and one removed only (each once), and are those of the values read."""
    from topostore.reason import flip, kinds

    store = memory_store()
    a, b, c = N("i1"), N("i2"), N("i3")
    p, q, r = N("p"), N("q"), N("r")
    store.add([Triple(a, p, b), Triple(a, q, b), Triple(a, q, c), Triple(b, p, c), Triple(b, r, c), Triple(b, r, a),
               Triple(c, TYPE, N("B"))], ASSERTED)
    added = [Triple(a, p, b), Triple(a, q, c), Triple(b, p, c), Triple(b, r, c), Triple(b, r, a), Triple(c, TYPE, N("B"))]
    removed = [Triple(a, p, c), Triple(a, q, a), Triple(b, p, b), Triple(b, r, b), Triple(c, TYPE, N("A"))]
    asked: list[tuple] = []
    objects = store.objects

    def spied(s, pred, graph):
        asked.append((s, pred))
        return objects(s, pred, graph)

    with mock.patch.object(store, "objects", spied):
        found = kinds.replaced_in(store, added, removed, ASSERTED)
    assert sorted(asked, key=str) == sorted([(a, p), (a, q), (b, p)], key=str)  # (b, r): two added; types: never
    assert found == flip.clean_replacements(added, removed, lambda s, pred: objects(s, pred, ASSERTED))
    assert sorted(found) == [f"<{p.value}>"]  # (a, q) holds two values now, (b, r) had two added
    assert sorted(str(x.new.subject) for x in found[f"<{p.value}>"]) == sorted([str(a), str(b)])


def test_a_tbox_change_between_reasons_drops_the_operations_bound_per_program() -> None:
    """What a run looks up about each operation is bound once per program (reason/staged._bound); a
    TBox change between two clock ticks drops the programs: the next tick's run reads a new program's
    operations, and a member of Hot is now also one of B (a stale program would leave it out)."""

    onto = new_ontology()
    for k in range(4):
        onto.replace(N(f"i{k}"), N("seen"), 90 + 2 * k)
    onto.reason()
    programs: list = []
    original = staged_code.run

    def run(staged_run):
        form = original(staged_run)
        program = staged_run.program
        programs.append((program, program.segments, program.fused))
        return form

    with mock.patch.object(staged_code, "run", run):
        for now in (101, 103):
            onto.replace(N("clock"), N("now"), now)
            assert_as_from_scratch(onto, onto.reason())
        onto.add(Triple(N("Hot"), NamedNode("http://www.w3.org/2000/01/rdf-schema#subClassOf"), N("B")))
        onto.reason()
        for now in (105, 107):
            onto.replace(N("clock"), N("now"), now)
            report = onto.reason()
            assert report.stats.program == "compiled"
            assert_as_from_scratch(onto, report)
    assert programs[0][0] is programs[1][0] and programs[0][1] is programs[1][1]  # bound once, kept
    assert programs[0][2] is programs[1][2]  # generated once (None where interpreted)
    assert programs[2][0] is not programs[1][0] and programs[2][1] is not programs[1][1]
    assert programs[2][1] is programs[3][1] and programs[2][2] is programs[3][2]
    if staged_code.GENERATED:
        assert programs[2][2] is not programs[1][2]
    assert any(t.object == N("B") for t in onto.store.triples(None, TYPE, None, INFERRED))


def test_a_clock_flip_reads_the_inferred_graph_once_a_rule_writing_its_keys_can_fire() -> None:
    """The look-ups of a program read an atom's facts from the graphs of the rules that can have written it
    (reason/look_join.StateGraphs.firing): ``seen2`` is a subproperty of ``seen``, but while no ``seen2``
    fact exists its rule never fired, and the clock flip reads visit times from the asserted graph alone.
    Once j has one, j's visit time is inferred only, and the next tick's flip must read it there: j is Hot
    as from scratch (the tick's program kept from before, reading the asserted graph, misses it)."""
    onto = turtle(TBOX + ":seen2 a owl:DatatypeProperty ; rdfs:subPropertyOf :seen .\n")
    onto.add(Triple(N("clock"), N("now"), Literal("100", datatype=NamedNode("http://www.w3.org/2001/XMLSchema#long"))))
    onto.reason()
    _clock_walk(onto)  # the tick's program compiled: no seen2 fact yet
    onto.replace(N("j"), N("seen2"), 99)
    onto.reason(mode="incremental")
    for now, hot in ((115, {"i0", "i1", "i2", "j"}), (70, set()), (116, {"i0", "i1", "i2", "j"})):
        onto.replace(N("clock"), N("now"), now)
        report = onto.reason(mode="incremental")
        assert report.stats.program == "compiled" and report.stats.flipped == 1
        assert_as_from_scratch(onto, report)
        assert {onto.short(i) for i in onto.instances(N("Hot"))} == hot
