"""topostore against the reference reasoner itself: Pellet 2.3.1 (bundled with Owlready2 0.49).

Each scenario changes the example environment of ``../shared/ontology`` through the Python
API, saves it, and compares what topostore infers with what Pellet infers for the same file:
consistency, the named classes of every individual, and the connectedTo / canReach values.
Skipped when Java or Owlready2 is not installed (``pip install owlready2==0.49`` and Debian's
``openjdk-17-jre-headless``).

Two behaviours of Pellet 2.3.1 are deliberately not reproduced, so no scenario here provokes
them: it sometimes reports only one direction of a symmetric SWRL conclusion found by
refutation, and it misses the clash between two integer values of very different magnitude
(``5`` and ``1665579710``) under a maximum cardinality, which is plainly wrong in OWL.
"""

from __future__ import annotations

import json
import shutil
import subprocess
import sys
from collections.abc import Callable
from pathlib import Path

import pytest
from pyoxigraph import Triple

from topostore import Ontology
from topostore.demo import mapgen
from topostore.ontology.nary import axiom_of_list_node
from topostore.rdf.vocab import DIFFERENT_FROM, FIRST

ROOT = Path(__file__).resolve().parents[1]
ABOX = ROOT.parent / "shared" / "ontology" / "topological_map_abox.owl"
TBOX = ROOT.parent / "shared" / "ontology" / "topological_map.owl"
NS = "http://bnc/exp-rob-lab/2022-23#"
NAMES = ["C1", "C2", "R1", "R2", "R3", "D1", "D2", "D3", "D4", "Robot1", "Robot2", "X"]
PROPS = ["canReach", "connectedTo"]

pytestmark = [
    pytest.mark.skipif(shutil.which("java") is None, reason="Pellet needs a Java runtime"),
    pytest.mark.skipif(
        subprocess.run([sys.executable, "-c", "import owlready2"], capture_output=True).returncode != 0,
        reason="Owlready2 (which bundles Pellet) is not installed",
    ),
]

PELLET_SCRIPT = r"""
import json, sys, owlready2
NS, names, props = sys.argv[2], json.loads(open(sys.argv[3]).read()), json.loads(sys.argv[4])
world = owlready2.World()
onto = world.get_ontology(sys.argv[1]).load()
try:
    with onto:
        owlready2.sync_reasoner_pellet(world, infer_property_values=True, infer_data_property_values=True, debug=0)
except owlready2.OwlReadyInconsistentOntologyError:
    print(json.dumps({"consistent": False})); sys.exit()
out = {}
for name in names:
    ind = world[NS + name]
    if ind is None:
        continue
    types = set()
    for c in ind.is_a:
        if isinstance(c, owlready2.ThingClass):
            types |= {a.name for a in c.ancestors() if a.iri.startswith(NS)}
    facts = {"types": sorted(types)}
    for p in props:
        prop = world[NS + p]
        values = sorted({v.name for v in prop[ind]}) if prop is not None else []
        if values:
            facts[p] = values
    out[name] = facts
print(json.dumps({"consistent": True, "individuals": out}))
"""


def pellet(path: Path, names: list[str], ns: str = NS, props: list[str] = PROPS) -> dict:
    names_file = path.with_suffix(".names.json")
    names_file.write_text(json.dumps(names))
    run = subprocess.run(
        [sys.executable, "-c", PELLET_SCRIPT, path.resolve().as_uri(), ns, str(names_file), json.dumps(props)],
        capture_output=True, text=True, timeout=300,
    )
    assert run.returncode == 0, run.stderr[-2000:]
    return json.loads(run.stdout.strip().splitlines()[-1])


def topostore(onto: Ontology, names: list[str], ns: str = NS, props: list[str] = PROPS) -> dict:
    if not onto.reason().consistent:
        return {"consistent": False}
    out = {}
    for name in names:
        types = sorted(onto.short(t) for t in onto.types(name) if t.value.startswith(ns))
        facts: dict = {"types": types}
        for p in props:
            values = sorted(onto.object_values(p, name))
            if values:
                facts[p] = values
        if mentioned(onto, name):
            out[name] = facts
    return {"consistent": True, "individuals": out}


def mentioned(onto: Ontology, name: str) -> bool:
    """Whether the file names this individual at all (Owlready2 then knows the entity)."""
    iri = onto.iri(name)
    return any(True for _ in onto.store.triples(iri, None, None)) or any(True for _ in onto.store.triples(None, None, iri))


def drop_all_different(onto: Ontology, member: str) -> None:
    """Remove the owl:AllDifferent axiom listing ``member`` (its other facts stay)."""
    for t in list(onto.store.triples(None, FIRST, onto.iri(member))):
        onto.remove(*axiom_of_list_node(onto.store, t.subject))


def long(onto: Ontology, n: int):
    return onto.value(n, "long")


SCENARIOS: dict[str, Callable[[Ontology], None]] = {
    "example": lambda o: None,
    "doors not declared different": lambda o: drop_all_different(o, "D1"),
    "locations not declared different, distinct visits": lambda o: drop_all_different(o, "C1"),
    "robot moved to R1": lambda o: o.replace("Robot1", "isIn", "R1"),
    "robot in an undeclared place: sameAs merge": lambda o: o.add_fact("Robot1", "isIn", "X"),
    "robot in two places declared different": lambda o: o.add_fact("Robot1", "isIn", "R1"),
    "a door that is a location": lambda o: o.add_fact("R1", "hasDoor", "R2"),
    "a room with a second, different door": lambda o: (o.add_fact("R1", "hasDoor", "D3"),
                                                       o.add_all_different(["D1", "D3"])),
    "a door link removed": lambda o: o.remove_fact("C1", "hasDoor", "D2"),
    "visited in the future": lambda o: o.replace("R2", "visitedAt", long(o, 1665579999)),
    "time advances": lambda o: o.replace("Robot1", "now", long(o, 1665579760)),
    "a new room not declared different": lambda o: (o.add_fact("R3", "hasDoor", "D1"),
                                                    o.add_fact("R3", "visitedAt", long(o, 1665579000))),
    "a new room declared different from C1 only": lambda o: (
        o.add_fact("R3", "hasDoor", "D1"), o.add_fact("R3", "visitedAt", long(o, 1665579000)),
        o.add(Triple(o.iri("R3"), DIFFERENT_FROM, o.iri("C1")))),
    "a location without doors": lambda o: o.add_fact("R3", "visitedAt", long(o, 1665579700)),
    "two visit times of one location": lambda o: o.add_fact("R1", "visitedAt", long(o, 1665579720)),
    "a literal outside its range": lambda o: o.add_data("visitedAt", "R1", "1.5", "decimal"),
    "second robot on the map": lambda o: (o.add_fact("Robot2", "isIn", "R2"), o.add_fact("Robot2", "now", long(o, 1665579800)),
                                          o.add_fact("Robot2", "urgencyThreshold", long(o, 50))),
}


@pytest.mark.parametrize("name", list(SCENARIOS))
def test_same_inferences_as_pellet(name: str, tmp_path: Path) -> None:
    onto = Ontology.from_file(ABOX)
    SCENARIOS[name](onto)
    path = tmp_path / "scenario.nt"
    onto.save(path, fmt="ntriples")
    expected = pellet(path, NAMES)
    assert topostore(Ontology.from_file(path), NAMES) == expected


def generated(size: int, seed: int, declared: bool) -> tuple[Ontology, list[str]]:
    """A generated map (corridors and rooms) on the reference TBox, and its individuals."""
    m = mapgen.generate(size, seed=seed)
    onto = Ontology.from_file(TBOX)
    onto.add(*m.triples(all_different=declared))
    return onto, m.locations + m.doors + list(m.robots)


@pytest.mark.parametrize("size,seed,declared", [(9, 1, True), (9, 2, False)])
def test_generated_maps_with_robot_moves_as_pellet(size: int, seed: int, declared: bool, tmp_path: Path) -> None:
    # a map that is not the example: the robot moves into a room off its corridor, time passes
    onto, names = generated(size, seed, declared)
    room = sorted(mapgen.generate(size, seed=seed).neighbours("C1") - {"C2"})[0]
    onto.replace("Robot1", "isIn", room)
    onto.replace("Robot1", "now", onto.value(1665579760, "long"))
    onto.replace(room, "visitedAt", onto.value(1665579760, "long"))
    path = tmp_path / "map.nt"
    onto.save(path, fmt="ntriples")
    assert topostore(Ontology.from_file(path), names) == pellet(path, names)


def test_repaired_saved_map_saves_rules_pellet_fires(tmp_path: Path) -> None:
    """A map whose rules a save damaged (nested atom lists): topostore repairs it on load, and its
    own SAVE (RDF/XML) is read by Pellet, whose rules then draw what topostore draws."""
    import warnings

    from test_saved_rules import damage

    from topostore import OntologyWarning

    damaged = tmp_path / "damaged.owl"
    damage(ABOX, damaged)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", OntologyWarning)
        onto = Ontology.from_file(damaged)
    path = tmp_path / "resaved.owl"
    onto.save(path)
    names = ["C1", "R1", "R2", "D1", "D2", "Robot1"]
    expected = pellet(path, names)
    assert expected["individuals"]["Robot1"].get("canReach") == ["R1", "R2"]  # Pellet fires the saved rules
    assert topostore(Ontology.from_file(path), names) == expected


def test_swrl_difference_by_disjoint_classes_chains_as_in_pellet(tmp_path: Path) -> None:
    """A family ontology whose sibling rule reads DifferentFrom and whose brother rule reads the
    sibling rule's conclusion: children different by declaration or by disjoint classes (disjointWith,
    AllDisjointClasses, a disjoint union, a complement; asserted or derived types) get the same
    siblings, brothers and types as Pellet gives them."""
    import warnings

    from topostore import OntologyWarning

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", OntologyWarning)  # the complement and the union's covering are named
        onto = Ontology.from_file(ROOT / "tests" / "data" / "family_difference.ttl")
        path = tmp_path / "family.nt"
        onto.save(path, fmt="ntriples")
        ns, props = "http://example.org/family#", ["hasSibling", "hasBrother"]
        names = sorted({onto.short(t.subject) for t in onto.store.triples(None, onto.iri("hasParent"), None)}
                       | {onto.short(t.object) for t in onto.store.triples(None, onto.iri("hasParent"), None)}
                       | {"carl", "dora", "sue"})
        expected = pellet(path, names, ns, props)
        got = topostore(Ontology.from_file(path), names, ns, props)
    assert sum("hasBrother" in facts for facts in expected["individuals"].values()) == 7  # Pellet chains
    assert got == expected
