"""Classes with no member by clashes among unnamed values (compile/unsatisfiable.py): a member of one is an
inconsistency, by a full REASON and an incremental one alike; what the tests do not decide is named in a
notice; satisfiable look-alikes stay consistent and silent."""

from __future__ import annotations

import warnings

import pytest
from pyoxigraph import NamedNode, Triple
from support import SHARED
from unsat_cases import EMPTY, NS, PREFIXES, SATISFIABLE, card, only, some

from topostore import Ontology, OntologyWarning
from topostore.compile.unsatisfiable import UNNAMED_CLASH
from topostore.rdf.vocab import ASSERTED, TYPE
from topostore.reason import Materializer, check_consistency
from topostore.stores import memory_store


def loaded(text: str) -> tuple[Ontology, list[str]]:
    """The ontology of ``text`` (after :data:`PREFIXES`), and the OntologyWarnings its load gave."""
    o = Ontology()
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", OntologyWarning)
        o.load_data(PREFIXES + text)
    return o, [str(w.message) for w in caught if issubclass(w.category, OntologyWarning)]


def x_typed(o: Ontology) -> Triple:
    return Triple(NamedNode(NS + "x"), TYPE, NamedNode(NS + "C"))


@pytest.mark.parametrize("name", list(EMPTY))
def test_a_member_of_an_empty_class_is_one_inconsistency(name: str) -> None:
    text, check = EMPTY[name]
    o, _ = loaded(text + " :x a :C .")
    report = o.reason()
    assert not report.consistent
    assert [v.rule for v in report.violations] == [check]
    assert report.violations[0].individuals["x"] == NamedNode(NS + "x")


@pytest.mark.parametrize("name", list(EMPTY))
def test_incremental_finds_it_as_from_scratch(name: str) -> None:
    text, check = EMPTY[name]
    o, _ = loaded(text + " :y a owl:NamedIndividual .")
    assert o.reason().consistent
    o.add(x_typed(o))
    bad = o.reason(mode="incremental")
    assert bad.stats.mode == "incremental" and not bad.consistent
    assert [v.rule for v in bad.violations] == [check]
    scratch = memory_store()
    scratch.add(o.store.triples(graph=ASSERTED), ASSERTED)
    Materializer(scratch, o.rules).run()
    assert [v.rule for v in check_consistency(scratch, o.rules)] == [check]
    o.remove(x_typed(o))
    good = o.reason(mode="incremental")
    assert good.stats.mode == "incremental" and good.consistent


def test_a_subclass_of_an_empty_class_is_reported_once() -> None:
    o, _ = loaded(f":p a owl:FunctionalProperty . :C rdfs:subClassOf {card('min', 2, 'p')} . :D rdfs:subClassOf :C . "
                  ":E rdfs:subClassOf :D . :x a :E .")
    report = o.reason()
    assert [(v.rule, v.individuals["x"]) for v in report.violations] == [("cls-unsat", NamedNode(NS + "x"))]
    assert report.violations[0].axiom.startswith("(p min 2 Thing) has no member")


@pytest.mark.parametrize("name", list(SATISFIABLE))
def test_satisfiable_look_alikes_stay_consistent_and_silent(name: str) -> None:
    o, said = loaded(SATISFIABLE[name] + " :x a :C .")
    assert o.reason().consistent
    assert not [w for w in said if UNNAMED_CLASH in w]


#: name -> (TBox whose clash the tests do not decide, a word of the notice)
UNDECIDED = {
    "minimum meeting a maximum on overlapping fillers": (
        f":C rdfs:subClassOf {card('min', 2, 'p', ':A')} , {card('max', 1, 'p', ':B')} .", "max 1 B"),
    "existential meeting a universal of a union": (
        f":C rdfs:subClassOf {some('p', ':A')} , {only('p', '[ owl:unionOf ( :B :D ) ]')} .", "union"),
    "existential meeting a universal of a complement": (
        f":C rdfs:subClassOf {some('p', ':A')} , {only('p', '[ owl:complementOf :B ]')} .", "complement"),
}


@pytest.mark.parametrize("name", list(UNDECIDED))
def test_an_undecided_clash_is_named_once(name: str) -> None:
    text, word = UNDECIDED[name]
    o, said = loaded(text + " :D rdfs:subClassOf :C .")
    found = [n for n in o.notices if n.axiom_kind == UNNAMED_CLASH]
    assert len(found) == 1, [str(n) for n in found]
    assert word in str(found[0])
    assert any(UNNAMED_CLASH in w for w in said)
    o.add(x_typed(o))
    report = o.reason()
    assert report.consistent and found[0] in report.incomplete


def test_the_tutorial_has_no_empty_class_and_no_undecided_clash() -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("error", OntologyWarning)
        o = Ontology.from_file(SHARED / "topological_map.owl", SHARED / "topological_map_abox.owl")
    assert not [n for n in o.notices if n.axiom_kind == UNNAMED_CLASH]
    assert not [r for r in o.rules.checks if r.name in ("cls-unsat", "cls-svf-fp")]
    assert o.reason().consistent
