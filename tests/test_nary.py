"""N-ary axioms as RDF lists (topostore.ontology.nary): the one builder and remover used by Ontology and the aRMOR commands."""

from __future__ import annotations

from pyoxigraph import NamedNode, Triple

from topostore import Ontology
from topostore.ontology.nary import (
    all_different,
    all_disjoint_classes,
    axiom_of_list_node,
    individual_triples,
    rdf_list,
)
from topostore.rdf.vocab import ASSERTED, FIRST, NIL, REST, TYPE, owl

NS = "http://example.org/m#"
A, B, C = (NamedNode(NS + n) for n in "ABC")


def list_items(triples: list[Triple], head) -> list:
    """Walk an RDF list written as triples."""
    first = {t.subject: t.object for t in triples if t.predicate == FIRST}
    rest = {t.subject: t.object for t in triples if t.predicate == REST}
    items = []
    while head != NIL:
        items.append(first[head])
        head = rest[head]
    return items


def test_rdf_list_shape() -> None:
    assert rdf_list([]) == (NIL, [])
    head, triples = rdf_list([A, B, C])
    assert len(triples) == 6 and list_items(triples, head) == [A, B, C]


def test_group_axioms_are_linear_and_typed() -> None:
    for build, kind, link in ((all_different, "AllDifferent", "distinctMembers"),
                              (all_disjoint_classes, "AllDisjointClasses", "members")):
        triples = build([A, B, C])
        group = triples[0].subject
        assert triples[0] == Triple(group, TYPE, owl(kind))
        assert triples[1].subject == group and triples[1].predicate == owl(link)
        assert len(triples) == 2 + 2 * 3 and list_items(triples, triples[1].object) == [A, B, C]


def test_removing_a_member_takes_the_whole_axiom_and_nothing_else() -> None:
    onto = Ontology(prefix=NS)
    onto.add_all_different([A, B])
    onto.add_all_different([B, C])
    fact = Triple(A, NamedNode(NS + "p"), C)
    onto.add(fact, Triple(A, TYPE, NamedNode(NS + "Room")))
    list_of_first = next(t.subject for t in onto.store.triples(None, FIRST, A, ASSERTED))
    assert len(axiom_of_list_node(onto.store, list_of_first)) == 2 + 4  # group, its link, two cells
    doomed = individual_triples(onto.store, A)
    assert len(doomed) == 2 + 6  # A's own two facts and the whole first AllDifferent
    assert onto.remove_individual(A) == 8
    remaining = set(onto.store.triples(None, None, None, ASSERTED))
    assert fact not in remaining and len(remaining) == 6  # C stays in the AllDifferent over B, C, untouched
    assert {t.object for t in remaining if t.predicate == FIRST} == {B, C}


def test_a_list_outside_an_axiom_is_not_removed() -> None:
    onto = Ontology(prefix=NS)
    head, triples = rdf_list([A, B])  # e.g. a SWRL argument list: no AllDifferent owns it
    onto.add(*triples)
    assert axiom_of_list_node(onto.store, head) == []
    assert len(individual_triples(onto.store, A)) == 1  # only the cell's rdf:first naming A
