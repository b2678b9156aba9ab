"""What is decided of the data ranges built of others (:mod:`.data_ranges`) without testing a store: whether
one has no value (:func:`emptiness`), whether a literal is in one (:func:`contains`), whether every value of one
is in another (:func:`included`).  Each answers True, False or None: None where it is not decided simply and
exactly, for the caller to say so by a notice rather than guess."""

from __future__ import annotations

from collections.abc import Iterable
from decimal import Decimal, InvalidOperation
from itertools import product

from pyoxigraph import Literal, NamedNode

from ..rdf.terms import INTEGER_TYPES, sparql, value_key
from ..rdf.vocab import RDF, RDFS, TYPE, XSD
from . import data_ranges
from .datatypes import (
    _FAMILY_TOPS,
    _INTEGER_TEXT,
    _ancestors,
    _family,
    _integer_bounds,
    _short,
    disjoint_datatypes,
    implied_ranges,
    is_empty,
)
from .model import Expr, is_datatype
from .rule import Atom, Rule

LITERAL = NamedNode(RDFS + "Literal")
#: the most conjunctions a union inside an intersection is spread into before the answer is left undecided
_MAX_CASES = 64


def normal(dt: NamedNode, negated: bool = False) -> tuple:
    """The range as a tree with complements pushed onto named datatypes and one-ofs (De Morgan):
    ``("atom", IRI)``, ``("one", [literals])``, ``("not", leaf)``, ``("or", [trees])``, ``("and", [trees])``."""
    built = data_ranges.composition(dt)
    if built is None:
        leaf = ("atom", dt)
        return ("not", leaf) if negated else leaf
    kind, members = built
    if kind == "oneOf":
        leaf = ("one", [m for m in members if isinstance(m, Literal)])
        return ("not", leaf) if negated else leaf
    if kind == "complementOf":
        return normal(members[0], not negated)
    joined = "or" if (kind == "unionOf") != negated else "and"
    return (joined, [normal(m, negated) for m in members])


def _all(answers) -> bool | None:
    answers = list(answers)
    return False if False in answers else (None if None in answers else True)


def _any(answers) -> bool | None:
    answers = list(answers)
    return True if True in answers else (None if None in answers else False)


def _not(answer: bool | None) -> bool | None:
    return None if answer is None else not answer


def contains(value: Literal, dt: NamedNode) -> bool | None:
    """Whether the literal ``value`` is in the range ``dt``."""
    return _contains(value, normal(dt))


def _contains(value: Literal, tree: tuple) -> bool | None:
    kind, arg = tree
    if kind == "one":
        return value_key(value) in {value_key(m) for m in arg}
    if kind == "not":
        return _not(_contains(value, arg))
    if kind == "or":
        return _any(_contains(value, m) for m in arg)
    if kind == "and":
        return _all(_contains(value, m) for m in arg)
    return _in_atom(value, arg)


def _in_atom(value: Literal, dt: NamedNode) -> bool | None:

    if dt == LITERAL:
        return True
    found = data_ranges.parts(dt)
    if found is not None:
        base, tests = found
        inside = _in_atom(value, base)
        if inside is not True:
            return inside
        number = _number(value)
        if number is None or base.value[len(XSD):] in ("float", "double"):
            return None
        answers = []
        for op, literal in tests:
            try:
                bound = Decimal(literal.split("^^")[0].strip('"'))
            except InvalidOperation:
                return None
            answers.append({">=": number >= bound, ">": number > bound, "<=": number <= bound,
                            "<": number < bound}[op])
        return all(answers)
    own = value.datatype.value
    if value.language:
        own = RDF + "langString"
    if own == dt.value:
        return True
    if _integer_bounds(own, dt.value) is not None and _INTEGER_TEXT.fullmatch(value.value):
        low, high = _integer_bounds(own, dt.value)
        number = int(value.value)
        return (low is None or number >= low) and (high is None or number <= high)
    if disjoint_datatypes(NamedNode(own), dt):
        return False
    if dt.value in _ancestors(own) and not (dt.value.startswith(XSD) and dt.value[len(XSD):] in INTEGER_TYPES):
        return True
    return None


def _number(value: Literal) -> Decimal | None:
    local = value.datatype.value[len(XSD):] if value.datatype.value.startswith(XSD) else ""
    if local != "decimal" and local not in INTEGER_TYPES:
        return None
    try:
        return Decimal(value.value)
    except InvalidOperation:
        return None


def emptiness(dt: NamedNode) -> bool | None:
    """Whether the range ``dt`` has no value (None: not decided)."""
    return _empty(normal(dt))


def _atom_empty(dt: NamedNode) -> bool:
    return is_empty(dt)


def _empty(tree: tuple) -> bool | None:
    kind, arg = tree
    if kind == "atom":
        return _atom_empty(arg)
    if kind == "one":
        return not arg
    if kind == "not":  # the complement of a datatype or a one-of: empty only for all literals
        return arg == ("atom", LITERAL)
    if kind == "or":
        return _all(_empty(m) for m in arg)
    return _and_empty(_conjuncts(arg))


def _conjuncts(members: list) -> list:
    out = []
    for m in members:
        out += _conjuncts(m[1]) if m[0] == "and" else [m]
    return out


def _and_empty(conj: list) -> bool | None:
    if any(_empty(m) is True for m in conj):
        return True
    ones = [m for m in conj if m[0] == "one"]
    if ones:  # the values of a one-of, each tested against the other members
        first, rest = ones[0], [m for m in conj if m is not ones[0]]
        return _all(_not(_all(_contains(v, m) for m in rest)) for v in first[1])
    unions = [m for m in conj if m[0] == "or"]
    if unions:
        rest = [m for m in conj if m[0] != "or"]
        cases = 1
        for u in unions:
            cases *= len(u[1])
        if cases > _MAX_CASES:
            return None
        return _all(_and_empty(_conjuncts(rest + list(pick))) for pick in product(*(u[1] for u in unions)))
    positives = [m[1] for m in conj if m[0] == "atom"]
    negatives = [m[1] for m in conj if m[0] == "not"]
    if any(disjoint_datatypes(a, b) for i, a in enumerate(positives) for b in positives[i + 1:]):
        return True
    for n in negatives:
        if any(_included_tree(("atom", p), n) is True for p in positives):
            return True
    if not negatives and positives:
        return False
    return None


def included(a: NamedNode, b: NamedNode) -> bool | None:
    """Whether every value of ``a`` is in ``b`` (None: not decided)."""
    if a == b:
        return True
    return _included_tree(normal(a), normal(b))


def _included_tree(a: tuple, b: tuple) -> bool | None:
    if a == b or b == ("atom", LITERAL):
        return True
    if _infinite(a) and _finite(b):
        return False
    if b[0] == "not" and b[1][0] == "one":  # outside a one-of: none of its values is in a
        return _all(_not(_contains(v, a)) for v in b[1][1])
    if a[0] == "one":  # each value tested against the right side
        return _all(_contains(v, b) for v in a[1])
    if a[0] == "and" and any(m[0] == "one" for m in a[1]):  # the one-of's values the other members keep
        first = next(m for m in a[1] if m[0] == "one")
        rest = [m for m in a[1] if m is not first]
        answers = []
        for v in first[1]:
            kept = _all(_contains(v, m) for m in rest)
            if kept is not False:
                found = _contains(v, b)
                answers.append(found if kept is True or found is True else None)
        return _all(answers)
    if a[0] == "not" and a[1][0] in ("atom", "one") and b[0] == "or" and _uncovered(a[1], b[1]):
        return False
    if a[0] == "or":
        return _all(_included_tree(m, b) for m in a[1])
    if b[0] == "and":
        return _all(_included_tree(a, m) for m in b[1])
    if a[0] == "and":
        if any(_included_tree(m, b) is True for m in a[1]):
            return True
        return None
    if b[0] == "or":
        answers = [_included_tree(a, m) for m in b[1]]
        if True in answers:
            return True
        if a[0] == "atom" and _built_in(a[1]) and all(
                m[0] == "atom" and _disjoint(a[1], m[1]) for m in b[1]):  # no value of a in any member
            return False
        return None
    if a[0] == "not" and b[0] == "not":  # ¬X ⊆ ¬Y when Y ⊆ X
        return _included_tree(b[1], a[1])
    if a[0] == "atom" and b[0] == "atom":
        if data_ranges.parts(b[1]) is None and b[1] in implied_ranges([a[1]]):
            return True
        if _built_in(a[1]) and _built_in(b[1]):  # the table of value-space inclusions is complete for these
            return False
        return False if _atom_empty(a[1]) is False and disjoint_datatypes(a[1], b[1]) else None
    if a[0] == "atom" and b[0] == "not":  # X ⊆ ¬Y when no value is in both
        if b[1][0] == "atom" and disjoint_datatypes(a[1], b[1][1]):
            return True
        if b[1][0] == "atom" and _built_in(a[1]) and _built_in(b[1][1]):
            return False  # two datatypes of the map that share values
        return None
    if a[0] == "not" and b[0] == "atom" and a[1][0] == "atom":  # the complement of a datatype holds values of every family but one
        return False if _built_in(b[1]) and _built_in(a[1][1]) else None
    if a[0] == "atom" and b[0] == "one":  # a datatype with more values than the one-of lists
        size = _size(a[1])
        if size is not None and len({value_key(v) for v in b[1]}) < size:
            return False
        return None
    return None


def _uncovered(x: tuple, members: list) -> bool:
    """Whether a family of the datatype map has no value in ``x`` nor in any of ``members`` (datatypes of the
    map, restricted ones, one-ofs): its values are in the complement of ``x`` and outside the members."""

    covered = set()
    for m in [x, *members]:
        if m[0] == "one":
            covered |= {_family(v.datatype.value) for v in m[1]}
            continue
        if m[0] != "atom":
            return False
        found = data_ranges.parts(m[1])
        base = found[0] if found is not None else m[1]
        if not _built_in(base):
            return False
        covered.add(_family(base.value))
    return None not in covered and bool(set(_FAMILY_TOPS) - covered)


def _disjoint(a: NamedNode, b: NamedNode) -> bool:
    return disjoint_datatypes(a, b)


def _finite(tree: tuple) -> bool:
    """Whether the range surely has finitely many values."""
    if tree[0] == "one":
        return True
    if tree[0] == "and":
        return any(_finite(m) for m in tree[1])
    if tree[0] == "or":
        return all(_finite(m) for m in tree[1])
    return tree[0] == "atom" and _size(tree[1]) not in (None, float("inf"))


def _infinite(tree: tuple) -> bool:
    """Whether the range surely has infinitely many values."""
    if tree[0] == "not":  # the complement of a one-of or of a datatype of the map (or restricted) other than all
        inner = tree[1]
        return inner[0] == "one" or (inner[1] != LITERAL and (_built_in(inner[1]) or
                                                             data_ranges.parts(inner[1]) is not None))
    if tree[0] == "or":
        return any(_infinite(m) for m in tree[1])
    return tree[0] == "atom" and _size(tree[1]) == float("inf")


def _built_in(dt: NamedNode) -> bool:
    """A datatype of the OWL 2 datatype map, not restricted, other than rdfs:Literal."""
    return dt != LITERAL and data_ranges.parts(dt) is None and is_datatype(dt)


def _size(dt: NamedNode) -> float | None:
    """How many values a named datatype of the map has (infinity for most; None where not known)."""
    if not _built_in(dt):
        return None
    local = dt.value[len(XSD):] if dt.value.startswith(XSD) else ""
    if local == "boolean":
        return 2
    if local in INTEGER_TYPES:
        low, high = INTEGER_TYPES[local]
        return float("inf") if low is None or high is None else high - low + 1
    return float("inf")


def most_values(dt: NamedNode) -> int | None:
    """An upper bound of how many distinct values ``dt`` has (None: not known to be finite)."""
    tree = normal(dt)
    if tree[0] == "one":
        return len({value_key(v) for v in tree[1]})
    if tree[0] == "and":
        conj = _conjuncts(tree[1])
        ones = [m for m in conj if m[0] == "one"]
        if ones:
            rest = [m for m in conj if m is not ones[0]]
            kept = {value_key(v) for v in ones[0][1] if _all(_contains(v, m) for m in rest) is not False}
            return len(kept)
    return None


def disjoint(a: NamedNode, b: NamedNode) -> bool:
    """Whether no value is surely in both ``a`` and ``b`` (any data ranges): their intersection is empty."""
    return _and_empty(_conjuncts([normal(a), normal(b)])) is True


def empty_range_rules(expressions: Iterable[Expr]) -> list[Rule]:
    """An individual in a restriction that needs a value of an empty data range is inconsistent."""
    rules = []
    for e in expressions:
        if e.datatype is not None and (e.kind == "some" or (e.kind in ("min", "exact") and e.n >= 1)) \
                and emptiness(e.datatype) is True:
            rules.append(Rule("ext-empty-range", f"{e} needs a value of {_short(e.datatype)}, which has none", (
                Atom("?x", str(TYPE), sparql(e.node)),), violation=("?x",),
                message=f"{{x}} is in {e}, but {_short(e.datatype)} has no value"))
        elif e.datatype is not None and e.kind in ("min", "exact") and e.n >= 2:
            most = most_values(e.datatype)
            if most is not None and most < e.n:
                rules.append(Rule("ext-empty-range", f"{e} needs {e.n} values of {_short(e.datatype)}, which has "
                                  f"{most}", (Atom("?x", str(TYPE), sparql(e.node)),), violation=("?x",),
                                  message=f"{{x}} is in {e}, but {_short(e.datatype)} has fewer than {e.n} values"))
    return rules


__all__ = ["contains", "disjoint", "emptiness", "empty_range_rules", "included", "most_values", "normal"]
