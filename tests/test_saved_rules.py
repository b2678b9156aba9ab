"""Maps saved through aRMOR (the OWL API's RDF/XML writer) whose SWRL rules hold nested atom lists.

They load: nested lists are flattened, a body carrying another rule's atoms is recognised, an
unreadable rule is skipped, and each of these is said (OntologyWarning, the log, the aRMOR LOAD
reply, ``topostore check``).  ``topostore repair`` puts the original rules back.
"""

from __future__ import annotations

import logging
import warnings
from pathlib import Path

import pytest
from click.testing import CliRunner
from pyoxigraph import NamedNode
from scenarios import damage
from support import ABOX_OWL as ABOX
from support import DATA, armor_load
from support import TBOX_OWL as TBOX

from topostore import Ontology, OntologyWarning
from topostore.armor import ArmorService
from topostore.cli.group import cli
from topostore.compile.notices import RULE_REPAIRED, RULE_SKIPPED
from topostore.compile.swrl_repair import repair_rules
from topostore.rdf.vocab import ASSERTED, FIRST, TYPE, swrl
from topostore.stores import memory_store

SAVED = DATA / "saved_nested_rules.owl"



def load_quietly(*paths: Path) -> Ontology:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", OntologyWarning)
        return Ontology.from_file(*paths)


def nested_atom_lists(onto: Ontology) -> int:
    """Cells whose rdf:first is itself an atom list (what a well-formed rule never has)."""
    cells = set(onto.store.subjects(TYPE, swrl("AtomList"), ASSERTED))
    return sum(1 for c in cells for o in onto.store.objects(c, FIRST, ASSERTED) if o in cells)


def test_saved_rules_load_repaired_and_warn() -> None:
    with pytest.warns(OntologyWarning) as caught:
        onto = Ontology.from_file(SAVED)
    text = " ".join(str(w.message) for w in caught)
    assert "Adjacency" in text and "Reach" in text and "Broken" in text
    kinds = {n.subject: n.kind for n in onto.load_notices}
    assert kinds == {"Adjacency": RULE_REPAIRED, "Reach": RULE_REPAIRED, "Broken": RULE_SKIPPED}
    reach = next(n for n in onto.load_notices if n.subject == "Reach")
    assert "'Adjacency'" in reach.reason  # the carried atoms are named by their rule
    assert onto.rule_labels() == ["Adjacency", "Reach"]
    assert onto.reason().consistent
    assert onto.object_values("adjacent", "p2") == ["p1"]
    assert onto.object_values("reaches", "bot") == ["p1"]  # at(bot, p2) ^ adjacent(p2, p1): the carried atoms are gone
    assert onto.instances("Hub") == []  # the skipped rule draws nothing
    assert nested_atom_lists(onto) == 0


def test_notices_go_to_the_log(caplog: pytest.LogCaptureFixture) -> None:
    with caplog.at_level(logging.WARNING, logger="topostore.load"):
        load_quietly(SAVED)
    assert any("Broken" in r.getMessage() and "skipped" in r.getMessage() for r in caplog.records)


def test_save_writes_flat_rules_that_reload_without_notices(tmp_path: Path) -> None:
    onto = load_quietly(SAVED)
    onto.save(tmp_path / "again.owl")
    with warnings.catch_warnings():
        warnings.simplefilter("error", OntologyWarning)  # a second load has nothing to repair
        again = Ontology.from_file(tmp_path / "again.owl")
    assert again.load_notices == [] and nested_atom_lists(again) == 0
    again.reason()
    assert again.object_values("reaches", "bot") == ["p1"]
    # no list cell of the damaged structure is left behind: every AtomList cell belongs to a rule
    assert len(again.store.subjects(TYPE, swrl("AtomList"), ASSERTED)) == 6


def test_armor_load_reply_names_repaired_and_skipped_rules() -> None:
    res = armor_load(ArmorService(), SAVED, "http://example.org/saved")
    assert res.success and res.exit_code == 0
    assert "SWRL rule repaired: Adjacency" in res.error_description
    assert "SWRL rule skipped: Broken" in res.error_description


def test_armor_load_of_a_rule_that_cannot_compile_succeeds_and_names_it(tmp_path: Path) -> None:
    """A third-party file whose rule uses a built-in topostore does not evaluate: LOAD succeeds (it was refused
    with 209), the reply names the rule set aside, and the other rules are reasoned."""
    path = tmp_path / "tan.ttl"
    path.write_text("""
    @prefix : <http://example.org/u#> . @prefix swrl: <http://www.w3.org/2003/11/swrl#> .
    @prefix swrlb: <http://www.w3.org/2003/11/swrlb#> . @prefix owl: <http://www.w3.org/2002/07/owl#> .
    @prefix rdfs: <http://www.w3.org/2000/01/rdf-schema#> .
    :A a owl:Class . :B a owl:Class . :C a owl:Class . :d a owl:DatatypeProperty . :x a swrl:Variable .
    :v a swrl:Variable . :r a swrl:Variable . :i a owl:NamedIndividual , :A ; :d 1 .
    [] a swrl:Imp ; rdfs:label "Trig" ;
       swrl:body ( [ a swrl:DatavaluedPropertyAtom ; swrl:propertyPredicate :d ; swrl:argument1 :x ; swrl:argument2 :v ]
                   [ a swrl:BuiltinAtom ; swrl:builtin swrlb:tan ; swrl:arguments ( :r :v ) ] ) ;
       swrl:head ( [ a swrl:ClassAtom ; swrl:classPredicate :C ; swrl:argument1 :x ] ) .
    [] a swrl:Imp ; rdfs:label "Plain" ; swrl:body ( [ a swrl:ClassAtom ; swrl:classPredicate :A ; swrl:argument1 :x ] ) ;
       swrl:head ( [ a swrl:ClassAtom ; swrl:classPredicate :B ; swrl:argument1 :x ] ) .
    """)
    service = ArmorService()
    res = armor_load(service, path, "http://example.org/u")
    assert res.success and res.exit_code == 0
    assert "SWRL rule set aside: Trig (atom BuiltinAtom(tan, r, v): unsupported built-in" in res.error_description
    assert [c.value for c in service.reference("ref").ontology.types("i")] == ["http://example.org/u#A",
                                                                             "http://example.org/u#B"]


def test_check_command_prints_the_report() -> None:
    result = CliRunner().invoke(cli, ["check", str(SAVED)])
    assert result.exit_code == 0, result.output
    assert "SWRL rule repaired: Adjacency" in result.output and "SWRL rule skipped: Broken" in result.output
    strict = CliRunner().invoke(cli, ["check", "--strict", str(SAVED)])
    assert strict.exit_code == 1 and "--strict" in strict.output


def test_a_repaired_rule_that_still_cannot_compile_is_skipped() -> None:
    """Flattening gives a rule whose head variable no body atom binds: set aside, not a refusal."""
    ttl = """
    @prefix : <http://example.org/u#> . @prefix swrl: <http://www.w3.org/2003/11/swrl#> .
    @prefix rdf: <http://www.w3.org/1999/02/22-rdf-syntax-ns#> . @prefix owl: <http://www.w3.org/2002/07/owl#> .
    @prefix rdfs: <http://www.w3.org/2000/01/rdf-schema#> .
    :A a owl:Class . :B a owl:Class . :x a swrl:Variable . :z a swrl:Variable . :i a :A .
    [] a swrl:Imp ; rdfs:label "Unsafe" ;
       swrl:body [ a swrl:AtomList ; rdf:first [ a swrl:AtomList ; rdf:rest rdf:nil ;
                     rdf:first [ a swrl:ClassAtom ; swrl:classPredicate :A ; swrl:argument1 :x ] ] ;
                   rdf:rest rdf:nil ] ;
       swrl:head [ a swrl:AtomList ; rdf:rest rdf:nil ;
                   rdf:first [ a swrl:ClassAtom ; swrl:classPredicate :B ; swrl:argument1 :z ] ] .
    """
    onto = Ontology()
    with pytest.warns(OntologyWarning, match="Unsafe"):
        onto.load_data(ttl)
    (notice,) = onto.load_notices
    assert notice.kind == RULE_SKIPPED and "not bound" in notice.reason
    assert onto.rule_labels() == [] and onto.reason().consistent
    onto.prefix = "http://example.org/u#"
    assert [onto.short(i) for i in onto.instances("A")] == ["i"]


def test_an_untouched_untranslatable_rule_is_set_aside_and_kept() -> None:
    """A rule no save damaged that cannot be compiled: loaded as written, set aside with a warning naming it."""
    onto = Ontology()
    with pytest.warns(OntologyWarning, match="SWRL rule set aside: Unsafe .*not bound"):
        onto.load_data("""
        @prefix : <http://example.org/u#> . @prefix swrl: <http://www.w3.org/2003/11/swrl#> .
        @prefix rdf: <http://www.w3.org/1999/02/22-rdf-syntax-ns#> . @prefix owl: <http://www.w3.org/2002/07/owl#> .
        @prefix rdfs: <http://www.w3.org/2000/01/rdf-schema#> .
        :A a owl:Class . :B a owl:Class . :x a swrl:Variable . :z a swrl:Variable . :i a :A .
        [] a swrl:Imp ; rdfs:label "Unsafe" ;
           swrl:body [ a swrl:AtomList ; rdf:rest rdf:nil ;
                       rdf:first [ a swrl:ClassAtom ; swrl:classPredicate :A ; swrl:argument1 :x ] ] ;
           swrl:head [ a swrl:AtomList ; rdf:rest rdf:nil ;
                       rdf:first [ a swrl:ClassAtom ; swrl:classPredicate :B ; swrl:argument1 :z ] ] .
        """)
    assert onto.load_notices == [] and onto.rule_labels() == ["Unsafe"]
    assert onto.reason().consistent and not list(onto.store.triples(None, TYPE, NamedNode("http://example.org/u#B")))


def test_well_formed_rules_are_not_touched() -> None:
    triples = memory_store().parse_file(ABOX)
    assert repair_rules(triples) == (triples, [])


# ---------------------------------------------------------------- the tutorial map, damaged as a save leaves it

def test_damaged_tutorial_map_reasons_as_pellet_does(tmp_path: Path) -> None:
    broken = tmp_path / "saved.owl"
    damage(ABOX, broken)
    with pytest.warns(OntologyWarning):
        onto = Ontology.from_file(broken)
    assert sorted(n.kind for n in onto.load_notices) == [RULE_REPAIRED] * 3
    assert onto.reason().consistent
    assert sorted(onto.object_values("canReach", "Robot1")) == ["R1", "R2"]
    assert [onto.short(i) for i in onto.instances("URGENT")] == ["R1"]
    assert sorted(onto.short(c) for c in onto.types("C1")) == ["CORRIDOR", "LOCATION", "ROOM"]


def test_repair_command_puts_the_original_rules_back(tmp_path: Path) -> None:
    broken, fixed = tmp_path / "saved.owl", tmp_path / "fixed.owl"
    damage(ABOX, broken)
    result = CliRunner().invoke(cli, ["repair", str(broken), "--rules-from", str(TBOX), "-o", str(fixed)])
    assert result.exit_code == 0, result.output
    assert "3 SWRL rule(s) removed, 3 put back" in result.output
    with warnings.catch_warnings():
        warnings.simplefilter("error", OntologyWarning)
        onto = Ontology.from_file(fixed)
    original = load_quietly(ABOX)
    assert onto.rule_labels() == original.rule_labels()
    assert onto.reason().consistent
    assert sorted(onto.object_values("canReach", "Robot1")) == ["R1", "R2"]
    assert [onto.short(i) for i in onto.instances("URGENT")] == ["R1"]
    assert nested_atom_lists(onto) == 0
