"""reason/plan.py (join plans for evaluations from a small graph) and reason/classify.py (named superclasses),
checked by running the planned WHERE groups on a store and by classifying the tutorial's TBox."""

from __future__ import annotations

import pytest
from pyoxigraph import NamedNode, Triple
from support import TBOX_OWL as TBOX

from topostore import Ontology
from topostore.compile import Atom, Rule, compile_ontology
from topostore.rdf.vocab import ASSERTED, DELTA, INFERRED
from topostore.reason.classify import classify
from topostore.reason.plan import LATERAL_MAX, is_small, key_counts, nested, plan_where
from topostore.stores import memory_store
from topostore.stores.base import Store

NS = "http://e.org/t#"
TYPE = NamedNode("http://www.w3.org/1999/02/22-rdf-syntax-ns#type")


def iri(local: str) -> NamedNode:
    return NamedNode(NS + local)


#: canReach(r, l) <- isIn(r, x), connectedTo(x, l), LOCATION(l)
REACH = Rule("reach", "test", (Atom("?r", str(iri("isIn")), "?x"), Atom("?x", str(iri("connectedTo")), "?l"),
                               Atom("?l", str(TYPE), str(iri("LOCATION")))),
             Atom("?r", str(iri("canReach")), "?l"))


@pytest.fixture
def store() -> Store:
    """Two robots on a small map; only Robot2's position is in the delta graph."""
    s = memory_store()
    facts = [Triple(iri("Robot1"), iri("isIn"), iri("C1")), Triple(iri("Robot2"), iri("isIn"), iri("C2"))]
    for a, b in (("C1", "R1"), ("C1", "R2"), ("C2", "R3"), ("C2", "R4")):
        facts.append(Triple(iri(a), iri("connectedTo"), iri(b)))
    facts += [Triple(iri(x), TYPE, iri("LOCATION")) for x in ("C1", "C2", "R1", "R2", "R3")]  # R4 is not
    s.add(facts, ASSERTED)
    s.add([Triple(iri("Robot2"), iri("isIn"), iri("C2"))], DELTA)
    s.add([Triple(iri("Robot1"), iri("canReach"), iri("R2"))], INFERRED)
    return s


def solutions(store: Store, where: str, named: NamedNode = DELTA) -> set[tuple[str, str]]:
    """Answers of ``where`` over the asserted graph, with ``named`` as the one named graph (as the reasoner runs it)."""
    rows = store.query(f"SELECT ?r ?l WHERE {{ {where} }}", [ASSERTED], named=[named])
    return {(r["r"].value[len(NS):], r["l"].value[len(NS):]) for r in rows}


@pytest.mark.parametrize("lateral", [True, False])
def test_a_delta_atom_reads_only_the_delta_graph(store: Store, lateral: bool) -> None:
    where = plan_where(REACH, delta=0, delta_graph=DELTA, lateral=lateral)
    assert ("LATERAL" in where) is lateral
    assert solutions(store, where) == {("Robot2", "R3")}  # Robot1's position is not new; R4 is no LOCATION


def test_without_a_delta_the_whole_body_is_evaluated(store: Store) -> None:
    assert solutions(store, plan_where(REACH)) == {("Robot1", "R1"), ("Robot1", "R2"), ("Robot2", "R3")}


@pytest.mark.parametrize("lateral", [True, False])
def test_a_head_graph_keeps_the_conclusions_it_holds(store: Store, lateral: bool) -> None:
    """With ``head_graph``, only solutions whose conclusion is a fact of that graph (here: the inferred one)."""
    where = plan_where(REACH, head_graph=INFERRED, lateral=lateral)
    assert solutions(store, where, INFERRED) == {("Robot1", "R2")}


def test_nested_puts_each_pattern_in_its_own_lateral_level() -> None:
    assert nested(["?a <urn:p> ?b .", "?b <urn:q> ?c ."], "FILTER(?a != ?c)") == (
        "\n  LATERAL { ?a <urn:p> ?b .\n  LATERAL { ?b <urn:q> ?c .\n  FILTER(?a != ?c) } }")
    assert nested([], "") == ""


def test_key_counts_and_is_small(store: Store) -> None:
    counts = key_counts(store, ASSERTED)
    assert counts == ({f"<{NS}isIn>": 2, f"<{NS}connectedTo>": 4, f"<{TYPE.value}>": 5}, {f"<{NS}LOCATION>": 5})
    assert key_counts(store, DELTA) == ({f"<{NS}isIn>": 1}, {})
    assert is_small(counts) and is_small(counts, ("p", f"<{NS}isIn>")) and is_small(counts, ("t", f"<{NS}ROOM>"))
    big = ({f"<{NS}isIn>": LATERAL_MAX + 1}, {f"<{NS}ROOM>": LATERAL_MAX})
    assert is_small(big, ("p", f"<{NS}isIn>")) is False and is_small(big, ("*",)) is False
    assert is_small(big, ("t", f"<{NS}ROOM>")) is True


def test_classify_the_tutorial_tbox() -> None:
    """Told and entailed named superclasses: CORRIDOR (≥ 2 doors) is a ROOM (≥ 1 door) through the rules."""
    onto = Ontology.from_file(TBOX)
    supers = classify(compile_ontology(onto.store, ASSERTED))
    assert {onto.short(c): sorted(onto.short(s) for s in ss) for c, ss in supers.items()} == {
        "CORRIDOR": ["LOCATION", "ROOM"], "DOOR": [], "LOCATION": [], "ROBOT": [], "ROOM": ["LOCATION"],
        "URGENT": ["LOCATION"]}


def test_classify_follows_chains_and_equivalences() -> None:
    onto = Ontology()
    onto.load_data(f"""@prefix : <{NS}> . @prefix owl: <http://www.w3.org/2002/07/owl#> .
        @prefix rdfs: <http://www.w3.org/2000/01/rdf-schema#> .
        :A rdfs:subClassOf :B . :B rdfs:subClassOf :C . :C owl:equivalentClass :D . :E a owl:Class .""", "turtle")
    supers = classify(compile_ontology(onto.store, ASSERTED))
    assert {c.value[len(NS):]: sorted(s.value[len(NS):] for s in ss) for c, ss in supers.items()} == {
        "A": ["B", "C", "D"], "B": ["C", "D"], "C": ["D"], "D": ["C"], "E": []}
