"""Names, IRIs and typed literals.

This module is the only place where user text becomes RDF terms.  Every term
that later appears inside a SPARQL string is a pyoxigraph object rendered by
pyoxigraph itself, so no user text is ever pasted into a query.
"""

from __future__ import annotations

import math
import re
from datetime import date
from decimal import MAX_PREC, Context, Decimal, InvalidOperation
from functools import lru_cache

from pyoxigraph import BlankNode, Literal, NamedNode, Quad, RdfFormat, Triple, parse

from ..errors import InvalidNameError, InvalidValueError, UnknownTypeError
from .vocab import OWL, PLACEHOLDER_PREDICATE, PLACEHOLDER_SUBJECT, XSD

Term = NamedNode | BlankNode | Literal

# Characters that may not appear in an IRI (RFC 3987) and would let a name
# break out of ``<...>`` in SPARQL.  Whitespace and control characters too.
_ILLEGAL_IRI_CHARS = re.compile(r'[\s<>"{}|^`\\\x00-\x1f\x7f]')
_SCHEME = re.compile(r"^[A-Za-z][A-Za-z0-9+.\-]*:")

#: the context a number's value key is normalised in: exact (no rounding to the thread's 28 digits, which made
#: 10**30 and 10**30 + 1 one value), and the same in every thread
EXACT = Context(prec=MAX_PREC)


def validate_name(name: str, what: str = "name") -> str:
    """Return ``name`` if it can be appended to a namespace to make an IRI.

    Rejects empty names, whitespace and the IRI-illegal characters
    ``< > " { } | ^ ` \\`` so that no name can alter a SPARQL query.
    """
    if not isinstance(name, str):
        raise InvalidNameError(f"{what} must be a string, got {type(name).__name__}")
    if name == "":
        raise InvalidNameError(f"{what} is empty")
    bad = _ILLEGAL_IRI_CHARS.search(name)
    if bad:
        raise InvalidNameError(
            f"{what} {name!r} contains the character {bad.group()!r}, which is not allowed in an IRI"
        )
    return name


def iri(value: str) -> NamedNode:
    """A NamedNode from an absolute IRI, with a clear error when it is not one."""
    validate_name(value, "IRI")
    if not _SCHEME.match(value):
        raise InvalidNameError(f"{value!r} is not an absolute IRI (no scheme)")
    try:
        return NamedNode(value)
    except ValueError as exc:  # pyoxigraph's own IRI validation
        raise InvalidNameError(f"{value!r} is not a valid IRI: {exc}") from exc


def entity(name: str, prefix: str) -> NamedNode:
    """IRI of an entity named by a user.

    ``<http://full/iri>`` is taken as a full IRI; anything else is appended to
    ``prefix`` (aRMOR's ``args[1] + "#" + name`` convention).
    """
    if isinstance(name, str) and len(name) > 2 and name.startswith("<") and name.endswith(">"):
        return iri(name[1:-1])
    return iri(prefix + validate_name(name))


# ---------------------------------------------------------------- datatypes

INTEGER_TYPES: dict[str, tuple[int | None, int | None]] = {
    "integer": (None, None),
    "long": (-(2**63), 2**63 - 1),
    "int": (-(2**31), 2**31 - 1),
    "short": (-(2**15), 2**15 - 1),
    "byte": (-(2**7), 2**7 - 1),
    "nonNegativeInteger": (0, None),
    "positiveInteger": (1, None),
    "nonPositiveInteger": (None, 0),
    "negativeInteger": (None, -1),
    "unsignedLong": (0, 2**64 - 1),
    "unsignedInt": (0, 2**32 - 1),
    "unsignedShort": (0, 2**16 - 1),
    "unsignedByte": (0, 2**8 - 1),
}
REAL_TYPES = set(INTEGER_TYPES) | {"decimal"}
#: XSD types SPARQL compares as numbers (promoted to a common type)
NUMERIC_TYPES = REAL_TYPES | {"float", "double"}
#: XSD types whose values lie on the time line: instants, dates and their parts
CALENDAR_TYPES = frozenset(("dateTime", "dateTimeStamp", "date", "time", "gYear", "gYearMonth", "gMonth",
                            "gMonthDay", "gDay"))

#: aRMOR value type names (case-insensitive) → XSD local name.  DOUBLE is a
#: real xsd:double here (aRMOR narrowed it to float: a bug, spec §7 item 9).
ARMOR_TYPES: dict[str, str] = {
    "STRING": "string",
    "INT": "int32",
    "INTEGER": "int32",
    "LONG": "long",
    "FLOAT": "float",
    "DOUBLE": "double",
    "BOOL": "boolean",
    "BOOLEAN": "boolean",
    "DECIMAL": "decimal",
    "SHORT": "short",
    "BYTE": "byte",
    "DATETIME": "dateTime",
    "DATE": "date",
}

_INT_RE = re.compile(r"^[+-]?[0-9]+$")
_DEC_RE = re.compile(r"^[+-]?([0-9]+(\.[0-9]*)?|\.[0-9]+)$")
_FLOAT_RE = re.compile(r"^[+-]?(([0-9]+(\.[0-9]*)?|\.[0-9]+)([eE][+-]?[0-9]+)?|INF|NaN)$")
#: owl:rational's lexical space (OWL 2 Structural Specification §4.1): a numerator, "/", a positive denominator
_RATIONAL_RE = re.compile(r"^[+-]?[0-9]+/0*[1-9][0-9]*$")
#: where an xsd:float overflows; a float or double written finite that reads beyond its type's range is refused
#: (Java's Float.parseFloat, as Pellet reads it, rounds to the nearest float: a value below the midpoint
#: between the largest float and 2^128 is that largest float, from the midpoint on it is an infinity)
_FLOAT_OVERFLOW = 2.0 ** 128 - 2.0 ** 103


def _java_float_text(value: float) -> str:
    """Render like Java's Float/Double.toString for the common cases ("3" → "3.0")."""
    if math.isnan(value):
        return "NaN"
    if math.isinf(value):
        return "INF" if value > 0 else "-INF"
    if value == int(value) and abs(value) < 1e7:
        return f"{int(value)}.0"
    text = repr(value)
    if "e" in text:
        mantissa, exponent = text.split("e")
        if "." not in mantissa:
            mantissa += ".0"
        return f"{mantissa}E{int(exponent)}"
    return text


def typed_literal(value: str, type_name: str) -> Literal:
    """Parse ``value`` as aRMOR type ``type_name`` (STRING, INTEGER, LONG, ...).

    Raises :class:`UnknownTypeError` for an unsupported type name and
    :class:`InvalidValueError` when the text is not a valid value of the type.
    """
    if not isinstance(value, str):
        raise InvalidValueError(f"value must be a string, got {type(value).__name__}")
    local = ARMOR_TYPES.get(type_name.upper()) if isinstance(type_name, str) else None
    if local is None:
        raise UnknownTypeError(
            f"unsupported value type {type_name!r}; use one of {', '.join(sorted(ARMOR_TYPES))}"
        )
    if local == "int32":
        # aRMOR parses INT/INTEGER as a 32-bit Java int and asserts xsd:integer
        literal_of(value, "int")
        local = "integer"
    made = literal_of(value, local)
    _known_valid(made)  # made by validation: checking it again (as every assertion does) would parse it twice
    return made


#: literals checked lately (:func:`check_literal`), and those :func:`typed_literal` made
_VALID: dict[Literal, None] = {}
_VALID_MAX = 4096


def check_literal(lit: Literal) -> None:
    """Raise :class:`InvalidValueError` when ``lit`` is not a valid value of its XSD type, or of owl:real
    (none is) or owl:rational (a literal of a datatype topostore does not validate, xsd:anyURI, xsd:gYear,
    ..., is kept as written)."""
    if lit in _VALID:
        return
    dt = lit.datatype.value
    if not lit.language and dt.startswith(XSD):
        try:
            literal_of(lit.value, dt[len(XSD):])  # an invalid value of a type topostore knows raises
        except UnknownTypeError:
            pass
    elif dt == OWL + "real":  # Pellet 2.3.1 finds such a literal ill-typed (inconsistent), as OWL 2 makes it
        raise InvalidValueError(f"{lit.value[:40]!r} is not a valid owl:real: owl:real has no lexical forms "
                                "(write an xsd:decimal or an owl:rational such as \"1/3\")")
    elif dt == OWL + "rational" and not _RATIONAL_RE.match(lit.value.strip()):
        raise InvalidValueError(f"{lit.value[:40]!r} is not a valid owl:rational (a numerator, '/' and a "
                                "positive denominator, such as \"1/3\")")
    _known_valid(lit)


def _known_valid(lit: Literal) -> None:
    if len(_VALID) >= _VALID_MAX:
        _VALID.clear()
    _VALID[lit] = None


#: the IRIs of the XSD datatypes :func:`literal_of` validates (an IRI is checked by pyoxigraph as it is made)
_DATATYPES: dict[str, NamedNode] = {
    local: NamedNode(XSD + local)
    for local in (*INTEGER_TYPES, "decimal", "float", "double", "boolean", "dateTime", "date")
}

#: longest integer accepted (Python refuses to parse more than 4,300 digits; no robot measures more)
_MAX_INTEGER_DIGITS = 4000


def literal_of(value: str, local: str) -> Literal:
    """A canonical literal of XSD type ``local`` from its lexical text, validated."""
    if local == "string":
        return Literal(value)
    datatype = _DATATYPES.get(local)
    if datatype is None:  # not a type topostore validates: the IRI is made (and checked by pyoxigraph) to say so
        datatype = NamedNode(XSD + local)
    text = value.strip()
    if local in INTEGER_TYPES:
        if not (text.isdigit() and text.isascii()) and not _INT_RE.match(text):  # digits alone: a robot's clock
            raise InvalidValueError(f"{value[:40]!r} is not a valid xsd:{local}")
        if len(text) > _MAX_INTEGER_DIGITS:
            raise InvalidValueError(f"an xsd:{local} of {len(text)} digits is out of range "
                                    f"(at most {_MAX_INTEGER_DIGITS} digits are accepted)")
        number = int(text)
        low, high = INTEGER_TYPES[local]
        if (low is not None and number < low) or (high is not None and number > high):
            raise InvalidValueError(f"{value!r} is out of range for xsd:{local}")
        made = Literal(str(number), datatype=datatype)
        # its value key from the number read here (the one _literal_key computes): a robot's clock is a new
        # integer every step, keyed at once
        _keep_key(made, ("real", Decimal(number).normalize(EXACT)))
        return made
    if local == "decimal":
        if not _DEC_RE.match(text):
            raise InvalidValueError(f"{value!r} is not a valid xsd:decimal")
        return Literal(text, datatype=datatype)
    if local in ("float", "double"):
        if not _FLOAT_RE.match(text):
            raise InvalidValueError(f"{value!r} is not a valid xsd:{local}")
        number = float(text.replace("INF", "inf"))
        if "INF" not in text and (math.isinf(number) or (local == "float" and abs(number) >= _FLOAT_OVERFLOW)):
            # XSD 1.1 would read it as ±INF; Pellet 2.3.1 (through the OWL API's "Infinity") finds the
            # ontology inconsistent, as it does for every ill-typed literal: refused as those are
            raise InvalidValueError(f"{value!r} is out of range for xsd:{local} (write INF or -INF for an infinity)")
        return Literal(_java_float_text(number), datatype=datatype)
    if local == "boolean":
        # aRMOR: true iff equal to "true" ignoring case; we also accept 1/0 and
        # refuse anything else instead of silently storing false.
        lowered = text.lower()
        if lowered in ("true", "1"):
            return Literal("true", datatype=datatype)
        if lowered in ("false", "0"):
            return Literal("false", datatype=datatype)
        raise InvalidValueError(f"{value!r} is not a valid xsd:boolean (true/false)")
    if local in ("dateTime", "date"):
        pattern = (
            r"^-?\d{4,}-\d{2}-\d{2}T\d{2}:\d{2}:\d{2}(\.\d+)?(Z|[+-]\d{2}:\d{2})?$"
            if local == "dateTime"
            else r"^-?\d{4,}-\d{2}-\d{2}(Z|[+-]\d{2}:\d{2})?$"
        )
        if not re.match(pattern, text):
            raise InvalidValueError(f"{value!r} is not a valid xsd:{local}")
        return Literal(text, datatype=datatype)
    raise UnknownTypeError(f"unsupported datatype xsd:{local}")  # pragma: no cover


#: value keys of recent literals: a manipulation asks the key of one literal a dozen times (its read, its
#: presence, the ledger, the literal forms), and parsing a decimal is most of a key's cost
_VALUE_KEYS: dict[Literal, tuple] = {}
_VALUE_KEYS_MAX = 4096


def value_key(term: Term) -> tuple:
    """A key equal for two literals exactly when they denote the same OWL data value.

    ``"5"^^xsd:long`` and ``"5"^^xsd:integer`` share a key (the store keeps only
    one of them); floats, doubles and reals stay apart, as in OWL 2.
    """
    if not isinstance(term, Literal):
        return ("term", str(term))
    key = _VALUE_KEYS.get(term)
    if key is None:
        key = _literal_key(term)
        if key[1] != key[1]:  # NaN: never equal to another key, as computed afresh (one object would be)
            return key
        _keep_key(term, key)
    return key


def _keep_key(term: Literal, key: tuple) -> None:
    """Remember the value key of ``term`` (:func:`value_key`'s, computed or known from its parse)."""
    if len(_VALUE_KEYS) >= _VALUE_KEYS_MAX:
        _VALUE_KEYS.clear()
    _VALUE_KEYS[term] = key


def note_stored_value(stored: Literal, written: Literal) -> None:
    """``stored`` is how the store holds ``written`` (``"5"^^xsd:integer`` for ``"5"^^xsd:long``): where
    ``written``'s value key is known and is a number's or a boolean's (the store's canonical form is the
    same value), ``stored`` gets it too, so that reading the stored form back (a REPLACE reads the value it
    replaces a step later) computes no key again.  A string's key names its form (a language tag's case),
    so it is left to be computed."""
    key = _VALUE_KEYS.get(written)
    if key is not None and key[0] != "literal" and stored not in _VALUE_KEYS:
        if len(_VALUE_KEYS) >= _VALUE_KEYS_MAX:
            _VALUE_KEYS.clear()
        _VALUE_KEYS[stored] = key


def _literal_key(term: Literal) -> tuple:
    """:func:`value_key` of a literal, computed."""
    dt = term.datatype.value
    local = dt[len(XSD):] if dt.startswith(XSD) else None
    try:
        if local in REAL_TYPES:
            return ("real", Decimal(term.value).normalize(EXACT))
        if local == "float":
            return ("float", float(term.value.replace("INF", "inf")))
        if local == "double":
            return ("double", float(term.value.replace("INF", "inf")))
        if local == "boolean":
            return ("boolean", term.value in ("true", "1"))
        if local in ("dateTime", "date", "dateTimeStamp"):
            # a dateTimeStamp is a dateTime with a time zone: the store keeps it as an xsd:dateTime (one without
            # a zone, ill-typed, too), so its key is that dateTime's, under which its written form is found
            kind = "dateTime" if local == "dateTimeStamp" else local
            moment = _moment(term.value, kind)
            if moment is not None:
                return (kind, *moment)
    except (InvalidOperation, ValueError):
        pass
    return ("literal", term.value, dt, term.language)


_MOMENT_RE = re.compile(r"(\d{4})-(\d{2})-(\d{2})(?:T(\d{2}):(\d{2}):(\d{2})(?:\.(\d+))?)?(?:(Z)|([+-])(\d{2}):(\d{2}))?")
#: the fractional digits of a second the store keeps (a longer fraction is not read as an instant)
_SECOND_DIGITS = 18


def _moment(text: str, local: str) -> tuple[int, int, int | None] | None:
    """An ``xsd:dateTime`` or ``xsd:date`` as the store tells it apart: its instant on the timeline (whole
    seconds and the fraction in units of 10⁻¹⁸ s) and its zone's offset in minutes (``None`` without a zone).
    ``…T00:00:00Z``, ``…T00:00:00+00:00`` and ``…T00:00:00.000Z`` are one triple of the store and one key
    here; the same instant in another zone stays apart, as the store keeps both.  ``None`` (the lexical key)
    for whatever the store may not read as an instant: a field out of range, spaces, a year outside
    1–9999, a fraction finer than it keeps.  Two keys may differ where the store keeps one triple (a
    second count twice); never the reverse, which would lose a value."""
    match = _MOMENT_RE.fullmatch(text)
    if match is None or (local == "date") != (match.group(4) is None):
        return None
    year, month, day, hour, minute, second = (int(match.group(i) or 0) for i in range(1, 7))
    fraction = (match.group(7) or "").rstrip("0")
    if (year == 0 or minute > 59 or second > 59 or len(fraction) > _SECOND_DIGITS
            or hour > 24 or (hour == 24 and (minute or second or fraction))):
        return None
    offset = None
    if match.group(8):
        offset = 0
    elif match.group(9):
        zone_hours, zone_minutes = int(match.group(10)), int(match.group(11))
        if zone_minutes > 59 or zone_hours * 60 + zone_minutes > 14 * 60:
            return None
        offset = (1 if match.group(9) == "+" else -1) * (zone_hours * 60 + zone_minutes)
    try:
        days = date(year, month, day).toordinal()
    except ValueError:
        return None
    seconds = days * 86400 + hour * 3600 + minute * 60 + second - (offset or 0) * 60
    return seconds, int(fraction.ljust(_SECOND_DIGITS, "0") or 0), offset


#: triples and quads with a literal object made lately, by their terms: pyoxigraph takes a literal argument
#: only after trying it as a NamedNode and a BlankNode (building an error for each), ten times an IRI's
#: cost, and a manipulation makes the same few again (a step's clock value is written, and removed as
#: the old value a step later; a changed triple is made as a triple, a pending quad and its stored form)
_MADE: dict[tuple, Triple | Quad] = {}
_MADE_MAX = 4096


def triple(s: Term, p: NamedNode, o: Term) -> Triple:
    """``Triple(s, p, o)``; one with a literal object is kept for the next few thousand (see ``_MADE``)."""
    if not isinstance(o, Literal):
        return Triple(s, p, o)
    key = (s, p, o)
    made = _MADE.get(key)
    return made if made is not None else _keep(key, Triple(s, p, o))


def keep_triple(s: Term, p: NamedNode, o: Literal, made: Triple) -> None:
    """``made`` is ``Triple(s, p, o)``, taken from a quad (pyoxigraph makes that without trying the kinds of
    term): kept for :func:`triple` to answer with, as one it made itself (a step later, the same value is
    named again as the old value it replaces)."""
    _keep((s, p, o), made)


def quad(s: Term, p: NamedNode, o: Term, g: NamedNode) -> Quad:
    """``Quad(s, p, o, g)``, kept as :func:`triple` keeps a triple."""
    if not isinstance(o, Literal):
        return Quad(s, p, o, g)
    key = (s, p, o, g)
    made = _MADE.get(key)
    return made if made is not None else _keep(key, Quad(s, p, o, g))


def _keep(key: tuple, made: Triple | Quad):  # noqa: ANN202 - the type it was given
    if len(_MADE) >= _MADE_MAX:
        _MADE.clear()
    _MADE[key] = made
    return made


def sparql(term: Term) -> str:
    """SPARQL text of a term, rendered by pyoxigraph (escaped, never pasted)."""
    if isinstance(term, BlankNode):
        raise InvalidNameError("blank nodes cannot be named in a query")
    return str(term)


@lru_cache(maxsize=1 << 16)
def parse_term(text: str) -> Term | None:
    """The RDF term written in N-Triples syntax (``<iri>``, ``"lex"^^<dt>``), None when ``text`` is not one.

    Parsed by pyoxigraph as the object of a one-line document, so the rules of the
    syntax (escapes, datatypes, language tags) are pyoxigraph's, not a hand-written lexer's.  Kept
    per text (a term is immutable): a robot step's look-ups read the terms of the rules they
    compile, the same few hundred on every step of a large TBox.
    """
    line = f"{PLACEHOLDER_SUBJECT} {PLACEHOLDER_PREDICATE} {text} ."
    try:
        quads = list(parse(line.encode("utf-8", errors="surrogatepass"), format=RdfFormat.N_TRIPLES))
    except (SyntaxError, ValueError):
        return None
    return quads[0].object if len(quads) == 1 else None
