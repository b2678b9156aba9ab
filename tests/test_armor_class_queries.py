"""aRMOR's class queries as aRMOR over Pellet answers them (spec §3.2, §3.4): QUERY CLASS CLASS is the OWL API's
``getSubClasses(cls, false)`` (a DL-safe rule entails no subsumption, equivalent classes are the class's own node,
an unsatisfiable class is under every class, named in the reply), QUERY IND on what is no individual, the
bottom flag read as Java's ``Boolean.parseBoolean``, every named individual an instance of a class equal to
owl:Thing, and QUERY CLASS RESTRICTIONS over nested class expressions.  The same hierarchy is compared with
Pellet itself in ``test_class_hierarchy_pellet.py``."""

from __future__ import annotations

import warnings
from pathlib import Path

import pytest

from topostore import Ontology, OntologyWarning
from topostore.armor import ArmorResponse, ArmorService

NS = "http://example.org/h#"
PREFIXES = (f"@prefix : <{NS}> . @prefix owl: <http://www.w3.org/2002/07/owl#> . "
            "@prefix rdfs: <http://www.w3.org/2000/01/rdf-schema#> . "
            "@prefix xsd: <http://www.w3.org/2001/XMLSchema#> . @prefix swrl: <http://www.w3.org/2003/11/swrl#> .\n")

#: ``R(?x) -> K(?x)`` with ``b ∈ R2 ⊑ R``
RULE = """:R a owl:Class . :K a owl:Class . :R2 a owl:Class ; rdfs:subClassOf :R . :b a owl:NamedIndividual , :R2 .
:r a swrl:Imp ; swrl:body ( [ a swrl:ClassAtom ; swrl:classPredicate :R ; swrl:argument1 :v ] ) ;
   swrl:head ( [ a swrl:ClassAtom ; swrl:classPredicate :K ; swrl:argument1 :v ] ) . :v a swrl:Variable ."""
#: ``U ⊑ X ⊓ Y`` with X and Y disjoint: U is unsatisfiable; Z is unrelated
UNSATISFIABLE = """:X a owl:Class . :Y a owl:Class ; owl:disjointWith :X . :U a owl:Class ; rdfs:subClassOf :X , :Y .
:Z a owl:Class ."""
#: ``B ≡ A``, S ⊑ B
EQUIVALENT = """:A a owl:Class . :B a owl:Class ; owl:equivalentClass :A . :S a owl:Class ; rdfs:subClassOf :B .
:a a owl:NamedIndividual , :A ."""


class Service:
    """One reference loaded from a Turtle body, asked by command."""

    def __init__(self, tmp_path: Path, body: str) -> None:
        path = tmp_path / "o.ttl"
        path.write_text(PREFIXES + f"<{NS[:-1]}> a owl:Ontology .\n" + body)
        self.service = ArmorService()
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", OntologyWarning)
            assert self("LOAD", "FILE", "", str(path), NS[:-1], "false", "PELLET", "false").success

    def __call__(self, command: str, spec1: str = "", spec2: str = "", *args: str) -> ArmorResponse:
        return self.service.call({"client_name": "c", "reference_name": "ref", "command": command,
                                  "primary_command_spec": spec1, "secondary_command_spec": spec2,
                                  "args": list(args)})

    def names(self, *command: str) -> list[str]:
        reply = self(*command)
        assert reply.success and reply.exit_code == 0, reply
        return [x[len(NS) + 1:-1] if x.startswith(f"<{NS}") else x for x in reply.queried_objects]


def test_a_swrl_rule_makes_no_subclass(tmp_path: Path) -> None:
    """A DL-safe rule binds named individuals only: b is a K, R is no subclass of K (Pellet: getSubClasses(K)
    is empty), so DISJOINT CLASS CLASS K adds nothing and the map stays consistent."""
    s = Service(tmp_path, RULE)
    assert s("REASON").is_consistent
    assert s.names("QUERY", "IND", "CLASS", "K") == ["b"]
    assert s.names("QUERY", "CLASS", "CLASS", "K") == []
    assert s.names("QUERY", "CLASS", "CLASS", "R") == ["R2"]
    assert "0 subclass(es); no axiom added" in s("DISJOINT", "CLASS", "CLASS", "K").error_description
    assert s("REASON").is_consistent


def test_equivalent_classes_are_not_subclasses(tmp_path: Path) -> None:
    """The OWL API leaves the class's own node (its equivalents) out of getSubClasses; a told SubClassOf is in
    aRMOR's answer (the asserted part of its union) even between equivalent classes."""
    s = Service(tmp_path, EQUIVALENT)
    s("REASON")
    assert s.names("QUERY", "CLASS", "CLASS", "A") == ["S"]
    assert s.names("QUERY", "CLASS", "CLASS", "B") == ["S"]
    s("ADD", "CLASS", "CLASS", "B", "A")
    s("REASON")
    assert s.names("QUERY", "CLASS", "CLASS", "A") == ["B", "S"]
    assert s.names("QUERY", "CLASS", "CLASS", "B") == ["S"]
    assert s.names("QUERY", "CLASS", "IND", "a", "true") == ["A", "B"]  # equivalent types both stay


def test_an_unsatisfiable_class_is_under_every_class_and_named(tmp_path: Path) -> None:
    s = Service(tmp_path, UNSATISFIABLE)
    s("REASON")
    for cls in ("X", "Y", "Z"):
        reply = s("QUERY", "CLASS", "CLASS", cls)
        assert reply.queried_objects == [f"<{NS}U>"]
        assert "unsatisfiable class U" in reply.error_description
    assert s.names("QUERY", "CLASS", "CLASS", "U") == []
    assert s("QUERY", "CLASS", "CLASS", "U").error_description == ""


def test_the_ontology_says_which_class_is_unsatisfiable() -> None:
    o = Ontology(prefix=NS)
    o.load_data(PREFIXES + UNSATISFIABLE, "turtle")
    with pytest.warns(OntologyWarning, match="unsatisfiable class U"):
        assert o.subclasses("Z") == {o.iri("U")}
    assert o.reasoning.unsatisfiable() == [o.iri("U")]


@pytest.mark.parametrize("thing", [":T owl:equivalentClass owl:Thing .", "owl:Thing rdfs:subClassOf :T ."])
def test_every_named_individual_is_in_a_class_equal_to_thing(tmp_path: Path, thing: str) -> None:
    """Individuals named only in owl:differentFrom, owl:sameAs or owl:AllDifferent (as aRMOR's DISJOINT IND
    writes them) are individuals too: Pellet lists them all under T."""
    s = Service(tmp_path, f":T a owl:Class . {thing} :e owl:differentFrom :f . :g owl:sameAs :h . "
                          "[] a owl:AllDifferent ; owl:distinctMembers ( :j :k ) .")
    s("DISJOINT", "IND", "", "m", "n")
    s("REASON")
    assert s.names("QUERY", "IND", "CLASS", "T") == ["e", "f", "g", "h", "j", "k", "m", "n"]


def test_query_ind_answers_for_individuals_only(tmp_path: Path) -> None:
    """A class or a property named in axioms only is no individual: aRMOR (Pellet) answers success=false."""
    s = Service(tmp_path, ":A a owl:Class . :p a owl:ObjectProperty . :d a owl:DatatypeProperty ; rdfs:domain :A . "
                          ":P a :A . :z :p :P . :w :d 5 . :t a owl:Thing . "
                          "[] a owl:AllDifferent ; owl:distinctMembers ( :j :k ) . :e owl:differentFrom :f .")
    s("REASON")
    for name in ("A", "p", "d", "nobody"):
        assert s("QUERY", "IND", "", name).success is False, name
    for name, classes in (("P", ["A"]), ("z", ["owl:Thing"]), ("w", ["A"]), ("t", ["owl:Thing"]),
                          ("j", ["owl:Thing"]), ("f", ["owl:Thing"])):
        assert s.names("QUERY", "IND", "", name) == classes, name


RESTRICTIONS = """:p a owl:ObjectProperty . :q a owl:ObjectProperty . :d a owl:DatatypeProperty .
:A a owl:Class . :B a owl:Class . :D a owl:Class . :i a owl:NamedIndividual .
:C1 owl:equivalentClass [ a owl:Class ; owl:unionOf ( :A [ a owl:Restriction ; owl:onProperty :p ;
    owl:someValuesFrom :B ] ) ] .
:C2 owl:equivalentClass [ a owl:Restriction ; owl:onProperty :p ; owl:someValuesFrom [ a owl:Restriction ;
    owl:onProperty :q ; owl:someValuesFrom :D ] ] .
:C3 owl:equivalentClass [ a owl:Class ; owl:intersectionOf ( :A [ a owl:Restriction ; owl:onProperty :d ;
    owl:someValuesFrom xsd:long ] [ a owl:Restriction ; owl:onProperty :p ; owl:hasValue :i ] ) ] .
:C4 owl:equivalentClass [ a owl:Restriction ; owl:onProperty [ owl:inverseOf :p ] ;
    owl:minQualifiedCardinality "2"^^xsd:nonNegativeInteger ; owl:onClass :D ] .
:C5 owl:equivalentClass [ a owl:Class ; owl:complementOf [ a owl:Restriction ; owl:onProperty :p ;
    owl:allValuesFrom :D ] ] .
:C6 owl:equivalentClass [ a owl:Restriction ; owl:onProperty :p ; owl:allValuesFrom [ a owl:Class ;
    owl:unionOf ( :A :B ) ] ] ."""


@pytest.mark.parametrize(("cls", "answer"), [
    ("C1", "[C-DEFINITION_CLASS : C1 -> (A), C-DEFINITION_SOME_OBJECT : C1 -> p(B)]"),
    ("C2", "[C-DEFINITION_SOME_OBJECT : C2 -> p(D), C-DEFINITION_SOME_OBJECT : C2 -> q(D)]"),
    ("C3", "[C-DEFINITION_CLASS : C3 -> (A), C-DEFINITION_SOME_DATA : C3 -> d(xsd:long)]"),
    ("C4", "[C-DEFINITION_MIN_OBJECT : C4 -> p 2(D)]"),
    ("C5", "[C-DEFINITION_ALL_OBJECT : C5 -> p(D)]"),
    # the OWL API writes ObjectUnionOf(<…#A> <…#B>): aRMOR's short name is what follows the last '#'
    ("C6", "[C-DEFINITION_ALL_OBJECT : C6 -> p(B)]"),
])
def test_restrictions_nested_as_armor_writes_them(tmp_path: Path, cls: str, answer: str) -> None:
    """Every nested expression is classified (spec §3.4); an expression filler is the OWL API's text cut by
    aRMOR's short-name heuristic (§2.4), never a blank node's label, which changes on every LOAD."""
    s = Service(tmp_path, RESTRICTIONS)
    first = s("QUERY", "CLASS", "RESTRICTIONS", cls).queried_objects
    assert first == [answer]
    s("LOAD", "FILE", "", str(tmp_path / "o.ttl"), NS[:-1], "false", "PELLET", "false")
    assert s("QUERY", "CLASS", "RESTRICTIONS", cls).queried_objects == first


def test_a_data_minimum_is_named_with_literal() -> None:
    o = Ontology()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", OntologyWarning)
        o.load_data(PREFIXES + ":d3 a owl:DatatypeProperty ; owl:equivalentProperty :e3 . :e3 a owl:DatatypeProperty . "
                    ":E3 rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :d3 ; "
                    "owl:minCardinality \"1\"^^xsd:nonNegativeInteger ] . :C3 owl:equivalentClass [ a owl:Restriction ; "
                    "owl:onProperty :e3 ; owl:someValuesFrom rdfs:Literal ] . :x3 a :E3 .", "turtle")
    texts = [str(n) for n in o.notices]
    assert texts and all("min 1 Thing" not in t for t in texts)
    assert any("(d3 min 1 Literal)" in t for t in texts)


def test_a_subsumption_through_a_value_s_classes_is_found() -> None:
    """``E ⊑ ∃p.{a}``, ``a ∈ K``, ``C ≡ ∃p.K``: Pellet places E under C, and so does the hierarchy (it reads
    the classes of a hasValue's individual), with no notice; the members of E are found in C."""
    o = Ontology(prefix=NS)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", OntologyWarning)
        o.load_data(PREFIXES + ":p a owl:ObjectProperty . :K a owl:Class . :a a owl:NamedIndividual , :K . "
                    ":C owl:equivalentClass [ a owl:Restriction ; owl:onProperty :p ; owl:someValuesFrom :K ] . "
                    ":E rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :p ; owl:hasValue :a ] . :x a :E .",
                    "turtle")
    assert not o.notices
    o.reason()
    assert o.iri("C") in o.types("x")
    assert o.iri("C") in o.reasoning.superclasses(o.iri("E"))


def test_the_inspector_says_why_an_unsatisfiable_class_is_under_every_class() -> None:
    from topostore.http.schema import prototypes

    o = Ontology(prefix=NS)
    o.load_data(PREFIXES + UNSATISFIABLE, "turtle")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", OntologyWarning)
        proof = prototypes(o.rules).proof(o, o.iri("U"), o.iri("Z"))
    assert proof["origin"] == "U is unsatisfiable (no individual can be a member): under every class"
    assert proof["premises"] == []


#: ``A ⊑ p value o``, ``B ⊑ p value o``, p inverse functional: a member of A and one of B are one individual
SHARED_VALUE = """:p a owl:ObjectProperty , owl:InverseFunctionalProperty . :o a owl:NamedIndividual . :K a owl:Class .
:A a owl:Class ; rdfs:subClassOf :K , [ a owl:Restriction ; owl:onProperty :p ; owl:hasValue :o ] .
:B a owl:Class ; rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :p ; owl:hasValue :o ] . :Z a owl:Class ."""


def test_classes_whose_members_would_be_one_individual_are_classified_apart(tmp_path: Path) -> None:
    """Merged in one run, A's and B's prototypes took each other's classes: B is no subclass of K (only A is),
    and A disjoint with B makes neither unsatisfiable (each has members; only their intersection is empty):
    Pellet's getSubClasses."""
    s = Service(tmp_path, SHARED_VALUE)
    assert s.names("QUERY", "CLASS", "CLASS", "K") == ["A"]
    assert s.names("QUERY", "CLASS", "CLASS", "A") == [] and s.names("QUERY", "CLASS", "CLASS", "B") == []
    s2 = Service(tmp_path, SHARED_VALUE + "\n:A owl:disjointWith :B .")
    assert s2.names("QUERY", "CLASS", "CLASS", "Z") == []
    reply = s2("QUERY", "CLASS", "CLASS", "Z")
    assert "unsatisfiable" not in reply.error_description


def test_an_unsatisfiable_class_is_under_a_class_used_as_a_type_only(tmp_path: Path) -> None:
    """Y2 is named in a type only (no axiom): U, unsatisfiable, is under it as under every class."""
    s = Service(tmp_path, UNSATISFIABLE + "\n:z a owl:NamedIndividual , :Y2 .")
    assert s.names("QUERY", "CLASS", "CLASS", "Y2") == ["U"]


def test_restrictions_of_an_expression_nested_in_itself_are_answered(tmp_path: Path) -> None:
    """RDF can nest a restriction or a complement in itself (not OWL): the query answers, once round."""
    s = Service(tmp_path, """:p a owl:ObjectProperty . :C a owl:Class ; rdfs:subClassOf _:r .
_:r a owl:Restriction ; owl:onProperty :p ; owl:someValuesFrom _:r .
:D a owl:Class ; rdfs:subClassOf _:n . _:n a owl:Class ; owl:complementOf _:n .""")
    assert len(s.names("QUERY", "CLASS", "RESTRICTIONS", "C")) == 1
    assert s.names("QUERY", "CLASS", "RESTRICTIONS", "D") == []


def test_a_key_binds_no_prototype(tmp_path: Path) -> None:
    """A key binds named individuals only: K ⊑ p value v with K's key p does not merge K's prototype with o (a
    K, and an L, named by E's hasValue), so A ⊑ K, A disjoint with L, stays satisfiable and K is no L
    (Pellet: QUERY CLASS CLASS L and Z are empty)."""
    s = Service(tmp_path, """:p a owl:ObjectProperty . :q a owl:ObjectProperty . :v a owl:NamedIndividual .
:K a owl:Class ; owl:hasKey ( :p ) ; rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :p ; owl:hasValue :v ] .
:L a owl:Class . :A a owl:Class ; rdfs:subClassOf :K ; owl:disjointWith :L .
:E a owl:Class ; rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :q ; owl:hasValue :o ] .
:o a owl:NamedIndividual , :K , :L . :Z a owl:Class .""")
    assert s.names("QUERY", "CLASS", "CLASS", "L") == [] and s.names("QUERY", "CLASS", "CLASS", "Z") == []
    assert s.names("QUERY", "CLASS", "CLASS", "K") == ["A"]


@pytest.mark.parametrize("name", ["Typo", "p"])
def test_no_unsatisfiable_class_under_what_is_no_class(tmp_path: Path, name: str) -> None:
    """Unsatisfiable classes are under every class, not under a name nothing uses, or a property."""
    s = Service(tmp_path, UNSATISFIABLE + "\n:p a owl:ObjectProperty .")
    assert s.names("QUERY", "CLASS", "CLASS", "Z") == ["U"]
    assert s.names("QUERY", "CLASS", "CLASS", name) == []


def test_no_class_under_nothing() -> None:
    """owl:Nothing has no subclass to show (the OWL API answers none for a class equivalent to it), though an
    unsatisfiable class is under every other class."""
    from pyoxigraph import NamedNode

    o = Ontology(prefix=NS)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", OntologyWarning)
        o.load_data(PREFIXES + UNSATISFIABLE, "turtle")
        o.reason()
        assert o.subclasses("Z") == {o.iri("U")}
        assert o.subclasses(NamedNode("http://www.w3.org/2002/07/owl#Nothing")) == set()


def test_annotation_assertions_are_no_property_values(tmp_path: Path) -> None:
    """An individual's annotation assertions (a declared owl:AnnotationProperty, as Protégé writes dc:creator or
    skos:prefLabel) are not listed by QUERY IND OBJECTPROP / DATAPROP (the OWL API keeps them apart); a property
    declared both ways is listed."""
    s = Service(tmp_path, """:note a owl:AnnotationProperty . :see a owl:AnnotationProperty . :d a owl:DatatypeProperty .
:p a owl:ObjectProperty . :both a owl:AnnotationProperty , owl:DatatypeProperty .
:x a owl:NamedIndividual ; :note "n" ; :see :y ; :d 1 ; :p :y ; :both 2 . :y a owl:NamedIndividual .""")
    assert sorted(s.names("QUERY", "IND", "DATAPROP", "x")) == ["both", "d"]
    assert s.names("QUERY", "IND", "OBJECTPROP", "x") == ["p"]


#: ``S ⊑ B ⊑ A``, E ≡ A, a told ``C ⊑ C`` and an anonymous subclass of A; D and A disjoint
TOLD = """:A a owl:Class ; owl:disjointWith :D . :B a owl:Class ; rdfs:subClassOf :A . :S a owl:Class ; rdfs:subClassOf :B .
:E a owl:Class ; owl:equivalentClass :A . :C a owl:Class ; rdfs:subClassOf :C . :D a owl:Class .
[ a owl:Restriction ; owl:onProperty :p ; owl:someValuesFrom :D ] rdfs:subClassOf :A . :p a owl:ObjectProperty .
:k a owl:NamedIndividual , :C , :S ."""


def test_told_subclass_of_itself_is_listed_as_armor_does(tmp_path: Path) -> None:
    """aRMOR adds the told SubClassOf(X C) of a named X to the reasoner's answer: C itself when C ⊑ C is told."""
    s = Service(tmp_path, TOLD)
    assert s.names("QUERY", "CLASS", "CLASS", "C") == ["C"]
    assert s.names("QUERY", "CLASS", "CLASS", "A") == ["B", "S"]


def test_subclasses_while_inconsistent_are_the_told_ones(tmp_path: Path) -> None:
    """While the ontology is inconsistent aRMOR answers from the asserted axioms only, as every query: the
    told SubClassOf(X A) of a named X, not the classified hierarchy (S under B under A); it again once consistent."""
    s = Service(tmp_path, TOLD)
    assert s("ADD", "IND", "CLASS", "k", "D").success
    s("REASON")
    assert s("QUERY", "IND", "CLASS", "A").is_consistent is False
    assert s.names("QUERY", "CLASS", "CLASS", "A") == ["B"]
    assert s.names("QUERY", "CLASS", "CLASS", "C") == ["C"]
    assert s("REMOVE", "IND", "CLASS", "k", "D").success
    s("REASON")
    assert s.names("QUERY", "CLASS", "CLASS", "A") == ["B", "S"]
