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
import subprocess
import sys
from pathlib import Path

import pytest
from scenarios import NAMES, PROPS, SCENARIOS, damage, generated, topostore
from support import ABOX_OWL as ABOX
from support import DATA, NEEDS_PELLET, NS, pellet_env

from topostore import Ontology
from topostore.demo import mapgen

ROOT = Path(__file__).resolve().parents[1]

pytestmark = NEEDS_PELLET

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
        capture_output=True, text=True, timeout=300, env=pellet_env(),
    )
    assert run.returncode == 0, run.stderr[-2000:]
    return json.loads(run.stdout.strip().splitlines()[-1])


def test_pellet_runs_in_a_jvm_with_the_quick_jit_only() -> None:
    """The ``java`` launcher of a Pellet run reads :func:`pellet_env`'s options (and says so on stderr)."""
    run = subprocess.run(["java", "-XX:+PrintFlagsFinal", "-version"], env=pellet_env(), capture_output=True,
                         text=True, timeout=60, check=True)
    assert "Picked up JDK_JAVA_OPTIONS" in run.stderr
    assert any(line.split()[:1] == ["intx"] and "TieredStopAtLevel" in line and line.split()[3] == "1"
               for line in run.stdout.splitlines())


@pytest.mark.parametrize("name", list(SCENARIOS))
def test_same_inferences_as_pellet(name: str, tmp_path: Path) -> None:
    onto = Ontology.from_file(ABOX)
    SCENARIOS[name](onto)
    path = tmp_path / "scenario.nt"
    onto.save(path, fmt="ntriples")
    expected = pellet(path, NAMES)
    assert topostore(Ontology.from_file(path), NAMES) == expected


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
        onto = Ontology.from_file(DATA / "family_difference.ttl")
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
