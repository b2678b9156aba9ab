"""Data values written as other terms: ``xsd:dateTimeStamp`` (kept by the store as an ``xsd:dateTime``) and the
types derived from ``xsd:string`` (``"a"^^xsd:token`` is the string ``"a"``), where Pellet 2.3.1 answers as
OWL 2 does (tests/fidelity_cases.py ``date_time_stamps`` and ``derived_strings`` give it the same) and where it
answers otherwise (said, docs/reasoning.md)."""

from __future__ import annotations

import warnings
from pathlib import Path

import pytest
from pyoxigraph import Literal, NamedNode, Triple
from support import typed

from topostore import Ontology, PelletDifferenceWarning
from topostore.armor import ArmorService
from topostore.rdf.terms import value_key

EX = "http://example.org/values#"
HEAD = f"""@prefix : <{EX}> . @prefix owl: <http://www.w3.org/2002/07/owl#> .
@prefix rdfs: <http://www.w3.org/2000/01/rdf-schema#> . @prefix xsd: <http://www.w3.org/2001/XMLSchema#> .
@prefix rdf: <http://www.w3.org/1999/02/22-rdf-syntax-ns#> .
"""
STAMP = '"2021-05-01T00:00:00Z"^^xsd:dateTimeStamp'
ZONED = '"2021-05-01T02:00:00+02:00"^^xsd:dateTime'
UNZONED = '"2021-05-01T00:00:00"^^xsd:dateTime'


def ex(name: str) -> NamedNode:
    return NamedNode(EX + name)


def reasoned(body: str) -> tuple[Ontology, bool, list[str]]:
    """The ontology of ``body``, whether its REASON found it consistent, and the PelletDifferenceWarnings said."""
    o = Ontology()
    o.load_data(HEAD + body, "turtle")
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        consistent = o.reason().consistent
    return o, consistent, [str(w.message) for w in caught if w.category is PelletDifferenceWarning]


def types(o: Ontology, name: str) -> set[str]:
    return {t.value[len(EX):] for t in o.types(ex(name)) if t.value.startswith(EX)}


# ------------------------------------------------------------------ xsd:dateTimeStamp

RANGE = ":t a owl:DatatypeProperty ; rdfs:range xsd:dateTimeStamp .\n"
ONLY = (":t a owl:DatatypeProperty . :C rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :t ; "
        "owl:allValuesFrom xsd:dateTimeStamp ] . :c a :C .\n")


@pytest.mark.parametrize("axiom", [RANGE, ONLY], ids=["range", "only"])
@pytest.mark.parametrize("value", [STAMP, ZONED], ids=["stamp", "zoned_date_time"])
def test_a_date_time_with_a_zone_is_a_date_time_stamp(axiom: str, value: str) -> None:
    _, consistent, said = reasoned(axiom + f":c a owl:NamedIndividual ; :t {value} .")
    assert consistent and not said


@pytest.mark.parametrize("axiom", [RANGE, ONLY], ids=["range", "only"])
def test_a_date_time_without_a_zone_is_outside_it_and_said(axiom: str) -> None:
    """OWL 2 (XSD 1.1): a dateTimeStamp has a time zone.  Pellet 2.3.1 takes every dateTime for one: said."""
    _, consistent, said = reasoned(axiom + f":c a owl:NamedIndividual ; :t {UNZONED} .")
    assert not consistent
    assert len(said) == 1 and "dateTimeStamp" in said[0] and "Pellet 2.3.1" in said[0]


def test_an_existential_of_date_time_stamps_holds_of_values_with_a_zone() -> None:
    o, consistent, _ = reasoned(
        ":t a owl:DatatypeProperty .\n:St owl:equivalentClass [ a owl:Restriction ; owl:onProperty :t ; "
        f"owl:someValuesFrom xsd:dateTimeStamp ] .\n:c :t {STAMP} . :e :t {ZONED} . :n :t {UNZONED} .")
    assert consistent
    assert [types(o, n) for n in ("c", "e", "n")] == [{"St"}, {"St"}, set()]


def test_a_date_time_stamp_has_the_value_key_of_its_stored_date_time() -> None:
    """The store keeps the stamp as an xsd:dateTime (one without a zone too): one value key, so the written
    datatype is found again."""
    for text in ("2021-05-01T00:00:00Z", "2021-05-01T00:00:00"):
        assert value_key(typed(text, "dateTimeStamp")) == value_key(typed(text, "dateTime"))
    assert value_key(typed("2021-05-01T00:00:00Z", "dateTimeStamp")) != value_key(typed("2021-05-01T00:00:00",
                                                                                     "dateTime"))


def test_a_date_time_stamp_is_answered_as_written(tmp_path: Path) -> None:
    """QUERY DATAPROP IND gives the value with the datatype it was written with, as aRMOR does."""
    path = tmp_path / "stamp.ttl"
    path.write_text(HEAD + f":t a owl:DatatypeProperty .\n:c a owl:NamedIndividual ; :t {STAMP} .")
    svc = ArmorService()
    load = svc.call({"reference_name": "r", "command": "LOAD", "primary_command_spec": "FILE",
                     "args": [str(path), EX.rstrip("#"), "false", "PELLET", "false"]})
    assert load.success, load.error_description
    res = svc.call({"reference_name": "r", "command": "QUERY", "primary_command_spec": "DATAPROP",
                    "secondary_command_spec": "IND", "args": ["t", "c"]})
    assert res.queried_objects == ['"2021-05-01T00:00:00Z"^^xsd:dateTimeStamp']


# ------------------------------------------------------------------ strings of derived types

DERIVED = ["normalizedString", "token", "language", "Name", "NCName", "NMTOKEN"]
TWO = (":d a owl:DatatypeProperty .\n:Two owl:equivalentClass [ a owl:Restriction ; owl:onProperty :d ; "
       'owl:minCardinality "2"^^xsd:nonNegativeInteger ] .\n')


@pytest.mark.parametrize("derived", DERIVED)
def test_a_derived_string_is_the_string_of_its_characters(derived: str) -> None:
    """One value: a functional property holds both, a minimum of two is not met, a hasValue meets it."""
    text = "en" if derived == "language" else "a"
    o, consistent, said = reasoned(
        TWO + ":f a owl:DatatypeProperty, owl:FunctionalProperty .\n"
        f':H owl:equivalentClass [ a owl:Restriction ; owl:onProperty :d ; owl:hasValue "{text}" ] .\n'
        f':x :d "{text}", "{text}"^^xsd:{derived} ; :f "{text}", "{text}"^^xsd:{derived} . '
        f':y :d "{text}"^^xsd:{derived} .')
    assert consistent and not said
    assert types(o, "x") == {"H"} and types(o, "y") == {"H"}


def test_derived_strings_of_other_characters_stay_two_values() -> None:
    o, consistent, said = reasoned(
        TWO + ":f a owl:DatatypeProperty, owl:FunctionalProperty .\n"
        ':x :d "a", "b"^^xsd:token . :y :f "a"^^xsd:Name, "b"^^xsd:NCName .')
    assert not consistent
    assert said == []  # Pellet tells two strings of other characters apart too


def test_a_derived_string_and_the_same_string_of_another_individual_are_one_value() -> None:
    """Individuals told the same share their values (no clash); a key matches them (merged)."""
    o, consistent, _ = reasoned(
        ':f a owl:DatatypeProperty, owl:FunctionalProperty . :m a owl:ObjectProperty .\n'
        ':x :f "x"^^xsd:Name ; owl:sameAs :y . :y :f "x"^^xsd:NCName .\n'
        ':k a owl:DatatypeProperty . :K a owl:Class ; owl:hasKey ( :k ) .\n'
        ':a a :K ; :k "a"^^xsd:token ; :m :a1 . :b a :K ; :k "a" ; :m :b1 . :c a :K ; :k "b"^^xsd:token .')
    assert consistent
    assert set(o.object_values(ex("m"), ex("a"), names=False)) == {ex("a1"), ex("b1")}
    assert set(o.object_values(ex("m"), ex("c"), names=False)) == set()


def test_a_key_of_two_properties_matches_each_by_its_string() -> None:
    o, consistent, _ = reasoned(
        ':k a owl:DatatypeProperty . :l a owl:DatatypeProperty . :m a owl:ObjectProperty .\n'
        ':K a owl:Class ; owl:hasKey ( :k :l ) .\n'
        ':a a :K ; :k "a"^^xsd:token ; :l "b" ; :m :a1 . :b a :K ; :k "a" ; :l "b"^^xsd:Name ; :m :b1 .\n'
        ':c a :K ; :k "a" ; :l "c" ; :m :c1 .')
    assert consistent
    assert set(o.object_values(ex("m"), ex("a"), names=False)) == {ex("a1"), ex("b1")}
    assert set(o.object_values(ex("m"), ex("c"), names=False)) == {ex("c1")}


def test_four_literals_of_three_strings_are_counted_three() -> None:
    """Above three values a minimum is counted by value keys (compile/counting.py), not pairwise."""
    o, consistent, _ = reasoned(
        TWO.replace(":Two", ":Four").replace('"2"', '"4"') +
        ':x :d "a", "a"^^xsd:token, "b"^^xsd:Name, "c" . :y :d "a", "a"^^xsd:token, "b", "c", "d"^^xsd:NCName .')
    assert consistent
    assert types(o, "x") == set() and types(o, "y") == {"Four"}


def test_a_derived_string_added_later_is_one_value_with_the_string() -> None:
    """The incremental REASON answers as the full one."""
    o, consistent, _ = reasoned(":f a owl:DatatypeProperty, owl:FunctionalProperty .\n:x :f \"a\" .")
    assert consistent
    o.add(Triple(ex("x"), ex("f"), typed("a", "token")))
    assert o.reason().consistent
    o.add(Triple(ex("x"), ex("f"), typed("b", "token")))
    assert not o.reason().consistent


def test_a_string_with_a_language_tag_is_another_value_than_the_plain_string() -> None:
    """OWL 2: ``"a"@en`` and ``"a"`` are two values (a minimum of two is met); Pellet 2.3.1 finds one
    (docs/reasoning.md)."""
    o, consistent, _ = reasoned(TWO + ':x :d "a"@en, "a" . :y :d "a"@en, "a"@EN .')
    assert consistent
    assert types(o, "x") == {"Two"} and types(o, "y") == set()


def test_any_uri_and_the_string_of_its_characters_are_two_values_and_pellet_agrees() -> None:
    """Inconsistent in OWL 2 and in Pellet 2.3.1: no PelletDifferenceWarning claims otherwise."""
    _, consistent, said = reasoned(':f a owl:DatatypeProperty, owl:FunctionalProperty .\n'
                                   ':c :f "a"^^xsd:anyURI, "a" .')
    assert not consistent and said == []


def test_a_plain_string_is_written_back_as_given() -> None:
    o, _, _ = reasoned(':d a owl:DatatypeProperty .\n:x :d "a", "a"^^xsd:token .')
    assert sorted(o.data_values(ex("d"), ex("x")), key=str) == sorted([Literal("a"), typed("a", "token")], key=str)


def test_a_negative_assertion_of_a_string_forbids_the_same_string_of_a_derived_type() -> None:
    _, consistent, _ = reasoned(
        ':d a owl:DatatypeProperty .\n:x :d "a"^^xsd:token .\n'
        '[] a owl:NegativePropertyAssertion ; owl:sourceIndividual :x ; owl:assertionProperty :d ; owl:targetValue "a" .')
    assert not consistent
