"""A compiled step's staged run as one generated function (reason/staged_code.py): the robot's moves run it,
it writes what the interpreted run writes, and a rule or TBox change never runs a function made before it."""

from __future__ import annotations

from pathlib import Path
from unittest import mock

import pytest
from pyoxigraph import NamedNode, Triple
from test_step_program import N, assert_as_from_scratch, new_ontology

from benchmarks import maps
from benchmarks.armor_robot import ArmorRobot
from benchmarks.walk import plan
from topostore.rdf.vocab import ASSERTED, AUX, INFERRED, INTERNAL, SKOLEM_PREFIX, TYPE
from topostore.reason import staged_code

NAMED_APART = (SKOLEM_PREFIX, INTERNAL + "key:")


def _graphs(robot: ArmorRobot) -> list[tuple[int, set]]:
    """Each graph's size and its triples without a skolemised blank node or a key made from one (two loads name
    those apart)."""
    store = robot.ontology.store
    out = []
    for graph in (ASSERTED, INFERRED, AUX):
        triples = list(store.triples(graph=graph))
        out.append((len(triples), {t for t in triples if not any(n in f"{t.subject} {t.object}" for n in NAMED_APART)}))
    return out


def _recording() -> tuple[list, object]:
    """A wrapper of :func:`staged_code.run` recording each run's form and program."""
    forms: list = []
    original = staged_code.run

    def run(staged_run):
        form = original(staged_run)
        forms.append((form, staged_run.program))
        return form

    return forms, run


@pytest.mark.parametrize("size", ["example", "8", "200"])
def test_the_robots_moves_run_generated_and_write_what_the_interpreted_run_writes(size: str, tmp_path: Path) -> None:
    """Two robots walk the same moves, one REASON generated, the other interpreted: every graph equal after
    every step, and no move of the walk (to a room, a corridor, the clock's jumps) falls back."""
    path, bench = maps.write(size, tmp_path)
    generated, interpreted = ArmorRobot(path), ArmorRobot(path)
    forms, run = _recording()
    with mock.patch.object(staged_code, "run", run):
        for move in plan(bench, 40):
            with mock.patch.object(staged_code, "GENERATED", True):
                generated.step(move)
            with mock.patch.object(staged_code, "GENERATED", False):
                interpreted.step(move)
            assert _graphs(generated) == _graphs(interpreted), move
    assert [f for f, _ in forms[0::2]] == ["generated"] * 40
    assert {f for f, _ in forms[1::2]} == {"interpreted: generated form switched off"}


@pytest.mark.parametrize("generated", [True, False])
def test_a_flip_joining_a_key_without_facts_sends_no_text_on_a_large_map(generated: bool, tmp_path: Path) -> None:
    """On 200 locations many visit times are equal, so the difference flip of the map's one-value restriction
    (``visitedAt exact 1``) cannot be left out by its values; its rule joins a helper key that has had facts
    but has none now (the keys with facts before a run are a superset), so its text would find nothing:
    after the first move (whose clock jump makes many locations urgent at once, a flip of more facts than
    look-ups take) the moves send no SPARQL text, in either form of the run."""
    path, bench = maps.write("200", tmp_path)
    robot = ArmorRobot(path)
    texts: list[bool] = []
    original = staged_code.run

    def run(staged_run):
        form = original(staged_run)
        texts.append(staged_run.texts)
        return form

    with mock.patch.object(staged_code, "run", run), mock.patch.object(staged_code, "GENERATED", generated):
        for move in plan(bench, 30):
            robot.step(move)
    assert len(texts) == 30 and not any(texts[1:])


def test_a_store_whose_look_ups_are_round_trips_runs_interpreted_and_says_so() -> None:
    """The generated form inlines the look-ups' decisions; where a run has none (a round-trip store's), the
    interpreted run goes, and the form says why (never silent)."""
    onto = new_ontology()
    for k in range(3):
        onto.replace(N(f"i{k}"), N("seen"), 90 + 2 * k)
    onto.reason()
    forms, run = _recording()

    def staged(staged_run):
        staged_run.direct = {}  # as a round-trip store's run has it
        return run(staged_run)

    with mock.patch.object(staged_code, "run", staged):
        onto.replace(N("clock"), N("now"), 104)
        report = onto.reason(mode="incremental")
    assert report.stats.staged == "interpreted: look-ups are round trips"
    assert_as_from_scratch(onto, report)


def test_a_rule_or_axiom_added_after_the_first_step_is_never_run_by_a_function_made_before_it() -> None:
    """Ticks generate the clock's function; a SWRL rule (Hot members are B) and then a TBox axiom (B below D,
    so B's members are D) change the rules: the next ticks run new functions, and their answers are those
    from scratch (the function made before either change writes no B and no D of a new Hot member)."""
    onto = new_ontology()
    for k in range(4):
        onto.replace(N(f"i{k}"), N("seen"), 90 + 2 * k)
    onto.reason()
    forms, run = _recording()
    with mock.patch.object(staged_code, "run", run):
        onto.replace(N("clock"), N("now"), 101)
        assert_as_from_scratch(onto, onto.reason())
        before = forms[-1][1].fused
        assert before is not None
        onto.add_rule("Hot(?x) -> B(?x)", "HotB")
        onto.reason()
        onto.replace(N("clock"), N("now"), 103)
        report = onto.reason()
        assert report.stats.program == "compiled" and report.stats.staged == "generated"
        assert_as_from_scratch(onto, report)
        after_rule = forms[-1][1].fused
        assert after_rule is not before
        onto.add(Triple(N("D"), TYPE, NamedNode("http://www.w3.org/2002/07/owl#Class")))
        onto.add(Triple(N("B"), NamedNode("http://www.w3.org/2000/01/rdf-schema#subClassOf"), N("D")))
        onto.reason()
        for now in (105, 108):
            onto.replace(N("clock"), N("now"), now)
            report = onto.reason()
            assert report.stats.staged == "generated"
            assert_as_from_scratch(onto, report)
        assert forms[-1][1].fused is not after_rule
    hot = {onto.short(i) for i in onto.instances(N("Hot"))}
    assert hot and {onto.short(i) for i in onto.instances(N("D"))} >= hot


@pytest.mark.parametrize("generated", [True, False])
def test_a_key_no_rule_writes_is_given_its_changed_facts_and_a_derived_key_is_read_back(generated: bool) -> None:
    """The lost and gained facts of a key no rule writes are the change's all run long, so its look-ups are given
    them instead of reading OVERDELETED and NEW_FACTS back (reason/staged_plan.py ``_given``); a key a rule writes
    (``:C``, the range of ``:r``, read by ``C ⊑ A``) is read back, since the run adds its derived facts to those
    graphs."""
    from test_step_program import NS

    from topostore.reason import staged
    from topostore.reason.program import signature
    from topostore.reason.scratch import NEW_FACTS, OVERDELETED
    from topostore.stores.oxigraph import OxigraphStore

    onto = new_ontology()
    read_back: list = []
    original = OxigraphStore.few_facts

    def few_facts(self, s, p, o, graphs, limit):
        if any(g in (NEW_FACTS, OVERDELETED) for g in graphs):
            read_back.append(p)
        return original(self, s, p, o, graphs, limit)

    with mock.patch.object(OxigraphStore, "few_facts", few_facts), mock.patch.object(staged_code, "GENERATED", generated):
        for batch in ([("i0", "p", "i1"), ("i1", "q", "i2")], [("i0", "p", "i1")], [("i0", "p", "i3"), ("i3", "q", "i4")]):
            for s, p, o in batch:
                fact = Triple(N(s), N(p), N(o))
                onto.remove(fact) if fact in set(onto.store.triples(graph=ASSERTED)) else onto.add(fact)
            report = onto.reason(mode="incremental")
            assert report.stats.program == "compiled"
            assert_as_from_scratch(onto, report)
    assert N("p") not in read_back and N("q") not in read_back
    reasoner = onto._reasoner
    sig = signature(({f"<{NS}p>": 1}, {f"<{NS}C>": 1}), ({f"<{NS}p>": 1}, {f"<{NS}C>": 1}), ())
    program = reasoner.step.compiler.compile(sig, reasoner.state.present, reasoner.state.asserted)
    given = {(op.kind, op.key): op.given for part in staged.segments(program) for op in part.ops
             if op.kind in ("minus", "plus") and op.direct is not None}
    assert given[("plus", ("p", f"<{NS}p>"))] == 0 and given[("minus", ("p", f"<{NS}p>"))] == 1
    assert {g for (_, key), g in given.items() if key == ("t", f"<{NS}C>")} == {None}


@pytest.mark.parametrize("generated", [True, False])
def test_an_atom_naming_an_individual_is_never_given_a_fact_naming_another(generated: bool) -> None:
    """A look-up binds a fact to its atom without testing the atom's constants (its facts are read by its own
    pattern), so a key's changed facts are handed over only to an atom naming no constant: ``isIn(?r, :kitchen) →
    InKitchen(?r)`` must not fire on ``isIn(robot, hall)`` nor keep the robot in after a move to the corridor."""
    from pyoxigraph import NamedNode

    from topostore import Ontology

    ex = "http://example.org/r#"
    onto = Ontology()
    onto.load_data(f"""@prefix : <{ex}> . @prefix owl: <http://www.w3.org/2002/07/owl#> .
@prefix swrl: <http://www.w3.org/2003/11/swrl#> . @prefix var: <http://example.org/rvar#> .
<{ex}> a owl:Ontology . :isIn a owl:ObjectProperty . :InKitchen a owl:Class . var:r a swrl:Variable .
[ a swrl:Imp ;
  swrl:body ( [ a swrl:IndividualPropertyAtom ; swrl:propertyPredicate :isIn ; swrl:argument1 var:r ;
                swrl:argument2 :kitchen ] ) ;
  swrl:head ( [ a swrl:ClassAtom ; swrl:classPredicate :InKitchen ; swrl:argument1 var:r ] ) ] .
""")
    robot, is_in = NamedNode(ex + "robot"), NamedNode(ex + "isIn")
    in_kitchen = NamedNode(ex + "InKitchen")
    with mock.patch.object(staged_code, "GENERATED", generated):
        onto.reason()
        for change in ("hall", "kitchen", "corridor"):
            for old in list(onto.store.triples(robot, is_in, None, graph=ASSERTED)):
                onto.remove(old)
            onto.add(Triple(robot, is_in, NamedNode(ex + change)))
            report = onto.reason(mode="incremental")
            assert report.stats.program == "compiled"
            assert (robot in set(onto.instances(in_kitchen))) == (change == "kitchen")
            assert_as_from_scratch(onto, report)
