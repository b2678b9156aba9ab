"""The reads behind the robot's two questions answer as the general reads: a class view's touched members
and a property's values over the visible graphs."""

from __future__ import annotations

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
