"""Two spellings of one value through robot steps: incremental REASON equals a REASON from scratch.

The store keeps one fact per value (``"8"^^xsd:integer`` and ``"8.0"^^xsd:decimal`` are one OWL value), but
a rule head built from a row carries the spelling that row read.  The look-ups that decide a head's standing
by its triple (a flip's lost head, reason/flips.py; an entailed-only conclusion's, reason/entailed.py) must
find the fact whatever spelling the store holds it in.
"""

from __future__ import annotations

import warnings
from unittest import mock

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from profiles import property_examples
from pyoxigraph import Literal, NamedNode
from test_incremental import assert_helper_facts, from_scratch

from topostore import Ontology, OntologyWarning
from topostore.rdf.vocab import ENTAILED, INFERRED, XSD
from topostore.reason import flips

NS = "http://example.org/spellings#"
TBOX = f"""@prefix : <{NS}> . @prefix owl: <http://www.w3.org/2002/07/owl#> .
<http://example.org/spellings> a owl:Ontology .
:score a owl:DatatypeProperty . :score2 a owl:DatatypeProperty . :limit a owl:DatatypeProperty .
:limit2 a owl:DatatypeProperty . :high a owl:DatatypeProperty . :flag a owl:DatatypeProperty .
:shown a owl:DatatypeProperty . :kept a owl:DatatypeProperty . :On a owl:Class . :Robot a owl:Class .
:id a owl:DatatypeProperty, owl:FunctionalProperty .
:x a owl:NamedIndividual, :Robot ; :id 1 . :y a owl:NamedIndividual, :Robot . :z a owl:NamedIndividual, :Robot ; :id 2 .
"""
RULES = {
    "HighByScore": "score(?x, ?v) ^ limit(?x, ?l) ^ swrlb:greaterThan(?v, ?l) -> high(?x, ?v)",
    "HighByScore2": "score2(?x, ?v) ^ limit2(?x, ?l) ^ swrlb:greaterThan(?v, ?l) -> high(?x, ?v)",
    "On": "flag(?x, ?b) ^ swrlb:equal(?b, true) -> On(?x)",
    "Shown": "flag(?x, ?b) ^ limit(?x, ?l) ^ swrlb:greaterThan(?l, 3) -> shown(?x, ?b)",
    # x and z are different only by entailment (two values of a functional property): an entailed-only conclusion
    "Apart": "score(?x, ?v) ^ Robot(?z) ^ differentFrom(?x, ?z) -> kept(?x, ?v)",
}
EIGHT = [("8", "integer"), ("8.0", "decimal"), ("8", "long"), ("08", "int"), ("8.00", "decimal"), ("9", "integer")]
TRUTH = [("1", "boolean"), ("true", "boolean"), ("0", "boolean"), ("false", "boolean")]


def N(name: str) -> NamedNode:
    return NamedNode(NS + name)


def lit(spelled: tuple[str, str]) -> Literal:
    return Literal(spelled[0], datatype=NamedNode(XSD + spelled[1]))


def ontology() -> Ontology:
    o = Ontology()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", OntologyWarning)
        o.load_data(TBOX)
        for label, rule in RULES.items():
            o.add_rule(rule, label)
    o.max_change_share = 1.0
    return o


def assert_same_as_scratch(o: Ontology) -> None:
    report = o.reason()
    inferred, aux, entailed, consistent = from_scratch(o)
    assert set(o.store.triples(graph=INFERRED)) == inferred, report.stats
    assert_helper_facts(o, aux)
    assert set(o.store.triples(graph=ENTAILED)) == entailed, report.stats
    assert report.consistent == consistent, report.stats


def put(o: Ontology, who: str, prop: str, value: Literal) -> None:
    """The one value of ``prop`` of ``who`` replaced (added when it has none)."""
    old = o.data_values(N(prop), N(who))
    for v in old:
        o.remove(o.fact(N(who), N(prop), v))
    o.add(o.fact(N(who), N(prop), value))


who = st.sampled_from(["x", "y", "z"])
step = st.one_of(
    st.tuples(who, st.sampled_from(["score", "score2", "high", "kept"]), st.sampled_from(EIGHT).map(lit)),
    st.tuples(who, st.sampled_from(["limit", "limit2"]), st.integers(2, 10).map(lambda n: Literal(n))),
    st.tuples(who, st.just("flag"), st.sampled_from(TRUTH).map(lit)),
)


@settings(max_examples=property_examples(40), deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(steps=st.lists(st.lists(step, min_size=1, max_size=3), min_size=1, max_size=6))
def test_two_spellings_through_steps_equal_from_scratch(steps: list) -> None:
    o = ontology()
    for w in ("x", "y"):
        put(o, w, "score", lit(("8", "integer")))
        put(o, w, "score2", lit(("8.0", "decimal")))
        put(o, w, "limit", Literal(5))
        put(o, w, "limit2", Literal(5))
        put(o, w, "flag", lit(("1", "boolean")))
    o.reason()
    with mock.patch.object(flips, "WINDOW_MIN", 0):  # flip windows on this small ontology too
        for batch in steps:
            for w, prop, value in batch:
                put(o, w, prop, value)
            assert_same_as_scratch(o)


def test_the_head_spelled_by_the_other_rule_is_lost_by_a_flip() -> None:
    """``high`` is derived by both rules, the stored spelling one rule's; the other rule's derivation
    then goes by a flip of its limit, then the first's: nothing is left to derive it."""
    o = ontology()
    put(o, "x", "score", lit(("8", "integer")))
    put(o, "x", "score2", lit(("8.0", "decimal")))
    put(o, "x", "limit", Literal(5))
    put(o, "x", "limit2", Literal(5))
    o.reason()
    for prop in ("limit2", "limit"):
        put(o, "x", prop, Literal(9))
        assert_same_as_scratch(o)
    assert not o.data_values(N("high"), N("x"))


def test_an_entailed_conclusion_in_a_new_spelling_replaces_the_old() -> None:
    """``kept`` holds by an entailed difference only (ENTAILED); its value respelled, the new spelling's twin
    is present and the old one's gone: asked together by value they took one answer, and both were dropped."""
    o = ontology()
    put(o, "x", "score", lit(("8", "integer")))
    o.reason()
    put(o, "x", "score", lit(("8.0", "decimal")))
    assert_same_as_scratch(o)
    assert [v.datatype.value for v in o.store.objects(N("x"), N("kept"), ENTAILED)] == [XSD + "decimal"]
