"""terms.py, where user text becomes RDF terms: names, IRIs, typed literals and data-value keys."""

from __future__ import annotations

import pytest
from pyoxigraph import BlankNode, Literal, NamedNode
from support import NS

from topostore.errors import InvalidNameError, InvalidValueError, UnknownTypeError
from topostore.rdf.terms import check_literal, entity, iri, literal_of, sparql, typed_literal, validate_name, value_key
from topostore.rdf.vocab import OWL

XSD = "http://www.w3.org/2001/XMLSchema#"


def lit(value: str, local: str) -> Literal:
    return Literal(value, datatype=NamedNode(XSD + local))


# ---------------------------------------------------------------- names and IRIs

@pytest.mark.parametrize("name", ["R1", "a-b_c.d", "Ünïcode", "x/y#z", "0"])
def test_validate_name_returns_good_names_unchanged(name: str) -> None:
    assert validate_name(name) == name


@pytest.mark.parametrize("name,bad", [("R 1", " "), ("a<b", "<"), ("a>b", ">"), ('a"b', '"'), ("a{b", "{"),
                                      ("a}b", "}"), ("a|b", "|"), ("a^b", "^"), ("a`b", "`"), ("a\\b", "\\"),
                                      ("a\nb", "\n"), ("a\x00b", "\x00"), ("a\x7fb", "\x7f")])
def test_validate_name_names_the_bad_character(name: str, bad: str) -> None:
    with pytest.raises(InvalidNameError) as err:
        validate_name(name, "individual")
    assert str(err.value) == (f"individual {name!r} contains the character {bad!r}, "
                              "which is not allowed in an IRI")


def test_validate_name_refuses_empty_and_non_strings() -> None:
    with pytest.raises(InvalidNameError, match="^class is empty$"):
        validate_name("", "class")
    with pytest.raises(InvalidNameError, match="^name must be a string, got int$"):
        validate_name(5)  # type: ignore[arg-type]


def test_iri_needs_a_scheme() -> None:
    assert iri("urn:x") == NamedNode("urn:x")
    assert iri("http://example.org/a#b") == NamedNode("http://example.org/a#b")
    with pytest.raises(InvalidNameError, match="is not an absolute IRI"):
        iri("relative/path")
    with pytest.raises(InvalidNameError, match="not allowed in an IRI"):
        iri("http://example.org/a b")


def test_entity_appends_to_the_prefix_or_takes_a_full_iri() -> None:
    assert entity("R1", NS) == NamedNode(NS + "R1")
    assert entity("<http://other.org/x#Z>", NS) == NamedNode("http://other.org/x#Z")
    with pytest.raises(InvalidNameError):
        entity("<>", NS)  # too short to be <IRI>, and "<" may not be part of a name
    with pytest.raises(InvalidNameError, match="is not an absolute IRI"):
        entity("<no-scheme>", NS)


# ---------------------------------------------------------------- typed literals

@pytest.mark.parametrize("value,type_name,expected", [
    ("42", "LONG", lit("42", "long")),
    ("  42 ", "long", lit("42", "long")),  # type names are case-insensitive; numbers are trimmed
    ("+7", "INTEGER", lit("7", "integer")),  # aRMOR asserts xsd:integer for INT/INTEGER
    ("-2147483648", "INT", lit("-2147483648", "integer")),
    ("007", "SHORT", lit("7", "short")),
    ("-128", "BYTE", lit("-128", "byte")),
    ("3", "FLOAT", lit("3.0", "float")),  # Java's Float.toString
    ("1e10", "DOUBLE", lit("10000000000.0", "double")),
    ("1.5e-7", "DOUBLE", lit("1.5E-7", "double")),
    ("1e300", "DOUBLE", lit("1.0E300", "double")),  # as Java writes it
    ("INF", "FLOAT", lit("INF", "float")),
    ("-INF", "DOUBLE", lit("-INF", "double")),
    ("NaN", "DOUBLE", lit("NaN", "double")),
    (".5", "DECIMAL", lit(".5", "decimal")),
    ("TRUE", "BOOL", lit("true", "boolean")),
    ("0", "BOOLEAN", lit("false", "boolean")),
    ("2022-10-12T10:00:00Z", "DATETIME", lit("2022-10-12T10:00:00Z", "dateTime")),
    ("2022-10-12", "DATE", lit("2022-10-12", "date")),
    (' say "hi" ', "STRING", Literal(' say "hi" ')),  # strings are kept as given
])
def test_typed_literal(value: str, type_name: str, expected: Literal) -> None:
    assert typed_literal(value, type_name) == expected


@pytest.mark.parametrize("value,type_name,message", [
    ("12x", "LONG", "'12x' is not a valid xsd:long"),
    ("1.0", "INT", "'1.0' is not a valid xsd:int"),
    ("2147483648", "INT", "'2147483648' is out of range for xsd:int"),
    ("9223372036854775808", "LONG", "'9223372036854775808' is out of range for xsd:long"),
    ("128", "BYTE", "'128' is out of range for xsd:byte"),
    ("1e39", "FLOAT", "'1e39' is out of range for xsd:float (write INF or -INF for an infinity)"),
    ("-1e400", "DOUBLE", "'-1e400' is out of range for xsd:double (write INF or -INF for an infinity)"),
    ("one", "DOUBLE", "'one' is not a valid xsd:double"),
    ("1.2.3", "DECIMAL", "'1.2.3' is not a valid xsd:decimal"),
    ("yes", "BOOLEAN", "'yes' is not a valid xsd:boolean (true/false)"),
    ("2022-13", "DATE", "'2022-13' is not a valid xsd:date"),
    ("12:00", "DATETIME", "'12:00' is not a valid xsd:dateTime"),
])
def test_typed_literal_refuses_bad_values(value: str, type_name: str, message: str) -> None:
    with pytest.raises(InvalidValueError) as err:
        typed_literal(value, type_name)
    assert str(err.value) == message


def test_typed_literal_refuses_unknown_types_and_huge_integers() -> None:
    with pytest.raises(UnknownTypeError, match="unsupported value type 'NUMBER'; use one of BOOL, BOOLEAN, BYTE"):
        typed_literal("5", "NUMBER")
    with pytest.raises(UnknownTypeError):
        typed_literal("5", None)  # type: ignore[arg-type]
    with pytest.raises(InvalidValueError, match="^value must be a string, got int$"):
        typed_literal(5, "LONG")  # type: ignore[arg-type]
    with pytest.raises(InvalidValueError, match="of 4001 digits is out of range"):
        typed_literal("9" * 4001, "INTEGER")


def test_literal_of_covers_the_unsigned_and_sign_restricted_types() -> None:
    assert literal_of("0", "nonNegativeInteger") == lit("0", "nonNegativeInteger")
    assert literal_of("18446744073709551615", "unsignedLong") == lit("18446744073709551615", "unsignedLong")
    for value, local in (("0", "positiveInteger"), ("1", "nonPositiveInteger"), ("0", "negativeInteger"),
                         ("-1", "unsignedByte"), ("256", "unsignedByte")):
        with pytest.raises(InvalidValueError, match=f"out of range for xsd:{local}"):
            literal_of(value, local)


def test_check_literal_refuses_floats_and_doubles_beyond_their_range_and_ill_typed_owl_numbers() -> None:
    """Read as ±INF by XSD 1.1 and as ill-typed by Pellet 2.3.1: refused alike for float and double; owl:real
    has no lexical forms, owl:rational's are n/d with d positive."""
    for text, local in (("1e40", "float"), ("-3.5e38", "float"), ("3.4028236e38", "float"), ("1e400", "double"),
                        ("-1E309", "double")):
        with pytest.raises(InvalidValueError, match=f"out of range for xsd:{local}"):
            check_literal(lit(text, local))
    for text, local in (("INF", "float"), ("-INF", "double"), ("3.4028235e38", "float"), ("1e-50", "float"),
                        ("3.40282356e38", "float"), ("-3.4028235677e38", "float"),
                        ("1.7976931348623157e308", "double"), ("NaN", "double")):
        check_literal(lit(text, local))
    for text in ("3", "1/3", "0.5"):
        with pytest.raises(InvalidValueError, match="not a valid owl:real"):
            check_literal(Literal(text, datatype=NamedNode(OWL + "real")))
    for text in ("3", "1/0", "1/-3", "a/b", "1.5/2"):
        with pytest.raises(InvalidValueError, match="not a valid owl:rational"):
            check_literal(Literal(text, datatype=NamedNode(OWL + "rational")))
    for text in ("1/3", "-2/04", "0/1"):
        check_literal(Literal(text, datatype=NamedNode(OWL + "rational")))


# ---------------------------------------------------------------- data-value keys and SPARQL text

def test_value_key_is_equal_exactly_for_equal_data_values() -> None:
    assert value_key(lit("5", "long")) == value_key(lit("5", "integer")) == value_key(lit("5.0", "decimal"))
    assert value_key(lit("5", "long")) != value_key(lit("5.0", "double"))  # reals and doubles stay apart
    assert value_key(lit("5.0", "double")) != value_key(lit("5.0", "float"))
    assert value_key(lit("2.50", "double")) == value_key(lit("2.5", "double"))
    assert value_key(lit("1", "boolean")) == value_key(lit("true", "boolean"))
    assert value_key(Literal("5")) != value_key(lit("5", "integer"))
    assert value_key(Literal("chat", language="fr")) != value_key(Literal("chat", language="en"))
    assert value_key(lit("abc", "long")) == ("literal", "abc", XSD + "long", None)  # ill-typed: compared as text
    assert value_key(NamedNode(NS + "R1")) == ("term", f"<{NS}R1>")


def test_sparql_renders_escaped_terms_and_refuses_blank_nodes() -> None:
    assert sparql(Literal('a"b\\c')) == '"a\\"b\\\\c"'
    assert sparql(lit("5", "long")) == f'"5"^^<{XSD}long>'
    assert sparql(NamedNode(NS + "R1")) == f"<{NS}R1>"
    with pytest.raises(InvalidNameError, match="blank nodes cannot be named in a query"):
        sparql(BlankNode("b0"))


def test_value_key_is_the_same_when_asked_again() -> None:
    """Keys are kept per literal: asking again gives an equal key, and a NaN's key still equals no other
    (not even its own, as when each key was computed afresh)."""
    five = lit("5", "long")
    assert value_key(five) == value_key(five) == value_key(lit("5", "integer"))
    nan = lit("NaN", "float")
    assert value_key(nan) != value_key(nan)


MOMENTS = [("2020-01-01T00:00:00Z", "dateTime"), ("2020-01-01T00:00:00+00:00", "dateTime"),
           ("2020-01-01T00:00:00-00:00", "dateTime"), ("2020-01-01T00:00:00.000Z", "dateTime"),
           ("2020-01-01T01:00:00+01:00", "dateTime"), ("2020-01-01T00:00:00", "dateTime"),
           ("2019-12-31T24:00:00Z", "dateTime"), ("2019-12-31T23:30:00-00:30", "dateTime"),
           ("2020-01-01T00:00:00.5Z", "dateTime"), ("2020-01-01T00:00:00.50Z", "dateTime"),
           ("10000-01-01T00:00:00Z", "dateTime"), ("2020-02-30T00:00:00Z", "dateTime"),
           ("2020-01-01", "date"), ("2020-01-01Z", "date"), ("2020-01-01+00:00", "date"),
           ("2020-01-02+01:00", "date"), ("2020-01-01T00:00:00Z", "date"),
           ("2020-01-01T00:00:00.123456789012345678Z", "dateTime"),
           ("2020-01-01T00:00:00.123456789012345679Z", "dateTime"),
           ("2020-01-01T00:00:00.5000000000000000000Z", "dateTime"), ("2020-01-01T25:00:00Z", "dateTime"),
           ("2020-01-02T01:00:00Z", "dateTime"), ("2019-12-31T24:30:00Z", "dateTime"),
           ("2020-01-01T00:30:00Z", "dateTime"), ("2020-01-01T00:60:00Z", "dateTime"),
           ("2020-01-01T01:00:00Z", "dateTime"), ("2020-01-01T00:00:60Z", "dateTime"),
           ("2020-01-01T00:01:00Z", "dateTime"), ("2020-01-01T00:00:00+15:00", "dateTime"),
           ("2019-12-31T09:00:00Z", "dateTime"), ("2020-01-01T01:00:00+01:60", "dateTime"),
           ("2019-12-31T23:00:00Z", "dateTime"), (" 2020-01-01T00:00:00Z", "dateTime"),
           ("2020-01-01T00:00:00Z ", "dateTime")]


def test_value_key_of_instants_is_equal_exactly_where_the_store_keeps_one_triple() -> None:
    """An instant spelled with ``Z``, ``+00:00`` or trailing zeros is one triple of the store, and a change
    of it must be one fact too (one ``added``, the other spelling said); the same instant in another zone is
    two triples of the store, and two keys."""
    from pyoxigraph import Quad, Store

    s = NamedNode("urn:s")
    terms = [Literal(text, datatype=NamedNode("http://www.w3.org/2001/XMLSchema#" + local)) for text, local in MOMENTS]
    for i, a in enumerate(terms):
        for b in terms[i + 1:]:
            store = Store()
            store.add(Quad(s, s, a))
            store.add(Quad(s, s, b))
            assert (len(store) == 1) == (value_key(a) == value_key(b)), (a, b)


def test_numbers_past_28_digits_keep_their_own_value_keys_in_every_thread() -> None:
    """A number's value key is exact: two integers (or decimals) that differ past the 28th significant digit are
    two values, whatever precision the calling thread's decimal context has; both are kept as asserted."""
    import decimal
    import threading

    from topostore import Ontology

    xsd = "http://www.w3.org/2001/XMLSchema#"
    pairs = [(str(10**30), str(10**30 + 1), "integer"), ("0.1", "0.10000000000000000000000000001", "decimal")]
    keys: list[tuple] = []

    def compare() -> None:
        decimal.getcontext().prec = 6  # a thread with a narrow context of its own
        keys.extend((value_key(Literal(a, datatype=NamedNode(xsd + t))), value_key(Literal(b, datatype=NamedNode(xsd + t))))
                    for a, b, t in pairs)

    worker = threading.Thread(target=compare)
    worker.start()
    worker.join()
    for a, b, t in pairs:
        ka, kb = value_key(Literal(a, datatype=NamedNode(xsd + t))), value_key(Literal(b, datatype=NamedNode(xsd + t)))
        assert ka != kb and (ka, kb) in keys
    onto = Ontology("http://ex.org/t#")
    onto.add_data("p", "x", 10**30)
    onto.add_data("p", "x", 10**30 + 1)
    onto.reason()
    assert sorted(int(v.value) for v in onto.data_values("p", "x")) == [10**30, 10**30 + 1]
