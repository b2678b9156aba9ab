"""What the unnamed value of an existential is: its property's ranges (its own, a super-property's, an equivalent
property's, an inverse's domain), the universals told of its subject (of the same class, on a super-property, of
another class of the individual), a data range, a class defined as an intersection; memberships and subsumptions
as Pellet finds them (tests/existential_value_cases.py; the comparison with Pellet itself is in
tests/test_fidelity_pellet.py), the mirror images underived, incremental REASONs as a fresh one."""

from __future__ import annotations

import warnings

import pytest
from existential_value_cases import CASES, document, namespace
from pyoxigraph import NamedNode, Triple

from topostore import Ontology, OntologyWarning
from topostore.rdf.vocab import TYPE


def loaded(text: str) -> Ontology:
    with warnings.catch_warnings():
        warnings.simplefilter("error", OntologyWarning)  # each case is decided: no notice
        o = Ontology()
        o.load_data(text)
        assert o.reason().consistent
    return o


def node(case: str, short: str) -> NamedNode:
    return NamedNode(namespace(case) + short)


@pytest.mark.parametrize("name", list(CASES))
def test_memberships_and_subsumptions_as_pellet(name: str) -> None:
    case = CASES[name]
    o = loaded(document(name))
    for ind, cls in case.members:
        assert node(name, cls) in o.types(node(name, ind)), (ind, cls)
    for ind, cls in case.not_members:
        assert node(name, cls) not in o.types(node(name, ind)), (ind, cls)
    for sub, sup in case.subclasses:
        assert node(name, sup) in o.superclasses(node(name, sub)), (sub, sup)
    for sub, sup in case.not_subclasses:
        assert node(name, sup) not in o.superclasses(node(name, sub)), (sub, sup)


@pytest.mark.parametrize("name", [n for n in CASES if n != "has_value_classified"])
def test_incremental_reason_as_from_scratch(name: str) -> None:
    """The individuals' types taken away and given back, one REASON each: the memberships go and come as a
    fresh load finds them."""
    fresh = loaded(document(name))
    individuals = {t.subject for t in fresh.store.triples(None, TYPE, None)
                   if t.subject.value.startswith(namespace(name)) and t.object.value.startswith(namespace(name))}
    told = [t for i in individuals for t in fresh.store.triples(i, TYPE, None)
            if t.object.value.startswith(namespace(name))]
    o = loaded(document(name))
    expected = {i: set(o.types(i)) for i in individuals}
    o.remove(*told)
    o.reason()
    for ind, cls in CASES[name].members:
        assert node(name, cls) not in o.types(node(name, ind)), (ind, cls)
    o.add(*told)
    o.reason()
    assert {i: set(o.types(i)) for i in individuals} == expected


def test_an_existential_into_an_intersection_of_the_filler_and_a_universals_filler() -> None:
    """``x ∈ ∃p.D``, ``x ∈ ∀p.G``: ``x ∈ ∃p.(D ⊓ G)`` (its filler's own restrictions are named, as before)."""
    text = document("filler_and_universal_meet").replace(
        ":C a owl:Class ; owl:equivalentClass [ a owl:Restriction ; owl:onProperty :p ; owl:someValuesFrom :X ]",
        ":C a owl:Class ; owl:equivalentClass [ a owl:Restriction ; owl:onProperty :p ; owl:someValuesFrom "
        "[ a owl:Class ; owl:intersectionOf ( :D :G ) ] ]")
    o = Ontology()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", OntologyWarning)
        o.load_data(text)
    o.reason()
    name = "filler_and_universal_meet"
    assert node(name, "C") in o.types(node(name, "x"))
    assert node(name, "C") in o.types(node(name, "x2"))
    assert node(name, "C") in o.superclasses(node(name, "E2"))
    assert node(name, "C") not in o.superclasses(node(name, "E"))


def test_a_classification_follows_the_class_of_a_told_value() -> None:
    """``E ⊑ ∃p.{a}`` is under ``∃p.K`` while ``a`` is a ``K``, and no longer once it is not."""
    name = "has_value_classified"
    o = loaded(document(name))
    assert node(name, "C") in o.superclasses(node(name, "E"))
    o.remove(Triple(node(name, "a"), TYPE, node(name, "K")))
    o.reason()
    assert node(name, "C") not in o.superclasses(node(name, "E"))


def test_rows_not_rules_per_universal() -> None:
    """A universal and an existential it gives are one row of a table, not a rule per existential beside it: a
    class of pizzas with many toppings' existentials and one closure adds two rows per existential at most."""
    toppings = 30
    body = ":hasTopping a owl:ObjectProperty ; rdfs:range :Topping . :Topping a owl:Class .\n" + "".join(
        f":T{i} a owl:Class ; rdfs:subClassOf :Topping .\n" for i in range(toppings))
    body += ":P a owl:Class ; rdfs:subClassOf " + " , ".join(
        f"[ a owl:Restriction ; owl:onProperty :hasTopping ; owl:someValuesFrom :T{i} ]" for i in range(toppings))
    body += " , [ a owl:Restriction ; owl:onProperty :hasTopping ; owl:allValuesFrom :G ] .\n:G a owl:Class .\n"
    body += (":C a owl:Class ; owl:equivalentClass [ a owl:Restriction ; owl:onProperty :hasTopping ; "
             "owl:someValuesFrom :G ] .\n:x a owl:NamedIndividual , :P .\n")
    o = loaded(document("own_range").split("@prefix : ")[0] + f"@prefix : <{namespace('rows')}> .\n" + body)
    assert node("rows", "C") in o.types(node("rows", "x"))
    names = [r.name for r in o.reasoning.rules().inference_rules]
    assert names.count("ext-all-value") == 1
    assert names.count("ext-some-value") == toppings + 1  # and C's own existential
    assert "ext-some-all" not in names


def test_a_filler_defined_by_a_restriction_the_value_may_hold_is_named() -> None:
    """``E ⊑ ∃p.D``, ``p rdfs:range R``, ``R ⊑ ∃q.F`` and ``C ≡ ∃p.X`` with ``X ≡ ∃q.F``: every ``E`` is a ``C``,
    which told subsumption (by names) does not find: the load names the existential instead of missing it in
    silence."""
    text = document("own_range").replace(":R a owl:Class .", ":R a owl:Class ; rdfs:subClassOf [ a owl:Restriction ; "
                                         "owl:onProperty :q ; owl:someValuesFrom :D ] . :q a owl:ObjectProperty .")
    text = text.replace(":C a owl:Class ; owl:equivalentClass [ a owl:Restriction ; owl:onProperty :p ; "
                        "owl:someValuesFrom :R ]", ":C a owl:Class ; owl:equivalentClass [ a owl:Restriction ; "
                        "owl:onProperty :p ; owl:someValuesFrom :X ] . :X owl:equivalentClass [ a owl:Restriction ; "
                        "owl:onProperty :q ; owl:someValuesFrom :D ]")
    assert ":X owl:equivalentClass" in text and "owl:onProperty :q ; owl:someValuesFrom :D ] ." in text
    o = Ontology()
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", OntologyWarning)
        o.load_data(text)
    said = " ".join(str(w.message) for w in caught)
    assert "the unnamed value of (p some D) has restrictions of its own: whether it is in X" in said
