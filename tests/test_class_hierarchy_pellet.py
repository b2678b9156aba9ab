"""QUERY CLASS CLASS against Pellet 2.3.1 itself (through Owlready2): for every class, what aRMOR's
``getSubClasses(cls, false)`` answers over Pellet.

Owlready2 gives Pellet's classification as each class's subclasses, an unsatisfiable class apart
(``inconsistent_classes``); the OWL API puts such a class in owl:Nothing's node, which is under every class, so
the expected answer lists it under each other class.  Equivalent classes are the class's own node and are left
out, as the OWL API leaves them out."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest
from support import NEEDS_PELLET, pellet_env
from test_armor_class_queries import EQUIVALENT, NS, RULE, UNSATISFIABLE, Service

pytestmark = [*NEEDS_PELLET, pytest.mark.external]

PELLET_SCRIPT = r"""
import json, sys, owlready2
base = sys.argv[2]
world = owlready2.World()
onto = world.get_ontology(sys.argv[1]).load()
with onto:
    owlready2.sync_reasoner_pellet(world, infer_property_values=True, debug=0)
empty = sorted(c.iri for c in world.inconsistent_classes() if c.iri.startswith(base))
out = {}
for c in world.classes():
    if c.iri.startswith(base):
        same = {e.iri for e in c.equivalent_to if hasattr(e, "iri")}
        out[c.iri] = sorted({d.iri for d in c.descendants(include_self=False) if d.iri.startswith(base)} - same)
print(json.dumps({"subclasses": out, "unsatisfiable": empty}))
"""


def pellet_subclasses(path: Path) -> dict[str, list[str]]:
    """Each class's subclasses as the OWL API answers them over Pellet (local names)."""
    run = subprocess.run([sys.executable, "-c", PELLET_SCRIPT, path.resolve().as_uri(), NS],
                         capture_output=True, text=True, timeout=300, env=pellet_env())
    assert run.returncode == 0, run.stderr[-2000:]
    found = json.loads(run.stdout.strip().splitlines()[-1])
    empty = set(found["unsatisfiable"])
    return {c[len(NS):]: sorted(d[len(NS):] for d in set(subs) | (empty - {c} if c not in empty else set()))
            for c, subs in found["subclasses"].items()}


def test_query_class_class_as_pellet(tmp_path: Path) -> None:
    s = Service(tmp_path, "\n".join([RULE, EQUIVALENT, UNSATISFIABLE]))
    assert s("REASON").is_consistent
    saved = tmp_path / "saved.owl"
    assert s("SAVE", "", "", str(saved)).success
    expected = pellet_subclasses(saved)
    # the cases this file is about: no subclass by the rule, equivalents left out, U under every class
    assert (expected["K"], expected["A"], expected["Z"]) == (["U"], ["S", "U"], ["U"])
    assert {c: s.names("QUERY", "CLASS", "CLASS", c) for c in expected} == expected
