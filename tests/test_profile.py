"""The profile report: every axiom topostore does not reason completely is named, with the reason,
at LOAD (OntologyWarning, once per kind), in ReasonReport.incomplete, the aRMOR LOAD reply and
`topostore check`; a strict load refuses such files and changes nothing."""

from __future__ import annotations

import warnings
from pathlib import Path

import pytest
from click.testing import CliRunner
from support import SHARED, armor_load

from topostore import IncompleteOntologyError, Ontology, OntologyWarning
from topostore.armor import ArmorService
from topostore.cli.group import cli
from topostore.compile import profile as kinds
from topostore.compile.notices import NON_SIMPLE, NOT_STORED
from topostore.rdf.vocab import ASSERTED
from topostore.resources import default_ontology_files

PREFIXES = """@prefix : <http://e.org/a#> . @prefix owl: <http://www.w3.org/2002/07/owl#> .
@prefix rdfs: <http://www.w3.org/2000/01/rdf-schema#> . @prefix xsd: <http://www.w3.org/2001/XMLSchema#> .
<http://e.org/a> a owl:Ontology . :p a owl:ObjectProperty .
"""

RDF = "http://www.w3.org/1999/02/22-rdf-syntax-ns#"

#: name -> (Turtle, axiom kind expected, a word of the axiom named)
CASES = {
    "union superclass": (":A rdfs:subClassOf [ owl:unionOf (:B :C) ] . :a a :A .", kinds.UNION, "A SubClassOf"),
    "union type": (":a a [ owl:unionOf (:B :C) ] .", kinds.UNION, "typed"),
    "union range": (":p rdfs:range [ owl:unionOf (:B :C) ] .", kinds.UNION, "range"),
    "one-of superclass": (":A rdfs:subClassOf [ owl:oneOf (:x :y) ] .", kinds.UNION, "{x, y}"),
    "disjoint union": (":A owl:disjointUnionOf (:B :C) .", kinds.UNION, "DisjointUnionOf"),
    "complement on the left": ("[ owl:complementOf :A ] rdfs:subClassOf :B .", kinds.COMPLEMENT, "not A"),
    "universal on the left": (":B owl:equivalentClass [ a owl:Restriction ; owl:onProperty :p ; "
                              "owl:allValuesFrom :C ] .", kinds.UNIVERSAL, "only C"),
    "max on the left": (":p a owl:FunctionalProperty . :B owl:equivalentClass [ a owl:Restriction ; "
                        "owl:onProperty :p ; owl:maxCardinality 1 ] .", kinds.MAX_LEFT, "max 1"),
    "max on the left under a functional property": (
        ":f a owl:ObjectProperty, owl:FunctionalProperty . :p rdfs:subPropertyOf :f . "
        "[ a owl:Restriction ; owl:onProperty :p ; owl:maxCardinality 1 ] rdfs:subClassOf :B .", kinds.MAX_LEFT,
        "max 1"),
    "a class list looping back": (
        ":E owl:equivalentClass [ a owl:Class ; owl:intersectionOf _:l1 ] . _:l1 <%sfirst> :C ; <%srest> _:l2 . "
        "_:l2 <%sfirst> :D ; <%srest> _:l1 ." % ((RDF,) * 4), kinds.UNSUPPORTED, "loops back"),
    "a class list cell with two firsts": (
        ":E owl:equivalentClass [ a owl:Class ; owl:intersectionOf _:l1 ] . _:l1 <%sfirst> :C, :D ; <%srest> <%snil> ."
        % ((RDF,) * 3), kinds.UNSUPPORTED, "2 rdf:first"),
    "an AllDifferent list looping back": (
        "[] a owl:AllDifferent ; owl:distinctMembers _:l1 . _:l1 <%sfirst> :a ; <%srest> _:l2 . "
        "_:l2 <%sfirst> :b ; <%srest> _:l1 ." % ((RDF,) * 4), kinds.UNSUPPORTED, "does not end in rdf:nil"),
    "max 2": (":B rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :p ; owl:maxCardinality 2 ] .",
              kinds.MAX_CASES, "max 2"),
    "existential into a class linked to an individual": (
        ":q a owl:ObjectProperty ; rdfs:range :R . :A rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :p ; "
        "owl:someValuesFrom :F ] . :F rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :q ; owl:hasValue :i ] .",
        kinds.EXISTENTIAL, "a link to i"),
    "existential through a chain": (":q a owl:ObjectProperty . :t a owl:ObjectProperty ; rdfs:domain :D ; "
                                    "owl:propertyChainAxiom ( :q :p ) . :B rdfs:subClassOf [ a owl:Restriction ; "
                                    "owl:onProperty :p ; owl:someValuesFrom :C ] .", kinds.EXISTENTIAL,
                                    "chain of t"),
    "existential through a chain to a named value": (
        ":s a owl:ObjectProperty . :t a owl:ObjectProperty ; owl:propertyChainAxiom ( :p :s ) . :A rdfs:subClassOf "
        "[ a owl:Restriction ; owl:onProperty :p ; owl:someValuesFrom :F ] . :F rdfs:subClassOf "
        "[ a owl:Restriction ; owl:onProperty :s ; owl:hasValue :i ] .", kinds.EXISTENTIAL, "chain of t"),
    "existential starting a chain read backwards": (
        ":s a owl:ObjectProperty . :t a owl:ObjectProperty ; rdfs:range :R ; owl:propertyChainAxiom "
        "( [ owl:inverseOf :p ] :s ) . :A rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :p ; "
        "owl:someValuesFrom :F ] .", kinds.EXISTENTIAL, "chain of t"),
    "existential whose value links to itself in a chain": (
        ":s a owl:ObjectProperty . :t a owl:ObjectProperty ; owl:propertyChainAxiom ( :p :s ) . "
        "[ a owl:Restriction ; owl:onProperty :t ; owl:someValuesFrom owl:Thing ] rdfs:subClassOf :D . "
        ":A rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :p ; owl:someValuesFrom :F ] . "
        ":F rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :s ; owl:hasSelf true ] .", kinds.EXISTENTIAL,
        "chain of t"),
    "existential ending a chain whose range flows back": (
        ":s a owl:ObjectProperty . :t a owl:ObjectProperty ; rdfs:range :R ; owl:propertyChainAxiom ( :s :p ) . "
        ":R rdfs:subClassOf [ a owl:Restriction ; owl:onProperty [ owl:inverseOf :t ] ; owl:allValuesFrom :D ] . "
        ":A rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :p ; owl:someValuesFrom owl:Thing ] .",
        kinds.EXISTENTIAL, "chain of t"),
    "existential whose value links back in a chain": (
        ":t a owl:ObjectProperty ; owl:propertyChainAxiom ( :p [ owl:inverseOf :p ] ) . "
        ":A rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :p ; owl:someValuesFrom owl:Thing ] .",
        kinds.EXISTENTIAL, "chain of t"),
    "existential in a chain read both ways": (
        ":p a owl:SymmetricProperty . :s a owl:ObjectProperty . :t a owl:ObjectProperty ; "
        "owl:propertyChainAxiom ( :s :p ) . :A rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :p ; "
        "owl:someValuesFrom :F ] . :F rdfs:subClassOf [ a owl:Restriction ; owl:onProperty [ owl:inverseOf :s ] ; "
        "owl:hasValue :i ] .", kinds.EXISTENTIAL, "chain of t"),
    "existential on a transitive property to a named value": (
        ":t a owl:ObjectProperty, owl:TransitiveProperty . :A rdfs:subClassOf [ a owl:Restriction ; "
        "owl:onProperty :t ; owl:someValuesFrom :F ] . :F rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :t ; "
        "owl:hasValue :i ] .", kinds.EXISTENTIAL, "chain of t"),
    "existential and functional": (":p a owl:FunctionalProperty . :R rdfs:subClassOf [ a owl:Restriction ; "
                                   "owl:onProperty :p ; owl:someValuesFrom :L ] .", kinds.EXISTENTIAL,
                                   "at most one value"),
    "existential under a maximum told on another class": (
        ":A rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :p ; owl:maxCardinality 1 ] . :B rdfs:subClassOf "
        "[ a owl:Restriction ; owl:onProperty :p ; owl:someValuesFrom :F ] .", kinds.EXISTENTIAL,
        "on instances of (p max 1"),
    "minimum of two under a maximum told on another class": (
        ":A rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :p ; owl:maxCardinality 1 ] . :B rdfs:subClassOf "
        "[ a owl:Restriction ; owl:onProperty :p ; owl:minQualifiedCardinality 2 ; owl:onClass :F ] .",
        kinds.EXISTENTIAL, "in both (p min 2 F) and (p max 1"),
    "unqualified minimum of two under a maximum told on another class": (
        ":A rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :p ; owl:maxCardinality 1 ] . :B rdfs:subClassOf "
        "[ a owl:Restriction ; owl:onProperty :p ; owl:minCardinality 2 ] .", kinds.EXISTENTIAL,
        "in both (p min 2 Thing) and (p max 1"),
    "data minimum of two under a maximum told on another class": (
        ":d a owl:DatatypeProperty . :A rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :d ; "
        "owl:maxCardinality 1 ] . :B rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :d ; "
        "owl:cardinality 2 ] .", kinds.EXISTENTIAL, "not where the individual is in two classes"),
    "existential under a maximum of none told on another class": (
        ":A rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :p ; owl:maxCardinality 0 ] . :B rdfs:subClassOf "
        "[ a owl:Restriction ; owl:onProperty :p ; owl:someValuesFrom :F ] .", kinds.EXISTENTIAL,
        "in both (p some F) and (p max 0"),
    "existential into disjoint classes": (":A rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :p ; "
                                          "owl:someValuesFrom :B ] . :p rdfs:range :C . :B owl:disjointWith :C .",
                                          kinds.EXISTENTIAL, "disjoint"),
    "existential chain": (":A rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :p ; owl:someValuesFrom "
                          "[ a owl:Restriction ; owl:onProperty :p ; owl:someValuesFrom :B ] ] .",
                          kinds.EXISTENTIAL, "own restrictions"),
    "existential under a sub-property": (":p rdfs:subPropertyOf :q . :q a owl:ObjectProperty . "
                                         ":A rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :p ; "
                                         "owl:someValuesFrom :C ] . :D owl:equivalentClass [ a owl:Restriction ; "
                                         "owl:onProperty :q ; owl:minCardinality 2 ] .", kinds.EXISTENTIAL,
                                         "super-properties"),
    "existential into a class whose universal on the inverse flows back": (
        ":A rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :p ; owl:someValuesFrom :F ] . :F rdfs:subClassOf "
        "[ a owl:Restriction ; owl:onProperty [ owl:inverseOf :p ] ; owl:allValuesFrom :D ] .", kinds.EXISTENTIAL,
        "says more of the individual linked to it"),
    "existential whose universal's class is linked to an individual": (
        ":s a owl:ObjectProperty ; rdfs:range :D . :A rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :p ; "
        "owl:someValuesFrom owl:Thing ] , [ a owl:Restriction ; owl:onProperty :p ; owl:allValuesFrom :F ] . "
        ":F rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :s ; owl:hasValue :i ] .", kinds.EXISTENTIAL,
        "a link to i"),
    "existential going on in a chain to a value whose class flows back": (
        ":s a owl:ObjectProperty . :t a owl:ObjectProperty ; owl:propertyChainAxiom ( :p :s ) . "
        ":A rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :p ; owl:someValuesFrom :F ] . "
        ":F rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :s ; owl:someValuesFrom :G ] . "
        ":G rdfs:subClassOf [ a owl:Restriction ; owl:onProperty [ owl:inverseOf :t ] ; owl:allValuesFrom :D ] .",
        kinds.EXISTENTIAL, "chain of t"),
    "properties made the same": (":a :p :b . :p owl:sameAs :q .", kinds.UNSUPPORTED, "p sameAs q"),
    "irreflexive difference": (":p a owl:IrreflexiveProperty , owl:FunctionalProperty .", kinds.DIFFERENCE,
                               "irreflexive"),
    "rdf:nil with a first element": ("<http://www.w3.org/1999/02/22-rdf-syntax-ns#nil> "
                                     "<http://www.w3.org/1999/02/22-rdf-syntax-ns#first> :x .", kinds.UNSUPPORTED,
                                     "nil first x"),
    "rdf:nil with a rest": ("<http://www.w3.org/1999/02/22-rdf-syntax-ns#nil> "
                            "<http://www.w3.org/1999/02/22-rdf-syntax-ns#rest> [] .", kinds.UNSUPPORTED, "nil rest"),
    "import not loaded": ("<http://e.org/a> owl:imports <http://e.org/b> .", kinds.UNSUPPORTED,
                          "imports http://e.org/b"),
    "datatypes made the same": (":bar owl:sameAs xsd:decimal . :x :n \"01\"^^:bar .", kinds.UNSUPPORTED,
                                "bar sameAs decimal"),
    "empty property": (":a a [ a owl:Restriction ; owl:onProperty owl:bottomObjectProperty ; "
                       "owl:someValuesFrom owl:Thing ] .", kinds.UNSUPPORTED, "owl:bottomObjectProperty"),
    "universal property": (":a owl:topObjectProperty :b .", kinds.UNSUPPORTED, "owl:topObjectProperty"),
    "string facet": (":code a owl:DatatypeProperty . :B owl:equivalentClass [ a owl:Restriction ; "
                     "owl:onProperty :code ; owl:someValuesFrom [ a rdfs:Datatype ; owl:onDatatype xsd:string ; "
                     "owl:withRestrictions ( [ xsd:pattern \"A.*\" ] ) ] ] .", kinds.UNSUPPORTED, "set aside"),
    "range of an undeclared datatype": (":d a owl:DatatypeProperty ; rdfs:range :MyType . :x :d 3 .",
                                        kinds.UNCHECKED_DATATYPE, "not declared rdfs:Datatype"),
    "range of rdf:XMLLiteral (in the datatype map)": (":d a owl:DatatypeProperty ; rdfs:range "
                                                     "<http://www.w3.org/1999/02/22-rdf-syntax-ns#XMLLiteral> .",
                                                     kinds.UNCHECKED_DATATYPE, "XMLLiteral is a datatype whose values"),
    "universal into an own datatype": (":Small a rdfs:Datatype . :d a owl:DatatypeProperty . :A rdfs:subClassOf "
                                       "[ a owl:Restriction ; owl:onProperty :d ; owl:allValuesFrom :Small ] .",
                                       kinds.UNCHECKED_DATATYPE, "Small is not a datatype of the OWL 2"),
    "data one-of of an individual": (":code a owl:DatatypeProperty . :B owl:equivalentClass [ a owl:Restriction ; "
                                     "owl:onProperty :code ; owl:someValuesFrom [ a rdfs:Datatype ; owl:oneOf ( 1 :b ) ] ] .",
                                     kinds.UNSUPPORTED, "set aside"),
    "data union with an own datatype": (":Mine a rdfs:Datatype . :code a owl:DatatypeProperty . :B owl:equivalentClass "
                                        "[ a owl:Restriction ; owl:onProperty :code ; owl:someValuesFrom [ a rdfs:Datatype ; "
                                        "owl:unionOf ( xsd:boolean :Mine ) ] ] .",
                                        kinds.UNCHECKED_DATATYPE, "built of a datatype whose values"),
}


def quietly(text: str, strict: bool = False) -> Ontology:
    o = Ontology(strict=strict)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", OntologyWarning)
        o.load_data(PREFIXES + text)
    return o


@pytest.mark.parametrize("name", list(CASES))
def test_each_kind_is_named_at_load_and_in_the_reason_report(name: str) -> None:
    text, kind, word = CASES[name]
    o = Ontology()
    with pytest.warns(OntologyWarning, match=kind):
        o.load_data(PREFIXES + text)
    report = o.reason()
    found = [n for n in report.incomplete if n.axiom_kind == kind]
    assert found, [str(n) for n in report.incomplete]
    assert any(word in str(n) for n in found), [str(n) for n in found]


@pytest.mark.parametrize("files", [
    [SHARED / "topological_map_abox.owl"],
    [SHARED / "topological_map.owl"],
    list(default_ontology_files()),
])
def test_the_horn_map_is_reasoned_completely(files: list[Path]) -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("error", OntologyWarning)
        o = Ontology.from_file(*files, strict=True)
    assert o.notices == [] and o.reason().incomplete == []


def test_horn_axioms_give_no_notice() -> None:
    o = quietly(":A rdfs:subClassOf :B , [ a owl:Restriction ; owl:onProperty :p ; owl:hasValue :v ] . "
                ":C owl:equivalentClass [ a owl:Class ; owl:intersectionOf ( :A [ a owl:Restriction ; owl:onProperty :p ; "
                "owl:someValuesFrom :B ] ) ] . [ owl:unionOf ( :A :B ) ] rdfs:subClassOf :D . "
                ":E rdfs:subClassOf [ owl:complementOf :A ] . :p rdfs:domain :A ; rdfs:range :B .")
    assert o.notices == []


def test_a_union_of_one_member_as_a_superclass_is_that_member() -> None:
    """What is left of a union once its owl:Nothing members are dropped may be one class: no case analysis."""
    o = quietly(":A rdfs:subClassOf [ owl:unionOf ( :B owl:Nothing ) ] . :U owl:equivalentClass [ a owl:Class ; owl:unionOf "
                "( :C ) ] . :a a :A . :u a :U .")
    assert o.notices == []
    o.reason()
    assert {t.value.rsplit("#", 1)[-1] for t in o.types("a")} >= {"A", "B"}
    assert {t.value.rsplit("#", 1)[-1] for t in o.types("u")} >= {"U", "C"}


@pytest.mark.parametrize("second", [
    "",  # the unnamed value's class has no second link: the chain goes through named individuals only
    ":F rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :p ; owl:hasValue :i ] .",  # a link, not by s
])
def test_a_chain_that_cannot_pass_through_an_unnamed_value_is_not_named(second: str) -> None:
    o = quietly(":s a owl:ObjectProperty . :t a owl:ObjectProperty ; rdfs:domain :D ; rdfs:range :R ; "
                "owl:propertyChainAxiom ( :p :s ) . :A rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :p ; "
                f"owl:someValuesFrom :F ] . {second} :a a :A ; :p :b . :b :s :c .")
    assert o.notices == [] and o.reason().incomplete == []
    assert [v.value for v in o.object_values("t", "a", names=False)] == ["http://e.org/a#c"]
    assert "http://e.org/a#D" in {c.value for c in o.types("a")}


@pytest.mark.parametrize("tbox", [
    # the chain goes on to a second unnamed value, and a link by t to it gives nothing: t has a range only
    ":s a owl:ObjectProperty . :t a owl:ObjectProperty ; rdfs:range :R ; owl:propertyChainAxiom ( :p :s ) . "
    ":A rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :p ; owl:someValuesFrom :F ] . "
    ":F rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :s ; owl:someValuesFrom :G ] .",
    # transitive t with a domain: the subject already has that domain by its stored link, the value no t link
    ":t a owl:ObjectProperty, owl:TransitiveProperty ; rdfs:domain :D ; rdfs:range :D . :p rdfs:subPropertyOf :t . "
    ":A rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :p ; owl:someValuesFrom :F ] .",
])
def test_a_chain_whose_conclusion_through_an_unnamed_value_carries_nothing_is_not_named(tbox: str) -> None:
    o = quietly(tbox + " :a a :A . :b :t :a .")
    assert o.notices == [] and o.reason().incomplete == []


@pytest.mark.parametrize("extra", [
    ":R rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :q ; owl:someValuesFrom :G ] .",  # the value says more
    ":R owl:disjointWith :F .",  # the value may be in disjoint classes
    "[ a owl:Restriction ; owl:onProperty :t ; owl:someValuesFrom :G ] rdfs:subClassOf :H .",  # read on the left
    # the value is in a restriction on the inverse read on the left, or its range is a filler read there
    "[ a owl:Restriction ; owl:onProperty [ owl:inverseOf :t ] ; owl:someValuesFrom :A ] rdfs:subClassOf :H .",
    "[ a owl:Restriction ; owl:onProperty :q ; owl:someValuesFrom :R ] rdfs:subClassOf :H .",
])
def test_a_chain_to_a_second_unnamed_value_is_named_unless_shown_to_carry_nothing(extra: str) -> None:
    o = quietly(":s a owl:ObjectProperty . :q a owl:ObjectProperty . :t a owl:ObjectProperty ; rdfs:range :R ; "
                "owl:propertyChainAxiom ( :p :s ) . :A rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :p ; "
                "owl:someValuesFrom :F ] . :F rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :s ; "
                f"owl:someValuesFrom :G ] . {extra} :a a :A .")
    assert any("chain of t" in n.reason for n in o.reason().incomplete)


def test_a_chain_of_a_functional_property_is_ignored_as_pellet_ignores_it_not_named_as_through_a_value() -> None:
    """t functional and defined by a chain is outside OWL 2 DL: its chain is ignored (as Pellet ignores it) and named so."""
    o = quietly(":s a owl:ObjectProperty . :t a owl:ObjectProperty, owl:FunctionalProperty ; rdfs:range :R ; "
                "owl:propertyChainAxiom ( :p :s ) . :A rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :p ; "
                "owl:someValuesFrom :F ] . :F rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :s ; "
                "owl:someValuesFrom :G ] . :a a :A .")
    incomplete = o.reason().incomplete
    assert not any("chain of t" in n.reason for n in incomplete)
    assert [n.subject for n in incomplete if n.axiom_kind == NON_SIMPLE] == ["t chain of p o s"]


def test_one_warning_per_kind_naming_every_axiom() -> None:
    o = Ontology()
    with pytest.warns(OntologyWarning) as caught:
        o.load_data(PREFIXES + ":A rdfs:subClassOf [ owl:unionOf (:B :C) ] . :D rdfs:subClassOf [ owl:unionOf (:E :F) ] .")
    lines = [str(w.message) for w in caught if kinds.UNION in str(w.message)]
    assert len(lines) == 1 and "A SubClassOf" in lines[0] and "D SubClassOf" in lines[0]


def test_a_file_with_unsupported_facets_loads_instead_of_being_refused() -> None:
    o = quietly(CASES["string facet"][0] + ' :x :code "A1" .')
    assert o.reason().consistent


def test_strict_refuses_and_changes_nothing() -> None:
    o = quietly(":a a :A .", strict=True)
    before = o.store.count(ASSERTED)
    with pytest.raises(IncompleteOntologyError, match="A SubClassOf"):
        o.load_data(PREFIXES + CASES["union superclass"][0])
    assert o.store.count(ASSERTED) == before and o.notices == []


def test_armor_load_reply_and_strict_service(tmp_path: Path) -> None:
    path = tmp_path / "union.ttl"
    path.write_text(PREFIXES + CASES["union superclass"][0])
    res = armor_load(ArmorService(), path, "http://e.org/a")
    strict = armor_load(ArmorService(strict=True), path, "http://e.org/a")
    assert res.success and kinds.UNION in res.error_description and "A SubClassOf" in res.error_description
    assert not strict.success and strict.exit_code == 209 and "A SubClassOf" in strict.error_description


def test_check_command(tmp_path: Path) -> None:
    path = tmp_path / "union.ttl"
    path.write_text(PREFIXES + CASES["union superclass"][0])
    result = CliRunner().invoke(cli, ["check", str(path)])
    assert result.exit_code == 0 and kinds.UNION in result.output
    assert CliRunner().invoke(cli, ["check", "--strict", str(path)]).exit_code == 1
    clean = CliRunner().invoke(cli, ["check", "--strict", str(SHARED / "topological_map_abox.owl")])
    assert clean.exit_code == 0 and "reasoned completely" in clean.output


def test_reason_strict_refuses_with_one_line(tmp_path: Path) -> None:
    path = tmp_path / "union.ttl"
    path.write_text(PREFIXES + CASES["union superclass"][0])
    result = CliRunner().invoke(cli, ["reason", "--strict", str(path)])
    assert result.exit_code == 1 and "refused (strict)" in result.output and "A SubClassOf" in result.output
    assert CliRunner().invoke(cli, ["reason", str(path)]).exit_code == 0


def test_served_service_is_strict_when_asked(tmp_path: Path) -> None:
    from starlette.testclient import TestClient

    from topostore.http.app import ServerConfig, create_app

    (tmp_path / "union.ttl").write_text(PREFIXES + CASES["union superclass"][0])
    load = {"client_name": "c", "reference_name": "ref", "command": "LOAD", "primary_command_spec": "FILE",
            "secondary_command_spec": "", "args": ["union.ttl", "http://e.org/a", "false", "PELLET", "false"]}
    for strict, code in ((True, 209), (False, 0)):
        app = create_app(ServerConfig(data_dir=tmp_path, strict=strict))
        with TestClient(app, base_url="http://127.0.0.1") as client, warnings.catch_warnings():
            warnings.simplefilter("ignore", OntologyWarning)
            reply = client.post("/armor", json=load).json()
        assert reply["exit_code"] == code and "A SubClassOf" in reply["error_description"], reply


def test_tutorial_tbox_complement_is_derived_and_what_is_not_is_named_at_load(tmp_path: Path) -> None:
    """The tutorial-style TBox's NonVegetarianPizza (the complement of a universal restriction) is derived on
    pizzaA and pizzaC without case analysis; LOAD, the reason report and `topostore check` still name that
    definition, saying that what needs case analysis is not derived (not "never derived")."""
    from benchmarks import tbox

    onto = Ontology()
    with pytest.warns(OntologyWarning, match="NonVegetarianPizza EquivalentTo"):
        onto.load_data(tbox.turtle(100))
    report = onto.reason()
    named = [n for n in report.incomplete if "NonVegetarianPizza" in str(n)]
    assert named and named[0].axiom_kind == kinds.COMPLEMENT
    assert "case analysis" in named[0].reason and "never derived" not in named[0].reason
    for pizza in ("pizzaA", "pizzaC"):
        assert "NonVegetarianPizza" in {onto.short(t) for t in onto.types(pizza)}
    assert "CheeseOrMeatPizza" in {onto.short(t) for t in onto.types("pizzaC")}
    path = tbox.write(100, tmp_path)
    result = CliRunner().invoke(cli, ["check", str(path)])
    assert result.exit_code == 0 and "NonVegetarianPizza EquivalentTo" in result.output


def test_reflexive_equality_is_said_when_a_file_states_an_equality_and_blocks_nothing() -> None:
    """x sameAs x is not stored: an informative notice names it (the reason in the text) where a file uses
    owl:sameAs, never elsewhere; it is no incompleteness (a strict load accepts the file), and individuals
    made the same are not taken for properties made the same."""
    text = ":a owl:sameAs :b . :a :p :c . :b a :A ."
    with pytest.warns(OntologyWarning, match="x sameAs x"):
        o = Ontology(strict=True)
        o.load_data(PREFIXES + text)
    said = [n for n in o.notices if n.kind == NOT_STORED]
    assert len(said) == 1 and "a sameAs b" in said[0].subject and "not stored" in said[0].reason
    assert [n for n in o.notices if n.incomplete] == []
    report = o.reason()
    assert report.consistent and report.incomplete == []
    assert o.object_values("p", "b") == ["c"]  # the facts of one name are answered for the other
    assert not o.sparql("ASK { <http://e.org/a#a> <http://www.w3.org/2002/07/owl#sameAs> <http://e.org/a#a> }")
    assert not [n for n in quietly(":a :p :b .").notices if n.kind == NOT_STORED]


def test_an_equality_with_a_literal_loads() -> None:
    """RDF-Based documents may state owl:sameAs of a literal: read as a plain triple, not a crash."""
    o = quietly(':a owl:sameAs "one" .')
    assert o.reason().consistent and any(n.kind == NOT_STORED for n in o.notices)


def test_rdf_nil_statements_are_incomplete_only_when_made() -> None:
    """A well-formed list (an axiom's members) is no statement about rdf:nil."""
    o = quietly(":A owl:disjointUnionOf ( :B :C ) . :x a :B .")
    assert not any("nil" in n.subject for n in o.notices)
    with pytest.raises(IncompleteOntologyError, match="nil first"):
        quietly(CASES["rdf:nil with a first element"][0], strict=True)


def test_an_import_is_named_only_while_its_ontology_is_not_loaded() -> None:
    o = quietly("<http://e.org/a> owl:imports <http://e.org/b> , <http://e.org/c> . "
                "<http://e.org/b> a owl:Ontology . <http://e.org/d> owl:versionIRI <http://e.org/c> .")
    assert not any("imports" in n.subject for n in o.notices)


def test_a_malformed_list_is_named_inside_an_open_transaction_which_stays_undoable() -> None:
    """Read inside a transaction (the rules compiled while a change is pending), the lists are checked without
    committing the pending writes: the transaction's failure still takes them back."""
    text, kind, word = CASES["an AllDifferent list looping back"]
    o = Ontology()
    o.load_data(PREFIXES)
    scratch = Ontology()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", OntologyWarning)
        scratch.load_data(PREFIXES + text)
    triples = list(scratch.store.triples(graph=ASSERTED))
    before = set(o.store.triples(graph=ASSERTED))
    with pytest.raises(RuntimeError), o.store.transaction():
        o.changes.add(*triples)
        assert any(word in str(n) for n in o.notices if n.axiom_kind == kind)
        raise RuntimeError("the transaction's own failure")
    assert set(o.store.triples(graph=ASSERTED)) == before
