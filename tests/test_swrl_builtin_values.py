"""SWRL built-ins hold only on data values they can compute with, as Pellet evaluates them.

Pellet's answers for the same rules are checked in tests/test_fidelity_pellet.py (``swrl_builtins``);
these tests run without Java, in full and incremental REASONs alike.
"""

from __future__ import annotations

import warnings

import pytest
from test_incremental import from_scratch

from topostore import Ontology, OntologyWarning
from topostore.errors import RuleCompileError
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


#: swrlb:date and swrlb:dateTime split a calendar value (Pellet's answers: tests/test_fidelity_pellet.py, swrl_calendar)
CALENDAR_RULES = {
    "Year2020": "d(?x, ?t) ^ swrlb:date(?t, 2020, ?m, ?day, ?tz) -> Year2020(?x)",
    "NoHour": "d(?x, ?t) ^ swrlb:dateTime(?t, ?y, ?m, ?day, -2147483648, ?mi, ?s) -> NoHour(?x)",
    "PlusTwo": 'd(?x, ?t) ^ swrlb:date(?t, ?y, ?m, ?day, "+02:02d") -> PlusTwo(?x)',
    "AnyZone": "d(?x, ?t) ^ swrlb:dateTime(?t, ?y, ?m, ?day, ?h, ?mi, ?s, ?tz) -> AnyZone(?x)",
    "Later": "d(?x, ?t) ^ swrlb:date(?t, ?y, ?m, ?day) ^ swrlb:greaterThan(?y, 2019) -> Later(?x)",
}
CALENDAR_FACTS = (":d a owl:DatatypeProperty . :y a owl:DatatypeProperty . :z a owl:DatatypeProperty . "
                  + " ".join(f":{c} a owl:Class ." for c in CALENDAR_RULES)
                  + ' :instant :d "2020-01-01T07:00:00Z"^^xsd:dateTime . :day :d "2020-03-01"^^xsd:date .'
                  ' :zoned :d "2021-12-31T23:59:30.50+02:00"^^xsd:dateTime . :text :d "2020-01-01" .')


def test_date_and_date_time_split_a_calendar_value_as_pellet() -> None:
    o = ontology(CALENDAR_FACTS, CALENDAR_RULES)
    assert o.reason().consistent
    assert members(o, "Year2020") == {"instant", "day"}
    assert members(o, "NoHour") == {"day"}  # a date has no hour: Java's FIELD_UNDEFINED
    assert members(o, "PlusTwo") == {"zoned"}  # Pellet's time zone string
    assert members(o, "AnyZone") == {"instant", "zoned"}  # no time zone: an unbound one fails
    assert members(o, "Later") == {"instant", "day", "zoned"}


def test_the_parts_bound_into_data_values() -> None:
    o = ontology(CALENDAR_FACTS, {"Parts": 'd(?x, ?t) ^ swrlb:dateTime(?t, ?y, ?m, ?day, ?h, ?mi, ?s, ?tz) '
                                           '-> y(?x, ?s) ^ z(?x, ?tz)'})
    assert o.reason().consistent
    assert {str(v) for v in o.data_values("y", "zoned")} == {'"30.5"^^<http://www.w3.org/2001/XMLSchema#decimal>'}
    assert {str(v) for v in o.data_values("z", "zoned")} == {'"+02:02d"'}


def test_an_incremental_reason_splits_calendar_values_as_from_scratch() -> None:
    o = ontology(CALENDAR_FACTS, CALENDAR_RULES)
    assert o.reason().consistent
    o.load_data(PREFIXES + ':late :d "2019-07-04T07:00:00-05:30"^^xsd:dateTime . :gone :d "2024"^^xsd:gYear .')
    o.remove_individual("day")
    report = o.reason()
    assert report.consistent and report.stats.mode == "incremental"
    assert members(o, "NoHour") == {"gone"} and members(o, "AnyZone") == {"instant", "zoned", "late"}
    inferred, _aux, _entailed, _ok = from_scratch(o)
    assert set(o.store.triples(graph=INFERRED)) == inferred


@pytest.mark.parametrize("rule,why", [
    ('d(?x, ?v) ^ swrlb:date(?t, 2020, 1, 1, "Z") -> Built(?x)', "unbound first argument"),
    ('d(?x, ?t) ^ swrlb:dateTime(?t, 2020, 1, 1, 7, 0, 0, "Z") -> Built(?x)', "every part bound"),
    ("d(?x, ?t) ^ swrlb:date(?t, ?y, ?n, ?n) -> Built(?x)", "two unbound parts"),
    ("d(?x, ?t) ^ swrlb:date(?t, ?y, ?m) -> Built(?x)", "takes 4 or 5 arguments"),
])
def test_the_forms_pellet_builds_a_value_for_are_not_translated(rule: str, why: str) -> None:
    """Where Pellet builds the value from the parts (or stops), the rule is refused; a loaded one is set aside
    with its notice (the same RuleCompileError)."""
    o = ontology(CALENDAR_FACTS + " :Built a owl:Class .", {})
    with pytest.raises(RuleCompileError, match=why):
        o.add_rule(rule, "Built")
    assert o.rule_labels() == [] and o.reason().consistent and members(o, "Built") == set()
