"""An existential into a one-of of a single individual is a hasValue (OWL 2 Direct Semantics: the value of
``∃p.{b}`` is in ``{b}``, so it is ``b``), and so for a data one-of of a single literal: ``a ∈ ∃p.{b}`` gives
``p(a, b)`` and ``p(a, b)`` gives ``a ∈ ∃p.{b}``, with no notice; a one-of of two or more keeps its notices.
The comparison with Pellet is tests/fidelity_cases.py (``existential_into_a_single_individual_one_of``)."""

from __future__ import annotations

import warnings

import pytest
from pyoxigraph import Literal, NamedNode, RdfFormat, Triple, parse
from support import same_as_fresh_load

from topostore import Ontology, OntologyWarning
from topostore.rdf.vocab import TYPE

NS = "http://example.org/singleton/"
PREFIXES = f"""@prefix : <{NS}> . @prefix owl: <http://www.w3.org/2002/07/owl#> .
@prefix rdfs: <http://www.w3.org/2000/01/rdf-schema#> . @prefix xsd: <http://www.w3.org/2001/XMLSchema#> .
:p a owl:ObjectProperty . :d a owl:DatatypeProperty . :C a owl:Class . :E a owl:Class .
:a a owl:NamedIndividual . :b a owl:NamedIndividual . :c a owl:NamedIndividual .
"""


def n(name: str) -> NamedNode:
    return NamedNode(NS + name)


def some(prop: str, members: str, data: bool = False) -> str:
    kind = "rdfs:Datatype" if data else "owl:Class"
    return (f"[ a owl:Restriction ; owl:onProperty {prop} ; "
            f"owl:someValuesFrom [ a {kind} ; owl:oneOf ( {members} ) ] ]")


def triples(text: str) -> list[Triple]:
    return [q.triple for q in parse(PREFIXES + text, RdfFormat.TURTLE)]


def reasoned(text: str) -> tuple[Ontology, list[str]]:
    """The ontology of ``text`` reasoned (consistent), and the notices it gave."""
    o = Ontology()
    with warnings.catch_warnings(record=True) as said:
        warnings.simplefilter("always", OntologyWarning)
        o.load_data(PREFIXES + text)
        assert o.reason().consistent
    return o, [str(w.message) for w in said if issubclass(w.category, OntologyWarning)]


#: ∃d.{"v"} and ∃d.{"v" "w"}
ONE_LITERAL, TWO_LITERALS = some(":d", '"v"', data=True), some(":d", '"v" "w"', data=True)

#: name -> (Turtle, the triple it entails): the value told by the existential, on several shapes
VALUES = {
    "superclass": (f":C rdfs:subClassOf {some(':p', ':b')} . :a a :C .", (n("a"), n("p"), n("b"))),
    "type": (f":a a {some(':p', ':b')} .", (n("a"), n("p"), n("b"))),
    "equivalence_sufficient": (f":E owl:equivalentClass {some(':p', ':b')} . :a :p :b .", (n("a"), TYPE, n("E"))),
    "equivalence_necessary": (f":E owl:equivalentClass {some(':p', ':b')} . :a a :E .", (n("a"), n("p"), n("b"))),
    "inverse": (f":C rdfs:subClassOf {some('[ owl:inverseOf :p ]', ':b')} . :a a :C .", (n("b"), n("p"), n("a"))),
    "in_an_intersection": (f":C rdfs:subClassOf [ a owl:Class ; owl:intersectionOf ( :E {some(':p', ':b')} ) ] ."
                           " :a a :C .", (n("a"), n("p"), n("b"))),
    "in_a_union_on_the_left": (f"[ a owl:Class ; owl:unionOf ( :C {some(':p', ':b')} ) ] rdfs:subClassOf :E ."
                               " :a :p :b .", (n("a"), TYPE, n("E"))),
    "as_a_filler": (f":E owl:equivalentClass [ a owl:Restriction ; owl:onProperty :p ; owl:someValuesFrom "
                    f"{some(':p', ':b')} ] . :c :p :a . :a :p :b .", (n("c"), TYPE, n("E"))),
    "repeated_member": (f":C rdfs:subClassOf {some(':p', ':b :b')} . :a a :C .", (n("a"), n("p"), n("b"))),
    "named_filler_defined": (":B owl:oneOf ( :b ) . :C rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :p ;"
                             " owl:someValuesFrom :B ] . :a a :C .", (n("a"), n("p"), n("b"))),
    "named_filler_equivalent": (":B a owl:Class ; owl:equivalentClass [ a owl:Class ; owl:oneOf ( :b ) ] . :C rdfs:subClassOf"
                                " [ a owl:Restriction ; owl:onProperty :p ; owl:someValuesFrom :B ] . :a a :C .",
                                (n("a"), n("p"), n("b"))),
    "qualified_minimum_of_one": (":C rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :p ; owl:minQualifiedCardinality"
                                 ' "1"^^xsd:nonNegativeInteger ; owl:onClass [ a owl:Class ; owl:oneOf ( :b ) ] ] . :a a :C .',
                                 (n("a"), n("p"), n("b"))),
    "data_superclass": (f':C rdfs:subClassOf {ONE_LITERAL} . :a a :C .',
                        (n("a"), n("d"), Literal("v"))),
    "data_sufficient": (f':E owl:equivalentClass {ONE_LITERAL} . :a :d "v" .',
                        (n("a"), TYPE, n("E"))),
}


@pytest.mark.parametrize("name", list(VALUES))
def test_an_existential_into_one_member_is_its_value(name: str) -> None:
    text, (s, p, o) = VALUES[name]
    onto, said = reasoned(text)
    assert Triple(s, p, o) in set(onto.store.triples())
    assert not [m for m in said if "{" in m]  # no notice of a one-of (written {b, c})


@pytest.mark.parametrize("text, noticed", [(f":C rdfs:subClassOf {some(':p', ':b :c')} . :a a :C .", True),
                                           (f':C rdfs:subClassOf {TWO_LITERALS} . :a a :C .', False)])
def test_two_members_keep_their_notice(text: str, noticed: bool) -> None:
    """An existential into a one-of of two individuals is named (which one is not derived); into a data one-of of two
    literals it is reasoned (compile/data_ranges.py), and no value is told either."""
    onto, said = reasoned(text)
    assert bool(said) == noticed  # the one-of's notice
    assert not any(t.subject == n("a") and t.predicate in (n("p"), n("d")) for t in onto.store.triples())


@pytest.mark.parametrize("name", list(VALUES))
def test_the_axiom_added_at_run_time_concludes_as_a_fresh_load(name: str) -> None:
    """The individuals first, reasoned; then the axioms added by ``Ontology.add`` and a REASON: what a fresh load
    of both concludes; and removed again, what a fresh load of the individuals does."""
    text, _ = VALUES[name]
    everything = triples(text)
    base = set(triples(""))
    schema = [t for t in everything if t not in base and t.subject not in (n("a"), n("c"))]
    onto = Ontology()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", OntologyWarning)
        onto.add(*[t for t in everything if t not in set(schema)])
        onto.reason()
        onto.add(*schema)
        same_as_fresh_load(onto, onto.reason())
        onto.remove(*schema)
        same_as_fresh_load(onto, onto.reason())
