"""The maps every reasoner in the benchmark gets: the shipped example, or a chain of corridors.

A map is written as one file (the project's TBox ``ontology/topological_map.ttl`` with its
SWRL rules, plus the ABox), so that topostore's LOAD FILE and the OWL API read the very same
triples.  The robot's view of the map (who neighbours whom, when each place was visited, the
clock) is read back from those triples, not from the generator, so the example file and a
generated chain go through one code path.
"""

from __future__ import annotations

import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path

from pyoxigraph import Literal, NamedNode, RdfFormat, Triple

from topostore import Ontology
from topostore.demo.mapgen import MAP_NS, generate
from topostore.resources import default_ontology, ontology_dir
from topostore.stores import memory_store
from topostore.stores.base import serialize, unskolemize

#: the name of the shipped example map on the command line and in the tables
EXAMPLE = "example"
ROBOT = "Robot1"
PREFIXES = {"": MAP_NS, "owl": "http://www.w3.org/2002/07/owl#", "xsd": "http://www.w3.org/2001/XMLSchema#",
            "rdf": "http://www.w3.org/1999/02/22-rdf-syntax-ns#", "rdfs": "http://www.w3.org/2000/01/rdf-schema#",
            "swrl": "http://www.w3.org/2003/11/swrl#", "swrlb": "http://www.w3.org/2003/11/swrlb#"}


@dataclass
class BenchMap:
    """What the robot knows of a map: enough to plan moves and to predict the answers."""

    name: str
    neighbours: dict[str, list[str]] = field(default_factory=dict)  # location -> locations sharing a door
    visited: dict[str, int] = field(default_factory=dict)  # location -> visitedAt
    doors: int = 0
    start: str = ""
    now: int = 0
    threshold: int = 0
    triples: int = 0

    @property
    def locations(self) -> int:
        return len(self.neighbours)

    @property
    def label(self) -> str:
        return f"example file ({self.locations})" if self.name == EXAMPLE else f"chain {self.locations:,}"


def abox(size: str) -> list[Triple]:
    """The ABox of a size: the example file, or a chain of ``size / 2`` corridors with one room each.

    Chains come from :func:`topostore.demo.mapgen.generate` with one room per corridor: corridors
    in a row joined by doors, a room behind its own door off each corridor, one
    ``owl:AllDifferent`` over every location and door, visit times staggered over the last
    minute, Robot1 in the first corridor.
    """
    if size == EXAMPLE:
        return memory_store().parse_file(ontology_dir() / "topological_map_abox.ttl")
    n = int(size)
    if n < 2 or n % 2:
        raise ValueError(f"a chain map has an even number of locations (corridors + rooms), not {size!r}")
    return generate(n, rooms_per_corridor=1).triples()


def write(size: str, folder: Path, fmt: RdfFormat = RdfFormat.RDF_XML) -> tuple[Path, BenchMap]:
    """TBox + ABox of ``size`` as one file in ``folder`` (RDF/XML by default: the OWL API reads it)."""
    data = abox(size)
    triples = memory_store().parse_file(default_ontology()) + data
    suffix = {RdfFormat.RDF_XML: "owl", RdfFormat.N_TRIPLES: "nt"}[fmt]
    path = folder / f"map-{size}.{suffix}"
    path.write_bytes(serialize([unskolemize(t) for t in triples], fmt, PREFIXES))
    bench = read(size, data)
    bench.triples = len(triples)
    return path, bench


def loaded(size: str) -> tuple[Ontology, float]:
    """A new ontology holding the chain map of ``size`` (written to a temporary folder and loaded from
    the file, as a user loads it), with the CPU seconds of that LOAD."""
    with tempfile.TemporaryDirectory(prefix="topostore-map-") as tmp:
        path, _ = write(size, Path(tmp))
        onto = Ontology()
        start = time.process_time()
        onto.load(path)
        return onto, time.process_time() - start


def read(name: str, triples: list[Triple]) -> BenchMap:
    """The robot's view of a map from its ABox triples (hasDoor, visitedAt, isIn, now, urgencyThreshold)."""
    doors_of: dict[str, set[str]] = {}
    bench = BenchMap(name)
    for t in triples:
        p, s, o = t.predicate.value, local(t.subject), t.object
        if p == MAP_NS + "hasDoor":
            doors_of.setdefault(s, set()).add(local(o))
        elif p == MAP_NS + "visitedAt":
            doors_of.setdefault(s, set())
            bench.visited[s] = number(o)
        elif s == ROBOT and p == MAP_NS + "isIn":
            bench.start = local(o)
        elif s == ROBOT and p == MAP_NS + "now":
            bench.now = number(o)
        elif s == ROBOT and p == MAP_NS + "urgencyThreshold":
            bench.threshold = number(o)
    if not bench.start or bench.start not in doors_of:
        raise ValueError(f"map {name!r}: {ROBOT} is not in one of its locations")
    by_door: dict[str, set[str]] = {}
    for loc, doors in doors_of.items():
        for d in doors:
            by_door.setdefault(d, set()).add(loc)
    bench.doors = len(by_door)
    bench.neighbours = {loc: sorted(set().union(*(by_door[d] for d in doors)) - {loc})
                        for loc, doors in doors_of.items()}
    return bench


def local(term: object) -> str:
    """The name of a map entity (the part after ``#``)."""
    if not isinstance(term, NamedNode):
        return str(term)
    return term.value.removeprefix(MAP_NS)


def number(term: object) -> int:
    if not isinstance(term, Literal):
        raise ValueError(f"expected a number, got {term}")
    return int(term.value)
