"""A rule's conditions generated into one function (reason/look_code.py) answer as the closures of
reason/look_filters.py do, value for value: random expressions of the subset (and just outside it)
over random terms, as FILTERs alone and after a BIND whose value they read."""

from __future__ import annotations

from hypothesis import given, settings
from hypothesis import strategies as st
from profiles import property_examples
from test_look_filters import EXPRS, TERMS, VARS

from topostore.reason import look_code
from topostore.reason.look_code import compile_conditions, compile_exact_over
from topostore.reason.look_filters import Unsupported, closure, parse_expression
from topostore.reason.look_values import UNKNOWN, all_of


def reference(binds: list, tests: list, solution: dict) -> tuple[object, object]:
    """``holds`` and ``exact`` by the closures (as reason/look_join.Conditions computes them interpreted)."""
    s = dict(solution)
    for var, tree in binds:
        found = closure(tree)(s)
        if found is UNKNOWN:
            return UNKNOWN, None
        s[var] = found
    values = [closure(t)(s) for t in tests]
    holds = all_of([closure(t) for t in tests])(s)
    exact = None if any(type(v) is not bool for v in values) else all(values)
    return holds, exact


def trees(texts: list[str]) -> list | None:
    try:
        return [parse_expression(t) for t in texts]
    except Unsupported:
        return None


@settings(max_examples=property_examples(1500), deadline=None)
@given(terms=st.lists(TERMS, min_size=3, max_size=3), bound=st.one_of(st.none(), EXPRS),
       texts=st.lists(EXPRS, max_size=3))
def test_generated_conditions_answer_as_the_closures(terms: list, bound: str | None, texts: list[str]) -> None:
    solution = dict(zip(VARS, terms))
    parsed_binds = trees([bound]) if bound is not None else []
    parsed_tests = trees([t.replace("?c", "?d") for t in texts])  # ?d: the BIND's value where there is one
    if parsed_binds is None or parsed_tests is None:
        return
    binds = [("?d", tree) for tree in parsed_binds]
    holds, exact = compile_conditions(binds, parsed_tests)
    expected = reference(binds, parsed_tests, solution)
    assert (holds(solution), exact(solution)) == expected, (bound, texts, terms)
    # again: a string of one term is kept from the first call, and answers as made
    assert (holds(solution), exact(solution)) == expected, (bound, texts, terms)
    # the values as arguments (a generated flip branch's locals), the last variable left unbound
    names = sorted(solution)
    over = compile_exact_over(binds, parsed_tests, names[:-1])
    assert over(*(solution[n] for n in names[:-1])) == reference(binds, parsed_tests, {
        n: solution[n] for n in names[:-1]})[1], (bound, texts, terms)


def test_a_kept_string_is_the_one_of_its_own_term(monkeypatch) -> None:
    """An AllDifferent key's group is kept per key: two keys of one group and one of another, asked in
    turns and past the limit of kept terms, give each pair its own answer (a string kept for another
    term, or kept stale past the clearing, fails)."""
    from pyoxigraph import NamedNode
    tests = trees(['STRBEFORE(STRAFTER(STR(?a), "urn:topostore:key:"), ":") = '
                   'STRBEFORE(STRAFTER(STR(?b), "urn:topostore:key:"), ":")'])
    monkeypatch.setattr(look_code, "KEPT_MAX", 2)  # three keys: the kept strings are forgotten and made again
    holds, exact = compile_conditions([], tests)
    a1, a2, b1 = (NamedNode(f"urn:topostore:key:{g}:{n}") for g, n in (("a", 1), ("a", 2), ("b", 1)))
    for _ in range(3):
        for x, y, same in ((a1, a2, True), (a1, b1, False), (b1, a2, False), (a2, a1, True), (b1, b1, True)):
            assert exact({"?a": x, "?b": y}) is same and holds({"?a": x, "?b": y}) is same, (x, y)
    kept = [v for name, v in exact.__globals__.items() if name.startswith("k") and type(v) is dict and v]
    assert kept and all(len(k) <= 2 for k in kept)


def test_no_condition_holds() -> None:
    holds, exact = compile_conditions([], [])
    assert holds({}) is True and exact({}) is True


def test_overflow_foreign_values_and_three_valued_logic_as_the_closures() -> None:
    """The cases tests/test_look_filters.py names, through the generated function."""
    from test_look_filters import BIG, typed
    big, zero, one = typed(str(BIG - 1), "integer"), typed("0", "integer"), typed("1", "integer")
    cases = [("?a + 1 > 0", {"?a": big}), ("?a - 1 > 0", {"?a": big}), ("-(?a) - 2 < 0", {"?a": big}),
             ("?a > 0", {"?a": typed("1.5", "decimal")}), ("?a > 0 && ?b > 0", {"?a": zero, "?b": big}),
             ("?a > 0 || ?b + 1 > 0", {"?a": one, "?b": big}), ("?a > 0 || ?b + 1 > 0", {"?a": zero, "?b": big}),
             ('STRAFTER(STR(?a), "urn:") = ""', {"?a": typed("x", "string")}),
             ('STRBEFORE("ab", "x") = ""', {}), ("!(?a)", {"?a": zero}), ("sameTerm(?a, ?b)", {"?a": one})]
    for text, solution in cases:
        tree = parse_expression(text)
        holds, exact = compile_conditions([], [tree])
        assert (holds(solution), exact(solution)) == reference([], [tree], solution), text


def test_a_literals_value_read_from_the_cache_or_made_answers_alike() -> None:
    """The generated code reads a literal's value from :func:`value`'s cache inline: a value made fresh, one
    cached, and one cached as a falsy value (0, the empty string) answer as the closures, again and again."""
    from pyoxigraph import Literal, NamedNode

    from topostore.reason.look_values import VALUES

    integer = NamedNode("http://www.w3.org/2001/XMLSchema#integer")
    tests = trees(["?a < ?b", "?c = \"\""])
    holds, exact = compile_conditions([], tests)
    for a, b in (("0", "1"), ("-3", "0"), ("1", "0")):
        solution = {"?a": Literal(a, datatype=integer), "?b": Literal(b, datatype=integer), "?c": Literal("")}
        VALUES.pop(solution["?a"], None)
        first = (holds(solution), exact(solution))
        assert first == (holds(solution), exact(solution)) == reference([], tests, solution), (a, b)
        assert first[1] == (int(a) < int(b))

