"""A named class equivalent to an anonymous class expression stands for it in the rules
(compile/fold.py): the same members, no helper membership of the expression."""

from __future__ import annotations

import warnings

from pyoxigraph import NamedNode

from topostore import Ontology, OntologyWarning
from topostore.compile.fold import fold_equivalents
from topostore.rdf.vocab import AUX, TYPE, is_skolem
from topostore.resources import default_ontology_files

PREFIXES = """@prefix : <http://e.org/k#> . @prefix owl: <http://www.w3.org/2002/07/owl#> .
@prefix rdfs: <http://www.w3.org/2000/01/rdf-schema#> .
<http://e.org/k> a owl:Ontology . :has a owl:ObjectProperty . :Part a owl:Class . :Thing2 a owl:Class .
:Whole owl:equivalentClass [ a owl:Class ; owl:intersectionOf ( :Thing2
                             [ a owl:Restriction ; owl:onProperty :has ; owl:someValuesFrom :Part ] ) ] .
"""


def load(text: str) -> Ontology:
    o = Ontology()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", OntologyWarning)
        o.load_data(PREFIXES + text)
    assert o.reason().consistent
    return o


def members(o: Ontology, name: str) -> list[str]:
    return sorted(o.short(x) for x in o.instances(name))


def anonymous_memberships(o: Ontology) -> int:
    return sum(1 for t in o.store.triples(None, TYPE, None, AUX) if is_skolem(t.object))


def test_the_named_class_stands_for_its_equivalent_expression() -> None:
    o = load(":w a :Thing2 ; :has :p . :p a :Part . :v a :Thing2 .")
    assert members(o, "Whole") == ["w"]
    # only the restriction inside the intersection keeps a helper membership
    assert anonymous_memberships(o) == 1
    written = {a.o for r in o.rules.all_rules if r.head is not None for a in (*r.body, r.head) if a.p == str(TYPE)}
    intersection = [t for t in written if is_skolem(t[1:-1]) and any(
        r.name == "cls-int1" and r.head.o == t for r in o.rules.all_rules)]
    assert not intersection  # cls-int1 concludes Whole itself


def test_a_member_of_the_named_class_gets_the_expression_parts() -> None:
    o = load(":w a :Whole .")
    assert members(o, "Thing2") == ["w"]


def test_a_membership_of_the_expression_told_in_the_data_still_counts() -> None:
    o = load(":w a :Thing2 .")
    rules = o.rules.all_rules
    bridge = [r for r in rules if r.name == "cax-eqc2"]
    assert bridge and is_skolem(bridge[0].body[0].o[1:-1])
    anon = NamedNode(bridge[0].body[0].o[1:-1])
    o.add_type("v", anon)
    assert o.reason().consistent
    assert members(o, "Whole") == ["v"]


def test_two_named_equivalents_of_one_expression_are_not_folded() -> None:
    text = ("_:e a owl:Class ; owl:intersectionOf ( :Thing2 [ a owl:Restriction ; owl:onProperty :has ; "
            "owl:someValuesFrom :Part ] ) . :A owl:equivalentClass _:e . :B owl:equivalentClass _:e . "
            ":w a :Thing2 ; :has :p . :p a :Part . :v a :A .")
    o = load(text)
    assert members(o, "A") == members(o, "B") == ["v", "w"]
    assert members(o, "Thing2") == ["v", "w"]
    assert any(r.name == "cax-eqc1" and is_skolem(r.head.o[1:-1]) for r in o.rules.all_rules)


def test_the_tutorial_map_keeps_its_answers_without_the_helper_memberships() -> None:
    o = Ontology.from_file(*default_ontology_files())
    assert o.reason().consistent
    expected = {"ROOM": ["C1", "R1", "R2"], "CORRIDOR": ["C1"], "LOCATION": ["C1", "R1", "R2"], "URGENT": ["R1"],
                "ROBOT": ["Robot1"], "DOOR": ["D1", "D2"]}
    assert {c: members(o, c) for c in expected} == expected
    # LOCATION (visitedAt exactly 1), ROBOT (isIn exactly 1), ROOM and CORRIDOR (intersections) stand for
    # their expressions, and the restrictions inside the intersections (∃hasDoor, ≥ 2 hasDoor: hasDoor's
    # domain is LOCATION, the intersections' other part) for ROOM and CORRIDOR
    assert anonymous_memberships(o) == 0  # was 12: 3 + 3 + 3 + 1 + 1 + 1, then 4
    assert not any(r.name == "cax-eqc1" and is_skolem(r.head.o[1:-1]) for r in o.rules.all_rules)
    assert fold_equivalents(o.rules.all_rules) == o.rules.all_rules  # nothing left to fold


DOMAIN = ":has rdfs:domain :Thing2 . "


def test_a_restriction_implying_the_other_part_of_its_intersection_stands_for_the_named_class() -> None:
    """``Whole ≡ Thing2 ⊓ ∃has.Part`` with ``has``'s domain Thing2: every ∃has.Part is a Thing2, so
    ∃has.Part is Whole itself; cls-svf1 concludes Whole, no helper membership is written."""
    o = load(DOMAIN + ":w :has :p . :p a :Part . :u :has :q . :v a :Whole .")
    assert members(o, "Whole") == ["v", "w"]
    assert members(o, "Thing2") == ["u", "v", "w"]
    assert anonymous_memberships(o) == 0
    assert not any(r.name == "cls-int1" for r in o.rules.all_rules)  # it concluded what it read


def test_a_restriction_is_kept_where_its_property_says_nothing_of_the_other_part() -> None:
    """Without the domain, ∃has.Part holds of things that are no Thing2: its membership stays."""
    o = load(":w a :Thing2 ; :has :p . :p a :Part . :u :has :q . :q a :Part .")
    assert members(o, "Whole") == ["w"]
    assert anonymous_memberships(o) == 2


def test_an_inverse_restriction_reads_the_range() -> None:
    """``Whole ≡ Thing2 ⊓ ∃has⁻.Part`` stands for its restriction where ``has``'s range is Thing2."""
    text = ("<http://e.org/k> a owl:Ontology . :has a owl:ObjectProperty ; rdfs:range :Thing2 . :Part a owl:Class . "
            ":Thing2 a owl:Class . :Whole owl:equivalentClass [ a owl:Class ; owl:intersectionOf ( :Thing2 "
            "[ a owl:Restriction ; owl:onProperty [ owl:inverseOf :has ] ; owl:someValuesFrom :Part ] ) ] . "
            ":p a :Part ; :has :w . :q :has :u .")
    o = Ontology()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", OntologyWarning)
        o.load_data(PREFIXES.split("<http://e.org/k>")[0] + text)
    assert o.reason().consistent
    assert members(o, "Whole") == ["w"]
    assert members(o, "Thing2") == ["u", "w"]
    assert anonymous_memberships(o) == 0


def _told_copies(o: Ontology, name: str) -> list[str]:
    """The anonymous classes copied into class ``name`` by a one-atom rule (nodes are named anew by each load)."""
    return sorted(r.body[0].o[1:-1] for r in o.rules.all_rules
                  if r.name == "cax-eqc2" and r.head.o == f"<http://e.org/k#{name}>" and is_skolem(r.body[0].o[1:-1]))


def test_a_membership_of_the_restriction_told_later_gives_the_named_class() -> None:
    """The intersection's rule leaves a copy ``∃has.Part(x) ⟹ Whole(x)`` behind: an individual typed with
    the restriction's node after the load is a Whole, and so a Thing2 (``has``'s domain)."""
    assert len(_told_copies(load(DOMAIN), "Whole")) == 2  # the intersection's node, and the restriction's
    for n in range(2):
        o = load(DOMAIN + ":w :has :p . :p a :Part .")
        o.add_type("v", NamedNode(_told_copies(o, "Whole")[n]))
        assert o.reason().consistent
        assert members(o, "Whole") == members(o, "Thing2") == ["v", "w"]


def test_a_swrl_rule_in_place_of_the_domain_keeps_the_restriction() -> None:
    """A DL-safe rule ``has(?x, ?y) -> Thing2(?x)`` says nothing of a value only known to exist: the
    restriction is not read as Whole, its membership stays."""
    o = load(":w :has :p . :p a :Part .")
    o.add_rule("has(?x, ?y) -> Thing2(?x)", "HasThing")
    assert o.reason().consistent
    assert members(o, "Whole") == ["w"]
    assert anonymous_memberships(o) == 1
