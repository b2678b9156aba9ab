"""Entailed-only conclusions where the declared difference of a pair comes and goes.

A SWRL rule with a DifferentIndividuals atom concludes its head as an ordinary fact for a pair
declared different (owl:differentFrom, an AllDifferent group) and, as Pellet does, reports it as
entailed only for a pair different by values alone (two values of a functional property).  A pair
whose declaration is withdrawn must get its entailed-only conclusion (the values still tell the two
apart), and lose it again when declared once more; every step agrees with a REASON from scratch,
and none of them is a full run (ordinary facts changed, no schema).
"""

from __future__ import annotations

from pyoxigraph import BlankNode, NamedNode, Triple
from support import reasoned_turtle
from test_swrl_difference import PREFIXES, siblings

from topostore import Ontology
from topostore.rdf.vocab import ASSERTED, ENTAILED, INFERRED, OWL, RDF

F = "http://e.org/f#"
#: a functional data property: two birth years make two individuals different by entailment only
BORN = ":born a owl:DatatypeProperty , owl:FunctionalProperty . :a :born 1990 . :b :born 1992 . "
DIFFERENT_FROM = Triple(NamedNode(F + "b"), NamedNode(OWL + "differentFrom"), NamedNode(F + "a"))


def entailed(o: Ontology) -> set[tuple[str, str]]:
    """The (subject, object) pairs of hasSibling published as entailed only."""
    return {(o.short(t.subject), o.short(t.object)) for t in o.store.triples(None, None, None, ENTAILED)
            if t.predicate.value == F + "hasSibling"}


def inferred(o: Ontology) -> set[tuple[str, str]]:
    """The (subject, object) pairs of hasSibling inferred as ordinary facts (rules read them)."""
    return {(o.short(t.subject), o.short(t.object)) for t in o.store.triples(None, None, None, INFERRED)
            if t.predicate.value == F + "hasSibling"}


def graphs(o: Ontology) -> tuple[set[Triple], set[Triple]]:
    """The inferred and the entailed-only triples."""
    return set(o.store.triples(None, None, None, INFERRED)), set(o.store.triples(None, None, None, ENTAILED))


def assert_as_from_scratch(o: Ontology) -> None:
    """``o`` after maintenance holds what a REASON of its asserted facts from scratch holds."""
    scratch = Ontology()
    scratch.load_data(o.serialize("nt"), "nt")
    assert scratch.reason().consistent
    assert graphs(o) == graphs(scratch)


def step(o: Ontology, add: tuple[Triple, ...] = (), remove: tuple[Triple, ...] = ()) -> None:
    """Change the asserted facts, reason, and check the step against a REASON from scratch."""
    if remove:
        o.remove(*remove)
    if add:
        o.add(*add)
    report = o.reason()
    assert report.consistent
    assert report.stats.mode == "incremental", report.stats.reason
    assert_as_from_scratch(o)


def group(o: Ontology) -> tuple[Triple, ...]:
    """The asserted triples of the map's AllDifferent group (its node and its member list)."""
    kind = NamedNode(OWL + "AllDifferent")
    nodes = [t.subject for t in o.store.triples(None, NamedNode(RDF + "type"), kind, ASSERTED)]
    out: list[Triple] = []
    todo = list(nodes)
    while todo:
        node = todo.pop()
        for t in o.store.triples(node, None, None, ASSERTED):
            out.append(t)
            if isinstance(t.object, BlankNode) or (t.predicate.value in (OWL + "distinctMembers", RDF + "rest")
                                                    and t.object.value != RDF + "nil"):
                todo.append(t.object)
    return tuple(out)


def test_a_pair_different_by_values_only_is_published_as_entailed() -> None:
    o = reasoned_turtle(PREFIXES + BORN)
    assert entailed(o) == {("a", "b"), ("b", "a")} and not inferred(o)
    # shown to queries, read by no rule (Pellet reports it, and fires no rule with it)
    assert siblings(o) == {"hasSibling": ["b"], "hasBrother": []}
    assert_as_from_scratch(o)


def test_a_declaration_withdrawn_publishes_the_entailed_conclusion_and_back() -> None:
    o = reasoned_turtle(PREFIXES + BORN + ":b owl:differentFrom :a .")
    assert inferred(o) == {("a", "b"), ("b", "a")} and entailed(o) == set()
    step(o, remove=(DIFFERENT_FROM,))
    assert not inferred(o) and entailed(o) == {("a", "b"), ("b", "a")}
    step(o, add=(DIFFERENT_FROM,))
    assert inferred(o) == {("a", "b"), ("b", "a")} and entailed(o) == set()


def test_a_removed_all_different_group_publishes_the_entailed_conclusion() -> None:
    o = reasoned_turtle(PREFIXES + BORN + "[] a owl:AllDifferent ; owl:distinctMembers ( :a :b :t ) .")
    assert inferred(o) == {("a", "b"), ("b", "a")} and entailed(o) == set()
    members = group(o)
    assert members
    o.remove(*members)
    report = o.reason()
    assert report.consistent
    assert not inferred(o) and entailed(o) == {("a", "b"), ("b", "a")}
    assert_as_from_scratch(o)
    o.add(*members)
    assert o.reason().consistent
    assert inferred(o) == {("a", "b"), ("b", "a")} and entailed(o) == set()
    assert_as_from_scratch(o)


def test_a_value_made_equal_withdraws_the_entailed_conclusion_and_back() -> None:
    o = reasoned_turtle(PREFIXES + BORN)
    old = o.fact("b", "born", 1992)
    same = o.fact("b", "born", 1990)
    step(o, add=(same,), remove=(old,))
    assert entailed(o) == set() and not inferred(o)
    step(o, add=(old,), remove=(same,))
    assert entailed(o) == {("a", "b"), ("b", "a")}
