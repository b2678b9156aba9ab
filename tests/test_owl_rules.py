"""OWL compiler: the OWL 2 RL/RDF rules (W3C OWL 2 Profiles §4.3, rule names in
the comments) for the axioms present, the cardinality extensions a tableau
reasoner adds (OWL 2 Direct Semantics), sameAs merging and AllDifferent indexing.
"""

from __future__ import annotations

from pathlib import Path

from pyoxigraph import NamedNode
from support import TBOX_OWL

from topostore import Ontology
from topostore.rdf.vocab import ASSERTED, AUX, DIFFERENT_FROM, INFERRED, SAME_AS

ROOT = Path(__file__).resolve().parents[1]
NS = "http://example.org/owltest#"
PREFIXES = """\
@prefix : <http://example.org/owltest#> .
@prefix owl: <http://www.w3.org/2002/07/owl#> .
@prefix rdf: <http://www.w3.org/1999/02/22-rdf-syntax-ns#> .
@prefix rdfs: <http://www.w3.org/2000/01/rdf-schema#> .
@prefix xsd: <http://www.w3.org/2001/XMLSchema#> .
<http://example.org/owltest> a owl:Ontology .
"""


def load(text: str) -> Ontology:
    o = Ontology()
    o.load_data(PREFIXES + text, "turtle")
    return o


def reasoned(text: str) -> Ontology:
    o = load(text)
    report = o.reason()
    assert report.consistent, report.explain()
    return o


def inconsistent(text: str) -> list:
    o = load(text)
    report = o.reason()
    assert not report.consistent
    return report.violations


def types_of(o: Ontology, name: str) -> set[str]:
    return {o.short(t) for t in o.types(name)}


def objects(o: Ontology, prop: str, name: str) -> set[str]:
    return set(o.object_values(prop, name))


def same(o: Ontology, a: str, b: str) -> bool:
    return bool(o.sparql(f"ASK {{ <{NS}{a}> <{SAME_AS.value}> <{NS}{b}> }}"))


# ---------------------------------------------------------------- class axioms

def test_subclass_chain():
    # cax-sco
    o = reasoned(":A rdfs:subClassOf :B . :B rdfs:subClassOf :C . :a a :A . :b a :B .")
    assert types_of(o, "a") == {"A", "B", "C"}
    assert types_of(o, "b") == {"B", "C"}


def test_equivalent_named_classes():
    # cax-eqc1, cax-eqc2
    o = reasoned(":A owl:equivalentClass :B . :a a :A . :b a :B .")
    assert types_of(o, "a") == {"A", "B"}
    assert types_of(o, "b") == {"A", "B"}


def test_equivalent_intersection():
    # cls-int1 (both members -> intersection), cls-int2 (intersection -> each member)
    o = reasoned(":E owl:equivalentClass [ a owl:Class ; owl:intersectionOf ( :A :B ) ] . "
                 ":ab a :A , :B . :a a :A . :e a :E .")
    assert types_of(o, "ab") == {"A", "B", "E"}
    assert types_of(o, "a") == {"A"}
    assert types_of(o, "e") == {"A", "B", "E"}


def test_equivalent_union():
    # cls-uni: each member is in the union; the union is E (cax-eqc)
    o = reasoned(":E owl:equivalentClass [ a owl:Class ; owl:unionOf ( :A :B ) ] . :a a :A . :b a :B . :c a :C .")
    assert types_of(o, "a") == {"A", "E"}
    assert types_of(o, "b") == {"B", "E"}
    assert types_of(o, "c") == {"C"}


def test_equivalent_some_values_from():
    # cls-svf1 (p some B); cls-svf2 (p some Thing)
    o = reasoned(
        ":S owl:equivalentClass [ a owl:Restriction ; owl:onProperty :p ; owl:someValuesFrom :B ] . "
        ":T owl:equivalentClass [ a owl:Restriction ; owl:onProperty :q ; owl:someValuesFrom owl:Thing ] . "
        ":a :p :b . :b a :B . :c :p :d . :e :q :f ."
    )
    assert types_of(o, "a") == {"S"}
    assert types_of(o, "c") == set()
    assert types_of(o, "e") == {"T"}


def test_some_values_from_in_subclass_position():
    # cls-svf1 then cax-sco: (p some B) SubClassOf X
    o = reasoned("[ a owl:Restriction ; owl:onProperty :p ; owl:someValuesFrom :B ] rdfs:subClassOf :X . "
                 ":a :p :b . :b a :B . :c :p :d .")
    assert types_of(o, "a") == {"X"}
    assert types_of(o, "c") == set()


def test_all_values_from():
    # cls-avf
    o = reasoned(":V owl:equivalentClass [ a owl:Restriction ; owl:onProperty :p ; owl:allValuesFrom :B ] . "
                 ":a a :V ; :p :b1 , :b2 . :c :p :d .")
    assert types_of(o, "b1") == {"B"}
    assert types_of(o, "b2") == {"B"}
    assert types_of(o, "d") == set()


def test_has_value_both_ways():
    # cls-hv1 (member -> value), cls-hv2 (value -> member)
    o = reasoned(":H owl:equivalentClass [ a owl:Restriction ; owl:onProperty :p ; owl:hasValue :c ] . "
                 ":a :p :c . :h a :H . :x :p :y .")
    assert types_of(o, "a") == {"H"}
    assert objects(o, "p", "h") == {"c"}
    assert types_of(o, "x") == set()


def test_has_value_with_a_literal():
    # cls-hv1/cls-hv2 with a data value
    o = reasoned(":H owl:equivalentClass [ a owl:Restriction ; owl:onProperty :v ; owl:hasValue 5 ] . "
                 ":v a owl:DatatypeProperty . :a :v 5 . :h a :H . :b :v 6 .")
    assert types_of(o, "a") == {"H"}
    assert types_of(o, "b") == set()
    assert [x.value for x in o.data_values("v", "h")] == ["5"]


def test_disjoint_with_is_inconsistent():
    # cax-dw
    violations = inconsistent(":A owl:disjointWith :B . :x a :A , :B .")
    assert violations[0].rule == "cax-dw"
    assert violations[0].individuals["x"] == NamedNode(NS + "x")
    reasoned(":A owl:disjointWith :B . :x a :A . :y a :B .")


def test_all_disjoint_classes_is_pairwise():
    # cax-adc
    for a, b in (("A", "B"), ("A", "C"), ("B", "C")):
        inconsistent(f"[] a owl:AllDisjointClasses ; owl:members ( :A :B :C ) . :x a :{a} , :{b} .")


def test_complement_of_is_inconsistent():
    # cls-com
    violations = inconsistent(":N owl:equivalentClass [ a owl:Class ; owl:complementOf :A ] . :x a :A , :N .")
    assert any(v.rule == "cls-com" for v in violations)
    reasoned(":N owl:equivalentClass [ a owl:Class ; owl:complementOf :A ] . :x a :A . :y a :N .")


def test_nothing_has_no_instances():
    # cls-nothing2
    inconsistent(":x a owl:Nothing .")


# ---------------------------------------------------------------- property axioms

def test_domain_and_range():
    # prp-dom, prp-rng
    o = reasoned(":p rdfs:domain :D ; rdfs:range :R . :a :p :b .")
    assert types_of(o, "a") == {"D"}
    assert types_of(o, "b") == {"R"}


def test_sub_property_of():
    # prp-spo1 (transitively through the hierarchy)
    o = reasoned(":p rdfs:subPropertyOf :q . :q rdfs:subPropertyOf :r . :a :p :b .")
    assert objects(o, "q", "a") == {"b"}
    assert objects(o, "r", "a") == {"b"}


def test_equivalent_property():
    # prp-eqp1, prp-eqp2
    o = reasoned(":p owl:equivalentProperty :q . :a :p :b . :c :q :d .")
    assert objects(o, "q", "a") == {"b"}
    assert objects(o, "p", "c") == {"d"}


def test_inverse_of():
    # prp-inv1, prp-inv2
    o = reasoned(":p owl:inverseOf :q . :a :p :b . :c :q :d .")
    assert objects(o, "q", "b") == {"a"}
    assert objects(o, "p", "d") == {"c"}


def test_symmetric():
    # prp-symp
    o = reasoned(":p a owl:SymmetricProperty . :a :p :b .")
    assert objects(o, "p", "b") == {"a"}


def test_transitive():
    # prp-trp
    o = reasoned(":p a owl:TransitiveProperty . :a :p :b . :b :p :c . :c :p :d .")
    assert objects(o, "p", "a") == {"b", "c", "d"}
    assert objects(o, "p", "d") == set()


def test_functional_object_property_merges_or_is_inconsistent():
    # prp-fp: the two values are the same individual; eq-diff1 when they are declared different
    o = reasoned(":p a owl:ObjectProperty , owl:FunctionalProperty . :a :p :b , :c . :b a :B .")
    assert same(o, "b", "c") and same(o, "c", "b")
    assert types_of(o, "c") == {"B"}  # eq-rep-s
    violations = inconsistent(":p a owl:ObjectProperty , owl:FunctionalProperty . :a :p :b , :c . :b owl:differentFrom :c .")
    assert [(v.rule, v.axiom, sorted(str(x) for x in v.individuals.values())) for v in violations] == [
        ("prp-fp", "p is functional", [f"<{NS}a>", f"<{NS}b>", f"<{NS}c>"])]


def test_functional_data_property_with_two_values_is_inconsistent():
    # prp-fp for data values: two different literals cannot be the same value
    violations = inconsistent(":v a owl:DatatypeProperty , owl:FunctionalProperty . :a :v 1 , 2 .")
    assert violations[0].individuals["x"] == NamedNode(NS + "a")
    # the same value written as two integer types is one value
    reasoned(':v a owl:DatatypeProperty , owl:FunctionalProperty . :a :v 1 , "1"^^xsd:long .')


def test_inverse_functional():
    # prp-ifp
    o = reasoned(":p a owl:ObjectProperty , owl:InverseFunctionalProperty . :a :p :z . :b :p :z .")
    assert same(o, "a", "b")
    inconsistent(":p a owl:ObjectProperty , owl:InverseFunctionalProperty . :a :p :z . :b :p :z . "
                 ":a owl:differentFrom :b .")


def test_property_chain():
    # prp-spo2
    o = reasoned(":uncle owl:propertyChainAxiom ( :parent :brother ) . :a :parent :b . :b :brother :c . :x :parent :y .")
    assert objects(o, "uncle", "a") == {"c"}
    assert objects(o, "uncle", "x") == set()


def test_asymmetric_and_irreflexive():
    # prp-asyp, prp-irp
    reasoned(":p a owl:AsymmetricProperty . :a :p :b .")
    assert any(v.rule == "prp-asyp" for v in inconsistent(":p a owl:AsymmetricProperty . :a :p :b . :b :p :a ."))
    reasoned(":p a owl:IrreflexiveProperty . :a :p :b .")
    assert any(v.rule == "prp-irp" for v in inconsistent(":p a owl:IrreflexiveProperty . :a :p :a ."))


def test_property_disjoint_with():
    # prp-pdw
    reasoned(":p owl:propertyDisjointWith :q . :a :p :b . :a :q :c .")
    assert any(v.rule == "prp-pdw" for v in inconsistent(":p owl:propertyDisjointWith :q . :a :p :b . :a :q :b ."))


# ---------------------------------------------------------------- cardinality

MIN2 = (":G owl:equivalentClass [ a owl:Restriction ; owl:onProperty :p ; "
        "owl:minQualifiedCardinality \"2\"^^xsd:nonNegativeInteger ; owl:onClass :B ] . ")


def test_min_qualified_cardinality_needs_pairwise_different_fillers():
    # OWL 2 Direct Semantics: ≥2 p.B needs two fillers in B that are different (no UNA)
    o = reasoned(MIN2 + ":a :p :b1 , :b2 . :b1 a :B . :b2 a :B .")
    assert types_of(o, "a") == set()
    o = reasoned(MIN2 + ":a :p :b1 , :b2 . :b1 a :B . :b2 a :B . :b1 owl:differentFrom :b2 .")
    assert types_of(o, "a") == {"G"}
    # both fillers must be in B
    o = reasoned(MIN2 + ":a :p :b1 , :b2 . :b1 a :B . :b1 owl:differentFrom :b2 .")
    assert types_of(o, "a") == set()


def test_min_cardinality_three_with_all_different():
    # OWL 2 Direct Semantics: ≥3 p needs three pairwise different values (eq-diff2 via AllDifferent)
    o = reasoned(":G owl:equivalentClass [ a owl:Restriction ; owl:onProperty :p ; "
                 "owl:minCardinality \"3\"^^xsd:nonNegativeInteger ] . "
                 ":a :p :x , :y , :z . :b :p :x , :y . [] a owl:AllDifferent ; owl:distinctMembers ( :x :y :z ) .")
    assert types_of(o, "a") == {"G"}
    assert types_of(o, "b") == set()


def test_min_cardinality_implies_some_values_from():
    # ≥n p.C ⊑ ∃p.C for n ≥ 1 (Direct Semantics); classification and instances
    o = reasoned(MIN2 + ":S owl:equivalentClass [ a owl:Restriction ; owl:onProperty :p ; owl:someValuesFrom :B ] . "
                 ":k a :G .")
    assert {o.short(c) for c in o.superclasses("G")} == {"S"}
    assert types_of(o, "k") == {"G", "S"}


def test_exact_cardinality_with_functional_property():
    # =1 p.B when p is functional (at most one value) and one B value is known
    o = reasoned(":p a owl:ObjectProperty , owl:FunctionalProperty . "
                 ":K owl:equivalentClass [ a owl:Restriction ; owl:onProperty :p ; "
                 "owl:qualifiedCardinality \"1\"^^xsd:nonNegativeInteger ; owl:onClass :B ] . "
                 ":a :p :b . :b a :B . :c :p :d .")
    assert types_of(o, "a") == {"K"}
    assert types_of(o, "c") == set()


def test_exact_cardinality_with_a_known_maximum():
    # a is in ≤2 p.B (from M) and has two different B values, so it is in =2 p.B
    o = reasoned(":M rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :p ; "
                 "owl:maxQualifiedCardinality \"2\"^^xsd:nonNegativeInteger ; owl:onClass :B ] . "
                 ":E owl:equivalentClass [ a owl:Restriction ; owl:onProperty :p ; "
                 "owl:qualifiedCardinality \"2\"^^xsd:nonNegativeInteger ; owl:onClass :B ] . "
                 ":a a :M ; :p :b1 , :b2 . :b1 a :B . :b2 a :B . :b1 owl:differentFrom :b2 . "
                 ":c :p :b1 , :b2 .")
    assert types_of(o, "a") == {"M", "E"}
    assert types_of(o, "c") == set()  # no maximum known for c


def test_max_cardinality_violated_and_merging():
    # cls-maxqc3 (too many different values), cls-maxqc4 / cls-maxc2 (≤1: values are the same)
    text = (":M rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :p ; "
            "owl:maxCardinality \"1\"^^xsd:nonNegativeInteger ] . :a a :M ; :p :b , :c . ")
    o = reasoned(text)
    assert same(o, "b", "c")
    inconsistent(text + ":b owl:differentFrom :c .")


def test_max_zero_cardinality_is_violated_by_any_value():
    # cls-maxc1
    inconsistent(":M rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :p ; "
                 "owl:maxCardinality \"0\"^^xsd:nonNegativeInteger ] . :a a :M ; :p :b .")


# ---------------------------------------------------------------- equality

def test_same_as_merges_facts():
    # eq-sym, eq-trans, eq-rep-s, eq-rep-o
    o = reasoned(":a owl:sameAs :b . :b owl:sameAs :c . :a a :A . :c :p :d . :e :q :a .")
    assert same(o, "c", "a")
    assert types_of(o, "c") == {"A"}
    assert objects(o, "p", "a") == {"d"}
    assert objects(o, "q", "e") == {"a", "b", "c"}


def test_same_as_with_declared_difference_is_inconsistent():
    # eq-diff1 / eq-diff2
    inconsistent(":a owl:sameAs :b . :a owl:differentFrom :b .")
    inconsistent(":a owl:sameAs :b . [] a owl:AllDifferent ; owl:distinctMembers ( :a :b :c ) .")


# ---------------------------------------------------------------- classification and AllDifferent

def test_subclasses_of_location():
    # README: CORRIDOR ⊑ ROOM ⊑ LOCATION; URGENT ⊑ LOCATION (told)
    o = Ontology.from_file(TBOX_OWL)
    assert {o.short(c) for c in o.subclasses("LOCATION")} == {"ROOM", "CORRIDOR", "URGENT"}
    assert {o.short(c) for c in o.subclasses("ROOM")} == {"CORRIDOR"}
    assert o.subclasses("DOOR") == set()


def test_all_different_is_not_expanded_to_pairs():
    # OWL 2 RL eq-diff2 implemented by group membership, never by n² owl:differentFrom pairs
    n = 150
    members = [f"m{i}" for i in range(n)]
    o = Ontology(prefix=NS)
    for m in members:
        o.add_type(m, "Member")
    o.add_all_different(members)
    assert o.reason().consistent
    assert not any(True for _ in o.store.triples(None, DIFFERENT_FROM, None, INFERRED))
    assert not any(True for _ in o.store.triples(None, DIFFERENT_FROM, None, ASSERTED))
    # one helper triple per member in the AUX graph (its key, the member as the object), linear overall
    for m in members:
        assert len(list(o.store.triples(None, None, o.iri(m), AUX))) == 1, m
    assert o.store.count(AUX) < 4 * n
    # the group still separates its members: a merge is inconsistent
    o.add_fact("m1", "<http://www.w3.org/2002/07/owl#sameAs>", "m2")
    assert not o.reason().consistent


def test_an_inverse_of_an_inverse_is_the_property_itself():
    """``inverseOf(inverseOf(p))`` (not OWL 2 DL syntax) is read as ``p``, as Pellet reads it, not dropped; three
    levels deep, the inverse."""
    o = reasoned(""":p a owl:ObjectProperty .
:C owl:equivalentClass [ a owl:Restriction ; owl:onProperty [ owl:inverseOf [ owl:inverseOf :p ] ] ;
    owl:someValuesFrom owl:Thing ] .
:D owl:equivalentClass [ a owl:Restriction ; owl:onProperty [ owl:inverseOf [ owl:inverseOf [ owl:inverseOf :p ] ] ] ;
    owl:someValuesFrom owl:Thing ] .
:a a owl:NamedIndividual ; :p :b . :b a owl:NamedIndividual .
""")
    assert "C" in types_of(o, "a") and "D" not in types_of(o, "a")
    assert "D" in types_of(o, "b") and "C" not in types_of(o, "b")
