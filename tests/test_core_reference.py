"""The reference example reasons to exactly Pellet's facts; loading formats, graphs and load errors.

Expected facts come from /work/shared/ontology/README.md, "Facts a Pellet run
gives on topological_map_abox.owl".
"""

from __future__ import annotations

import hashlib
from pathlib import Path

import pyoxigraph
import pytest
import rdflib
from pyoxigraph import Literal, NamedNode, Triple
from rdflib.compare import isomorphic
from support import ABOX_OWL, NS, TBOX_OWL, connected, instances, types_of

from topostore import LoadError, Ontology
from topostore.rdf.vocab import ASSERTED, AUX, INFERRED, TYPE, XSD
from topostore.resources import default_ontology, default_ontology_files

LONG = NamedNode(XSD + "long")

INDIVIDUALS = ("C1", "R1", "R2", "D1", "D2", "Robot1")
# README, Pellet section "Facts a Pellet run gives on topological_map_abox.owl"
README_TYPES = {
    "C1": {"LOCATION", "ROOM", "CORRIDOR"},
    "R1": {"LOCATION", "ROOM", "URGENT"},
    "R2": {"LOCATION", "ROOM"},
    "D1": {"DOOR"},
    "D2": {"DOOR"},
    "Robot1": {"ROBOT"},
}
README_CONNECTED = {("C1", "R1"), ("R1", "C1"), ("C1", "R2"), ("R2", "C1")}
README_CAN_REACH = {"R1", "R2"}
README_URGENT = {"R1"}



def assert_readme_facts(o: Ontology) -> None:
    report = o.reason()
    assert report.consistent, report.explain()
    for name in INDIVIDUALS:
        assert types_of(o, name) == README_TYPES[name], name
    assert connected(o) == README_CONNECTED
    assert set(o.object_values("canReach", "Robot1")) == README_CAN_REACH
    assert instances(o, "URGENT") == README_URGENT


def test_reference_abox_owl_gives_the_readme_facts():
    # README: Pellet's facts on topological_map_abox.owl (RDF/XML file loaded unchanged)
    digest = hashlib.sha256(ABOX_OWL.read_bytes()).hexdigest()
    o = Ontology.from_file(ABOX_OWL)
    assert_readme_facts(o)
    assert hashlib.sha256(ABOX_OWL.read_bytes()).hexdigest() == digest


def test_embedded_ontology_files_give_the_readme_facts():
    # README: our own Turtle files describe the same environment, so Pellet's facts hold
    files = default_ontology_files()
    assert files[0] == default_ontology()
    assert [f.name for f in files] == ["topological_map.ttl", "topological_map_abox.ttl"]
    o = Ontology.from_file(*files)
    assert o.prefix == NS
    assert_readme_facts(o)
    assert {o.short(c) for c in o.subclasses("LOCATION")} == {"ROOM", "CORRIDOR", "URGENT"}


def test_embedded_tbox_alone_has_no_individuals_and_is_consistent():
    o = Ontology.from_file(default_ontology())
    assert o.reason().consistent
    assert instances(o, "LOCATION") == set()
    assert instances(o, "ROBOT") == set()
    assert {r.name for r in o.rules.rules if r.name.startswith("swrl:")} == {
        "swrl:Connectability", "swrl:Urgency", "swrl:Reachability"}


@pytest.mark.parametrize("path", default_ontology_files(), ids=lambda p: p.name)
def test_embedded_files_parse_with_rdflib(path):
    """rdflib reads the embedded files as the same graph pyoxigraph reads (an independent parser agrees)."""
    g = rdflib.Graph()
    for s, p, o in rdflib.Graph().parse(path, format="turtle"):  # "x"^^xsd:string is "x" in RDF 1.1
        plain = isinstance(o, rdflib.Literal) and o.datatype == rdflib.XSD.string
        g.add((s, p, rdflib.Literal(str(o)) if plain else o))
    ours = pyoxigraph.serialize(pyoxigraph.parse(path=str(path), format=pyoxigraph.RdfFormat.TURTLE),
                                format=pyoxigraph.RdfFormat.N_TRIPLES)
    expected = rdflib.Graph().parse(data=ours, format="nt")
    assert len(g) == len(expected) and isomorphic(g, expected)


def test_embedded_tbox_has_the_reference_axioms():
    # Same TBox as the reference: compare the two graphs without SWRL variables'
    # IRIs (ours live in a namespace of their own), individuals and annotations.
    def axioms(path: Path, fmt: str) -> rdflib.Graph:
        g = rdflib.Graph()
        g.parse(path, format=fmt)
        out = rdflib.Graph()
        swrl = "http://www.w3.org/2003/11/swrl#"
        skip_subjects = set(g.subjects(rdflib.RDF.type, rdflib.URIRef(swrl + "Variable")))
        skip_subjects |= set(g.subjects(rdflib.RDF.type, rdflib.OWL.NamedIndividual))
        skip_subjects |= set(g.subjects(rdflib.RDF.type, rdflib.URIRef(swrl + "Imp")))
        for s, p, o in g:
            if s in skip_subjects or isinstance(s, rdflib.BNode) or isinstance(o, rdflib.BNode):
                continue
            if p == rdflib.RDFS.comment:
                continue
            out.add((s, p, o))
        return out

    ours = axioms(default_ontology(), "turtle")
    ref = axioms(TBOX_OWL, "xml")
    assert set(ours) == set(ref)
    # the anonymous parts (restrictions, rules) are checked by reasoning in the other tests,
    # and the SWRL rules compile to the same rules as the reference's


def test_embedded_swrl_rules_compile_like_the_reference_rules():
    def swrl_rules(o: Ontology) -> dict:
        return {r.name: (r.where(), r.head) for r in o.rules.rules if r.name.startswith("swrl:")}

    ours = swrl_rules(Ontology.from_file(default_ontology()))
    assert set(ours) == {"swrl:Connectability", "swrl:Urgency", "swrl:Reachability"}
    assert ours == swrl_rules(Ontology.from_file(TBOX_OWL))


def test_rebuilding_the_example_fact_by_fact_through_the_api():
    # README Pellet section: domains/ranges type individuals, CORRIDOR needs two
    # doors declared different, connectedTo/canReach need different locations.
    o = Ontology.from_file(TBOX_OWL)
    o.reason()
    # topological_map.owl gives Robot1 now/urgencyThreshold: domain ROBOT
    assert types_of(o, "Robot1") == {"ROBOT"}

    o.add_fact("C1", "hasDoor", "D1")
    o.add_fact("C1", "hasDoor", "D2")
    o.reason()
    # hasDoor domain LOCATION, range DOOR; ∃hasDoor.DOOR ⊓ LOCATION = ROOM;
    # D1, D2 not declared different: no CORRIDOR (README: no unique name assumption)
    assert types_of(o, "C1") == {"LOCATION", "ROOM"}
    assert types_of(o, "D1") == {"DOOR"}

    o.add_all_different(["D1", "D2"])
    o.reason()
    assert types_of(o, "C1") == {"LOCATION", "ROOM", "CORRIDOR"}

    o.add_fact("R1", "hasDoor", "D1")
    o.add_fact("R2", "hasDoor", "D2")
    o.reason()
    # locations neither declared nor entailed different yet: no connectedTo (README)
    assert connected(o) == set()

    for loc, t in (("C1", 1665579740), ("R1", 1665579710), ("R2", 1665579735)):
        o.add_fact(loc, "visitedAt", Literal(str(t), datatype=LONG))
    o.reason()
    # Urgency needs a ROBOT with now/urgencyThreshold, not where it is
    assert instances(o, "URGENT") == {"R1"}
    # different visit times make the locations necessarily different (LOCATION has exactly
    # one visitedAt): Pellet 2.3.1 then infers connectedTo, found by refutation
    assert connected(o) == README_CONNECTED

    o.add_all_different(["C1", "R1", "R2"])
    o.reason()
    assert connected(o) == README_CONNECTED
    assert o.object_values("canReach", "Robot1") == []

    o.add_fact("Robot1", "isIn", "C1")
    assert_readme_facts(o)


def test_ntriples_and_turtle_copies_of_the_reference_give_the_same_facts(tmp_path):
    # README facts; the format of the file must not matter
    g = rdflib.Graph()
    g.parse(ABOX_OWL, format="xml")
    nt = tmp_path / "abox.nt"
    ttl = tmp_path / "abox.ttl"
    g.serialize(nt, format="nt", encoding="utf-8")
    g.serialize(ttl, format="turtle")
    for path in (nt, ttl):
        o = Ontology.from_file(path)
        assert_readme_facts(o)


def test_asserted_and_inferred_live_in_separate_graphs():
    # README facts: R1 is URGENT (inferred), C1 hasDoor D1 (asserted)
    o = Ontology.from_file(ABOX_OWL)
    o.reason()
    urgent = Triple(NamedNode(NS + "R1"), TYPE, NamedNode(NS + "URGENT"))
    door = Triple(NamedNode(NS + "C1"), NamedNode(NS + "hasDoor"), NamedNode(NS + "D1"))
    assert o.store.contains(urgent, INFERRED) and not o.store.contains(urgent, ASSERTED)
    assert o.store.contains(door, ASSERTED) and not o.store.contains(door, INFERRED)
    # queries see the union of both graphs
    assert o.sparql(f"ASK {{ <{NS}R1> a <{NS}URGENT> . <{NS}C1> <{NS}hasDoor> <{NS}D1> }}")
    # nothing inferred leaks into the asserted graph
    assert not any(t.predicate == NamedNode(NS + "connectedTo") for t in o.store.triples(graph=ASSERTED))
    # saving asserted only gives back the file's triples
    assert urgent not in set(o.triples(inferred=False))
    assert urgent in set(o.triples(inferred=True))


def _counts(o: Ontology) -> tuple[int, int, int]:
    return o.store.count(ASSERTED), o.store.count(INFERRED), o.store.count(AUX)


BAD_TURTLE = '@prefix : <http://bnc/exp-rob-lab/2022-23#> .\n:C9 :hasDoor :D9 .\n:C9 :visitedAt "12 .\n'
BAD_RDFXML = (
    '<?xml version="1.0"?>\n'
    '<rdf:RDF xmlns:rdf="http://www.w3.org/1999/02/22-rdf-syntax-ns#">\n'
    '  <rdf:Description rdf:about="http://bnc/exp-rob-lab/2022-23#C9">\n'
    '</rdf:RDF>\n'
)


@pytest.mark.parametrize("name,text,line", [("broken.ttl", BAD_TURTLE, 3), ("broken.owl", BAD_RDFXML, 4)])
def test_invalid_rdf_gives_load_error_and_leaves_state_untouched(tmp_path, name, text, line):
    o = Ontology.from_file(ABOX_OWL)
    o.reason()
    before = _counts(o)
    bad = tmp_path / name
    bad.write_text(text)
    with pytest.raises(LoadError) as info:
        o.load(bad)
    message = str(info.value)
    assert str(bad) in message
    assert f":{line}:" in message
    assert "not valid" in message
    assert _counts(o) == before
    assert o.types("C9") == []
    assert_readme_facts(o)


def test_missing_file_gives_load_error(tmp_path):
    o = Ontology()
    with pytest.raises(LoadError) as info:
        o.load(tmp_path / "nowhere.ttl")
    assert "nowhere.ttl" in str(info.value)
    assert o.store.count(ASSERTED) == 0
