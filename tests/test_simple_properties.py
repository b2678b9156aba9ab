"""Non-simple properties where OWL 2 DL wants simple ones (topostore.compile.simple_properties).

The answers Pellet 2.3.1 gives are checked against Pellet in tests/test_fidelity_pellet.py; here: the set of
properties kept simple, shapes Owlready2's Jena loader reads otherwise than the OWL API (AllDisjointProperties,
checked against Pellet on the OWL API), the aRMOR command adding a cardinality at run time, and the decision
taken after changes of the schema equal to a fresh load's (incremental == from scratch).
"""

from __future__ import annotations

import warnings
from pathlib import Path

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from profiles import property_examples
from pyoxigraph import Literal, NamedNode, Triple
from support import same_as_fresh_load

from topostore import Ontology, OntologyWarning
from topostore.armor import ArmorService
from topostore.compile.notices import NON_SIMPLE
from topostore.compile.owl import OwlCompiler
from topostore.compile.simple_properties import kept_simple
from topostore.compile.tbox_reader import TBoxReader
from topostore.rdf.skolem import fresh_skolem
from topostore.rdf.vocab import ASSERTED, RDF, RDFS, TYPE, XSD, owl

NS = "http://example.org/simple#"
PREFIXES = f"""@prefix : <{NS}> . @prefix owl: <http://www.w3.org/2002/07/owl#> .
@prefix rdfs: <http://www.w3.org/2000/01/rdf-schema#> . @prefix xsd: <http://www.w3.org/2001/XMLSchema#> .
:p a owl:ObjectProperty . :q a owl:ObjectProperty . :r a owl:ObjectProperty . :s a owl:ObjectProperty .
:t a owl:ObjectProperty . :u a owl:ObjectProperty . :C a owl:Class . :M a owl:Class .
:a a owl:NamedIndividual . :b a owl:NamedIndividual . :c a owl:NamedIndividual . :d a owl:NamedIndividual .
"""


def _n(name: str) -> NamedNode:
    return NamedNode(NS + name)


def _loaded(body: str) -> Ontology:
    o = Ontology()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", OntologyWarning)
        o.load_data(PREFIXES + body, "turtle")
        o.reason()
    return o


def _kept(body: str) -> set[str]:
    tb = TBoxReader(_loaded(body).store, ASSERTED).read()
    return {p.value.removeprefix(NS) for p in kept_simple(tb, OwlCompiler(tb).all_expressions())}


def _ignored(o: Ontology) -> list[str]:
    return [n.subject for n in o.notices if n.axiom_kind == NON_SIMPLE]


def test_the_properties_kept_simple_are_those_used_and_below_through_inverses_and_equivalences() -> None:
    body = """:p a owl:FunctionalProperty . :q rdfs:subPropertyOf :p . :r owl:inverseOf :q .
:s owl:equivalentProperty :r . :t rdfs:subPropertyOf [ owl:inverseOf :s ] . :p rdfs:subPropertyOf :u ."""
    # p used; q below it; r the inverse of q (its inverse below p); s equivalent to r; t below s's inverse
    assert _kept(body) == {"p", "q", "r", "s", "t"}


def test_a_data_property_and_a_data_cardinality_keep_nothing_simple() -> None:
    body = """:d a owl:DatatypeProperty, owl:FunctionalProperty . :e a owl:DatatypeProperty .
:M rdfs:subClassOf [ a owl:Restriction ; owl:onProperty :e ; owl:maxCardinality "1"^^xsd:nonNegativeInteger ] ."""
    assert _kept(body) == set()


def test_all_disjoint_properties_keep_their_members_simple() -> None:
    """As Pellet on the OWL API answers (Owlready2's Jena loader reads no AllDisjointProperties): p's
    transitivity is ignored, so a p c is not entailed and does not meet a s c."""
    o = _loaded("""[] a owl:AllDisjointProperties ; owl:members ( :r :p :s ) . :p a owl:TransitiveProperty .
:a :p :b . :b :p :c . :a :s :c .""")
    assert o.reason().consistent
    assert set(o.object_values(_n("p"), _n("a"), names=False)) == {_n("b")}
    assert _ignored(o) == ["p is transitive"]


def test_without_a_simple_use_transitivity_and_chains_are_kept_and_nothing_is_said() -> None:
    o = _loaded(""":p a owl:TransitiveProperty . :q owl:propertyChainAxiom ( :r :s ) .
:a :p :b . :b :p :c . :a :r :b . :b :s :d .""")
    assert set(o.object_values(_n("p"), _n("a"), names=False)) == {_n("b"), _n("c")}
    assert set(o.object_values(_n("q"), _n("a"), names=False)) == {_n("d")}
    assert _ignored(o) == []


def _armor(svc: ArmorService, command: str, spec1: str, spec2: str, args: list[str]) -> list[str]:
    res = svc.call({"client_name": "c", "reference_name": "ref", "command": command, "primary_command_spec": spec1,
                    "secondary_command_spec": spec2, "args": args})
    assert res.success, res
    return sorted(res.queried_objects)


def test_a_cardinality_added_by_armor_ignores_the_transitivity_as_a_fresh_load(tmp_path: Path) -> None:
    path = tmp_path / "transitive.ttl"
    path.write_text(PREFIXES + ":p a owl:TransitiveProperty . :a :p :b . :b :p :c .")
    svc = ArmorService()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", OntologyWarning)
        _armor(svc, "LOAD", "FILE", "", [str(path), NS[:-1], "false", "PELLET", "false"])
        assert _armor(svc, "QUERY", "OBJECTPROP", "IND", ["p", "a"]) == [f"<{NS}b>", f"<{NS}c>"]
        _armor(svc, "ADD", "CARDINALITY", "MIN", ["M", "p", "1", "C"])
        assert _armor(svc, "QUERY", "OBJECTPROP", "IND", ["p", "a"]) == [f"<{NS}b>"]
    assert _ignored(svc.reference("ref").ontology) == ["p is transitive"]


def _literal(n: int) -> Literal:
    return Literal(str(n), datatype=NamedNode(XSD + "nonNegativeInteger"))


# ---------------------------------------------------------------- incremental = from scratch


def _restriction(kind: str, prop: str, n: int | None = None) -> list[Triple]:
    node = fresh_skolem()
    value = _literal(n) if n is not None else None
    triples = [Triple(node, TYPE, owl("Restriction")), Triple(node, owl("onProperty"), _n(prop)),
               Triple(_n("M"), NamedNode(RDFS + "subClassOf"), node)]
    if kind == "self":
        triples.append(Triple(node, owl("hasSelf"), Literal("true", datatype=NamedNode(XSD + "boolean"))))
    else:
        triples.append(Triple(node, owl(kind), value))
    return triples


def _chain(sup: str, *props: str) -> list[Triple]:
    cells = [fresh_skolem() for _ in props]
    triples = [Triple(_n(sup), owl("propertyChainAxiom"), cells[0])]
    for i, (cell, p) in enumerate(zip(cells, props, strict=True)):
        rest = cells[i + 1] if i + 1 < len(cells) else NamedNode(RDF + "nil")
        triples += [Triple(cell, NamedNode(RDF + "first"), _n(p)), Triple(cell, NamedNode(RDF + "rest"), rest)]
    return triples


def _t(s: str, p: str, o: str) -> list[Triple]:
    return [Triple(_n(s), _n(p) if ":" not in p else NamedNode(p), _n(o))]


#: the schema and facts the changes pick from: transitivity, chains, the simple uses, the hierarchy, values
POOL: list[list[Triple]] = [
    [Triple(_n("p"), TYPE, owl("TransitiveProperty"))],
    [Triple(_n("q"), TYPE, owl("TransitiveProperty"))],
    [Triple(_n("p"), TYPE, owl("FunctionalProperty"))],
    [Triple(_n("q"), TYPE, owl("InverseFunctionalProperty"))],
    [Triple(_n("p"), TYPE, owl("AsymmetricProperty"))],
    [Triple(_n("q"), TYPE, owl("IrreflexiveProperty"))],
    [Triple(_n("q"), NamedNode(RDFS + "subPropertyOf"), _n("p"))],
    [Triple(_n("r"), owl("inverseOf"), _n("q"))],
    [Triple(_n("s"), owl("propertyDisjointWith"), _n("p"))],
    _chain("p", "r", "s"),
    _chain("q", "q", "q"),
    _restriction("maxCardinality", "p", 1),
    _restriction("self", "q"),
    _t("a", "p", "b"), _t("b", "p", "c"), _t("c", "p", "a"), _t("a", "q", "b"), _t("b", "q", "c"),
    _t("c", "r", "d"), _t("a", "s", "c"), _t("d", "s", "b"), _t("a", "r", "a"),
    _t("b", str(owl("differentFrom").value), "c"), _t("a", str(TYPE.value), "M"),
]

operations = st.lists(st.tuples(st.sampled_from(["add", "remove", "reason"]), st.integers(0, len(POOL) - 1)),
                      min_size=1, max_size=14)


def _graph(o: Ontology, g: NamedNode) -> set:
    return set(o.store.triples(graph=g))


@settings(max_examples=property_examples(25), deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(operations)
def test_changes_of_simple_uses_and_transitivity_decide_as_a_fresh_load(ops) -> None:
    onto = _loaded("")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", OntologyWarning)
        for op, i in ops:
            if op == "add":
                onto.add(*POOL[i])
            elif op == "remove":
                onto.remove(*POOL[i])
            else:
                onto.reason()
        fresh, _ = same_as_fresh_load(onto, onto.reason())
    assert sorted(_ignored(onto)) == sorted(_ignored(fresh))
