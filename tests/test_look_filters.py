"""The condition evaluator of the look-up path (reason/look_filters.py, reason/look_values.py) against pyoxigraph's own FILTER.

Random small stores (typed literals near and beyond 64 bits, non-canonical and ill-typed spellings,
simple, typed and language-tagged strings, IRIs, blank nodes) and random expressions of the subset
and just outside it: wherever the evaluator answers True or False, it is pyoxigraph's answer; it
may answer UNKNOWN (the caller then runs the SPARQL text), never a different answer.
"""

from __future__ import annotations

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from profiles import property_examples
from pyoxigraph import BlankNode, Literal, NamedNode, Quad, Store

from topostore.reason.look_filters import Unsupported, compile_expression
from topostore.reason.look_values import UNKNOWN, ebv, filter_of

XSD = "http://www.w3.org/2001/XMLSchema#"
S = NamedNode("http://t/s")
VARS = ("?a", "?b", "?c")
BIG = 2 ** 63


def typed(lex: str, dt: str) -> Literal:
    return Literal(lex, datatype=NamedNode(XSD + dt))


TERMS = st.one_of(
    st.sampled_from([NamedNode("urn:topostore:key:a:1"), NamedNode("urn:topostore:key:a:2"),
                     NamedNode("urn:topostore:key:b:1"), NamedNode("http://t/x"), BlankNode("b1"), BlankNode("b2")]),
    st.integers(-3, 3).map(lambda n: typed(str(n), "integer")),
    st.sampled_from([BIG - 1, BIG - 2, -BIG, -BIG + 1, BIG, -BIG - 1]).map(lambda n: typed(str(n), "integer")),
    st.sampled_from(["05", "+3", "-0", " 4", "abc", "1.0"]).map(lambda lex: typed(lex, "integer")),
    st.sampled_from([("7", "int"), ("300", "byte"), ("-1", "nonNegativeInteger"), ("2", "long"),
                     ("1.5", "decimal"), ("1", "double"), ("true", "boolean"), ("0", "boolean"),
                     ("x", "string"), ("", "string")]).map(lambda p: typed(*p)),
    st.sampled_from(["", "a", "a:b", "urn:topostore:key:a:1", "b:1"]).map(Literal),
    st.sampled_from([("a", "en"), ("", "fr"), ("a:b", "en")]).map(lambda p: Literal(p[0], language=p[1])),
)

TYPED = "^^<http://www.w3.org/2001/XMLSchema#"
ATOMS = st.one_of(
    st.sampled_from(VARS),
    st.sampled_from(["0", "1", "3", "9223372036854775807", '""', '"a"', '":"', '"urn:topostore:key:"',
                     "true", "false", "<urn:topostore:key:a:1>", "<http://t/x>", '"a"@en', "1.0",
                     f'"1"{TYPED}integer>', f'"-5"{TYPED}integer>', f'"05"{TYPED}integer>', f'"x"{TYPED}integer>',
                     f'"9223372036854775808"{TYPED}integer>', f'"a:"{TYPED}string>', f'"10"{TYPED}int>',
                     "'a'", '"""a"""']),
)


def _expr(children):
    one, two = children, st.tuples(children, children)
    return st.one_of(
        one.map(lambda e: f"!({e})"), one.map(lambda e: f"-({e})"), one.map(lambda e: f"STR({e})"),
        two.map(lambda p: f"({p[0]}) && ({p[1]})"), two.map(lambda p: f"({p[0]}) || ({p[1]})"),
        two.map(lambda p: f"STRBEFORE({p[0]}, {p[1]})"), two.map(lambda p: f"STRAFTER({p[0]}, {p[1]})"),
        st.tuples(children, st.sampled_from(["+", "-", "*", "=", "!=", "<", "<=", ">", ">="]), children)
        .map(lambda p: f"({p[0]}) {p[1]} ({p[2]})"),
        st.tuples(st.sampled_from(["sameTerm", "isIRI", "isURI", "isBlank", "isLiteral", "isNumeric"]),
                  st.sampled_from(VARS), st.sampled_from(VARS))
        .map(lambda p: f"{p[0]}({p[1]}, {p[2]})" if p[0] == "sameTerm" else f"{p[0]}({p[1]})"),
    )


EXPRS = st.recursive(ATOMS, _expr, max_leaves=6)


def store_of(terms: list) -> tuple[Store, dict]:
    """A store holding each term as ?a, ?b, ?c's value, and the solution as read back from it."""
    store = Store()
    for var, term in zip(VARS, terms):
        store.add(Quad(S, NamedNode("http://t/" + var[1:]), term))
    solution = {var: next(iter(store.quads_for_pattern(S, NamedNode("http://t/" + var[1:]), None))).object
                for var in VARS}
    return store, solution


def sparql_answer(store: Store, group: str) -> bool | None:
    """Whether the group matches (None: pyoxigraph rejects the text)."""
    text = ("SELECT * WHERE { <http://t/s> <http://t/a> ?a . <http://t/s> <http://t/b> ?b . "
            f"<http://t/s> <http://t/c> ?c . {group} }}")
    try:
        return any(True for _ in store.query(text))
    except SyntaxError:
        return None


@settings(max_examples=property_examples(1500), deadline=None)
@given(terms=st.lists(TERMS, min_size=3, max_size=3), text=EXPRS)
def test_filter_answers_as_pyoxigraph(terms: list, text: str) -> None:
    store, solution = store_of(terms)
    try:
        test = filter_of(compile_expression(text))
    except Unsupported:
        return
    answer = test(solution)
    if answer is UNKNOWN:
        return
    assert answer == sparql_answer(store, f"FILTER({text})"), (text, terms)


@settings(max_examples=property_examples(800), deadline=None)
@given(terms=st.lists(TERMS, min_size=3, max_size=3), bound=EXPRS, text=EXPRS)
def test_bind_then_filter_answers_as_pyoxigraph(terms: list, bound: str, text: str) -> None:
    """A BIND's value read by a later FILTER (``?a`` of the filter reads the bound ``?d``)."""
    store, solution = store_of(terms)
    text = text.replace("?a", "?d")
    try:
        expr, test = compile_expression(bound), filter_of(compile_expression(text))
    except Unsupported:
        return
    found = expr(solution)
    if found is UNKNOWN:
        return
    answer = test({**solution, "?d": found})
    if answer is UNKNOWN:
        return
    assert answer == sparql_answer(store, f"BIND(({bound}) AS ?d) FILTER({text})"), (bound, text, terms)


@pytest.mark.parametrize("text", ["?a * 2", "?a / 2", "COALESCE(?a, 1)", "REGEX(?a, \"x\")", "1.5 > ?a",
                                  "\"a\"@en = ?a", "?a<?b>?c", "bound(?a)", "99999999999999999999 > ?a", "?a ="])
def test_outside_the_subset_is_refused(text: str) -> None:
    with pytest.raises(Unsupported):
        compile_expression(text)


def test_overflow_and_foreign_values_are_unknown() -> None:
    big = typed(str(BIG - 1), "integer")
    assert filter_of(compile_expression("?a + 1 > 0"))({"?a": big}) is UNKNOWN
    assert filter_of(compile_expression("?a - 1 > 0"))({"?a": big}) is True
    assert filter_of(compile_expression("?a > 0"))({"?a": typed("1.5", "decimal")}) is UNKNOWN
    assert filter_of(compile_expression("?a = \"a\""))({"?a": Literal("a", language="en")}) is UNKNOWN
    # three-valued logic: a known false conjunct decides whatever the other stands for
    assert filter_of(compile_expression("?a > 0 && ?b > 0"))({"?a": typed("0", "integer"), "?b": big}) is False
    assert filter_of(compile_expression("?a > 0 || ?b + 1 > 0"))({"?a": typed("1", "integer"), "?b": big}) is True
    assert ebv(object()) is UNKNOWN


def test_an_integer_too_long_for_python_is_outside_the_subset_not_a_crash() -> None:
    """Python refuses to read integers of more than 4,300 digits; such a constant is refused as outside
    the subset, and such a stored value is no value the evaluator models."""
    from topostore.reason.look_values import value
    with pytest.raises(Unsupported):
        compile_expression("?a < " + "9" * 5000)
    huge = Literal("9" * 5000, datatype=NamedNode("http://www.w3.org/2001/XMLSchema#integer"))
    assert value(huge) is huge
