"""Explanations: one derivation per triple, rules evaluated backwards, through every interface."""

from __future__ import annotations

import json

import pytest
from click.testing import CliRunner
from pyoxigraph import NamedNode, Triple

from topostore import Ontology
from topostore.cli.group import cli
from topostore.compile.snippets import VALUE_CANDIDATE
from topostore.demo import mapgen
from topostore.ontology.explain import parse_triple_text
from topostore.ontology.explain.search import Explainer
from topostore.rdf.vocab import AUX, DECLARED_DIFFERENT, DIFFERENCE_CANDIDATE, DIFFERENT, INFERRED
from topostore.resources import default_ontology, default_ontology_files
from topostore.stores import memory_store

URGENT_R1 = """\
R1 rdf:type URGENT  ← swrl:Urgency: SWRL rule Urgency
  where BIND((?t - ?v) AS ?d) FILTER(?d > ?h)  with ?d = 30, ?h = 7, ?l = R1, ?r = Robot1, ?t = 1665579740, ?v = 1665579710
  Robot1 rdf:type ROBOT  ← prp-dom: urgencyThreshold domain ROBOT
    Robot1 urgencyThreshold 7  [asserted]
  Robot1 now 1665579740  [asserted]
  R1 rdf:type LOCATION  ← prp-dom: visitedAt domain LOCATION
    R1 visitedAt 1665579710  [asserted]
  R1 visitedAt 1665579710  [asserted]
  Robot1 urgencyThreshold 7  [asserted]"""

CORRIDOR_C1 = """\
C1 rdf:type CORRIDOR  ← ext-min-card: class expression (hasDoor min 2 DOOR)
  where FILTER(STR(?y1) < STR(?y2) || (STR(?y1) = STR(?y2) && (isLiteral(?y1) && isLiteral(?y2)) && (STR(DATATYPE(?y1)) < STR(DATATYPE(?y2)) || (STR(DATATYPE(?y1)) = STR(DATATYPE(?y2)) && LANG(?y1) < LANG(?y2))))) FILTER(!sameTerm(?k1_d, ?k2_d) && STRBEFORE(STRAFTER(STR(?k1_d), "urn:topostore:key:"), ":") = STRBEFORE(STRAFTER(STR(?k2_d), "urn:topostore:key:"), ":")) FILTER(!sameTerm(?y1, ?y2))  with ?k1_d = D1, ?k2_d = D6, ?x = C1, ?y1 = D1, ?y2 = D6
  C1 hasDoor D1  [asserted]
  D1 rdf:type DOOR  ← prp-rng: hasDoor range DOOR
    C2 hasDoor D1  [asserted]
  C1 hasDoor D6  [asserted]
  D6 rdf:type DOOR  ← prp-rng: hasDoor range DOOR
    R5 hasDoor D6  [asserted]
  D1 in AllDifferent(C1, C2, R1, R2, R3, R4, … 15 members)  ← all-different: OWL 2 RL eq-diff2/eq-diff3 support where the asserted graph holds one owl:AllDifferent member list (rules/all-different-key.rq otherwise): its members are their own keys (one triple per member, no term made); a list reached only by inference keys by list and member, a group of its own
    where BIND(IF(sameTerm(?list, _:mapgen-l), ?x, IRI(CONCAT("urn:topostore:key:", MD5(STR(?list)), ":", MD5(STR(?x))))) AS ?key)  with ?group = AllDifferent(C1, C2, R1, R2, R3, R4, … 15 members), ?key = D1, ?list = _:mapgen-l, ?x = D1
    AllDifferent(C1, C2, R1, R2, R3, R4, … 15 members) rdf:type owl:AllDifferent  [asserted]
    AllDifferent(C1, C2, R1, R2, R3, R4, … 15 members) has the member list (C1, C2, R1, R2, R3, R4, … 15 members)  [asserted]
    D1 listed in (C1, C2, R1, R2, R3, R4, … 15 members)  [asserted]
  D6 in AllDifferent(C1, C2, R1, R2, R3, R4, … 15 members)  ← all-different: OWL 2 RL eq-diff2/eq-diff3 support where the asserted graph holds one owl:AllDifferent member list (rules/all-different-key.rq otherwise): its members are their own keys (one triple per member, no term made); a list reached only by inference keys by list and member, a group of its own
    where BIND(IF(sameTerm(?list, _:mapgen-l), ?x, IRI(CONCAT("urn:topostore:key:", MD5(STR(?list)), ":", MD5(STR(?x))))) AS ?key)  with ?group = AllDifferent(C1, C2, R1, R2, R3, R4, … 15 members), ?key = D6, ?list = _:mapgen-l, ?x = D6
    AllDifferent(C1, C2, R1, R2, R3, R4, … 15 members) rdf:type owl:AllDifferent  [asserted]
    AllDifferent(C1, C2, R1, R2, R3, R4, … 15 members) has the member list (C1, C2, R1, R2, R3, R4, … 15 members)  [asserted]
    D6 listed in (C1, C2, R1, R2, R3, R4, … 15 members)  [asserted]"""


@pytest.fixture(scope="module")
def example() -> Ontology:
    onto = Ontology.from_file(*default_ontology_files())
    assert onto.reason().consistent
    return onto


def leaves(tree) -> list:
    return [tree] if not tree.premises else [leaf for p in tree.premises for leaf in leaves(p)]


def test_r1_urgent_on_the_example_map(example: Ontology) -> None:
    tree = example.explain("R1", "rdf:type", "URGENT")
    assert str(tree) == URGENT_R1
    assert (tree.status, tree.rule, tree.height) == ("inferred", "swrl:Urgency", 3)


def test_corridor_by_cardinality_on_a_generated_map() -> None:
    onto = Ontology.from_file(default_ontology())
    onto.add(*mapgen.generate(8, seed=2).triples())
    onto.reason()
    tree = onto.explain("C1", "rdf:type", "CORRIDOR")
    assert str(tree) == CORRIDOR_C1


def test_a_key_names_its_own_member_list_when_a_node_has_two() -> None:
    """One owl:AllDifferent node with two member lists is two groups: the key and the list premises show
    the list that made the members different, not every member of the node."""
    onto = Ontology()
    onto.load_data("""@prefix : <urn:topostore:default#> . @prefix owl: <http://www.w3.org/2002/07/owl#> .
        :p a owl:ObjectProperty . :D a owl:Class .
        :C owl:equivalentClass [ a owl:Restriction ; owl:onProperty :p ; owl:minQualifiedCardinality 2 ;
                                 owl:onClass :D ] .
        :a a :D . :b a :D . :c a :D . :d a :D . :x :p :a, :b .
        [] a owl:AllDifferent ; owl:members (:a :b) , (:c :d) .""", "turtle")
    onto.reason()
    text = str(onto.explain("x", "rdf:type", "C"))
    assert "key of a in AllDifferent(a, b)" in text and "key of b in AllDifferent(a, b)" in text
    assert "has the member list (a, b)" in text and "a listed in (a, b)" in text
    assert "key of a in AllDifferent(c, d, a, b)" not in text and "key of a in AllDifferent(a, b, c, d)" not in text


def test_asserted_and_not_entailed(example: Ontology) -> None:
    asserted = example.explain("R1", "visitedAt", 1665579710)
    assert (str(asserted), asserted.entailed) == ("R1 visitedAt 1665579710  [asserted]", True)
    assert asserted.to_dict() == {"triple": "R1 visitedAt 1665579710", "status": "asserted"}
    missing = example.explain("R2", "rdf:type", "URGENT")
    assert (str(missing), missing.entailed) == ("R2 rdf:type URGENT  [not entailed]", False)
    assert example.explain("R1", "visitedAt", 5).status == "not entailed"


def test_every_inferred_and_helper_triple_is_explained_down_to_asserted_facts() -> None:
    """Cyclic axioms (LOCATION ≡ visitedAt exactly 1, URGENT ⊑ LOCATION) never loop or leave a gap."""
    onto = Ontology.from_file(default_ontology())
    onto.add(*mapgen.generate(6, seed=4).triples())
    onto.reason()
    triples = list(onto.store.triples(graph=INFERRED)) + list(onto.store.triples(graph=AUX))
    assert len(triples) == len(set(triples))
    for t in triples:
        tree = onto.explain(t.subject, t.predicate, t.object)
        assert tree.status == "inferred" and tree.rule, t
        assert {leaf.status for leaf in leaves(tree)} <= {"asserted", "condition"}, t


def test_json_form(example: Ontology) -> None:
    d = example.explain("R1", "rdf:type", "URGENT").to_dict()
    assert (d["triple"], d["rule"], d["origin"]) == ("R1 rdf:type URGENT", "swrl:Urgency", "SWRL rule Urgency")
    assert [p["triple"] for p in d["premises"]] == [
        "Robot1 rdf:type ROBOT", "Robot1 now 1665579740", "R1 rdf:type LOCATION", "R1 visitedAt 1665579710",
        "Robot1 urgencyThreshold 7"]
    assert d["bindings"]["?d"] == "30"
    assert d["premises"][2]["premises"] == [{"triple": "R1 visitedAt 1665579710", "status": "asserted"}]


def test_sameas_and_entailed_only_conclusions_are_explained() -> None:
    onto = Ontology.from_file(*default_ontology_files())
    onto.add_fact("Robot1", "isIn", "R9")            # R9 not declared different from C1: isIn is functional
    onto.reason()
    tree = onto.explain("C1", "owl:sameAs", "R9")
    assert (tree.status, tree.rule) == ("inferred", "prp-fp")
    assert [p.text for p in tree.premises] == ["Robot1 isIn C1", "Robot1 isIn R9"]


def test_triple_text_parsing(example: Ontology) -> None:
    t = parse_triple_text(example, "R1 a URGENT")
    assert t.predicate == NamedNode("http://www.w3.org/1999/02/22-rdf-syntax-ns#type")
    with pytest.raises(ValueError, match="SUBJECT PREDICATE OBJECT"):
        parse_triple_text(example, "R1 URGENT")


def test_cli_prints_the_tree_and_exits_4_when_not_entailed() -> None:
    files = [str(f) for f in default_ontology_files()]
    result = CliRunner().invoke(cli, ["explain", *files, "R1 rdf:type URGENT"])
    assert result.exit_code == 0, result.output
    lines = result.output.splitlines()
    assert lines[0] == "R1 rdf:type URGENT  ← swrl:Urgency: SWRL rule Urgency"
    assert "├── Robot1 now 1665579740  asserted" in lines
    assert "│   └── R1 visitedAt 1665579710  asserted" in lines
    missing = CliRunner().invoke(cli, ["explain", *files, "R2 rdf:type URGENT"])
    assert (missing.exit_code, missing.output.strip()) == (4, "R2 rdf:type URGENT  not entailed")
    as_json = CliRunner().invoke(cli, ["explain", *files, "R1 rdf:type URGENT", "--json"])
    assert json.loads(as_json.output)["rule"] == "swrl:Urgency"


def test_cli_explains_a_conclusion_of_a_rule_given_on_the_command_line() -> None:
    files = [str(f) for f in default_ontology_files()]
    rule = "Stale=LOCATION(?l) ^ visitedAt(?l, ?v) ^ swrlb:lessThan(?v, 1665579736) -> URGENT(?l)"
    result = CliRunner().invoke(cli, ["explain", *files, "R2 rdf:type URGENT", "--rule", rule])
    assert result.exit_code == 0, result.output
    assert result.output.splitlines()[0] == "R2 rdf:type URGENT  ← swrl:Stale: SWRL rule Stale"


def test_conclusion_with_difference_by_entailment_only() -> None:
    """R9 is not declared different from C1, but its other visit time makes it so: the
    Connectability conclusion is published (as Pellet reports it) and explained through the helper graph."""
    onto = Ontology.from_file(*default_ontology_files())
    onto.add_fact("R9", "hasDoor", "D2")
    onto.add_data("visitedAt", "R9", 1665579000, "long")
    onto.reason()
    tree = onto.explain("R9", "connectedTo", "C1")
    assert (tree.rule, [p.text for p in tree.premises]) == (
        "swrl-entailed", ["R9 connectedTo C1 (different by entailment only)"])
    inner = tree.premises[0]
    assert inner.origin == "SWRL rule Connectability (individuals different by entailment only)"
    assert [(p.text, p.rule) for p in inner.premises][-1] == ("R9 different from C1", "different-values")
    assert {leaf.status for leaf in leaves(tree)} == {"asserted"}


def test_helper_predicates_read_as_words() -> None:
    """The difference helpers an explanation may show are named in words, not as internal IRIs."""
    explainer = Explainer(memory_store(), [], lambda t: t.value.rsplit("#", 1)[-1])
    a, b = NamedNode("http://e.org/x#a"), NamedNode("http://e.org/x#b")
    for p in (DIFFERENCE_CANDIDATE, VALUE_CANDIDATE, DECLARED_DIFFERENT, DIFFERENT):
        text = explainer.render(Triple(a, p, b))
        assert "urn:topostore" not in text and text.startswith("a ") and text.endswith(" b"), text
