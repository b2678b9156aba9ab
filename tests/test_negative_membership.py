"""Negative membership (compile/negation.py): "x is not in C" derived where it follows without case analysis,
and membership of complements from it; one case per rule, one that must stay underived, the warning's
text, the tutorial-style TBox against Pellet and a property over random pizzas."""

from __future__ import annotations

import warnings
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from support import needs_pellet

from topostore import Ontology, OntologyWarning
from topostore.compile import profile as kinds
from topostore.compile.negation import NOT_TYPE
from topostore.rdf.vocab import AUX

NS = "http://example.org/neg#"
PREFIXES = f"""\
@prefix : <{NS}> .
@prefix owl: <http://www.w3.org/2002/07/owl#> .
@prefix rdf: <http://www.w3.org/1999/02/22-rdf-syntax-ns#> .
@prefix rdfs: <http://www.w3.org/2000/01/rdf-schema#> .
<http://example.org/neg> a owl:Ontology .
"""
#: N ≡ ¬C: whether x ∉ C is derived shows as x ∈ N
NOT_C = ":N owl:equivalentClass [ a owl:Class ; owl:complementOf :C ] .\n"


def reasoned(text: str) -> Ontology:
    o = Ontology()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", OntologyWarning)
        o.load_data(PREFIXES + text, "turtle")
    report = o.reason()
    assert report.consistent, report.explain()
    return o


def types_of(o: Ontology, name: str) -> set[str]:
    return {o.short(t) for t in o.types(name)}


def not_in(o: Ontology, name: str, cls: str) -> bool:
    return any(True for _ in o.store.triples(o.iri(name), NOT_TYPE, o.iri(cls), AUX))


# ---------------------------------------------------------------- 1. disjointness
@pytest.mark.parametrize("axiom", [
    ":D owl:disjointWith :C .",
    "[ a owl:AllDisjointClasses ; owl:members ( :B :C :D ) ] .",
    ":U owl:disjointUnionOf ( :C :D ) .",
    ":D owl:equivalentClass [ a owl:Class ; owl:complementOf :C ] .",
])
def test_a_member_of_a_class_disjoint_with_c_is_not_in_c(axiom: str) -> None:
    o = reasoned(NOT_C + axiom + " :x a :D . :y a :C .")
    assert "N" in types_of(o, "x") and not_in(o, "x", "C")
    assert "N" not in types_of(o, "y") and not not_in(o, "y", "C")


def test_disjointness_reaches_members_of_subclasses() -> None:
    o = reasoned(NOT_C + ":D owl:disjointWith :C . :E rdfs:subClassOf :D . :x a :E .")
    assert "N" in types_of(o, "x")


# ---------------------------------------------------------------- 2. unions and intersections
def test_outside_every_member_of_a_union_is_outside_the_union() -> None:
    o = reasoned(":C owl:equivalentClass [ a owl:Class ; owl:unionOf ( :A :B ) ] . " + NOT_C
                 + ":Z owl:disjointWith :A , :B . :Y owl:disjointWith :A . :x a :Z . :y a :Y .")
    assert "N" in types_of(o, "x")
    assert "N" not in types_of(o, "y")  # outside A only: it may be in B


def test_outside_one_conjunct_is_outside_the_intersection() -> None:
    o = reasoned(":C owl:equivalentClass [ a owl:Class ; owl:intersectionOf ( :A :B ) ] . " + NOT_C
                 + ":Z owl:disjointWith :B . :x a :Z , :A .")
    assert "N" in types_of(o, "x")


# ---------------------------------------------------------------- 3. universals, subclasses, equivalences
def test_a_value_outside_the_filler_puts_the_subject_outside_the_universal() -> None:
    o = reasoned(":C owl:equivalentClass [ a owl:Restriction ; owl:onProperty :p ; owl:allValuesFrom :U ] . "
                 + NOT_C + ":M owl:disjointWith :U . :x :p :m . :m a :M . :y :p :u . :u a :U .")
    assert "N" in types_of(o, "x")
    assert "N" not in types_of(o, "y")


def test_a_value_by_an_inverse_property_counts() -> None:
    o = reasoned(":C owl:equivalentClass [ a owl:Restriction ; owl:onProperty [ owl:inverseOf :q ] ; "
                 "owl:allValuesFrom :U ] . " + NOT_C + ":M owl:disjointWith :U . :m :q :x . :m a :M .")
    assert "N" in types_of(o, "x")


def test_outside_a_superclass_is_outside_its_subclasses_and_equivalents() -> None:
    o = reasoned(NOT_C + ":C rdfs:subClassOf :B . :E owl:equivalentClass :C . :Z owl:disjointWith :B . :x a :Z . "
                 ":NE owl:equivalentClass [ a owl:Class ; owl:complementOf :E ] .")
    assert {"N", "NE"} <= types_of(o, "x") and not_in(o, "x", "C")


# ---------------------------------------------------------------- 4. complement membership and the clash check
def test_the_complement_gives_the_defined_class_by_its_intersection() -> None:
    o = reasoned(":NV owl:equivalentClass [ a owl:Class ; owl:intersectionOf ( :P [ owl:complementOf :C ] ) ] . "
                 ":Z owl:disjointWith :C . :x a :Z , :P . :y a :Z .")
    assert "NV" in types_of(o, "x") and "NV" not in types_of(o, "y")


def test_in_c_and_derived_outside_c_is_inconsistent() -> None:
    o = Ontology()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", OntologyWarning)
        o.load_data(PREFIXES + ":C owl:equivalentClass [ a owl:Restriction ; owl:onProperty :p ; owl:allValuesFrom "
                    ":U ] . " + NOT_C + ":M owl:disjointWith :U . :x a :C ; :p :m . :m a :M .", "turtle")
    assert not o.reason().consistent


# ---------------------------------------------------------------- 5. an existential's unnamed value
def test_an_existential_value_of_a_class_disjoint_with_the_filler() -> None:
    o = reasoned(":C owl:equivalentClass [ a owl:Restriction ; owl:onProperty :p ; owl:allValuesFrom "
                 "[ owl:unionOf ( :U1 :U2 ) ] ] . " + NOT_C
                 + ":A rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :p ; owl:someValuesFrom :M ] . "
                 ":M rdfs:subClassOf :Meat . :Meat owl:disjointWith :U1 , :U2 . "
                 ":B rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :p ; owl:someValuesFrom :K ] . "
                 ":K owl:disjointWith :U1 . :x a :A . :y a :B .")
    assert "N" in types_of(o, "x")
    assert "N" not in types_of(o, "y")  # K is disjoint with U1 only: its value may be in U2


def test_an_existential_on_a_sub_property_counts_one_on_a_super_property_does_not() -> None:
    o = reasoned(":C owl:equivalentClass [ a owl:Restriction ; owl:onProperty :p ; owl:allValuesFrom :U ] . "
                 + NOT_C + ":q rdfs:subPropertyOf :p . :p rdfs:subPropertyOf :r . :M owl:disjointWith :U . "
                 ":A rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :q ; owl:someValuesFrom :M ] . "
                 ":B rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :r ; owl:someValuesFrom :M ] . "
                 ":x a :A . :y a :B .")
    assert "N" in types_of(o, "x")
    assert "N" not in types_of(o, "y")  # an r value need not be a p value


# ---------------------------------------------------------------- what stays underived, and is said
def test_case_analysis_stays_underived_and_the_warning_says_so() -> None:
    """m is in A ⊔ B, each disjoint with U: m ∉ U only by cases, so x ∈ ¬C is not derived (Pellet derives it)."""
    text = (":C owl:equivalentClass [ a owl:Restriction ; owl:onProperty :p ; owl:allValuesFrom :U ] . " + NOT_C
            + ":A owl:disjointWith :U . :B owl:disjointWith :U . :m a [ owl:unionOf ( :A :B ) ] . :x :p :m .")
    o = reasoned(text)
    assert "N" not in types_of(o, "x") and not not_in(o, "m", "U")
    said = [n for n in o.notices if n.axiom_kind == kinds.COMPLEMENT]
    assert len(said) == 1 and "case analysis" in said[0].reason and "never derived" not in said[0].reason


def test_parts_without_rules_are_named_never_derived() -> None:
    o = reasoned(":C owl:equivalentClass [ a owl:Class ; owl:unionOf ( :A [ a owl:Restriction ; owl:onProperty :p ; "
                 "owl:hasValue :v ] ) ] . " + NOT_C + ":Z owl:disjointWith :A . :x a :Z .")
    said = [n for n in o.notices if n.axiom_kind == kinds.COMPLEMENT]
    assert len(said) == 1 and said[0].reason.endswith("not being in (p value v) is never derived")
    assert "N" not in types_of(o, "x")  # outside A, but maybe p v


def test_an_ontology_without_complements_gets_no_rule_of_non_membership() -> None:
    o = reasoned(":D owl:disjointWith :C . :x a :D . :C rdfs:subClassOf [ owl:unionOf ( :A :B ) ] .")
    assert not any(r.name.startswith("neg-") for r in o.rules.rules)
    assert not not_in(o, "x", "C")


# ---------------------------------------------------------------- a property: random pizzas
CATEGORIES = ["Cheese", "Veg", "Meat", "Fish"]
VEGETARIAN = {"Cheese", "Veg"}
PIZZAS = (":VegPizza owl:equivalentClass [ a owl:Class ; owl:intersectionOf ( :Pizza [ a owl:Restriction ; owl:onProperty "
          ":hasTopping ; owl:allValuesFrom [ owl:unionOf ( :Cheese :Veg ) ] ] ) ] .\n"
          ":NonVegPizza owl:equivalentClass [ a owl:Class ; owl:intersectionOf ( :Pizza [ owl:complementOf :VegPizza ] ) ] .\n"
          "[ a owl:AllDisjointClasses ; owl:members ( :Cheese :Veg :Meat :Fish ) ] .\n"
          ":Salami rdfs:subClassOf :Meat .\n")


@settings(max_examples=15, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.lists(st.lists(st.sampled_from(CATEGORIES + ["Salami", None]), max_size=3), min_size=1, max_size=4))
def test_a_pizza_is_non_vegetarian_exactly_when_a_topping_is_of_a_non_vegetarian_kind(pizzas: list) -> None:
    """A topping of unknown kind (None) proves nothing either way: open world."""
    lines = []
    for i, toppings in enumerate(pizzas):
        lines.append(f":pizza{i} a :Pizza .")
        for j, kind in enumerate(toppings):
            lines.append(f":pizza{i} :hasTopping :t{i}_{j} ." + (f" :t{i}_{j} a :{kind} ." if kind else ""))
    o = reasoned(PIZZAS + "\n".join(lines))
    for i, toppings in enumerate(pizzas):
        expected = any(k is not None and k not in VEGETARIAN for k in toppings)
        assert ("NonVegPizza" in types_of(o, f"pizza{i}")) == expected, toppings


# ---------------------------------------------------------------- the tutorial-style TBox against Pellet
@needs_pellet
def test_the_tutorial_tbox_types_every_individual_as_pellet(tmp_path: Path) -> None:
    from benchmarks import full

    pellet = full.run("pellet", "tbox:100", tmp_path / "p")
    assert "error" not in pellet, pellet.get("error")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", OntologyWarning)
        mine = full.run("topostore", "tbox:100", tmp_path / "t")
    for name in ("pizzaA", "pizzaC"):
        assert "NonVegetarianPizza" in pellet["types"][name]
    assert mine["types"] == pellet["types"]


# ---------------------------------------------------------------- maintenance: REASON after changes
@pytest.mark.parametrize("mode", ["incremental", "full"])
def test_the_complement_follows_changes_of_toppings_and_types(mode: str) -> None:
    """A topping removed takes the non-vegetarian conclusion (and its helper facts) away; a type changed
    brings it back; each REASON equals a full one on the same facts."""
    o = reasoned(PIZZAS + ":p a :Pizza ; :hasTopping :s , :c . :s a :Salami . :c a :Cheese .")
    assert "NonVegPizza" in types_of(o, "p")
    o.remove_fact("p", "hasTopping", "s")
    assert o.reason(mode=mode).consistent
    assert "NonVegPizza" not in types_of(o, "p") and not not_in(o, "p", "VegPizza")
    o.remove_type("c", "Cheese")
    o.add_type("c", "Fish")
    assert o.reason(mode=mode).consistent
    assert "NonVegPizza" in types_of(o, "p")
    fresh = Ontology()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", OntologyWarning)
        fresh.load_data(PREFIXES + PIZZAS + ":p a :Pizza ; :hasTopping :c . :c a :Fish . :s a :Salami .", "turtle")
    fresh.reason()
    for name in ("p", "c", "s"):
        assert types_of(o, name) == types_of(fresh, name)
