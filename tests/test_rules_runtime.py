"""SWRL rules added and removed at run time in Protégé's syntax, stored in the SWRL RDF vocabulary."""

from __future__ import annotations

from pathlib import Path

import pytest
import rdflib

from topostore import Ontology
from topostore.compile.swrl_text import VARIABLE_NS, rule_labels
from topostore.errors import RuleCompileError
from topostore.rdf.vocab import ASSERTED
from topostore.resources import default_ontology_files

STALE = "LOCATION(?l) ^ visitedAt(?l, ?v) ^ swrlb:lessThan(?v, 1665579736) -> URGENT(?l)"
SWRL = "http://www.w3.org/2003/11/swrl#"


def urgent(onto: Ontology) -> list[str]:
    return sorted(onto.short(i) for i in onto.instances("URGENT"))


@pytest.fixture
def onto() -> Ontology:
    o = Ontology.from_file(*default_ontology_files())
    o.reason()
    return o


def test_added_rule_changes_the_next_reason_and_removing_it_undoes_that(onto: Ontology) -> None:
    assert urgent(onto) == ["R1"]
    onto.add_rule(STALE, "Stale")
    assert urgent(onto) == ["R1"]                      # takes effect at the next REASON
    onto.reason()
    assert urgent(onto) == ["R1", "R2"]
    assert onto.rule_labels() == ["Connectability", "Reachability", "Stale", "Urgency"]
    assert [r.name for r in onto.rules.rules if r.name == "swrl:Stale"] == ["swrl:Stale"]
    before = onto.store.count(ASSERTED)
    onto.remove_rule("Stale")
    onto.reason()
    assert urgent(onto) == ["R1"]
    assert onto.rule_labels() == ["Connectability", "Reachability", "Urgency"]
    onto.add_rule(STALE, "Stale")
    assert onto.store.count(ASSERTED) == before        # removal took every triple of the rule, no more


def test_loaded_rules_can_be_removed_too(onto: Ontology) -> None:
    onto.remove_rule("Urgency")
    onto.reason()
    assert urgent(onto) == []
    assert sorted(onto.object_values("canReach", "Robot1")) == ["R1", "R2"]  # the other rules stay


def test_rule_is_written_in_the_standard_swrl_vocabulary(onto: Ontology, tmp_path: Path) -> None:
    onto.add_rule("ROBOT(?r) ^ isIn(?r, ?l) ^ now(?r, ?t) ^ swrlb:add(?u, ?t, 5) -> visitedAt(?l, ?u)", "Mark",
                  comment="mark where the robot is")
    path = onto.save(tmp_path / "map.owl")
    g = rdflib.Graph().parse(path, format="xml")
    imp = next(s for s in g.subjects(rdflib.RDF.type, rdflib.URIRef(SWRL + "Imp"))
               if str(g.value(s, rdflib.RDFS.label)) == "Mark")
    assert isinstance(imp, rdflib.BNode)
    body = list(rdflib.collection.Collection(g, g.value(imp, rdflib.URIRef(SWRL + "body"))))
    kinds = [g.value(a, rdflib.RDF.type).split("#")[1] for a in body]
    assert kinds == ["ClassAtom", "IndividualPropertyAtom", "DatavaluedPropertyAtom", "BuiltinAtom"]
    for cell in g.objects(imp, rdflib.URIRef(SWRL + "body")):
        assert (cell, rdflib.RDF.type, rdflib.URIRef(SWRL + "AtomList")) in g
    args = list(rdflib.collection.Collection(g, g.value(body[3], rdflib.URIRef(SWRL + "arguments"))))
    assert args == [rdflib.URIRef(VARIABLE_NS + "u"), rdflib.URIRef(VARIABLE_NS + "t"), rdflib.Literal(5)]
    assert (rdflib.URIRef(VARIABLE_NS + "u"), rdflib.RDF.type, rdflib.URIRef(SWRL + "Variable")) in g


def test_save_and_reload_keeps_the_added_rule(onto: Ontology, tmp_path: Path) -> None:
    onto.add_rule(STALE, "Stale")
    for name in ("map.owl", "map.ttl"):
        path = onto.save(tmp_path / name)
        again = Ontology.from_file(path)
        again.reason()
        assert again.rule_labels() == ["Connectability", "Reachability", "Stale", "Urgency"]
        assert urgent(again) == ["R1", "R2"]
        again.remove_rule("Stale")
        again.reason()
        assert urgent(again) == ["R1"]


@pytest.mark.parametrize("text, message", [
    ("LOCATON(?l) -> URGENT(?l)", "atom LOCATON(?l): LOCATON is not a declared class"),
    ("LOCATION(?l) ^ visitedAt(?l) -> URGENT(?l)", "atom visitedAt(?l): visitedAt takes 2 argument(s), got 1"),
    ("LOCATION(?l) ^ hasDoor(?l, 5) -> URGENT(?l)", "atom hasDoor(?l, 5): hasDoor is an object property"),
    ("LOCATION(?l) ^ swrlb:frobnicate(?l) -> URGENT(?l)", "atom BuiltinAtom(frobnicate, l): unsupported built-in"),
    ("LOCATION(?l) -> URGENT(?x)", "head atom ClassAtom(URGENT, x): variable ?x is not bound by the body"),
    ("LOCATION(?l) ^ swrlb:greaterThan(?v, 3) -> URGENT(?l)", "atom BuiltinAtom(greaterThan, v, 3): its input variables are never bound"),
    ("LOCATION(?l) URGENT(?l)", "expected '->' between body and head, found 'URGENT' at position 14"),
    ("LOCATION(?l) -> foo:URGENT(?l)", "unknown prefix 'foo'"),
    ("LOCATION(?l) -> URGENT(?l) ^", "expected a head atom, found the end of the rule"),
    ("LOCATION(?l) -> URGENT(?l) $", "unexpected character '$' at position 28"),
])
def test_a_rule_that_cannot_compile_is_refused_naming_the_atom_and_nothing_changes(
        onto: Ontology, text: str, message: str) -> None:
    before = set(onto.store.triples(graph=ASSERTED))
    with pytest.raises(RuleCompileError, match=None) as info:
        onto.add_rule(text, "Bad")
    assert message in str(info.value)
    assert set(onto.store.triples(graph=ASSERTED)) == before
    assert onto.reason().stats.mode == "incremental"     # nothing changed, not even the rules


def test_labels_are_required_and_unique(onto: Ontology) -> None:
    with pytest.raises(RuleCompileError, match="non-empty label"):
        onto.add_rule(STALE, " ")
    with pytest.raises(RuleCompileError, match="already exists"):
        onto.add_rule(STALE, "Urgency")
    with pytest.raises(RuleCompileError, match="no SWRL rule labelled 'Nope'"):
        onto.remove_rule("Nope")
    assert rule_labels(onto.store) == ["Connectability", "Reachability", "Urgency"]


def test_same_different_and_data_range_atoms(onto: Ontology) -> None:
    onto.add_rule("LOCATION(?a) ^ LOCATION(?b) ^ differentFrom(?a, ?b) ^ visitedAt(?a, ?v) ^ xsd:long(?v) "
                  "^ visitedAt(?b, ?w) ^ swrlb:lessThan(?v, ?w) -> connectedTo(?a, ?b)", "Older")
    onto.reason()
    assert sorted(onto.object_values("connectedTo", "R1")) == ["C1", "R2"]
