"""Two literal values of a functional data property (or under a maximum of one): Pellet 2.3.1 against OWL 2.

The matrix below was measured through Pellet 2.3.1 itself (Owlready2); the tests that run Pellet check it
again, so a table that stops describing Pellet fails.  OWL 2 (Direct Semantics) makes two literals of
different values two values, and one subject may hold only one: inconsistent.  Pellet 2.3.1 finds two values
different only within one class of its datatype reasoner (integers of one magnitude, decimals with a fraction,
floats, doubles, booleans, dates and times, strings, strings of one language tag:
:mod:`topostore.ontology.pellet_values`) and otherwise misses the clash; there topostore follows OWL 2 and
says so (:class:`~topostore.PelletDifferenceWarning`).  Where Pellet agrees, the case is a differential case.
"""

from __future__ import annotations

import warnings

import pytest
from fidelity_cases import document, namespace
from pyoxigraph import Literal, NamedNode, RdfFormat, Triple, parse
from support import NEEDS_PELLET
from test_fidelity_pellet import loaded, pellet

from topostore import Ontology, PelletDifferenceWarning
from topostore.ontology.pellet_values import told_apart
from topostore.rdf.vocab import XSD

#: name -> (one value, another, whether Pellet 2.3.1 tells them apart, whether they are one value in topostore)
#: (values of different value in OWL 2 unless the last is true)
MATRIX: dict[str, tuple[str, str, bool, bool]] = {
    # one class of Pellet's, two values: both inconsistent
    "two_strings": ('"a"', '"b"', True, False),
    "int_and_long": ('"1"^^xsd:int', '"2"^^xsd:long', True, False),
    "two_shorts": ("300", "400", True, False),
    "two_ints_of_one_magnitude": ("1665579711", "1665579710", True, False),
    "integer_and_whole_decimal": ("1", '"2.0"^^xsd:decimal', True, False),
    "two_decimals": ('"1.5"^^xsd:decimal', '"2.5"^^xsd:decimal', True, False),
    "non_negative_and_integer": ('"1"^^xsd:nonNegativeInteger', '"2"^^xsd:integer', True, False),
    "two_floats": ('"1.5"^^xsd:float', '"2.5"^^xsd:float', True, False),
    "two_doubles": ('"1.5"^^xsd:double', '"2.5"^^xsd:double', True, False),
    "two_booleans": ("true", "false", True, False),
    "two_instants": ('"2020-01-01T12:00:00Z"^^xsd:dateTime', '"2020-01-01T13:00:00Z"^^xsd:dateTime', True, False),
    "date_time_and_date": ('"2020-01-01T00:00:00Z"^^xsd:dateTime', '"2020-01-02"^^xsd:date', True, False),
    "two_dates": ('"2020-01-01"^^xsd:date', '"2020-01-02"^^xsd:date', True, False),
    "string_and_token": ('"x"', '"y"^^xsd:token', True, False),
    "string_and_normalized_string": ('"x"', '"y"^^xsd:normalizedString', True, False),
    "string_and_any_uri": ('"x"', '"http://x"^^xsd:anyURI', True, False),
    "two_any_uris": ('"http://a"^^xsd:anyURI', '"http://b"^^xsd:anyURI', True, False),
    "one_language_tag": ('"a"@en', '"b"@en', True, False),
    "string_and_any_uri_of_one_text": ('"a"', '"a"^^xsd:anyURI', True, False),
    # one value, spelled twice: both consistent
    "plain_and_xsd_string": ('"a"', '"a"^^xsd:string', False, True),
    "integer_and_equal_decimal": ("1", '"1.0"^^xsd:decimal', False, True),
    "int_and_equal_long": ('"1"^^xsd:int', '"1"^^xsd:long', False, True),
    "tag_in_two_cases": ('"a"@en', '"a"@EN', False, True),
    # the value spaces of xsd:string's derived types are subsets of its own: "a"^^xsd:token is the string "a"
    "string_and_equal_token": ('"a"', '"a"^^xsd:token', False, True),
    "string_and_equal_normalized_string": ('"a"', '"a"^^xsd:normalizedString', False, True),
    "string_and_equal_language": ('"en"', '"en"^^xsd:language', False, True),
    "name_and_equal_ncname": ('"x"^^xsd:Name', '"x"^^xsd:NCName', False, True),
    "one_instant_in_two_zones": ('"2020-01-01T12:00:00Z"^^xsd:dateTime',
                                 '"2020-01-01T14:00:00+02:00"^^xsd:dateTime', False, True),
    # two values in OWL 2 (the value spaces of double, float and owl:real are disjoint), one value to
    # Pellet and topostore alike, both compare numbers across them by value: consistent, a documented difference
    # with OWL 2 (docs/reasoning.md)
    "double_and_equal_integer": ('"1.0"^^xsd:double', "1", False, True),
    "double_and_equal_float": ('"1.5"^^xsd:double', '"1.5"^^xsd:float', False, True),
    # two classes of Pellet's: OWL 2 and topostore inconsistent, Pellet consistent
    "integer_and_string": ("5", '"five"', False, False),
    "integer_and_its_digits": ("5", '"5"', False, False),
    "integer_and_decimal": ("1", '"1.5"^^xsd:decimal', False, False),
    "byte_and_short": ("5", "300", False, False),
    "byte_and_int": ("5", "1665579710", False, False),
    "byte_and_long": ("5", "16655797100000", False, False),
    "integer_and_double": ("1", '"2.0"^^xsd:double', False, False),
    "double_and_float": ('"1.5"^^xsd:double', '"2.5"^^xsd:float', False, False),
    "integer_and_boolean": ("1", "true", False, False),
    "string_and_boolean": ('"x"', "true", False, False),
    "date_time_and_integer": ('"2020-01-01T12:00:00Z"^^xsd:dateTime', "5", False, False),
    "two_language_tags": ('"a"@en', '"a"@fr', False, False),
    "two_tags_two_texts": ('"a"@en', '"b"@fr', False, False),
    "tag_and_plain": ('"a"@en', '"a"', False, False),
    "tag_and_plain_two_texts": ('"a"@en', '"b"', False, False),
    # one value in OWL 2 (xsd:NMTOKEN's values are strings), two to Pellet 2.3.1, which does not read NMTOKEN as a
    # string type: consistent in topostore, inconsistent in Pellet (docs/reasoning.md)
    "string_and_equal_nmtoken": ('"a"', '"a"^^xsd:NMTOKEN', True, True),
}


def functional(a: str, b: str) -> str:
    return f":d a owl:DatatypeProperty, owl:FunctionalProperty .\n:x a owl:NamedIndividual ; :d {a}, {b} .\n"


def maximum(kind: str) -> object:
    def text(a: str, b: str) -> str:
        return (f""":d a owl:DatatypeProperty . :C a owl:Class ; rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :d ;
    owl:{kind} "1"^^xsd:nonNegativeInteger ] .\n:x a owl:NamedIndividual, :C ; :d {a}, {b} .\n""")
    return text


def same_individual(a: str, b: str) -> str:
    return (f":d a owl:DatatypeProperty, owl:FunctionalProperty .\n:x a owl:NamedIndividual ; :d {a} .\n"
            f":y a owl:NamedIndividual ; :d {b} ; owl:sameAs :x .\n")


def ranged(datatype: str) -> object:
    def text(a: str, b: str) -> str:
        return (f":d a owl:DatatypeProperty, owl:FunctionalProperty ; rdfs:range {datatype} .\n"
                f":x a owl:NamedIndividual ; :d {a}, {b} .\n")
    return text


#: the forms the matrix is given in: each value pair as a functional property's; three pairs (one of each
#: verdict) as a maximum of one, an exact one, values of two individuals told the same, and under ranges
FORMS = {"functional": functional, "max_1": maximum("maxCardinality"), "exactly_1": maximum("cardinality"),
         "same_as": same_individual, "range_literal": ranged("rdfs:Literal"), "range_decimal": ranged("xsd:decimal")}
FEW = ("two_strings", "integer_and_equal_decimal", "integer_and_string")


def cases() -> dict[str, tuple[str, bool, bool]]:
    """name -> (Turtle body, Pellet consistent, topostore consistent)."""
    out = {}
    for form, text in FORMS.items():
        for pair in MATRIX if form == "functional" else FEW:
            a, b, apart, one = MATRIX[pair]
            out[f"{pair}_{form}"] = (text(a, b), not apart, one)
    return out


CASES = cases()
#: ranges that decide on their own in Pellet: one of a string catches the integer (the value Pellet kept of the
#: two it merged), one of an integer lets the string through (the one value checked is the integer)
CASES["integer_and_string_range_string"] = (ranged("xsd:string")("5", '"five"'), False, False)
CASES["integer_and_string_range_integer"] = (ranged("xsd:integer")("5", '"five"'), True, False)
#: a string and a token of the same text, one value: under a maximum, and as two individuals told the same
CASES["string_and_equal_token_max_1"] = (maximum("maxCardinality")('"a"', '"a"^^xsd:token'), True, True)
CASES["name_and_equal_ncname_same_as"] = (same_individual('"x"^^xsd:Name', '"x"^^xsd:NCName'), True, True)

AGREE_INCONSISTENT = [n for n, (_, theirs, ours) in CASES.items() if not theirs and not ours]
CONSISTENT = [n for n, (_, theirs, _) in CASES.items() if theirs]
#: one value in OWL 2 that Pellet 2.3.1 takes for two (docs/reasoning.md)
ONE_VALUE_IN_OWL_2 = [n for n, (_, theirs, ours) in CASES.items() if not theirs and ours]


def reasoned(name: str) -> tuple[bool, list[str]]:
    """topostore's verdict on the case, and the PelletDifferenceWarnings its REASON gave."""
    o = loaded(document(name, CASES[name][0]))
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        consistent = o.reason().consistent
    return consistent, [str(w.message) for w in caught if w.category is PelletDifferenceWarning]


@pytest.mark.external
@NEEDS_PELLET[0]
@NEEDS_PELLET[1]
@pytest.mark.parametrize("name", list(CASES))
def test_the_matrix_is_pellets(name: str) -> None:
    """Each case on its own (Pellet keeps one of two values it merges, chosen by the order it reads them in, so
    a document of several cases may answer otherwise than each alone)."""
    assert pellet(document(name, CASES[name][0]))["consistent"] == CASES[name][1]


@pytest.mark.parametrize("name", AGREE_INCONSISTENT)
def test_inconsistent_as_pellet(name: str) -> None:
    """Pellet finds the case inconsistent too: where it does not tell the two values apart (another axiom
    decided), the difference is still named, as the values alone would let Pellet find it consistent."""
    consistent, said = reasoned(name)
    assert not consistent
    assert bool(said) == ("range_string" in name), said


@pytest.mark.parametrize("name", CONSISTENT)
def test_consistent_as_pellet_or_inconsistent_in_owl_2_and_said(name: str) -> None:
    """Where Pellet finds the case consistent, topostore agrees (one value spelled twice) or follows OWL 2 and
    names the difference."""
    consistent, said = reasoned(name)
    assert consistent == CASES[name][2]
    assert bool(said) == (not consistent), said
    assert all("Pellet 2.3.1" in s and "OWL 2" in s for s in said)


@pytest.mark.parametrize("name", ONE_VALUE_IN_OWL_2)
def test_one_value_in_owl_2_is_consistent(name: str) -> None:
    consistent, said = reasoned(name)
    assert consistent and not said


def values(a: str, b: str) -> tuple[Literal, Literal]:
    triples = list(parse(f"@prefix xsd: <http://www.w3.org/2001/XMLSchema#> . <x:s> <x:p> {a}, {b} .",
                         RdfFormat.TURTLE))
    return triples[0].object, triples[1].object


@pytest.mark.parametrize("pair", [p for p, (*_, one) in MATRIX.items() if not one])
def test_which_values_pellet_tells_apart(pair: str) -> None:
    """The classes of :mod:`topostore.ontology.pellet_values` give the matrix Pellet answered."""
    a, b, apart, _ = MATRIX[pair]
    assert told_apart(*values(a, b)) == apart


def test_a_change_to_values_pellet_does_not_tell_apart_is_said_at_the_reason() -> None:
    """The warning follows the values a change leaves, on an incremental REASON too."""
    o = Ontology()
    o.load_data(document("changed", ":d a owl:DatatypeProperty, owl:FunctionalProperty .\n:x :d 5 ."), "turtle")
    assert o.reason().consistent
    x, d = NamedNode(namespace("changed") + "x"), NamedNode(namespace("changed") + "d")
    o.add(Triple(x, d, Literal("five")))
    with pytest.warns(PelletDifferenceWarning, match="five"):
        assert not o.reason().consistent
    o.change([Triple(x, d, Literal("6", datatype=NamedNode(XSD + "integer")))], [Triple(x, d, Literal("five"))])
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        assert not o.reason().consistent
    assert not [w for w in caught if w.category is PelletDifferenceWarning]


def test_the_warning_turned_into_an_error_leaves_the_reason_done() -> None:
    """Under ``warnings.simplefilter("error")`` the warning reaches the caller as an error, after the REASON
    has completed: the user's change stays and the report says inconsistent (nothing is undone)."""
    o = Ontology()
    o.load_data(document("strict", ":d a owl:DatatypeProperty, owl:FunctionalProperty .\n"
                                   ":q a owl:DatatypeProperty .\n:x :d 5 ."), "turtle")
    assert o.reason().consistent
    x, d, q = (NamedNode(namespace("strict") + n) for n in ("x", "d", "q"))
    o.add(Triple(x, d, Literal("five")), Triple(x, q, Literal("kept")))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with pytest.raises(PelletDifferenceWarning):
            o.reason()
    assert o.data_values(q, x) == [Literal("kept")]
    assert Literal("five") in o.data_values(d, x)
    assert o.report is not None and not o.report.consistent
    assert not o.dirty


def test_the_warning_turned_into_an_error_undoes_no_command_that_reasoned() -> None:
    """A REASON run inside a command's unit of work (a SPARQL Update with a live reasoner) says the warning
    when the command has ended well: as an error it reaches the caller, and the command's changes stay."""
    o = Ontology()
    o.load_data(document("command", ":d a owl:DatatypeProperty, owl:FunctionalProperty .\n"
                                    ":q a owl:DatatypeProperty .\n:x :d 5 ."), "turtle")
    assert o.reason().consistent
    ns = namespace("command")
    x, d, q = (NamedNode(ns + n) for n in ("x", "d", "q"))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with pytest.raises(PelletDifferenceWarning):
            with o.ledger.undoable(o):
                o.add(Triple(x, d, Literal("five")), Triple(x, q, Literal("kept")))
                o.reason()
    assert o.data_values(q, x) == [Literal("kept")]
    assert o.report is not None and not o.report.consistent


def test_a_command_undone_says_nothing_of_the_reason_it_ran() -> None:
    o = Ontology()
    o.load_data(document("undone", ":d a owl:DatatypeProperty, owl:FunctionalProperty .\n:x :d 5 ."), "turtle")
    assert o.reason().consistent
    x, d = (NamedNode(namespace("undone") + n) for n in ("x", "d"))
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        with pytest.raises(RuntimeError):
            with o.ledger.undoable(o):
                o.add(Triple(x, d, Literal("five")))
                o.reason()
                raise RuntimeError("the command fails after its REASON")
    assert not [w for w in caught if w.category is PelletDifferenceWarning]
    assert o.data_values(d, x) == [Literal("5", datatype=NamedNode(XSD + "integer"))]


#: inconsistencies resting on two values after equality: individuals held different by their values of a functional
#: data property, merged by a functional object property, an inverse-functional one or owl:sameAs (through an
#: equal's values too); name -> (Turtle body, Pellet consistent).  Where Pellet tells a pair of the values apart,
#: or the individuals are declared different, it finds the inconsistency too.
MERGING = (":d a owl:DatatypeProperty, owl:FunctionalProperty .\n:e a owl:DatatypeProperty, owl:FunctionalProperty .\n"
           ":f a owl:ObjectProperty, owl:FunctionalProperty .\n:g a owl:ObjectProperty, owl:InverseFunctionalProperty .\n"
           ":q a owl:ObjectProperty, owl:IrreflexiveProperty .\n:w a owl:ObjectProperty, owl:AsymmetricProperty .\n")
MERGED = {
    "merged_by_functional": (':x :d 5 . :y :d "five" . :a :f :x, :y .', True),
    "merged_by_inverse_functional": (':x :d 5 . :y :d "five" . :x :g :a . :y :g :a .', True),
    "merged_through_an_equal": (':x owl:sameAs :x2 . :x2 :d 5 . :y :d "five" . :a :f :x, :y .', True),
    "merged_by_same_as": (':x :d 5 . :y :d "five" . :x owl:sameAs :y .', True),
    "merged_values_told_apart": (":x :d 5 . :y :d 6 . :a :f :x, :y .", False),
    "merged_one_pair_told_apart": (':x :d 5 ; :e 1 . :y :d "five" ; :e 2 . :a :f :x, :y .', False),
    "merged_declared_different": (':x :d 5 . :y :d "five" . :x owl:differentFrom :y . :a :f :x, :y .', False),
    # merged, they clash in Pellet through a property between them
    "merged_linked_irreflexive": (':x :d 5 . :y :d "five" . :a :f :x, :y . :x :q :y .', False),
    "merged_linked_asymmetric": (':x :d 5 . :y :d "five" . :a :f :x, :y . :x :w :y . :y :w :x .', False),
}


def merged_document(name: str) -> str:
    return document(name, MERGING + MERGED[name][0])


@pytest.mark.external
@NEEDS_PELLET[0]
@NEEDS_PELLET[1]
@pytest.mark.parametrize("name", list(MERGED))
def test_values_after_equality_are_pellets(name: str) -> None:
    assert pellet(merged_document(name))["consistent"] == MERGED[name][1]


@pytest.mark.parametrize("name", list(MERGED))
def test_an_inconsistency_resting_on_values_after_equality_is_said(name: str) -> None:
    """topostore finds each inconsistent (OWL 2), and names it where Pellet finds it consistent."""
    o = loaded(merged_document(name))
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        assert not o.reason().consistent
    said = [str(w.message) for w in caught if w.category is PelletDifferenceWarning]
    assert bool(said) == MERGED[name][1], said
    assert all("five" in s for s in said)
    assert not any("<http" in s for s in said), said  # individuals and properties by their short names


def test_a_change_merging_individuals_told_apart_by_such_values_is_said_at_the_reason() -> None:
    """The warning after equality follows a change, on an incremental REASON too."""
    o = Ontology()
    o.load_data(document("merging", MERGING + ':x :d 5 . :y :d "five" . :a :f :x .'), "turtle")
    assert o.reason().consistent
    a, f, y = (NamedNode(namespace("merging") + n) for n in ("a", "f", "y"))
    o.add(Triple(a, f, y))
    with pytest.warns(PelletDifferenceWarning, match="five"):
        assert not o.reason().consistent
