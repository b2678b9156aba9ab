"""The inspector's entity pages on an ontology other than the map: inverse, sub-property, transitive and
chained properties, labels, never-reasoned and changed-since-reasoning states (``describe_entity`` directly)."""

from __future__ import annotations

import json

import pytest

from topostore import Ontology
from topostore.http.entities import resolve_entity
from topostore.http.inspector import NotFound, describe_entity

LAB = """
@prefix : <http://example.org/lab#> .
@prefix owl: <http://www.w3.org/2002/07/owl#> .
@prefix rdfs: <http://www.w3.org/2000/01/rdf-schema#> .
<http://example.org/lab> a owl:Ontology .
:Place a owl:Class ; rdfs:label "place"@en ; rdfs:comment "anywhere a robot can be" .
:Room a owl:Class ; rdfs:subClassOf :Place .
:contains a owl:ObjectProperty , owl:TransitiveProperty ; owl:inverseOf :inside ; rdfs:subPropertyOf :related .
:inside a owl:ObjectProperty .
:related a owl:ObjectProperty .
:near a owl:ObjectProperty ; owl:propertyChainAxiom ( :inside :contains ) .
:B1 :contains :F1 .
:F1 :contains :R1 , :R2 .
:R1 a :Room .
"""


@pytest.fixture
def lab() -> Ontology:
    onto = Ontology()
    onto.load_data(LAB)
    onto.reason()
    return onto


def page(onto: Ontology, name: str) -> dict:
    return json.loads(json.dumps(describe_entity(onto, resolve_entity(onto, name))))


def test_a_transitive_property_with_its_inverse_super_property_and_chain(lab: Ontology) -> None:
    contains = page(lab, "contains")
    assert (contains["kind"], contains["characteristics"]) == ("object property", ["Transitive"])
    assert [p["name"] for p in contains["superproperties"]] == ["related"]
    assert [p["name"] for p in contains["inverse_of"]] == ["inside"]
    axioms = {a["text"] for a in contains["axioms"]}
    assert {"contains InverseOf inside", "contains SubPropertyOf related", "inside o contains SubPropertyOf near"} <= axioms
    facts = {(a["subject"]["name"], a["value"]["name"]): a for a in contains["assertions"]}
    assert facts[("F1", "R1")]["inferred"] is False
    assert facts[("B1", "R1")]["inferred"] is True and facts[("B1", "R1")]["why"]["rule"] == "prp-trp"


def test_an_individual_sees_facts_inferred_by_inverse_and_chain(lab: Ontology) -> None:
    r1 = page(lab, "R1")
    values = {(v["property"]["name"], v["value"]["name"]): v for v in r1["values"]}
    assert values[("inside", "F1")]["why"]["rule"] in ("prp-inv1", "prp-inv2")
    assert values[("near", "R2")]["inferred"] is True  # R1 inside F1, F1 contains R2
    assert values[("near", "R2")]["why"]["rule"] == "prp-spo2"
    assert {t["class"]["name"]: t["inferred"] for t in r1["types"]} == {"Room": False, "Place": True}


def test_a_class_with_its_label_comment_and_told_subclass(lab: Ontology) -> None:
    place = page(lab, "Place")
    notes = {a["property"]["name"]: a["value"] for a in place["annotations"]}
    assert notes["rdfs:label"] == {"value": "place", "datatype": "rdf:langString", "language": "en"}
    assert notes["rdfs:comment"]["value"] == "anywhere a robot can be"
    assert [(s["class"]["name"], s["inferred"]) for s in place["subclasses"]] == [("Room", False)]
    assert [m["individual"]["name"] for m in place["members"]] == ["R1"]


def test_the_state_of_reasoning_is_said(lab: Ontology) -> None:
    lab.add_fact("R2", "contains", "R3")  # asserted, not yet reasoned
    r2 = page(lab, "R2")
    assert r2["changed_since_reasoning"] is True and "changed since its last REASON" in r2["warnings"][0]
    fresh = Ontology()
    fresh.load_data(LAB)
    b1 = page(fresh, "B1")
    assert b1["reasoned"] is False and "never reasoned" in b1["warnings"][0]
    assert [v["inferred"] for v in b1["values"]] == [False]
    with pytest.raises(NotFound):
        describe_entity(lab, resolve_entity(lab, "Nowhere"))
