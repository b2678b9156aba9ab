"""SPARQL fragments shared by the OWL and SWRL compilers.

Each fragment comes with the read keys it depends on, so that the reasoner
knows when a rule that uses it must be evaluated again.
"""

from __future__ import annotations

from pyoxigraph import NamedNode

from ..terms import INTEGER_TYPES, sparql
from ..vocab import AUX, DIFFERENT_FROM, IN_DIFFERENT_GROUP, OWL, RDF, RDFS, SAME_AS, TYPE, XSD

T = str(TYPE)
SAME = str(SAME_AS)

DIFFERENT_READS = frozenset({("p", str(IN_DIFFERENT_GROUP)), ("p", str(DIFFERENT_FROM)), ("p", SAME)})


def declared_different(a: str, b: str) -> str:
    """True when ``a`` and ``b`` are declared different (owl:differentFrom or one
    owl:AllDifferent), also through owl:sameAs.  Never expands AllDifferent to pairs:
    it tests membership of the same group (two index look-ups)."""
    return (
        f"(!sameTerm({a}, {b}) && EXISTS {{ {{ {a} {DIFFERENT_FROM} {b} }} UNION {{ {b} {DIFFERENT_FROM} {a} }} UNION "
        f"{{ {a} {SAME}? ?_m1 . {b} {SAME}? ?_m2 . GRAPH {AUX} {{ ?_m1 {IN_DIFFERENT_GROUP} ?_g . ?_m2 {IN_DIFFERENT_GROUP} ?_g }} "
        f"FILTER(!sameTerm(?_m1, ?_m2)) }} }})"
    )


def entailed_different(a: str, b: str, disjoint_pairs: list[tuple[NamedNode, NamedNode]]) -> tuple[str, frozenset]:
    """Declared difference, or membership of disjoint classes (which makes equality
    inconsistent, so a tableau reasoner concludes difference)."""
    text = declared_different(a, b)
    reads = set(DIFFERENT_READS)
    if disjoint_pairs:
        values = " ".join(f"({sparql(x)} {sparql(y)}) ({sparql(y)} {sparql(x)})" for x, y in disjoint_pairs)
        text = f"({text} || EXISTS {{ VALUES (?_c1 ?_c2) {{ {values} }} {a} {T} ?_c1 . {b} {T} ?_c2 }})"
        reads |= {("t", sparql(c)) for pair in disjoint_pairs for c in pair}
    return text, frozenset(reads)


def distinct_values(a: str, b: str) -> str:
    """Two data values that are different (an incomparable pair counts as different)."""
    return f"(!sameTerm({a}, {b}) && COALESCE({a} != {b}, true))"


_INTEGER_LIST = ", ".join(f"<{XSD}{t}>" for t in INTEGER_TYPES)


def in_datatype(var: str, datatype: NamedNode) -> str | None:
    """A boolean SPARQL expression: ``var`` is a literal of ``datatype``'s value space.

    Returns None for datatypes topostore does not check (any literal then fits).
    Errors (ill-typed literals) count as "not in the datatype".
    """
    dt = datatype.value
    local = dt[len(XSD):] if dt.startswith(XSD) else None
    if dt in (RDFS + "Literal",):
        return f"isLiteral({var})"
    if local in INTEGER_TYPES:
        low, high = INTEGER_TYPES[local]
        tests = [
            f"isLiteral({var})",
            f"(datatype({var}) IN ({_INTEGER_LIST}) || (datatype({var}) = <{XSD}decimal> && {var} = FLOOR({var})))",
        ]
        if low is not None:
            # written so that no SPARQL integer literal exceeds 64 bits
            tests.append(f"{var} >= ({low + 1} - 1)")
        if high is not None:
            tests.append(f"{var} <= {high}")
        return "COALESCE((" + " && ".join(tests) + "), false)"
    if local == "decimal" or dt in (OWL + "real", OWL + "rational"):
        return f"COALESCE((isLiteral({var}) && datatype({var}) IN ({_INTEGER_LIST}, <{XSD}decimal>) && {var} = {var}), false)"
    if local == "string":
        return f"COALESCE((isLiteral({var}) && datatype({var}) = <{XSD}string>), false)"
    if dt in (RDF + "PlainLiteral", RDF + "langString"):
        return f"COALESCE((isLiteral({var}) && (lang({var}) != \"\" || datatype({var}) = <{XSD}string>)), false)"
    if local in ("float", "double", "boolean", "dateTime", "date", "time", "anyURI", "dateTimeStamp", "duration"):
        return f"COALESCE((isLiteral({var}) && datatype({var}) = <{dt}> && str({var}) = str({var})), false)"
    return None
