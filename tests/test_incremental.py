"""Incremental REASON gives exactly what reasoning from scratch gives.

The property test applies random sequences of manipulations (robot moves,
clock ticks, visits, doors added and removed, AllDifferent axioms added and
removed, facts that make the ontology inconsistent or merge individuals) to
random small maps, reasons after every batch and compares the inferred and
helper graphs and the consistency verdict with a from-scratch
materialisation of the same asserted graph.  The helper graph is equal but for the asks a full
REASON leaves out where a conclusion is known (topostore.reason.negation): maintenance may keep
those, and what they derive, as long as the conclusion holds (:func:`assert_helper_facts`).
"""

from __future__ import annotations

import contextlib
from functools import cache
from unittest import mock

import pytest
from hypothesis import HealthCheck, example, given, settings
from hypothesis import strategies as st
from profiles import property_examples
from pyoxigraph import Literal, NamedNode, Triple
from support import TBOX_OWL as TBOX

from topostore import Ontology
from topostore.compile.rule import RuleSet
from topostore.compile.snippets import VALUE_CANDIDATE
from topostore.demo.mapgen import MAP_NS, generate
from topostore.rdf.vocab import ASSERTED, AUX, DIFFERENT, DIFFERENT_FROM, ENTAILED, ENTAILED_PREFIX, INFERRED, TYPE, owl
from topostore.reason import Materializer, check_consistency, direct, flips, look_flip
from topostore.reason.entailed import publish_entailed
from topostore.reason.incremental import is_monotone, negates_exists
from topostore.stores import memory_store

#: every test twice: the compiled step's staged runs generated and interpreted (reason/staged_code.py)
pytestmark = pytest.mark.usefixtures("staged_form")


def N(name: str) -> NamedNode:
    return NamedNode(MAP_NS + name)


@cache
def tbox_triples() -> tuple[Triple, ...]:
    return tuple(Ontology.from_file(TBOX).store.triples(graph=ASSERTED))


def new_map(n: int, seed: int, all_different: bool) -> Ontology:
    onto = Ontology()
    onto.add(*tbox_triples())
    onto.add(*generate(n, seed=seed).triples(all_different=all_different))
    return onto


def from_scratch(onto: Ontology) -> tuple[set, set, set, bool]:
    """Inferred, helper and entailed-only graphs and consistency of a fresh store holding the same asserted graph."""
    store = memory_store()
    store.add(onto.store.triples(graph=ASSERTED), ASSERTED)
    Materializer(store, onto.rules).run()
    violations = check_consistency(store, onto.rules)
    publish_entailed(store, onto.rules)
    return (set(store.triples(graph=INFERRED)), set(store.triples(graph=AUX)), set(store.triples(graph=ENTAILED)),
            not violations)


def assert_helper_facts(onto: Ontology, scratch: set) -> None:
    """The helper graph holds what a REASON from scratch holds, and beyond it only asks left out by a
    full REASON (a value candidate, a difference by values) of a pair whose ordinary conclusion is
    known, as the asking rule's ``unless_known`` names it, and entailed-only twins of known facts."""
    aux = set(onto.store.triples(graph=AUX))
    assert scratch <= aux, scratch - aux
    extra = aux - scratch
    if extra:
        assert all(_known_ask(onto.store, onto.rules, t) for t in extra), extra


def _known_ask(store, rules: RuleSet, t: Triple) -> bool:
    """Whether ``t`` is a deferred ask's fact (or one derived from it) on a pair whose conclusion is known,
    or an entailed-only twin whose ordinary fact is known (never published)."""
    def known(s, p: str, o) -> bool:
        triple = Triple(s, NamedNode(p), o)
        return store.contains(triple, INFERRED) or store.contains(triple, ASSERTED)

    if t.predicate.value.startswith(ENTAILED_PREFIX) and known(
            t.subject, t.predicate.value.removeprefix(ENTAILED_PREFIX), t.object):
        return True
    for r in rules.rules:
        if r.unless_known is None:
            continue
        p = r.unless_known.p[1:-1]
        same = r.unless_known.s == r.head.s
        if t.predicate in (VALUE_CANDIDATE, DIFFERENT) and (
                known(t.subject, p, t.object) if same else known(t.object, p, t.subject)):
            return True
    return False


def assert_same_as_scratch(onto: Ontology, profile: bool = False) -> None:
    report = onto.reason(profile=profile)
    inferred, aux, entailed, consistent = from_scratch(onto)
    assert set(onto.store.triples(graph=INFERRED)) == inferred, report.stats
    assert_helper_facts(onto, aux)
    assert set(onto.store.triples(graph=ENTAILED)) == entailed, report.stats
    assert report.consistent == consistent, report.stats
    assert_views_fresh(onto)


#: classes whose answers are kept as views (asked after every REASON, so the next one maintains them)
VIEWED = ("URGENT", "LOCATION", "ROOM", "CORRIDOR", "ROBOT", "DOOR")


def assert_views_fresh(onto: Ontology) -> None:
    """Class answers read from the maintained views equal a fresh read of the store."""
    for name in VIEWED:
        fresh = onto.reads._instances(N(name))
        assert sorted(onto.instances(N(name)), key=str) == sorted(fresh, key=str), name
        assert onto.rendered_instances(N(name), "local", _local) == sorted({_local(m) for m in fresh}), name


def _local(term: NamedNode) -> str:
    return term.value.rsplit("#", 1)[-1]


# ---------------------------------------------------------------- manipulations
NAMES = [f"C{i}" for i in range(1, 4)] + [f"R{i}" for i in range(1, 6)] + ["X1", "X2"]
DOORS = [f"D{i}" for i in range(1, 7)] + ["DX"]
TIMES = st.integers(1665579700, 1665579800)


def move(onto: Ontology, where: str) -> None:
    onto.replace(N("Robot1"), N("isIn"), N(where))


def tick(onto: Ontology, t: int) -> None:
    onto.replace(N("Robot1"), N("now"), t)


def visit(onto: Ontology, where: str, t: int) -> None:
    onto.replace(N(where), N("visitedAt"), t)


def second_visit(onto: Ontology, where: str, t: int) -> None:
    """Two different visitedAt values: inconsistent (exactly one visitedAt)."""
    onto.add(onto.fact(N(where), N("visitedAt"), t))


def add_door(onto: Ontology, where: str, door: str) -> None:
    onto.add(Triple(N(where), N("hasDoor"), N(door)))


def door_to_location(onto: Ontology, where: str, other: str) -> None:
    """hasDoor pointing at a location: DOOR and LOCATION are disjoint, inconsistent."""
    onto.add(Triple(N(where), N("hasDoor"), N(other)))


def remove_door(onto: Ontology, index: int) -> None:
    links = list(onto.store.triples(None, N("hasDoor"), None, ASSERTED))
    if links:
        onto.remove(links[index % len(links)])


def second_place(onto: Ontology, where: str) -> None:
    """Robot in two places: inconsistent if they are different, else merged by owl:sameAs."""
    onto.add(Triple(N("Robot1"), N("isIn"), N(where)))


def all_different(onto: Ontology, names: list[str]) -> None:
    onto.add_all_different([N(n) for n in names])


def drop_all_different(onto: Ontology, index: int) -> None:
    """Remove one whole AllDifferent axiom, or a single triple of one (a broken list)."""
    groups = list(onto.store.triples(None, TYPE, owl("AllDifferent"), ASSERTED))
    if not groups:
        return
    group = groups[index % len(groups)].subject
    if index % 2:
        onto.remove(groups[index % len(groups)])
    else:
        members = list(onto.store.triples(group, owl("distinctMembers"), None, ASSERTED))
        onto.remove(*members)


def different_from(onto: Ontology, a: str, b: str, add: bool) -> None:
    t = Triple(N(a), DIFFERENT_FROM, N(b))
    onto.add(t) if add else onto.remove(t)


def remove_any(onto: Ontology, index: int) -> None:
    """Retract one random asserted ABox fact (a declaration, a list cell, a value...)."""
    abox = [t for t in onto.store.triples(graph=ASSERTED) if t not in set(tbox_triples())]
    if abox:
        onto.remove(abox[index % len(abox)])


place = st.sampled_from(NAMES)
index = st.integers(0, 1000)
operation = st.one_of(
    st.tuples(st.just(move), place),
    st.tuples(st.just(tick), TIMES),
    st.tuples(st.just(visit), place, TIMES),
    st.tuples(st.just(add_door), place, st.sampled_from(DOORS)),
    st.tuples(st.just(remove_door), index),
    st.tuples(st.just(second_visit), place, TIMES),
    st.tuples(st.just(door_to_location), place, place),
    st.tuples(st.just(second_place), place),
    st.tuples(st.just(all_different), st.lists(place, min_size=2, max_size=4)),
    st.tuples(st.just(drop_all_different), index),
    st.tuples(st.just(different_from), place, place, st.booleans()),
    st.tuples(st.just(remove_any), index),
)
# a REASON after every batch of one to three manipulations
batches = st.lists(st.lists(operation, min_size=1, max_size=3), min_size=1, max_size=6)


@settings(max_examples=property_examples(80), deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(n=st.integers(1, 8), seed=st.integers(0, 3), declared=st.booleans(), share=st.sampled_from([0.1, 1.0]),
       steps=batches, profile=st.booleans())
# cases the compiled step once got wrong: a group naming one place twice, dropped (its BIND-made key is
# rechecked through KEEP, not inside NOT EXISTS); a lost difference noted although a look-up sent its key
@example(n=1, seed=0, declared=True, share=0.1, profile=False,
         steps=[[(all_different, ["C1", "C1"])], [(drop_all_different, 1)]])
@example(n=1, seed=0, declared=False, share=0.1, profile=False,
         steps=[[(all_different, ["C1", "C1"]), (all_different, ["C1", "C1"])], [(drop_all_different, 1)]])
@example(n=2, seed=0, declared=True, share=0.1, profile=False,
         steps=[[(drop_all_different, 1), (visit, "C1", 1_665_579_700)]])
def test_incremental_equals_from_scratch(n: int, seed: int, declared: bool, share: float, steps: list,
                                         profile: bool) -> None:
    """``profile`` runs every update on its own (timed) instead of one request per phase."""
    onto = new_map(n, seed, declared)
    onto.max_change_share = share
    assert_same_as_scratch(onto)
    with mock.patch.object(flips, "WINDOW_MIN", 0 if seed % 2 else flips.WINDOW_MIN):
        for batch in steps:
            for op, *args in batch:
                op(onto, *args)
            assert_same_as_scratch(onto, profile)


# ---------------------------------------------------------------- modes and fallbacks
def robot_step(onto: Ontology, where: str, t: int) -> None:
    move(onto, where)
    tick(onto, t)
    visit(onto, where, t)


def test_robot_step_is_incremental_and_exact() -> None:
    onto = new_map(20, 1, True)
    first = onto.reason()
    assert first.stats.mode == "full"
    for k, where in enumerate(["R3", "C2", "R7", "C1"]):
        robot_step(onto, where, 1665579750 + 5 * k)
        report = onto.reason()
        assert report.stats.mode == "incremental", report.stats.reason
        inferred, aux, entailed, consistent = from_scratch(onto)
        assert set(onto.store.triples(graph=INFERRED)) == inferred
        assert_helper_facts(onto, aux)
        assert set(onto.store.triples(graph=ENTAILED)) == entailed
        assert report.consistent == consistent
    assert sorted(onto.object_values("canReach", N("Robot1"))) == sorted(generate(20, seed=1).neighbours("C1"))


def test_no_change_keeps_the_report() -> None:
    onto = new_map(5, 0, True)
    onto.reason()
    report = onto.reason()
    assert report.stats.mode == "incremental" and report.stats.reason == "no asserted change"
    assert report.consistent


def test_add_then_remove_cancels() -> None:
    onto = new_map(5, 0, True)
    onto.reason()
    fact = Triple(N("R1"), N("hasDoor"), N("DX"))
    onto.add(fact)
    onto.remove(fact)
    assert onto.reason().stats.reason == "no asserted change"


def test_schema_change_forces_full() -> None:
    onto = new_map(5, 0, True)
    onto.reason()
    onto.add(Triple(N("SPARE"), TYPE, owl("Class")))
    report = onto.reason()
    assert report.stats.mode == "full"
    assert "schema" in report.stats.reason


def test_large_change_forces_full_unless_incremental_requested() -> None:
    onto = new_map(5, 0, True)
    onto.reason()
    onto.max_change_share = 0.01  # of the asserted graph, TBox included
    for k in range(6):
        visit(onto, f"R{k % 4 + 1}", 1665579700 + k)
        add_door(onto, f"R{k % 4 + 1}", f"DN{k}")
    report = onto.reason()
    assert report.stats.mode == "full" and "exceeds" in report.stats.reason
    robot_step(onto, "R2", 1665579760)
    assert onto.reason(mode="full").stats.mode == "full"
    onto.max_change_share = 0.0
    robot_step(onto, "R1", 1665579770)
    assert onto.reason(mode="incremental").stats.mode == "incremental"


def test_same_as_merge_falls_back_to_full_and_back() -> None:
    onto = new_map(5, 0, True)
    onto.reason()
    second_place(onto, "X1")  # X1 is not declared different from the robot's corridor
    merged = onto.reason()
    assert merged.stats.mode == "full" and "negated premise" in merged.stats.reason
    assert merged.consistent
    assert onto.store.contains(Triple(N("X1"), owl("sameAs"), N("C1")), INFERRED)
    onto.remove(Triple(N("Robot1"), N("isIn"), N("X1")))
    undone = onto.reason()
    assert undone.stats.mode == "full"  # the merge existed before: undone from scratch
    assert not onto.store.contains(Triple(N("X1"), owl("sameAs"), N("C1")), INFERRED)
    robot_step(onto, "R2", 1665579760)
    assert onto.reason().stats.mode == "incremental"


def test_lost_difference_makes_a_merge_and_falls_back_to_full() -> None:
    """The negated rules are asked only when a key they read changed: here no body atom gains a fact,
    the difference their filter reads is lost (the robot's two places stop being different)."""
    onto = new_map(5, 0, False)
    second_place(onto, "X1")
    different_from(onto, "X1", "C1", True)
    onto.reason()
    assert not onto.report.consistent  # one isIn (functional) value too many, and the two are different
    different_from(onto, "X1", "C1", False)
    merged = onto.reason()
    assert merged.stats.mode == "full" and "negated premise" in merged.stats.reason
    assert onto.store.contains(Triple(N("X1"), owl("sameAs"), N("C1")), INFERRED)
    inferred, aux, entailed, consistent = from_scratch(onto)
    assert set(onto.store.triples(graph=INFERRED)) == inferred and merged.consistent == consistent


def test_clean_step_asks_no_negated_rule() -> None:
    """A robot step (clean replacements of a functional property) cannot make a stratum-1 rule match:
    the ASK over them is not sent, and the step equals reasoning from scratch."""
    onto = new_map(8, 2, True)
    onto.reason()
    asked = []
    query = onto.store.query

    def counting(text, *args, **kwargs):
        asked.append(text)
        return query(text, *args, **kwargs)

    with mock.patch.object(onto.store, "query", counting):
        robot_step(onto, "R3", 1665579750)
        report = onto.reason()
    assert report.stats.mode == "incremental" and report.stats.program == "compiled"
    assert not any("NOT EXISTS" in text and text.startswith("ASK") for text in asked), asked
    inferred, aux, entailed, consistent = from_scratch(onto)
    assert set(onto.store.triples(graph=INFERRED)) == inferred and report.consistent == consistent


def test_inconsistency_appears_and_disappears_incrementally() -> None:
    onto = new_map(5, 0, True)
    onto.reason()
    door_to_location(onto, "C1", "R1")
    bad = onto.reason()
    assert bad.stats.mode == "incremental" and not bad.consistent
    onto.remove(Triple(N("C1"), N("hasDoor"), N("R1")))
    good = onto.reason()
    assert good.stats.mode == "incremental" and good.consistent


def test_unknown_mode_is_refused_and_keeps_pending_changes() -> None:
    onto = new_map(3, 0, True)
    onto.reason()
    visit(onto, "R1", 1665579790)
    try:
        onto.reason(mode="fast")
    except ValueError:
        pass
    else:
        raise AssertionError("mode 'fast' accepted")
    assert onto.reason().stats.reason == "1 added, 1 removed asserted triples"


def test_negation_detection() -> None:
    assert negates_exists("FILTER NOT EXISTS { ?x ?p ?y }")
    assert negates_exists("FILTER(!(?a && EXISTS { ?x ?p ?y }))")
    assert not negates_exists("FILTER(!sameTerm(?a, ?b) && EXISTS { ?x ?p ?y })")
    assert not negates_exists("BIND((?t - ?v) AS ?d)\n  FILTER(?d > ?h)")
    onto = new_map(2, 0, True)
    stratified = [r for r in onto.rules.inference_rules if r.stratum > 0]
    assert stratified and not any(is_monotone(r) for r in stratified)


# ---------------------------------------------------------------- the clock
def set_threshold(onto: Ontology, robot: str, h: int) -> None:
    onto.replace(N(robot), N("urgencyThreshold"), onto.value(h, "long"))


def set_clock(onto: Ontology, robot: str, t: int) -> None:
    onto.replace(N(robot), N("now"), onto.value(t, "long"))


def revisit(onto: Ontology, where: str, t: int) -> None:
    onto.replace(N(where), N("visitedAt"), onto.value(t, "long"))


robot = st.sampled_from(["Robot1", "Robot2"])
# a wide range: the clock jumps forward and back across every visit time and threshold
WIDE = st.integers(1665579600, 1665579900)
clock_change = st.one_of(
    st.tuples(st.just(set_clock), robot, WIDE),
    st.tuples(st.just(set_threshold), robot, st.integers(-5, 120)),
    st.tuples(st.just(revisit), place, WIDE),
    st.tuples(st.just(move), place),
)


@settings(max_examples=property_examples(60), deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(n=st.integers(2, 10), seed=st.integers(0, 3), steps=st.lists(st.lists(clock_change, min_size=1, max_size=4),
                                                                        min_size=1, max_size=6),
       windows=st.sampled_from([("WINDOW_MIN",), ("LOOKUP_WINDOW_MIN",), ("WINDOW_MIN", "LOOKUP_WINDOW_MIN")]))
def test_clock_changes_equal_from_scratch(n: int, seed: int, steps: list, windows: tuple) -> None:
    """Clocks jumping forward and back, thresholds and visit times changing, two robots: the
    replaced values only meet in the Urgency rule's comparison, which maintenance evaluates as
    a flip; every REASON must still equal a from-scratch run, with the flip's windows found by a
    query (WINDOW_MIN) or read by the look-up flip (LOOKUP_WINDOW_MIN) on these small maps too."""
    onto = Ontology()
    onto.add(*tbox_triples())
    onto.add(*generate(n, seed=seed, robots=2).triples(all_different=True))
    onto.max_change_share = 1.0
    onto.reason()
    with contextlib.ExitStack() as patches:
        for name in windows:
            patches.enter_context(mock.patch.object(flips, name, 0))
        for batch in steps:
            for op, *args in batch:
                op(onto, *args)
            assert_same_as_scratch(onto)


def test_the_look_up_flip_reads_only_the_visit_times_in_its_window() -> None:
    """A clock tick on a map with more visit times than a look-up reads at once: the look-up flip reads
    the few in the window between the old and the new threshold (no SPARQL text for the flip), and
    its answer is the from-scratch one, forward and back."""
    onto = new_map(30, 2, True)
    onto.max_change_share = 1.0
    onto.reason()
    reads: list = []
    windowed = look_flip.Flipped._windowed

    def spy(self, store, m, bound, old, index):
        found = windowed(self, store, m, bound, old, index)
        reads.append(found)
        return found

    with mock.patch.object(look_flip.Flipped, "_windowed", spy):
        for t in (1665579770, 1665579800, 1665579750, 1665579900):
            set_clock(onto, "Robot1", t)
            report = onto.reason()
            assert report.stats.mode == "incremental"
            assert report.stats.program == "compiled"
            assert_same_as_scratch(onto)
    assert reads and all(found is not None and len(found) <= direct.FEW for found in reads)
    assert any(found for found in reads)


def test_visit_times_of_other_numeric_types_keep_the_look_up_window_exact() -> None:
    """Decimal and double visit times, a string among them (no number: never in the window, and no flip),
    the clock moving forward and back across them, to decimal and double values too (the window then
    computed in fractions, widened for a double)."""
    onto = new_map(30, 2, True)
    onto.max_change_share = 1.0
    onto.reason()
    base = 1665579740
    for k, (text, datatype) in enumerate([(f"{base - 90}.5", "decimal"), (f"{base - 60}.25", "decimal"),
                                          (f"{base - 30}.0", "double"), ("soon", "string")]):
        onto.replace(N(f"R{k + 1}"), N("visitedAt"), onto.value(text, datatype))
    onto.reason()
    assert_same_as_scratch(onto)
    clock = [onto.value(t, "long") for t in (base + 30, base + 70)] + [onto.value(f"{base + 10}.75", "decimal"),
                                                                         onto.value(f"{base + 120}.5", "double")]
    for value in [*clock, onto.value(base - 40, "long")]:
        onto.replace(N("Robot1"), N("now"), value)
        assert onto.reason().stats.program == "compiled"
        assert_same_as_scratch(onto)


@pytest.mark.parametrize("windows", ["look-up", "query"])
def test_single_precision_values_take_no_window(windows: str) -> None:
    """An ``xsd:float`` clock or visit time is compared in single precision (near 1.6e9 only multiples
    of 128): a window computed exactly would leave out locations whose test flips, so with a float in
    play the flip reads every value, by the look-up flip or by the text (the window query)."""
    onto = new_map(40, 12, True)
    onto.max_change_share = 1.0
    onto.reason()
    with contextlib.ExitStack() as patches:
        if windows == "query":
            patches.enter_context(mock.patch.object(look_flip.Flipped, "heads", lambda self, store: None))
            patches.enter_context(mock.patch.object(flips, "WINDOW_MIN", 5))
        for text, datatype in [("1665579767.0", "float"), ("1665579797", "integer")]:
            onto.replace(N("Robot1"), N("now"), onto.value(text, datatype))
            onto.reason()
            assert_same_as_scratch(onto)
        for k in range(1, 6):
            onto.replace(N(f"R{k}"), N("visitedAt"), onto.value(str(1665579760 + 10 * k), "float"))
        onto.reason()
        assert_same_as_scratch(onto)
        for now in (1665579790, 1665579800, 1665579830, 1665579900):
            onto.replace(N("Robot1"), N("now"), onto.value(str(now), "integer"))
            assert onto.reason().stats.program == "compiled"
            assert_same_as_scratch(onto)


def test_a_look_up_flip_that_gives_up_leaves_the_flip_to_the_text_narrowed_by_a_window_query() -> None:
    """Where the look-up flip reading its own window gives up (too many facts in the window, a value it
    does not decide), the flip's text runs narrowed by a window query, as when no look-up reads one."""
    onto = new_map(30, 2, True)
    onto.max_change_share = 1.0
    onto.reason()
    windows = mock.Mock(wraps=onto._reasoner.flips._windows)
    with mock.patch.object(look_flip.Flipped, "heads", lambda self, store: None), \
            mock.patch.object(flips, "WINDOW_MIN", 5), mock.patch.object(onto._reasoner.flips, "_windows", windows):
        for t in (1665579770, 1665579800, 1665579750):
            set_clock(onto, "Robot1", t)
            report = onto.reason()
            assert report.stats.program == "compiled"
            assert_same_as_scratch(onto)
    assert windows.call_count >= 3


def test_a_look_up_flip_that_answers_makes_no_window_for_its_text() -> None:
    """A flip with a look-up form runs it first: the value window its text would be narrowed by is made
    only where the look-up gives up (the test above), never beside a look-up that answers.  With a
    window size of 5 on a map of 8 locations (no value index of the look-up's own), the window was made
    at every tick and the narrowed text ran instead of the look-up."""
    onto = new_map(8, 2, True)
    onto.max_change_share = 1.0
    onto.reason()
    windows = mock.Mock(wraps=onto._reasoner.flips._windows)
    answered = []
    heads = look_flip.Flipped.heads

    def answering(self, store):
        found = heads(self, store)
        answered.append(found is not None)
        return found

    with mock.patch.object(flips, "WINDOW_MIN", 5), mock.patch.object(onto._reasoner.flips, "_windows", windows), \
            mock.patch.object(look_flip.Flipped, "heads", answering):
        for t in (1665579770, 1665579800, 1665579750, 1665579900):
            set_clock(onto, "Robot1", t)
            report = onto.reason()
            assert report.stats.program == "compiled"
            assert_same_as_scratch(onto)
    assert len(answered) >= 4 and all(answered)
    assert windows.call_count == 0


def test_clock_tick_is_evaluated_as_a_flip() -> None:
    """A clock tick re-examines the Urgency rule once, not every URGENT fact."""
    onto = new_map(30, 2, True)
    onto.reason()
    before = {onto.short(i) for i in onto.instances("URGENT")}
    set_clock(onto, "Robot1", 1665579740 + 30)
    report = onto.reason()
    assert report.stats.mode == "incremental"
    assert report.stats.flipped >= 1
    m = generate(30, seed=2)
    expected = {loc for loc, v in m.visited_at.items() if 1665579770 - v > m.threshold}
    assert {onto.short(i) for i in onto.instances("URGENT")} == expected
    assert expected > before


def test_a_map_below_the_window_size_keeps_no_value_index() -> None:
    """Below WINDOW_MIN facts of a compared predicate no flip window is used, which the fact count
    tells without building the predicate's value index: none is built, and none is kept up to date
    at every step; above it the index is built and the windows give the from-scratch answer."""
    for window_min, indexed in ((flips.WINDOW_MIN, False), (5, True)):
        onto = new_map(30, 2, True)
        onto.max_change_share = 1.0
        onto.reason()
        with mock.patch.object(flips, "WINDOW_MIN", window_min), \
                mock.patch.object(flips, "LOOKUP_WINDOW_MIN", max(window_min, flips.LOOKUP_WINDOW_MIN)):
            for tick in range(1, 4):
                set_clock(onto, "Robot1", 1665579740 + 40 * tick)
                revisit(onto, f"R{tick}", 1665579740 + 40 * tick)
                assert onto.reason().stats.mode == "incremental"
                assert_same_as_scratch(onto)
        assert bool(onto._reasoner.flips._indexes) is indexed


SV = "http://example.org/sv#"
COUNT_UP = f"""@prefix : <{SV}> . @prefix owl: <http://www.w3.org/2002/07/owl#> .
@prefix swrl: <http://www.w3.org/2003/11/swrl#> . @prefix swrlb: <http://www.w3.org/2003/11/swrlb#> .
:d a owl:DatatypeProperty . :a a owl:NamedIndividual .
:x a swrl:Variable . :w a swrl:Variable . :u a swrl:Variable .
[ a swrl:Imp ;
  swrl:body ( [ a swrl:DatavaluedPropertyAtom ; swrl:propertyPredicate :d ; swrl:argument1 :x ; swrl:argument2 :w ]
              [ a swrl:BuiltinAtom ; swrl:builtin swrlb:add ; swrl:arguments ( :u :w 1 ) ]
              [ a swrl:BuiltinAtom ; swrl:builtin swrlb:lessThan ; swrl:arguments ( :u 5 ) ] ) ;
  swrl:head ( [ a swrl:DatavaluedPropertyAtom ; swrl:propertyPredicate :d ; swrl:argument1 :x ; swrl:argument2 :u ] ) ] .
:a :d 3 .
"""


def test_a_value_swapped_for_another_spelling_reasons_as_from_scratch() -> None:
    """One change removing ``3`` and adding ``"3.0"^^xsd:decimal`` leaves ``3`` asserted (the store keys
    literals by value); the incremental REASON must not derive from the spelling the graph does not hold."""
    import warnings

    from pyoxigraph import Literal

    from topostore.ontology.changes import SpellingKeptWarning

    xsd = "http://www.w3.org/2001/XMLSchema#"
    a, d = NamedNode(SV + "a"), NamedNode(SV + "d")
    onto = Ontology()
    onto.load_data(COUNT_UP)
    onto.reason()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", SpellingKeptWarning)
        onto.change([Triple(a, d, Literal("3.0", datatype=NamedNode(xsd + "decimal")))],
                    [Triple(a, d, Literal("3", datatype=NamedNode(xsd + "integer")))])
    onto.reason()
    inferred = set(onto.store.triples(graph=INFERRED))
    assert inferred == from_scratch(onto)[0]
    assert Triple(a, d, Literal("4", datatype=NamedNode(xsd + "integer"))) in inferred


COMPUTED = f"""@prefix : <{SV}> . @prefix owl: <http://www.w3.org/2002/07/owl#> .
@prefix swrl: <http://www.w3.org/2003/11/swrl#> . @prefix swrlb: <http://www.w3.org/2003/11/swrlb#> .
:d a owl:DatatypeProperty . :e a owl:DatatypeProperty . :f a owl:DatatypeProperty . :A a owl:Class .
:x a swrl:Variable . :v a swrl:Variable . :w a swrl:Variable . :u a swrl:Variable .
[ a swrl:Imp ;
  swrl:body ( [ a swrl:ClassAtom ; swrl:classPredicate :A ; swrl:argument1 :x ]
              [ a swrl:DatavaluedPropertyAtom ; swrl:propertyPredicate :d ; swrl:argument1 :x ; swrl:argument2 :v ]
              [ a swrl:BuiltinAtom ; swrl:builtin swrlb:add ; swrl:arguments ( :w :v 1 ) ] ) ;
  swrl:head ( [ a swrl:DatavaluedPropertyAtom ; swrl:propertyPredicate :e ; swrl:argument1 :x ; swrl:argument2 :w ] ) ] .
[ a swrl:Imp ;
  swrl:body ( [ a swrl:DatavaluedPropertyAtom ; swrl:propertyPredicate :d ; swrl:argument1 :x ; swrl:argument2 :v ]
              [ a swrl:BuiltinAtom ; swrl:builtin swrlb:multiply ; swrl:arguments ( :w :v 2 ) ]
              [ a swrl:BuiltinAtom ; swrl:builtin swrlb:add ; swrl:arguments ( :u :w 1 ) ]
              [ a swrl:BuiltinAtom ; swrl:builtin swrlb:lessThan ; swrl:arguments ( :w 100 ) ] ) ;
  swrl:head ( [ a swrl:DatavaluedPropertyAtom ; swrl:propertyPredicate :f ; swrl:argument1 :x ; swrl:argument2 :u ] ) ] .
:a a :A ; :d 3 . :b a :A ; :d 7 .
"""


@pytest.mark.parametrize("new", [10, 4, 7])
def test_a_replaced_value_a_builtin_turns_into_a_head_value_reasons_as_from_scratch(new: int) -> None:
    """A replaced value that a rule only passes to a built-in (``add(?w, ?v, 1)``) whose result is the head's
    value is no flip: the head itself changes (d 3 → 10 makes e 4 → 11, not e 4 kept), directly and through
    a chain of BINDs (f = 2d + 1); ``4`` and ``7`` are the old head's value and another subject's value."""
    xsd = "http://www.w3.org/2001/XMLSchema#"
    a, d, e, f = (NamedNode(SV + n) for n in "adef")
    onto = Ontology()
    onto.load_data(COMPUTED)
    onto.reason()
    onto.replace(a, d, Literal(str(new), datatype=NamedNode(xsd + "integer")))
    assert_same_as_scratch(onto)
    assert onto.data_values(e, a) == [Literal(str(new + 1), datatype=NamedNode(xsd + "integer"))]
    assert onto.data_values(f, a) == [Literal(str(2 * new + 1), datatype=NamedNode(xsd + "integer"))]


@pytest.mark.parametrize("prop", ["isIn", "hasDoor", "connectedTo", "canReach", "visitedAt"])
@pytest.mark.parametrize("subject", ["Robot1", "C1", "R1", "D1"])
def test_a_literal_given_to_an_object_property_is_reasoned_as_from_scratch(prop: str, subject: str) -> None:
    """A data value given to a property the TBox uses between individuals (aRMOR's ``REPLACE DATAPROP IND
    isIn Robot1 LONG 1 1`` does it) is a value no rule can join on as a subject: the incremental REASON
    matches nothing on it, as the rules' SPARQL does, instead of failing."""
    onto = new_map(6, 3, all_different=True)
    onto.reason()
    value = Literal("1", datatype=NamedNode("http://www.w3.org/2001/XMLSchema#long"))
    subject_node = N(subject) if subject != "D1" else next(iter(onto.store.triples(None, N("hasDoor"), None))).object
    onto.add(Triple(N(subject) if subject != "D1" else subject_node, N(prop), value))
    assert_same_as_scratch(onto)
    onto.remove(Triple(N(subject) if subject != "D1" else subject_node, N(prop), value))
    assert_same_as_scratch(onto)
