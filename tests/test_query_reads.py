"""The reads behind the robot's two questions answer as the general reads: a class view's touched members
and a property's values over the visible graphs."""

from __future__ import annotations

import pytest
from pyoxigraph import NamedNode, Quad, Triple

from topostore import Ontology
from topostore.rdf.vocab import ASSERTED, AUX, INFERRED, INTERNAL, TYPE

NS = "http://e/#"
C = NamedNode(NS + "C")
MEMBER, AUX_ONLY, INFERRED_ONLY = (NamedNode(NS + n) for n in ("a", "b", "c"))
INNER = NamedNode(INTERNAL + "node:1")  # the reasoner's own node: never shown


def _ontology() -> Ontology:
    onto = Ontology()
    onto.store._ox.extend([Quad(MEMBER, TYPE, C, ASSERTED), Quad(AUX_ONLY, TYPE, C, AUX),
                           Quad(INFERRED_ONLY, TYPE, C, INFERRED), Quad(INNER, TYPE, C, ASSERTED)])
    return onto


PAIRS = [(MEMBER, C), (AUX_ONLY, C), (INFERRED_ONLY, C), (INNER, C), (NamedNode(NS + "none"), C)]


def test_a_views_touched_members_are_decided_as_the_presence_batch_decides_them() -> None:
    """One index read per pair over every graph (``known_in``) decides as the quads per visible graph: a type
    fact only in the helper graph is no membership, an internal node is never a member."""
    onto = _ontology()
    graphs = onto.visible_graphs()
    by_quads = onto.reads._members(PAIRS, onto.store.contains_quads(onto.reads._type_quads(PAIRS, graphs)),
                                   len(graphs))
    assert onto.reads._instance_flags(PAIRS) == by_quads == [True, False, True, False, False]


def test_a_store_without_one_read_per_pair_decides_by_the_presence_batch() -> None:
    onto = _ontology()
    onto.store._one_read = lambda graphs: False  # e.g. a transaction open
    assert onto.reads._instance_flags(PAIRS) == [True, False, True, False, False]


def test_a_propertys_values_leave_out_the_helper_graph() -> None:
    """``object_values`` reads the visible graphs only: a value held in the helper graph is no answer."""
    onto = _ontology()
    p = NamedNode(NS + "p")
    onto.store._ox.extend([Quad(MEMBER, p, AUX_ONLY, ASSERTED), Quad(MEMBER, p, INFERRED_ONLY, INFERRED),
                           Quad(MEMBER, p, C, AUX)])
    assert sorted(onto.object_values(p, MEMBER, names=False), key=str) == [AUX_ONLY, INFERRED_ONLY]
    assert Triple(MEMBER, p, C) not in set(onto.store.triples(MEMBER, p, None, ASSERTED))


_INCONSISTENT = """@prefix : <http://e/#> . @prefix owl: <http://www.w3.org/2002/07/owl#> .
@prefix rdfs: <http://www.w3.org/2000/01/rdf-schema#> .
:A a owl:Class ; rdfs:subClassOf :B . :B a owl:Class ; owl:disjointWith :D . :D a owl:Class .
:x a :A , :D . :y a :A .
"""


def _same_as_fresh(onto: Ontology, classes: list[str]) -> None:
    fresh = Ontology()
    fresh.load_data(onto.serialize("turtle").decode(), "turtle")
    assert fresh.reason().consistent is onto.report.consistent
    for c in classes:
        assert sorted(map(str, onto.instances(f"<{NS}{c}>"))) == sorted(map(str, fresh.instances(f"<{NS}{c}>"))), c


def _fact(s: str, c: str) -> Triple:
    return Triple(NamedNode(NS + s), TYPE, NamedNode(NS + c))


@pytest.mark.parametrize("change", ["remove", "add"])
@pytest.mark.parametrize("who", ["x", "y"])
def test_a_class_asked_while_inconsistent_answers_an_asserted_change_of_a_type_also_inferred(change, who) -> None:
    """While inconsistent only asserted facts are answered; an asserted type fact the closure also infers
    (``y a :B`` beside ``y a :A``, ``:A ⊑ :B``) changes no inferred fact, so an incremental REASON does not
    touch it, and a class view kept from the last REASON must not answer as before."""
    onto = Ontology()
    onto.load_data(_INCONSISTENT, "turtle")
    if change == "remove":
        onto.add(_fact(who, "B"))
    assert not onto.reason().consistent
    before = sorted(map(str, onto.instances(f"<{NS}B>")))  # the class asked: its view is kept
    (onto.remove if change == "remove" else onto.add)(_fact(who, "B"))
    report = onto.reason(mode="incremental")  # a small change of a big map
    assert not report.consistent and report.stats.mode == "incremental"
    assert sorted(map(str, onto.instances(f"<{NS}B>"))) != before
    _same_as_fresh(onto, ["A", "B", "D"])
