"""SWRL built-ins hold only on data values they can compute with, as Pellet evaluates them.

Pellet's answers for the same rules are checked in tests/test_fidelity_pellet.py (``swrl_builtins``);
these tests run without Java, in full and incremental REASONs alike.
"""

from __future__ import annotations

import warnings

from test_incremental import from_scratch

from topostore import Ontology, OntologyWarning
from topostore.rdf.vocab import INFERRED

NS = "http://example.org/b#"
PREFIXES = f"""@prefix : <{NS}> . @prefix owl: <http://www.w3.org/2002/07/owl#> .
@prefix xsd: <http://www.w3.org/2001/XMLSchema#> .
"""


def ontology(facts: str, rules: dict[str, str]) -> Ontology:
    """An ontology of ``facts`` and the text ``rules`` (label: rule), not yet reasoned."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", OntologyWarning)
        o = Ontology(prefix=NS)
        o.load_data(PREFIXES + facts)
        for label, text in rules.items():
            o.add_rule(text, label)
    return o


def members(o: Ontology, name: str) -> set[str]:
    return {i.value.removeprefix(NS) for i in o.instances(name)}


ERRORS = {
    "Added": "d(?x, ?v) ^ swrlb:add(?z, ?v, 1) -> Added(?x)",
    "Divided": "d(?x, ?v) ^ swrlb:divide(?z, ?v, 0) -> Divided(?x)",
    "Upper": "d(?x, ?v) ^ swrlb:upperCase(?u, ?v) -> Upper(?x)",
}
ERROR_FACTS = ":d a owl:DatatypeProperty . :a :d \"abc\" . :b :d 4 . :c :d 2.5 . " + " ".join(
    f":{c} a owl:Class ." for c in ERRORS)


def test_a_built_in_whose_value_is_an_error_does_not_fire_its_rule() -> None:
    o = ontology(ERROR_FACTS, ERRORS)
    assert o.reason().consistent
    assert members(o, "Added") == {"b", "c"}  # "abc" + 1 is an error
    assert members(o, "Divided") == set()  # a division of an integer or a decimal by 0 is an error
    assert members(o, "Upper") == {"a", "b", "c"}


def test_an_incremental_reason_keeps_a_built_in_error_from_firing() -> None:
    o = ontology(ERROR_FACTS, ERRORS)
    assert o.reason().consistent
    o.load_data(PREFIXES + ':e :d "xyz" . :f :d 7 .')
    report = o.reason()
    assert report.consistent and report.stats.mode == "incremental"
    assert members(o, "Added") == {"b", "c", "f"}
    inferred, _aux, _entailed, _ok = from_scratch(o)
    assert set(o.store.triples(graph=INFERRED)) == inferred


def test_a_built_in_on_an_individual_is_false() -> None:
    o = ontology(":D a owl:Class . :Named a owl:Class . :Itself a owl:Class . :Kept a owl:Class . "
                 ":AtMost a owl:Class . :Length a owl:Class . "
                 ":d a owl:DatatypeProperty . :a a :D ; :d \"example\" . :b a :D .", {
                     "Named": 'D(?x) ^ swrlb:contains(?x, "example") -> Named(?x)',
                     "Itself": "D(?x) ^ D(?y) ^ swrlb:equal(?x, ?y) -> Itself(?x)",
                     "AtMost": "D(?x) ^ swrlb:lessThanOrEqual(?x, ?x) -> AtMost(?x)",
                     "Length": "D(?x) ^ swrlb:stringLength(?n, ?x) -> Length(?x)",
                     "Kept": 'D(?x) ^ d(?x, ?v) ^ swrlb:contains(?v, "example") -> Kept(?x)',
                 })
    assert o.reason().consistent
    assert members(o, "Named") == set()  # the IRI's text is not a data value
    assert members(o, "Itself") == set()
    assert members(o, "AtMost") == members(o, "Length") == set()
    assert members(o, "Kept") == {"a"}


def test_string_built_ins_read_a_number_s_lexical_form() -> None:
    o = ontology(":d a owl:DatatypeProperty . :Three a owl:Class . :Two a owl:Class . "
                 ':a :d 123 . :b :d "123" . :c :d 2.5 . :e :d "ab"@en .', {
                     "Three": "d(?x, ?v) ^ swrlb:stringLength(?n, ?v) ^ swrlb:equal(?n, 3) -> Three(?x)",
                     "Two": "d(?x, ?v) ^ swrlb:stringLength(2, ?v) -> Two(?x)",
                 })
    assert o.reason().consistent
    assert members(o, "Three") == {"a", "b", "c"}
    assert members(o, "Two") == {"e"}


def test_matches_takes_the_whole_string_and_ignores_flags() -> None:
    o = ontology(":d a owl:DatatypeProperty . :p a owl:DatatypeProperty . "
                 + " ".join(f":{c} a owl:Class ." for c in ("Part", "Either", "Whole", "Own", "Caseless", "Given"))
                 + ' :a :d "Hello" ; :p "H.*" . :b :d "ell" ; :p "e" .', {
                     "Part": 'd(?x, ?v) ^ swrlb:matches(?v, "ell") -> Part(?x)',
                     "Either": 'd(?x, ?v) ^ swrlb:matches(?v, "H|o") -> Either(?x)',
                     "Whole": 'd(?x, ?v) ^ swrlb:matches(?v, "H.*|e.*") -> Whole(?x)',
                     "Own": 'd(?x, ?v) ^ swrlb:matches(?v, "^H.*o$") -> Own(?x)',
                     "Caseless": 'd(?x, ?v) ^ swrlb:matches(?v, "hello", "i") -> Caseless(?x)',
                     "Given": "d(?x, ?v) ^ p(?x, ?r) ^ swrlb:matches(?v, ?r) -> Given(?x)",
                 })
    assert o.reason().consistent
    assert members(o, "Part") == {"b"}
    assert members(o, "Either") == set()
    assert members(o, "Whole") == {"a", "b"}
    assert members(o, "Own") == {"a"}
    assert members(o, "Caseless") == set()
    assert members(o, "Given") == {"a"}


#: Pellet's testers compare numbers by Java's compareTo (checked against Pellet through the OWL API: Owlready2
#: hands Pellet a Python float, not the literal "NaN"): NaN equals NaN, float or double, and is above every other
#: number, INF included; never comparable with a value of another kind
COMPARISONS = {"Eq": "equal", "Ne": "notEqual", "Lt": "lessThan", "Le": "lessThanOrEqual", "Gt": "greaterThan",
               "Ge": "greaterThanOrEqual"}
NAN_PAIRS = {"dd": ('"NaN"^^xsd:double', '"NaN"^^xsd:double', 0), "fd": ('"NaN"^^xsd:float', '"NaN"^^xsd:double', 0),
             "dn": ('"NaN"^^xsd:double', "5", 1), "nf": ('"2.5"^^xsd:decimal', '"NaN"^^xsd:float', -1),
             "fi": ('"NaN"^^xsd:float', '"INF"^^xsd:double', 1), "ds": ('"NaN"^^xsd:double', '"NaN"', None)}


def _holds(label: str, order: int | None) -> bool:
    """Whether comparison ``label`` holds of two values ``order`` (compareTo's sign; None: not comparable)."""
    if order is None:
        return label == "Ne"
    return {"Eq": order == 0, "Ne": order != 0, "Lt": order < 0, "Le": order <= 0, "Gt": order > 0,
            "Ge": order >= 0}[label]


def test_comparisons_with_nan_follow_javas_compare_to_as_pellet() -> None:
    rules = {c: f"d(?x, ?v) ^ e(?x, ?w) ^ swrlb:{op}(?v, ?w) -> {c}(?x)" for c, op in COMPARISONS.items()}
    rules |= {"Above": "d(?x, ?v) ^ swrlb:greaterThan(?v, 5) -> Above(?x)",  # a constant: NaN is above it
              "Below": "d(?x, ?v) ^ swrlb:lessThanOrEqual(5, ?v) -> Below(?x)"}
    facts = ":d a owl:DatatypeProperty . :e a owl:DatatypeProperty . " + " ".join(
        f":{n} :d {a} ; :e {b} ." for n, (a, b, _) in NAN_PAIRS.items()) + " ".join(f" :{c} a owl:Class ." for c in rules)
    o = ontology(facts, rules)
    assert o.reason().consistent
    for label in COMPARISONS:
        assert members(o, label) == {n for n, (_, _, order) in NAN_PAIRS.items() if _holds(label, order)}, label
    assert members(o, "Above") == members(o, "Below") == set(NAN_PAIRS) - {"nf"}  # each d a NaN but nf's 2.5
    inferred, _aux, _entailed, _ok = from_scratch(o)
    assert set(o.store.triples(graph=INFERRED)) == inferred


def test_comparisons_with_a_nan_constant_follow_javas_compare_to_as_pellet() -> None:
    """A NaN written as the constant argument orders and equates as one read from the graph: compareTo(NaN, NaN)
    is 0, so lessThan("NaN", NaN) and greaterThan(NaN, "NaN") are false, equal true."""
    nan = '"NaN"^^xsd:double'
    rules = {f"{c}R": f"d(?x, ?v) ^ swrlb:{op}(?v, {nan}) -> {c}R(?x)" for c, op in COMPARISONS.items()}
    rules |= {f"{c}L": f"d(?x, ?v) ^ swrlb:{op}({nan}, ?v) -> {c}L(?x)" for c, op in COMPARISONS.items()}
    values = {"n1": ('"NaN"^^xsd:double', 0), "n2": ('"NaN"^^xsd:float', 0), "low": ('"2.5"^^xsd:decimal', -1),
              "inf": ('"INF"^^xsd:double', -1)}
    facts = ":d a owl:DatatypeProperty . " + " ".join(f":{n} :d {v} ." for n, (v, _) in values.items()) + " ".join(
        f" :{c} a owl:Class ." for c in rules)
    o = ontology(facts, rules)
    assert o.reason().consistent
    for label in COMPARISONS:
        assert members(o, f"{label}R") == {n for n, (_, order) in values.items() if _holds(label, order)}, label
        assert members(o, f"{label}L") == {n for n, (_, order) in values.items() if _holds(label, -order)}, label
    inferred, _aux, _entailed, _ok = from_scratch(o)
    assert set(o.store.triples(graph=INFERRED)) == inferred
