"""SWRL DifferentFrom over entailed difference: members of disjoint classes are different as plainly
as individuals declared different, so a rule's conclusion about them fires the rules that read it
(Pellet does the same; tests/test_pellet_differential.py compares a family ontology with it)."""

from __future__ import annotations

import warnings

import pytest
from support import DATA, reasoned_turtle

from topostore import Ontology, OntologyWarning
from topostore.rdf.vocab import DECLARED_DIFFERENT, ENTAILED

PREFIXES = """@prefix : <http://e.org/f#> . @prefix owl: <http://www.w3.org/2002/07/owl#> .
@prefix rdfs: <http://www.w3.org/2000/01/rdf-schema#> . @prefix swrl: <http://www.w3.org/2003/11/swrl#> .
<http://e.org/f> a owl:Ontology .
:hasParent a owl:ObjectProperty . :hasSibling a owl:ObjectProperty . :hasBrother a owl:ObjectProperty .
:Man a owl:Class . :Woman a owl:Class . :Minor a owl:Class . :Adult a owl:Class .
:x a swrl:Variable . :y a swrl:Variable . :p a swrl:Variable .
[] a swrl:Imp ; rdfs:label "siblings" ;
   swrl:body ( [ a swrl:IndividualPropertyAtom ; swrl:propertyPredicate :hasParent ; swrl:argument1 :x ; swrl:argument2 :p ]
               [ a swrl:IndividualPropertyAtom ; swrl:propertyPredicate :hasParent ; swrl:argument1 :y ; swrl:argument2 :p ]
               [ a swrl:DifferentIndividualsAtom ; swrl:argument1 :x ; swrl:argument2 :y ] ) ;
   swrl:head ( [ a swrl:IndividualPropertyAtom ; swrl:propertyPredicate :hasSibling ; swrl:argument1 :x ; swrl:argument2 :y ] ) .
[] a swrl:Imp ; rdfs:label "brothers" ;
   swrl:body ( [ a swrl:IndividualPropertyAtom ; swrl:propertyPredicate :hasSibling ; swrl:argument1 :x ; swrl:argument2 :y ]
               [ a swrl:ClassAtom ; swrl:classPredicate :Man ; swrl:argument1 :y ] ) ;
   swrl:head ( [ a swrl:IndividualPropertyAtom ; swrl:propertyPredicate :hasBrother ; swrl:argument1 :x ; swrl:argument2 :y ] ) .
:a :hasParent :t . :b a :Man ; :hasParent :t .
"""


def family(axioms: str) -> Ontology:
    return reasoned_turtle(PREFIXES + axioms)


def siblings(o: Ontology) -> dict[str, list[str]]:
    return {p: sorted(o.object_values(p, "a")) for p in ("hasSibling", "hasBrother")}


@pytest.mark.parametrize("axioms", [
    ":Man owl:disjointWith :Woman . :a a :Woman .",
    "[] a owl:AllDisjointClasses ; owl:members ( :Woman :Minor :Man ) . :a a :Woman .",
    ":Person owl:disjointUnionOf ( :Man :Woman ) . :a a :Woman .",
    ":Man owl:equivalentClass [ a owl:Class ; owl:complementOf :Woman ] . :a a :Woman .",
    ":Man owl:disjointWith :Woman . :motherOf rdfs:domain :Woman . :a :motherOf :c .",
    ":Man owl:disjointWith :Woman . :Girl rdfs:subClassOf :Woman . :a a :Girl .",
    ":b owl:differentFrom :a .",
])
def test_difference_by_disjoint_classes_fires_the_rules_that_read_the_conclusion(axioms: str) -> None:
    o = family(axioms)
    assert siblings(o) == {"hasSibling": ["b"], "hasBrother": ["b"]}
    assert sorted(o.object_values("hasSibling", "b")) == ["a"]


def test_no_difference_no_conclusion() -> None:
    o = family(":Man owl:disjointWith :Woman .")
    assert siblings(o) == {"hasSibling": [], "hasBrother": []}


def test_difference_by_disjoint_classes_is_retracted_with_the_type() -> None:
    o = family(":Man owl:disjointWith :Woman . :a a :Woman .")
    assert siblings(o)["hasBrother"] == ["b"]
    o.remove_type("a", "Woman")
    assert o.reason().consistent
    assert siblings(o) == {"hasSibling": [], "hasBrother": []}
    o.add_type("a", "Woman")
    assert o.reason().consistent
    assert siblings(o) == {"hasSibling": ["b"], "hasBrother": ["b"]}


def test_disjoint_classes_make_plain_difference_not_entailed_only() -> None:
    o = family(":Man owl:disjointWith :Woman . :a a :Woman .")
    rules = [r for r in o.rules.all_rules if r.name == "different-disjoint"]
    assert rules and all(r.head.p == str(DECLARED_DIFFERENT) for r in rules)
    assert not any(True for _ in o.store.triples(None, None, None, ENTAILED))


def test_family_file_siblings_and_brothers() -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", OntologyWarning)
        o = Ontology.from_file(DATA / "family_difference.ttl")
    assert o.reason().consistent
    brothers = {n: sorted(o.object_values("hasBrother", n)) for n in ("ann", "dora", "fay", "ivy", "lea", "pam", "sam")}
    assert brothers == {"ann": ["bob"], "dora": ["carl"], "fay": ["gus"], "ivy": ["jon"], "lea": ["max"],
                        "pam": ["ola"], "sam": ["rob"]}
    assert o.object_values("hasSibling", "yan") == []  # nothing makes yan and zed different
    assert "HasBrother" in {o.short(t) for t in o.types("sam")}


def test_a_large_gain_beside_a_small_loss_keeps_entailed_only_conclusions_exact() -> None:
    """An incremental REASON that gains more facts than are read into memory while it loses a few (one
    changed graph read by pattern, the other as listed facts) brings ENTAILED up to date as a REASON from
    scratch does, instead of failing and reverting the changes."""
    import math

    from pyoxigraph import NamedNode, Triple
    from support import quiet_turtle
    from test_incremental import from_scratch

    from topostore.rdf.vocab import INFERRED
    from topostore.reason.changed import SMALL

    kids = math.isqrt(SMALL) + 5  # each child gains a sibling fact with every other: past SMALL new facts
    names = " ".join(f":c{i}" for i in range(kids))
    filler = "".join(f":f{i} :label{i % 7} :g{i} . " for i in range(SMALL + 600))  # keeps the change small
    onto = quiet_turtle(PREFIXES + filler + f"""
[] a owl:AllDifferent ; owl:distinctMembers ( {names} :d1 :d2 ) .
:d1 :hasParent :Q . :d2 :hasParent :Q .""")
    assert onto.reason().consistent
    parent = NamedNode("http://e.org/f#hasParent")
    onto.add(*[Triple(NamedNode(f"http://e.org/f#c{i}"), parent, NamedNode("http://e.org/f#P")) for i in range(kids)])
    onto.remove(Triple(NamedNode("http://e.org/f#d2"), parent, NamedNode("http://e.org/f#Q")))
    report = onto.reason()
    assert report.consistent and report.stats.mode == "incremental"
    inferred, _aux, entailed, _ok = from_scratch(onto)
    assert set(onto.store.triples(graph=INFERRED)) == inferred
    assert set(onto.store.triples(graph=ENTAILED)) == entailed
