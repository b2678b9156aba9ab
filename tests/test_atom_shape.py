"""An atom of a look-up operation resolved once (reason/atom_shape.Shape): the pattern it reads for a
solution and the bindings a fact read by it gives, for every arrangement of variables and named terms."""

from __future__ import annotations

from itertools import product

import pytest
from pyoxigraph import Literal, NamedNode, Triple

from topostore.reason.atom_shape import Shape

A, B, P, Q = (NamedNode(f"urn:x:{n}") for n in "abpq")
V = Literal("7")


def _generic(terms: tuple, t: Triple) -> dict | None:
    """The bindings as one position after the other gives them (a repeated variable must agree)."""
    bound: dict = {}
    for x, value in zip(terms, (t.subject, t.predicate, t.object)):
        if isinstance(x, str):
            if bound.setdefault(x, value) != value:
                return None
        elif x != value:
            return None
    return bound


FACTS = [Triple(A, P, B), Triple(A, P, A), Triple(B, Q, V), Triple(P, P, P)]


@pytest.mark.parametrize("terms", [t for t in product(("?x", A), ("?p", P), ("?y", "?x", B, V))])
def test_a_fact_read_by_the_pattern_binds_as_the_generic_match(terms: tuple) -> None:
    shape = Shape(terms)
    assert shape.free == tuple(None if isinstance(x, str) else x for x in terms)
    for t in FACTS:
        expected = _generic(terms, t)
        if expected is None and not _read_by(shape.free, t):
            continue  # not read by the atom's pattern: the index never gives it
        assert shape.bind(t) == expected
        assert shape.extend({"?z": B}, t) == (None if expected is None else {"?z": B, **expected})


def _read_by(pattern: tuple, t: Triple) -> bool:
    return all(x is None or x == v for x, v in zip(pattern, (t.subject, t.predicate, t.object)))


def test_a_solution_binds_the_read_pattern_and_leaves_the_rest_free() -> None:
    assert Shape(("?x", P, "?y")).read({"?x": A}) == (A, P, None)
    assert Shape(("?x", P, "?y")).read({"?y": B, "?z": A}) == (None, P, B)
    assert Shape((A, P, "?y")).read({"?y": V}) == (A, P, V)
    assert Shape(("?x", P, B)).read({}) == (None, P, B)
    assert Shape((A, P, B)).read({"?x": B}) == (A, P, B)
    assert Shape(("?x", "?p", "?x")).read({"?p": Q}) == (None, Q, None)


def test_a_repeated_variable_binds_only_where_its_positions_agree() -> None:
    shape = Shape(("?x", P, "?x"))
    assert shape.bind(Triple(A, P, A)) == {"?x": A}
    assert shape.bind(Triple(A, P, B)) is None
    assert shape.extend({"?y": B}, Triple(A, P, B)) is None
    assert shape.extend({"?y": B}, Triple(B, P, B)) == {"?y": B, "?x": B}
