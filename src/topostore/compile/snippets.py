"""SPARQL fragments shared by the OWL and SWRL compilers.

Each fragment comes with the read keys it depends on, so that the reasoner
knows when a rule that uses it must be evaluated again.
"""

from __future__ import annotations

from pyoxigraph import Literal, NamedNode

from ..rdf.terms import INTEGER_TYPES, REAL_TYPES
from ..rdf.vocab import AUX, DECLARED_DIFFERENT, DIFFERENCE_CANDIDATE, DIFFERENT, INTERNAL, OWL, RDF, RDFS, XSD
from . import data_ranges
from .condition import Condition, exists
from .rule import Atom

#: aux predicate: a pair whose difference by values is asked (see :mod:`.inline_difference`): the value
#: rules read it, the declared-difference rules read ``ts:differenceCandidate``
VALUE_CANDIDATE = NamedNode(INTERNAL + "valueCandidate")


def different_atom(a: str, b: str, declared: bool = False) -> Atom:
    """Body atom: ``a`` and ``b`` are known to be different — by entailment
    (vocab.DIFFERENT), or only by declaration (vocab.DECLARED_DIFFERENT)."""
    return Atom(a, str(DECLARED_DIFFERENT if declared else DIFFERENT), b, aux=True)


def candidate_atom(a: str, b: str) -> Atom:
    """Head atom of a candidate rule: ask whether ``a`` and ``b`` are different."""
    return Atom(a, str(DIFFERENCE_CANDIDATE), b, aux=True)


NOT_DIFFERENT_READS = frozenset({("p", str(DIFFERENT))})


def not_different(a: str, b: str) -> Condition:
    """Filter: ``a`` and ``b`` are not known to be different (a negated premise)."""
    return exists(f"GRAPH {AUX} {{ {a} {DIFFERENT} {b} }}", negated=True)


def known_different(a: str, b: str) -> Condition:
    """Filter: ``a`` and ``b`` are known to be different (reads the helper graph)."""
    return exists(f"GRAPH {AUX} {{ {a} {DIFFERENT} {b} }}")


def distinct_values(a: str, b: str) -> str:
    """Two data values that are different (an incomparable pair counts as different, but for two strings of
    the same characters: ``"a"`` and ``"a"^^xsd:token`` are one value, the string "a", which SPARQL's ``!=``
    does not compare, its operands of a type it does not know)."""
    return f"(!sameTerm({a}, {b}) && COALESCE({a} != {b}, !({one_string(a, b)}), true))"


def one_string(a: str, b: str) -> str:
    """``a`` and ``b`` are one string: both of xsd:string or a type derived from it (their value spaces
    are subsets of xsd:string's), written with the same characters."""
    return f"STR({a}) = STR({b}) && datatype({a}) IN ({STRINGS}) && datatype({b}) IN ({STRINGS})"


#: Numeric literals that are not of an integer or decimal type.
_FLOATING = "xsd:float, xsd:double"  # compiled rules run with the xsd: prefix (compile.generic.PREFIXES)


def _real(var: str) -> str:
    """``var`` is a valid literal of xsd:decimal or a type derived from it (xsd:integer, xsd:long, …).

    isNumeric is SPARQL's own test for a *valid* numeric literal of any of those
    types, so an ill-typed one ("abc"^^xsd:long) is in no value space; it keeps the
    rule text short (rules run in every step, and their text is parsed each time).
    """
    return f"isNumeric({var}) && !(datatype({var}) IN ({_FLOATING}))"


#: the string types derived by restricting characters (XSD 1.1 Part 2 §3.4.2-3.4.4), as SPARQL tests on ``{v}``
_STRING_FORMS = {
    "normalizedString": '!REGEX(STR({v}), "[\\r\\n\\t]")',
    "token": '!REGEX(STR({v}), "[\\r\\n\\t]|^ | $|  ")',
    "language": 'REGEX(STR({v}), "^[a-zA-Z]{{1,8}}(-[a-zA-Z0-9]{{1,8}})*$")',
}
#: the datatypes whose values are strings without a language tag (xsd:string and the types derived from it)
STRING_TYPES = ("string", "normalizedString", "token", "language", "NMTOKEN", "Name", "NCName")
STRINGS = ", ".join(f"xsd:{t}" for t in STRING_TYPES)
#: the datatypes derived from xsd:string (one of their literals is a string written as another term)
DERIVED_STRINGS = ", ".join(f"xsd:{t}" for t in STRING_TYPES[1:])


def in_datatype(var: str, datatype: NamedNode) -> str | None:
    """A boolean SPARQL expression: ``var`` is a literal of ``datatype``'s value space.

    Returns None for datatypes topostore does not check (any literal then fits).
    Errors (ill-typed literals) count as "not in the datatype".
    """
    built = data_ranges.composition(datatype)
    if built is not None:  # a one-of, complement, union or intersection of ranges
        return _composed_test(var, *built, surely=False)
    restricted = data_ranges.parts(datatype)
    if restricted is not None:  # a datatype restricted by numeric facets: the base, then each facet
        base = surely_in_datatype(var, restricted[0])
        facets = " && ".join(data_ranges.facet_tests(var, datatype))
        return f"COALESCE(({base} && {facets}), false)" if facets else base
    dt = datatype.value
    local = dt[len(XSD):] if dt.startswith(XSD) else None
    if dt in (RDFS + "Literal",):
        return f"isLiteral({var})"
    if local in INTEGER_TYPES:
        low, high = INTEGER_TYPES[local]
        tests = [_real(var), f"(datatype({var}) != xsd:decimal || {var} = FLOOR({var}))"]
        if low is not None:
            # written so that no SPARQL integer literal exceeds 64 bits
            tests.append(f"{var} >= ({low + 1} - 1)")
        if high is not None:
            tests.append(f"{var} <= {high}")
        return "COALESCE((" + " && ".join(tests) + "), false)"
    if local == "decimal" or dt in (OWL + "real", OWL + "rational"):
        return f"COALESCE(({_real(var)}), false)"
    if local == "string":
        return f"COALESCE((isLiteral({var}) && datatype({var}) IN ({STRINGS})), false)"
    if local in _STRING_FORMS:  # a string whose characters the derived type allows is one of its values
        return (f"COALESCE((isLiteral({var}) && datatype({var}) IN ({STRINGS}) && "
                f"{_STRING_FORMS[local].format(v=var)}), false)")
    if dt == RDF + "PlainLiteral":  # every string, with or without a language tag
        return f"COALESCE((isLiteral({var}) && (lang({var}) != \"\" || datatype({var}) IN ({STRINGS}))), false)"
    if dt == RDF + "langString":  # the strings with a language tag alone
        return f"COALESCE((isLiteral({var}) && lang({var}) != \"\"), false)"
    if local == "dateTimeStamp":  # a dateTime with a time zone (the store keeps it as an xsd:dateTime)
        return f"COALESCE((isLiteral({var}) && datatype({var}) = xsd:dateTime && TZ({var}) != \"\"), false)"
    if local in ("float", "double", "boolean", "dateTime", "date", "time", "anyURI", "duration"):
        return f"COALESCE((isLiteral({var}) && datatype({var}) = <{dt}> && str({var}) = str({var})), false)"
    return None


def surely_in_datatype(var: str, datatype: NamedNode) -> str:
    """A boolean SPARQL expression true only where ``var`` is surely in ``datatype``'s value space, for the
    rules that conclude a membership from it (an existential, a minimum, a SWRL data range).

    Why not "any literal" where :func:`in_datatype` does not check the datatype: a value outside it would
    make its subject a member of the restriction, a wrong answer ("hello" a value of a user's datatype of
    small integers).  A literal typed with a built-in datatype (``"ab"^^xsd:token``) is in it; a datatype of
    the ontology's own, whose definition is not read, is never known to hold a value."""
    checked = in_datatype(var, datatype)
    if checked is not None:
        return checked
    built = data_ranges.composition(datatype)
    if built is not None:  # a union or an intersection with a member not tested, a complement of one
        return _composed_test(var, *built, surely=True) or "false"
    if datatype.value.startswith(XSD) or datatype.value.startswith(RDF):
        return f"COALESCE((isLiteral({var}) && datatype({var}) = <{datatype.value}>), false)"
    return "false"


def _composed_test(var: str, kind: str, members: list, surely: bool) -> str | None:
    """The test of a range built of others (:func:`.data_ranges.composition`): a one-of is each member's value
    (:func:`same_value`: ``1`` holds ``"1"^^xsd:int`` and ``"1.0"^^xsd:decimal``, not ``"1"^^xsd:float``); a
    complement is every literal its member does not hold (OWL 2: the complement within all data values); a
    union or an intersection its members' tests joined.  None where a member is not tested (no literal is then
    known outside it); with ``surely``, a union or an intersection tests what is surely in its members instead
    (a member not tested holds no value surely), a complement stays None."""
    if kind == "oneOf":
        tests = [same_value(var, m) or _same_term_value(var, m) for m in members]
        return "COALESCE((" + (" || ".join(tests) or "false") + "), false)"
    if kind == "complementOf":
        inner = in_datatype(var, members[0])
        return None if inner is None else f"COALESCE((isLiteral({var}) && !({inner})), false)"
    tests = [(surely_in_datatype if surely else in_datatype)(var, m) for m in members]
    if any(t is None for t in tests):
        return None
    return "(" + (" || " if kind == "unionOf" else " && ").join(f"({t})" for t in tests) + ")"


def _same_term_value(var: str, value: Literal) -> str:
    """``var`` is the literal ``value`` of a datatype whose one value has one term, or two equal by SPARQL's
    ``=`` within that datatype (``"1"^^xsd:boolean`` and ``true``, ``"1.0"^^xsd:float`` and ``"1"^^xsd:float``)."""
    text = str(value)
    if value.language:
        return f"sameTerm({var}, {text})"
    return f"(isLiteral({var}) && datatype({var}) = <{value.datatype.value}> && {var} = {text})"


#: a literal of the decimal family (xsd:integer, long, …): its value is a real number, written many ways
_REAL_VALUE = "(isNumeric({v}) && !(datatype({v}) IN (xsd:float, xsd:double)))"


def same_value(var: str, value: Literal) -> str | None:
    """A SPARQL test that ``var`` is the data value ``value`` where one value has several literals that are
    not one RDF term: a real number (``3``, ``"3.0"^^xsd:decimal``, ``"3"^^xsd:long``), an instant
    (``12:00Z``, ``14:00+02:00``) or a string (``"a"``, ``"a"^^xsd:token``).  None for the others, whose one term is their value.

    Why: a rule matching the literal as a term (a hasValue's ``?x :d 3``) misses the value written
    another way, which the store keeps as written (Oxigraph makes ``"3"^^xsd:long`` ``3``, not ``3.0``)."""
    text = f'"{_escaped(value.value)}"^^<{value.datatype.value}>'
    if value.datatype.value[len(XSD):] in REAL_TYPES and value.datatype.value.startswith(XSD):
        return f"COALESCE(({_REAL_VALUE.format(v=var)} && {var} = {text}), false)"
    if value.language is None and value.datatype.value.startswith(XSD) \
            and value.datatype.value[len(XSD):] in STRING_TYPES:  # "a" is "a"^^xsd:token
        return (f"COALESCE((isLiteral({var}) && datatype({var}) IN ({STRINGS}) && "
                f"STR({var}) = \"{_escaped(value.value)}\"), false)")
    if value.datatype.value == XSD + "dateTime" and zoned(value.value):
        return f"COALESCE((datatype({var}) = xsd:dateTime && TZ({var}) != \"\" && {var} = {text}), false)"
    return None


def zoned(text: str) -> bool:
    """Whether a dateTime's lexical form names its time zone (only such instants compare across zones)."""
    return text.endswith("Z") or (len(text) > 6 and text[-6] in "+-" and text[-3] == ":")


def _escaped(text: str) -> str:
    return text.replace("\\", "\\\\").replace('"', '\\"').replace("\n", "\\n").replace("\r", "\\r")
