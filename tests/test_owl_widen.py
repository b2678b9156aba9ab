"""What topostore reasons beyond its first OWL reader: keys (owl:hasKey), OWL 1 definitions on a
named class read as equivalences, classes made the same (owl:sameAs) as equivalent, and an
individual declared different from itself as an inconsistency."""

from __future__ import annotations

from support import reasoned_turtle

from topostore import Ontology

PREFIXES = """@prefix : <http://e.org/a#> . @prefix owl: <http://www.w3.org/2002/07/owl#> .
@prefix rdfs: <http://www.w3.org/2000/01/rdf-schema#> . @prefix xsd: <http://www.w3.org/2001/XMLSchema#> .
<http://e.org/a> a owl:Ontology .
:p a owl:ObjectProperty . :n a owl:DatatypeProperty .
"""


def reasoned(text: str) -> Ontology:
    return reasoned_turtle(PREFIXES + text)


def types(o: Ontology, name: str) -> set[str]:
    return {o.short(t) for t in o.types(name)}


def same(o: Ontology, name: str) -> list[str]:
    return o.object_values("<http://www.w3.org/2002/07/owl#sameAs>", name)


def test_key_makes_named_individuals_the_same() -> None:
    o = reasoned(":C owl:hasKey ( :n :p ) . :a a :C ; :n 5 ; :p :z . :b a :C ; :n 5 ; :p :z . "
                 ":c a :C ; :n 5 ; :p :w . :d :n 5 ; :p :z .")
    assert same(o, "a") == ["b"]
    assert same(o, "c") == [] and same(o, "d") == []  # another key value; not in the class
    assert o.notices == []


def test_key_with_individuals_declared_different_is_inconsistent() -> None:
    o = Ontology()
    o.load_data(PREFIXES + ":C owl:hasKey ( :n ) . :a a :C ; :n 5 ; owl:differentFrom :b . :b a :C ; :n 5 .")
    assert not o.reason().consistent


def test_key_of_every_individual_needs_no_type() -> None:
    """owl:Thing hasKey: individuals typed with nothing are in owl:Thing all the same."""
    o = reasoned("owl:Thing owl:hasKey ( :n ) . :a :n 5 . :b :n 5 . :c :n 6 .")
    assert same(o, "a") == ["b"] and same(o, "c") == []
    different = Ontology()
    different.load_data(PREFIXES + "owl:Thing owl:hasKey ( :n ) . :a :n 5 ; owl:differentFrom :b . :b :n 5 .")
    assert not different.reason().consistent


def test_an_existential_into_nothing_has_no_instance() -> None:
    for filler in ("owl:someValuesFrom owl:Nothing", "owl:onClass owl:Nothing ; owl:minQualifiedCardinality 2"):
        o = Ontology()
        o.load_data(PREFIXES + f":a a [ a owl:Restriction ; owl:onProperty :p ; {filler} ] .")
        assert not o.reason().consistent, filler
    zero = reasoned(":a a [ a owl:Restriction ; owl:onProperty :p ; owl:onClass owl:Nothing ; "
                    "owl:maxQualifiedCardinality 0 ] . :B rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :p ; "
                    "owl:someValuesFrom owl:Nothing ] .")  # no member of the existential: consistent
    assert types(zero, "a") == set()


def test_exact_cardinalities_written_alike_are_one_class() -> None:
    o = reasoned(":C1 owl:equivalentClass [ a owl:Restriction ; owl:onProperty :p ; owl:cardinality 1 ] . "
                 ":C2 owl:equivalentClass [ a owl:Restriction ; owl:onProperty :p ; owl:cardinality 1 ] . "
                 ":C3 owl:equivalentClass [ a owl:Restriction ; owl:onProperty :p ; owl:cardinality 2 ] . "
                 ":Q1 owl:equivalentClass [ a owl:Restriction ; owl:onProperty :p ; owl:onClass :A ; "
                 "owl:qualifiedCardinality 1 ] . :a a :C1 . :q a :Q1 .")
    assert types(o, "a") == {"C1", "C2"}
    assert types(o, "q") == {"Q1"}  # = 1 p.A is not = 1 p (other values may be outside A)


def test_a_superclass_of_thing_holds_every_individual() -> None:
    """owl:Thing ⊑ ∀p.A is a range of p; owl:Thing ⊑ B types every individual, typed or only linked."""
    o = reasoned(":A a owl:Class . :B a owl:Class . :C a owl:Class . "
                 "owl:Thing rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :p ; owl:allValuesFrom :A ] . "
                 ":a :p :b . :c a :C .")
    assert types(o, "b") == {"A"} and types(o, "a") == set()
    o = reasoned(":B a owl:Class . :C a owl:Class . owl:Thing rdfs:subClassOf :B . :a :p :b . :c a :C . "
                 ":d :n 4 .")
    assert types(o, "a") == types(o, "b") == types(o, "d") == {"B"} and types(o, "c") == {"B", "C"}


def test_owl1_definitions_on_a_named_class_are_equivalences() -> None:
    o = reasoned(":Adult owl:intersectionOf ( :Person :Grown ) . :Pet owl:unionOf ( :Cat :Dog ) . "
                 ":Primary owl:oneOf ( :red :blue ) . "
                 ":x a :Person , :Grown . :y a :Adult . :felix a :Cat .")
    assert types(o, "x") == {"Person", "Grown", "Adult"}
    assert types(o, "y") == {"Adult", "Person", "Grown"}
    assert types(o, "felix") == {"Cat", "Pet"}
    assert types(o, "red") == {"Primary"}
    assert not any("OWL 1" in str(n) for n in o.notices)


def test_owl1_complement_definition_is_checked() -> None:
    o = Ontology()
    o.load_data(PREFIXES + ":Dead owl:complementOf :Alive . :x a :Dead , :Alive .")
    assert not o.reason().consistent


def test_classes_made_the_same_are_equivalent() -> None:
    o = reasoned(":C1 a owl:Class ; owl:sameAs :C2 . :C2 a owl:Class . :x a :C1 . :y a :C2 .")
    assert types(o, "x") == {"C1", "C2"} and types(o, "y") == {"C1", "C2"}


def test_different_from_itself_is_inconsistent() -> None:
    o = Ontology()
    o.load_data(PREFIXES + ":x owl:differentFrom :x .")
    report = o.reason()
    assert not report.consistent and "different from itself" in report.explain()


def facet_range(facets: str) -> str:
    return f"[ a rdfs:Datatype ; owl:onDatatype xsd:integer ; owl:withRestrictions ( {facets} ) ]"


def test_numeric_facets_in_a_restriction() -> None:
    o = reasoned(f":Adult owl:equivalentClass [ a owl:Restriction ; owl:onProperty :n ; owl:someValuesFrom "
                 f"{facet_range('[ xsd:minInclusive 18 ] [ xsd:maxExclusive 65 ]')} ] . "
                 ':a :n 18 . :b :n 17 . :c :n 65 . :d :n 40 . :e :n "40.5"^^xsd:decimal .')
    assert sorted(o.short(i) for i in o.instances("Adult")) == ["a", "d"]
    assert o.notices == []


def test_numeric_facets_in_a_range_are_checked() -> None:
    o = Ontology()
    o.load_data(PREFIXES + f":n rdfs:range {facet_range('[ xsd:minExclusive 0 ]')} . :a :n 0 .")
    report = o.reason()
    assert not report.consistent and "integer[> 0]" in report.explain()
    assert reasoned(f":n rdfs:range {facet_range('[ xsd:minExclusive 0 ]')} . :a :n 3 .").notices == []


def test_reflexive_property_links_every_individual_to_itself() -> None:
    o = reasoned(":knows a owl:ObjectProperty , owl:ReflexiveProperty . :Person a owl:Class . "
                 ":ann a :Person . :bob :n 3 . :cid :p :dan .")
    for name in ("ann", "bob", "cid", "dan"):
        assert name in o.object_values("knows", name)
    assert o.object_values("knows", "Person") == []  # a class is no individual
    assert o.notices == []


def test_a_restriction_named_by_an_iri_is_a_class_expression() -> None:
    """RDF-Based Semantics documents name restrictions by IRIs (``ex:z owl:onProperty ex:p``)."""
    o = reasoned(":z owl:onProperty :p ; owl:someValuesFrom :C . :w :p :x . :x a :C . "
                 ":m owl:onProperty :p ; owl:hasValue :v . :u a :m .")
    assert "z" in types(o, "w")
    assert o.object_values("p", "u") == ["v"]


def test_restrictions_subsumed_through_sub_properties_and_fillers() -> None:
    o = reasoned(":p rdfs:subPropertyOf :q . :q a owl:ObjectProperty . :C rdfs:subClassOf :D . "
                 ":A rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :p ; owl:someValuesFrom :C ] . "
                 ":B owl:equivalentClass [ a owl:Restriction ; owl:onProperty :q ; owl:someValuesFrom :D ] . "
                 ":U rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :q ; owl:allValuesFrom :C ] . "
                 ":V owl:equivalentClass [ a owl:Restriction ; owl:onProperty :p ; owl:allValuesFrom :D ] . "
                 ":a a :A . :u a :U .")
    assert "B" in types(o, "a")  # ∃p.C ⊑ ∃q.D: p ⊑ q, C ⊑ D, with no p value told
    assert "V" in types(o, "u")  # ∀q.C ⊑ ∀p.D
    assert not any("super-properties" in str(n) for n in o.notices)


def test_a_restriction_on_several_properties_is_the_restriction_on_each() -> None:
    # RDF-Based Semantics: one restriction node with two owl:onProperty is equal to the restriction on each
    o = reasoned(":q a owl:ObjectProperty . :R owl:equivalentClass [ a owl:Restriction ; owl:onProperty :p , :q ; "
                 "owl:hasValue :v ] . :a a :R . :b :p :v . :c :q :v .")
    assert o.object_values("p", "a") == ["v"] and o.object_values("q", "a") == ["v"]
    assert o.object_values("q", "b") == ["v"] and o.object_values("p", "c") == ["v"]
    assert {"R"} <= types(o, "b") and {"R"} <= types(o, "c")


def test_restrictions_subsumed_through_union_fillers_and_datatypes() -> None:
    o = reasoned(":C rdfs:subClassOf :D . :U owl:equivalentClass [ a owl:Restriction ; owl:onProperty :p ; "
                 "owl:someValuesFrom [ owl:unionOf ( :D :E ) ] ] . :A rdfs:subClassOf [ a owl:Restriction ; "
                 "owl:onProperty :p ; owl:someValuesFrom :C ] . :a a :A . "
                 ":S owl:equivalentClass [ a owl:Restriction ; owl:onProperty :n ; owl:someValuesFrom xsd:short ] . "
                 ":B rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :n ; owl:someValuesFrom xsd:byte ] . "
                 ":b a :B .")
    assert "U" in types(o, "a")  # ∃p.C ⊑ ∃p.(D ⊔ E) for C ⊑ D
    assert "S" in types(o, "b")  # ∃n.byte ⊑ ∃n.short
    assert "U" not in types(o, "b") and "S" not in types(o, "a")
