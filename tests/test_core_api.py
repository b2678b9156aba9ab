"""The Python API end to end, and a generated map of 1,000 locations.

Reasoning expectations come from /work/shared/ontology/README.md (Pellet
section) applied to the example environment or to the generator's structure.
"""

from __future__ import annotations

from pathlib import Path

import pytest
from pyoxigraph import BlankNode, NamedNode, Triple
from support import NOW, NS, instances, long, types_of

from topostore import InvalidValueError, Ontology, QueryError
from topostore.demo import mapgen
from topostore.rdf.declarations import missing_declarations
from topostore.rdf.vocab import ASSERTED, XSD
from topostore.resources import default_ontology, default_ontology_files


def values(items, key: str) -> list[str]:
    return [i.value for i in items if i.key == key]


def test_api_end_to_end(tmp_path: Path):
    # README facts for the example, then README behaviours after each change
    o = Ontology.from_file(*default_ontology_files())
    assert o.dirty
    report = o.reason()
    assert report.consistent and o.is_consistent and not o.dirty
    assert report.stats.derived > 0

    # named queries (README facts)
    assert values(o.query("reachable-locations", {"robot": "Robot1"}), "location") == [NS + "R1", NS + "R2"]
    assert values(o.query("urgent-locations"), "location") == [NS + "R1"]
    kinds = dict(zip(values(o.query("locations"), "location"), values(o.query("locations"), "kind")))
    assert kinds == {NS + "C1": "CORRIDOR", NS + "R1": "ROOM", NS + "R2": "ROOM"}
    with pytest.raises(QueryError):
        o.query("reachable-locations")  # missing parameter
    with pytest.raises(QueryError):
        o.query("no-such-query")

    # raw SPARQL over asserted ∪ inferred
    variables, rows, timed_out = o.select(f"SELECT ?l WHERE {{ ?l a <{NS}CORRIDOR> }}")
    assert variables == ["l"] and rows == [[NamedNode(NS + "C1")]] and not timed_out
    assert o.sparql(f"ASK {{ <{NS}Robot1> <{NS}canReach> <{NS}R2> }}")

    # manipulate: add a room behind a new door of C1
    o.add_fact("R3", "hasDoor", "D3")
    o.add_fact("C1", "hasDoor", "D3")
    o.add_data("visitedAt", "R3", NOW - 1, "long")
    o.add_all_different(["R3", "C1", "R1", "R2"])
    o.add_all_different(["D1", "D2", "D3"])
    assert o.dirty
    assert o.reason().consistent
    assert set(o.object_values("canReach", "Robot1")) == {"R1", "R2", "R3"}
    assert types_of(o, "R3") == {"LOCATION", "ROOM"}

    # replace: the robot moves to R3 and the clock advances (README: canReach of the old place is gone)
    assert o.replace("Robot1", "isIn", "R3") == 1
    assert o.replace("Robot1", "now", long(NOW + 10)) == 1
    assert o.reason().consistent
    assert set(o.object_values("canReach", "Robot1")) == {"C1"}
    assert instances(o, "URGENT") == {"C1", "R1", "R2", "R3"}

    # remove
    assert o.remove_fact("C1", "hasDoor", "D3") == 1
    assert o.reason().consistent
    assert set(o.object_values("canReach", "Robot1")) == set()
    assert o.remove_type("R3", "ROOM") == 0  # inferred facts cannot be removed, only premises

    # invalid values are refused before touching the store
    before = o.store.count(ASSERTED)
    with pytest.raises(InvalidValueError):
        o.add_data("visitedAt", "R3", "soon", "long")
    assert o.store.count(ASSERTED) == before

    # save asserted only, and asserted + inferred, then reload
    asserted_file = o.save(tmp_path / "asserted.ttl")
    inferred_file = o.save(tmp_path / "inferred.owl", inferred=True)
    nt_file = o.save(tmp_path / "asserted.nt")

    again = Ontology.from_file(asserted_file)
    # the file holds the asserted triples and the declarations they lack (rdf/declarations.py)
    assert again.store.count(ASSERTED) == o.store.count(ASSERTED) + len(missing_declarations(o.triples()))
    assert again.reason().consistent
    for name in ("C1", "R1", "R2", "R3", "D3", "Robot1"):
        assert types_of(again, name) == types_of(o, name), name
    assert set(again.object_values("canReach", "Robot1")) == set()
    assert [v.value for v in again.data_values("visitedAt", "R3")] == [str(NOW - 1)]
    assert again.data_values("visitedAt", "R3")[0].datatype == NamedNode(XSD + "long")

    from_nt = Ontology.from_file(nt_file)
    assert from_nt.store.count(ASSERTED) == again.store.count(ASSERTED)

    with_inferred = Ontology.from_file(inferred_file)
    # inferred facts are now asserted: visible before any reasoning
    assert {(t.subject.value, t.object.value) for t in with_inferred.store.triples(
        None, NamedNode("http://www.w3.org/1999/02/22-rdf-syntax-ns#type"), NamedNode(NS + "URGENT"), ASSERTED)} == {
        (NS + n, NS + "URGENT") for n in ("C1", "R1", "R2", "R3")}
    assert with_inferred.reason().consistent
    assert instances(with_inferred, "URGENT") == instances(o, "URGENT")


def test_queries_see_only_asserted_facts_while_inconsistent():
    # aRMOR behaviour (module docstring of topostore.ontology.facade): inconsistent -> asserted knowledge only
    o = Ontology.from_file(*default_ontology_files())
    o.reason()
    o.add_fact("C1", "hasDoor", "R1")  # README: DOOR and LOCATION are disjoint
    assert not o.reason().consistent
    assert o.violations
    assert o.object_values("canReach", "Robot1") == []
    assert instances(o, "URGENT") == set()
    o.remove_fact("C1", "hasDoor", "R1")
    assert o.reason().consistent
    assert instances(o, "URGENT") == {"R1"}


def test_prefix_comes_from_the_ontology_iri():
    o = Ontology.from_file(default_ontology())
    assert o.prefix == NS
    assert o.iri("R1") == NamedNode(NS + "R1")
    assert o.iri(f"<{NS}X>") == NamedNode(NS + "X")


# ---------------------------------------------------------------- generated map

def test_generated_map_of_1000_locations():
    m = mapgen.generate(1000)
    assert len(m.locations) == 1000
    o = Ontology.from_file(default_ontology())
    o.add(*m.triples())
    report = o.reason()
    assert report.consistent, report.explain()

    # README: connectedTo links two different locations sharing a door
    rows = o.sparql(f"SELECT ?a ?b WHERE {{ ?a <{NS}connectedTo> ?b }}")
    got: dict[str, set[str]] = {}
    for r in rows:
        got.setdefault(o.short(r["a"]), set()).add(o.short(r["b"]))
    expected = {loc: m.neighbours(loc) for loc in m.locations if m.neighbours(loc)}
    assert got == expected

    # README: CORRIDOR = at least two different doors (also ROOM); ROOM = some door
    doors = {loc: sum(1 for l, _ in m.has_door if l == loc) for loc in m.locations}
    assert instances(o, "CORRIDOR") == {loc for loc, n in doors.items() if n >= 2}
    assert instances(o, "ROOM") == {loc for loc, n in doors.items() if n >= 1}
    assert instances(o, "CORRIDOR") == set(m.corridors)
    assert len(instances(o, "ROOM")) == 1000
    assert instances(o, "DOOR") == set(m.doors)

    # README: canReach = the locations connected to the robot's location
    for robot, loc in m.robots.items():
        assert set(o.object_values("canReach", robot)) == m.neighbours(loc)

    # README: URGENT iff now - visitedAt > threshold
    assert instances(o, "URGENT") == {loc for loc, t in m.visited_at.items() if m.now - t > m.threshold}


def test_blank_nodes_added_through_the_api_are_named_as_a_load_names_them():
    """A restriction added as triples with a blank node is a class expression, as the same triples
    loaded from a file; the triples read back (blank nodes again) remove it."""
    def e(n: str) -> NamedNode:
        return NamedNode("http://ex/#" + n)

    owl = "http://www.w3.org/2002/07/owl#"
    sub, a = NamedNode("http://www.w3.org/2000/01/rdf-schema#subClassOf"), NamedNode(
        "http://www.w3.org/1999/02/22-rdf-syntax-ns#type")
    b = BlankNode()
    axiom = [Triple(e("A"), sub, b), Triple(b, a, NamedNode(owl + "Restriction")),
             Triple(b, NamedNode(owl + "onProperty"), e("p")), Triple(b, NamedNode(owl + "someValuesFrom"), e("B")),
             Triple(b, sub, e("S"))]
    onto = Ontology()
    onto.add(*axiom, Triple(e("z"), a, e("A")), Triple(e("S"), a, NamedNode(owl + "Class")))
    onto.reason()
    assert [i.value for i in onto.instances(e("S"))] == ["http://ex/#z"] and not onto.notice_lines()
    stored = [t for t in onto.triples() if isinstance(t.subject, BlankNode) or isinstance(t.object, BlankNode)]
    assert len(stored) == len(axiom)
    assert onto.remove(*stored) == len(axiom)
    onto.reason()
    assert not onto.instances(e("S"))
