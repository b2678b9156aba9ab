"""A full REASON's shortcuts keep its closure and its violations: first passes that read the asserted
facts alone where every derived fact's conclusion holds anyway (reason/order.py ``implied_first_passes``),
readers of a key only claimed by the same pass looked up first (reason/first_pass.py ``claims_hold``), class
atoms another atom's key carries left out of a first pass (reason/order.py ``implied_atoms``), checks
pairing two values kept to the subjects with two (reason/consistency.py ``several_values``); and a
minimum of two values meets every kind of difference."""

from __future__ import annotations

import sys
import warnings
from pathlib import Path

import pytest
from support import closure

from topostore import Ontology, OntologyWarning
from topostore.reason import first_pass, full_passes
from topostore.reason.implied_passes import implied_atoms, implied_first_passes, subject_classes

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))  # the benchmarks package lives beside src/
from benchmarks import tbox  # noqa: E402
from benchmarks.cardinality import PREFIXES  # noqa: E402

MIN2 = PREFIXES + """:p a owl:ObjectProperty . :D a owl:Class .
:C owl:equivalentClass [ a owl:Restriction ; owl:onProperty :p ; owl:minQualifiedCardinality 2 ; owl:onClass :D ] .
"""


def loaded(text: str) -> Ontology:
    onto = Ontology()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", OntologyWarning)
        onto.load_data(text, "turtle")
    return onto


def in_c(onto: Ontology, name: str = "x") -> bool:
    return name in {onto.short(i) for i in onto.instances("C")}


# ---------------------------------------------------------------- a minimum of two

@pytest.mark.parametrize(("data", "expected"), [
    (":x :p :a, :b . :a a :D . :b a :D . [] a owl:AllDifferent ; owl:distinctMembers (:a :b) .", True),
    (":x :p :a, :a2 . :a a :D . :a2 a :D . :a2 owl:sameAs :a . [] a owl:AllDifferent ; owl:distinctMembers (:a :b) .",
     False),  # one member under two names
    (":x :p :a, :b . :a a :D . :b a :D . [] a owl:AllDifferent ; owl:distinctMembers (:a :c) . "
     "[] a owl:AllDifferent ; owl:distinctMembers (:b :c) .", False),  # two groups say nothing of :a and :b
    (":x :p :a, :b . :a a :D . :b a :D . :a owl:differentFrom :b .", True),  # the pairwise rule's source
    (":x :p :a, :b . :a a :D . [] a owl:AllDifferent ; owl:distinctMembers (:a :b) .", False),  # :b is no D
    (":x :p :a, :b2 . :a a :D . :b a :D . :b2 owl:sameAs :b . [] a owl:AllDifferent ; owl:distinctMembers (:a :b) .",
     True),  # a member's key held by what is the same as it
])
def test_a_minimum_of_two_sees_group_members_and_other_differences(data: str, expected: bool) -> None:
    onto = loaded(MIN2 + data)
    assert onto.reason().consistent
    assert in_c(onto) is expected
    onto.reason(mode="full")
    assert in_c(onto) is expected


@pytest.mark.parametrize("change", [
    ":x :p :c . :c a :D .", ":y :p :a . :y :p :c . :c a :D .", ":c owl:sameAs :b .",
])
def test_a_minimum_of_two_follows_changes_as_a_full_reason_does(change: str) -> None:
    text = MIN2 + ":x :p :a . :a a :D . :b a :D . [] a owl:AllDifferent ; owl:distinctMembers (:a :b :c) ."
    onto = loaded(text)
    onto.reason()
    assert not in_c(onto)
    onto.load_data(PREFIXES + change, "turtle")
    onto.reason(mode="incremental")
    incremental = {onto.short(i) for i in onto.instances("C")}
    onto.reason(mode="full")
    assert {onto.short(i) for i in onto.instances("C")} == incremental


# ---------------------------------------------------------------- first passes over asserted facts

CHAIN = PREFIXES + """:q a owl:ObjectProperty ; rdfs:domain :D . :D rdfs:subClassOf :C .
:r a owl:ObjectProperty ; rdfs:domain :E . :r2 a owl:ObjectProperty ; rdfs:subPropertyOf :r .
:t a owl:ObjectProperty ; rdfs:domain :E .
"""


def test_a_conclusion_implied_only_through_itself_is_still_drawn() -> None:
    # D ⊑ C: the writer of D (q's domain) implies C only through D ⊑ C itself, so that rule reads every D
    onto = loaded(CHAIN + ":a :q :b .")
    assert onto.reason().consistent
    assert {"C", "D"} <= {onto.short(c) for c in onto.types("a")}


def test_asserted_facts_of_a_key_with_implied_writers_are_read() -> None:
    # r's domain E: its writer (r2 ⊑ r) has a body whose subject is an E by r2 ⊑ r ... only through r's own
    # domain, so nothing is restricted there; a key read alone in the asserted graph still finds them
    onto = loaded(CHAIN + ":a :r2 :b . :c :r :d . :e :t :f .")
    assert onto.reason().consistent
    assert {"a", "c", "e"} <= {onto.short(i) for i in onto.instances("E")}


@pytest.mark.parametrize("source", ["example", "tbox", "map"])
@pytest.mark.parametrize("shortcut", ["implied", "claims", "lean"])
def test_a_full_reason_reaches_the_same_closure_with_and_without_the_shortcuts(
        source: str, shortcut: str, monkeypatch: pytest.MonkeyPatch) -> None:
    """``implied``: first passes over the asserted facts alone; ``claims``: readers of a key the pass
    only claimed skipped when it has no fact after all; ``lean``: first passes without the class atoms
    another atom's key carries."""
    from benchmarks import maps
    from topostore.resources import default_ontology_files

    onto = Ontology()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", OntologyWarning)
        if source == "example":
            for path in default_ontology_files():
                onto.load(path)
        elif source == "tbox":
            onto.load_data(tbox.turtle(60), "turtle")
        else:
            import tempfile
            with tempfile.TemporaryDirectory() as tmp:
                path, _ = maps.write("200", Path(tmp))
                onto.load(path)
    onto.reason(mode="full")
    restricted = closure(onto)
    ordered = list(range(len(onto.rules.inference_rules)))
    assert implied_first_passes(onto.rules.inference_rules, ordered) or source == "tbox"
    if shortcut == "implied":
        monkeypatch.setattr(full_passes, "implied_first_passes", lambda rules, ordered, asserted=None: set())
    elif shortcut == "lean":
        assert implied_atoms(onto.rules.inference_rules, without_same_as(onto.rules.inference_rules),
                             (set(), set())) or source == "tbox"
        monkeypatch.setattr(full_passes, "implied_atoms", lambda rules, ordered, asserted: {})
    else:
        monkeypatch.setattr(first_pass, "claims_hold", lambda run, i: True)
    onto.reason(mode="full")
    assert closure(onto) == restricted


def test_on_the_map_the_links_domain_reads_the_asserted_links_alone() -> None:
    from topostore.resources import default_ontology_files

    onto = Ontology()
    for path in default_ontology_files():
        onto.load(path)
    rules = onto.rules.inference_rules
    chosen = {rules[i].origin for i in implied_first_passes(rules, list(range(len(rules))))}
    assert "connectedTo domain LOCATION" in chosen  # written by Connectability, whose doors say LOCATION
    assert "hasDoor domain LOCATION" not in chosen  # asserted only: it is what the others rest on


# ---------------------------------------------------------------- class atoms another atom carries

def test_on_the_map_no_intersection_is_left_to_read_location() -> None:
    """ROOM ≡ LOCATION ⊓ ∃hasDoor.DOOR and CORRIDOR ≡ LOCATION ⊓ ≥2 hasDoor.DOOR: hasDoor's domain is
    LOCATION, so the restrictions are ROOM and CORRIDOR themselves (compile/fold.py) and no first pass
    of an intersection copies them; what implies LOCATION is still read off the rules."""
    from topostore.resources import default_ontology_files

    onto = Ontology()
    for path in default_ontology_files():
        onto.load(path)
    rules = onto.rules.inference_rules
    assert not [r for r in rules if r.name == "cls-int1" and r.head.o.endswith(("#ROOM>", "#CORRIDOR>"))]
    # a key with an asserted fact carries nothing: an asserted member need not be a LOCATION
    ordered = without_same_as(rules)
    room = ("t", "<" + MAP_NS + "ROOM>")
    assert "<" + MAP_NS + "LOCATION>" in subject_classes(rules, ordered, (set(), set()))[room]
    assert room not in subject_classes(rules, ordered, (set(), {room[1]}))
    # eq-rep-s writes any class: where owl:sameAs may hold (it is ordered), no class key carries anything
    assert not implied_atoms(rules, list(range(len(rules))), (set(), set()))


def without_same_as(rules: list) -> list[int]:
    """The rules a full REASON orders first on a map without owl:sameAs (eq-rep-s cannot fire there)."""
    return [i for i, r in enumerate(rules) if r.stratum == 0 and not any("sameAs" in a.p for a in r.body)]


MAP_NS = "http://bnc/exp-rob-lab/2022-23#"
LEAN = PREFIXES + """:p a owl:ObjectProperty ; rdfs:domain :A . :q a owl:ObjectProperty ; rdfs:domain :B .
:X owl:equivalentClass [ a owl:Class ; owl:intersectionOf ( :A [ a owl:Restriction ; owl:onProperty :p ;
    owl:someValuesFrom owl:Thing ] ) ] .
:Y owl:equivalentClass [ a owl:Class ; owl:intersectionOf ( :B [ a owl:Restriction ; owl:onProperty :p ;
    owl:someValuesFrom owl:Thing ] ) ] .
"""


@pytest.mark.parametrize(("data", "members"), [
    (":a :p :b .", {"X": {"a"}, "Y": set()}),  # p's domain A: the restriction vouches for A, not for B
    (":a :p :b . :a :q :c .", {"X": {"a"}, "Y": {"a"}}),
    (":a :q :c . :b :p :c .", {"X": {"b"}, "Y": set()}),
])
def test_a_left_out_atom_is_one_every_writer_of_the_other_implies(data: str, members: dict) -> None:
    onto = loaded(LEAN + data)
    assert onto.reason(mode="full").consistent
    assert {c: {onto.short(i) for i in onto.instances(c)} for c in members} == members


def test_an_asserted_member_of_the_witness_keeps_the_atom() -> None:
    # Z ⊑ the restriction by an axiom, and :z asserted a Z: its membership is written by a rule whose body
    # (Z) says nothing of A, so X's first pass must still ask for A; z is in A by p's domain all the same
    # (ext-domain: its p value is unnamed), so in X, as Pellet answers
    onto = loaded(LEAN + ":Z rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :p ; owl:someValuesFrom owl:Thing ] ."
                  ":z a :Z . :a :p :b .")
    assert onto.reason(mode="full").consistent
    assert {onto.short(i) for i in onto.instances("X")} == {"a", "z"}
    assert {onto.short(i) for i in onto.instances("Y")} == set()


# ---------------------------------------------------------------- checks pairing two values

INCONSISTENT = PREFIXES + """:d a owl:DatatypeProperty , owl:FunctionalProperty . :p a owl:ObjectProperty .
:M owl:equivalentClass [ a owl:Restriction ; owl:onProperty :p ; owl:maxCardinality 1 ] .
:x :d 1, 2 . :z :d 3 . :w :d 4, "4"^^xsd:int .
:y a :M ; :p :a, :b . :a owl:differentFrom :b . :v a :M ; :p :a .
"""


def test_a_check_pairing_two_values_reports_what_it_did_without_the_count(monkeypatch: pytest.MonkeyPatch) -> None:
    from topostore.reason import consistency

    onto = loaded(INCONSISTENT)
    report = onto.reason()
    assert not report.consistent
    texts = [consistency.check_text(r) for r in onto.rules.checks]
    assert any("HAVING (COUNT(DISTINCT ?several_value) > 1)" in t for t in texts)
    found = sorted(str(v) for v in consistency.check_consistency(onto.store, onto.rules))
    assert any("x" in v for v in found) and any("y" in v for v in found)
    monkeypatch.setattr(consistency, "several_values", lambda rule, graphs: [])
    assert sorted(str(v) for v in consistency.check_consistency(onto.store, onto.rules)) == found


# ---------------------------------------------------------------- a disjointness check's classes, fewest members first

NS = "http://example.org/card#"
DISJOINT = PREFIXES + """:A a owl:Class . :B a owl:Class . :A owl:disjointWith :B .
:a1 a :A . :a2 a :A . :a3 a :A . :both a :A , :B .
"""


def test_a_disjointness_check_reads_its_smaller_class_first_and_reports_the_same(
        monkeypatch: pytest.MonkeyPatch) -> None:
    from topostore.reason import consistency

    onto = loaded(DISJOINT)
    assert not onto.reason().consistent
    check = next(r for r in onto.rules.checks if sorted(a.o for a in r.body) == [f"<{NS}A>", f"<{NS}B>"])
    ordered = consistency.small_first(onto.store, check, {})
    assert [a.o[-2] for a in ordered.body] == ["B", "A"]  # one B against four A
    found = sorted(str(v) for v in consistency.check_consistency(onto.store, onto.rules))
    assert any("both" in v for v in found)
    monkeypatch.setattr(consistency, "small_first", lambda store, rule, graphs: rule)
    assert sorted(str(v) for v in consistency.check_consistency(onto.store, onto.rules)) == found
