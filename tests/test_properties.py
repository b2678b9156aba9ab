"""Property tests.

1. On random ABoxes over an OWL 2 RL TBox, the closure over the named
   individuals equals owlrl's OWL 2 RL closure (the W3C OWL 2 RL/RDF rules).
2. After random additions and removals through the Python API, reasoning gives
   the same inferred graph as reasoning from scratch on the same asserted graph
   (README: "Inferences follow the current asserted state").
"""

from __future__ import annotations

import owlrl
import rdflib
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from profiles import property_examples
from pyoxigraph import Literal, NamedNode, Triple
from support import same_as_fresh_load

from topostore import Ontology
from topostore.rdf.vocab import XSD, owl
from topostore.resources import default_ontology

NS = "http://example.org/prop#"
RDF_TYPE = "http://www.w3.org/1999/02/22-rdf-syntax-ns#type"

TBOX = """\
@prefix : <http://example.org/prop#> .
@prefix owl: <http://www.w3.org/2002/07/owl#> .
@prefix rdf: <http://www.w3.org/1999/02/22-rdf-syntax-ns#> .
@prefix rdfs: <http://www.w3.org/2000/01/rdf-schema#> .
<http://example.org/prop> a owl:Ontology .
:C0 a owl:Class . :C1 a owl:Class . :C2 a owl:Class . :C3 a owl:Class .
:C4 a owl:Class . :C5 a owl:Class . :C6 a owl:Class .
:p0 a owl:ObjectProperty . :p1 a owl:ObjectProperty . :p2 a owl:ObjectProperty .
:p3 a owl:ObjectProperty . :s a owl:ObjectProperty . :t a owl:ObjectProperty .

# subclass
:C1 rdfs:subClassOf :C2 .
:C2 rdfs:subClassOf :C3 .
# domain / range
:p0 rdfs:domain :C0 .
:p1 rdfs:range :C1 .
# subproperty
:p2 rdfs:subPropertyOf :p0 .
# inverse
:p3 owl:inverseOf :p1 .
# symmetric, transitive
:s a owl:SymmetricProperty .
:t a owl:TransitiveProperty .
:t rdfs:subPropertyOf :p2 .
# someValuesFrom in subclass position
[ a owl:Restriction ; owl:onProperty :p1 ; owl:someValuesFrom :C2 ] rdfs:subClassOf :C4 .
[ a owl:Restriction ; owl:onProperty :s ; owl:someValuesFrom :C4 ] rdfs:subClassOf :C3 .
# hasValue
:C5 owl:equivalentClass [ a owl:Restriction ; owl:onProperty :p0 ; owl:hasValue :i0 ] .
# intersection
:C6 owl:equivalentClass [ a owl:Class ; owl:intersectionOf ( :C0 :C3 ) ] .
"""
CLASSES = [f"C{i}" for i in range(7)]
PROPERTIES = ["p0", "p1", "p2", "p3", "s", "t"]
INDIVIDUALS = [f"i{i}" for i in range(5)]

type_assertions = st.lists(st.tuples(st.sampled_from(INDIVIDUALS), st.sampled_from(CLASSES)), max_size=6)
property_assertions = st.lists(
    st.tuples(st.sampled_from(INDIVIDUALS), st.sampled_from(PROPERTIES), st.sampled_from(INDIVIDUALS)), max_size=10)


def abox_text(types, props) -> str:
    lines = [f":{i} a :{c} ." for i, c in types] + [f":{a} :{p} :{b} ." for a, p, b in props]
    lines += [f":{i} a owl:NamedIndividual ." for i in INDIVIDUALS]
    return "\n".join(lines) + "\n"


def restricted(triples) -> set[tuple[str, str, str]]:
    """Class memberships in named classes and property assertions between the named individuals."""
    inds = {NS + i for i in INDIVIDUALS}
    classes = {NS + c for c in CLASSES}
    props = {NS + p for p in PROPERTIES}
    out = set()
    for s, p, o in triples:
        if s not in inds:
            continue
        if (p == RDF_TYPE and o in classes) or (p in props and o in inds):
            out.add((s, p, o))
    return out


@settings(max_examples=property_examples(30), deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(type_assertions, property_assertions)
def test_named_closure_equals_owlrl(types, props):
    # Reference: owlrl's implementation of the OWL 2 RL/RDF rules (W3C OWL 2 Profiles §4.3)
    text = TBOX + abox_text(types, props)
    g = rdflib.Graph()
    g.parse(data=text, format="turtle")
    owlrl.DeductiveClosure(owlrl.OWLRL_Semantics).expand(g)
    expected = restricted((str(s), str(p), str(o)) for s, p, o in g)

    onto = Ontology()
    onto.load_data(text, "turtle")
    report = onto.reason()
    assert report.consistent, report.explain()
    ours = restricted((t.subject.value, t.predicate.value, getattr(t.object, "value", ""))
                      for t in onto.triples(inferred=True) if isinstance(t.subject, NamedNode))
    assert ours == expected


# ---------------------------------------------------------------- incremental = from scratch

MAP = "http://bnc/exp-rob-lab/2022-23#"
NOW = 1665579740


def _n(name: str) -> NamedNode:
    return NamedNode(MAP + name)


def _long(v: int) -> Literal:
    return Literal(str(v), datatype=NamedNode(XSD + "long"))


POOL: list[Triple] = (
    [Triple(_n(l), _n("hasDoor"), _n(d)) for l in ("L1", "L2", "L3") for d in ("D1", "D2")]
    + [Triple(_n(l), _n("visitedAt"), _long(t)) for l in ("L1", "L2", "L3") for t in (NOW - 20, NOW - 3)]
    + [Triple(_n("Robot1"), _n("isIn"), _n(l)) for l in ("L1", "L2", "L3")]
    + [Triple(_n("Robot1"), _n("now"), _long(NOW)), Triple(_n("Robot1"), _n("urgencyThreshold"), _long(7))]
    + [Triple(_n(a), owl("differentFrom"), _n(b)) for a, b in (("L1", "L2"), ("L2", "L3"), ("L1", "L3"), ("D1", "D2"))]
    + [Triple(_n("L1"), owl("sameAs"), _n("L3")), Triple(_n("L1"), _n("hasDoor"), _n("L2"))]
)

operations = st.lists(
    st.tuples(st.sampled_from(["add", "remove", "add_all_different", "reason"]), st.integers(0, len(POOL) - 1)),
    min_size=1, max_size=12,
)


def _graph(o: Ontology, g: NamedNode) -> set:
    return set(o.store.triples(graph=g))


@settings(max_examples=property_examples(25), deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(operations)
def test_reasoning_after_changes_equals_reasoning_from_scratch(ops):
    # README: "Reasoning again must never keep conclusions whose premises were removed"
    onto = Ontology.from_file(default_ontology())
    onto.reason()
    for op, i in ops:
        if op == "add":
            onto.add(POOL[i])
        elif op == "remove":
            onto.remove(POOL[i])
        elif op == "add_all_different":
            onto.add_all_different(["L1", "L2", "L3"] if i % 2 else ["D1", "D2"])
        else:
            onto.reason()
    report = onto.reason()

    fresh, fresh_report = same_as_fresh_load(onto, report)
    assert sorted(str(v) for v in report.violations) == sorted(str(v) for v in fresh_report.violations)
