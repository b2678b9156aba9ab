"""Generated topological maps: corridors in a row, rooms off the corridors.

Used by the tests, the benchmarks and the demo, so that nothing is tuned to
the three-room example.  Every location and door is declared different in one
owl:AllDifferent (the tutorial's DISJOINT IND), as a robot's map would be.
"""

from __future__ import annotations

import random
from collections import Counter
from dataclasses import dataclass, field

from pyoxigraph import Literal, NamedNode, Triple

from ..rdf.vocab import FIRST, MAP_NS, NIL, REST, SKOLEM_PREFIX, TYPE, XSD, owl

LONG = NamedNode(XSD + "long")


def _iri(name: str, ns: str = MAP_NS) -> NamedNode:
    return NamedNode(ns + name)


@dataclass
class TopoMap:
    """A generated map: locations, doors, which door each location has, robot state."""

    corridors: list[str] = field(default_factory=list)
    rooms: list[str] = field(default_factory=list)
    doors: list[str] = field(default_factory=list)
    has_door: list[tuple[str, str]] = field(default_factory=list)
    visited_at: dict[str, int] = field(default_factory=dict)
    robots: dict[str, str] = field(default_factory=dict)  # robot -> location
    now: int = 1665579740
    threshold: int = 7

    @property
    def locations(self) -> list[str]:
        return self.corridors + self.rooms

    def neighbours(self, location: str) -> set[str]:
        """Locations sharing a door with ``location`` (what connectedTo must give)."""
        doors = {d for l, d in self.has_door if l == location}
        return {l for l, d in self.has_door if d in doors and l != location}

    def triples(self, ns: str = MAP_NS, all_different: bool = True) -> list[Triple]:
        """The map as ABox triples (to add to an ontology holding the TBox)."""
        out: list[Triple] = []
        ni = owl("NamedIndividual")
        for name in self.locations + self.doors + list(self.robots):
            out.append(Triple(_iri(name, ns), TYPE, ni))
        for loc, door in self.has_door:
            out.append(Triple(_iri(loc, ns), _iri("hasDoor", ns), _iri(door, ns)))
        for loc, t in self.visited_at.items():
            out.append(Triple(_iri(loc, ns), _iri("visitedAt", ns), Literal(str(t), datatype=LONG)))
        for robot, loc in self.robots.items():
            out.append(Triple(_iri(robot, ns), _iri("isIn", ns), _iri(loc, ns)))
            out.append(Triple(_iri(robot, ns), _iri("now", ns), Literal(str(self.now), datatype=LONG)))
            out.append(Triple(_iri(robot, ns), _iri("urgencyThreshold", ns), Literal(str(self.threshold), datatype=LONG)))
        if all_different:
            out += all_different_triples([_iri(n, ns) for n in self.locations + self.doors], ns)
        return out


def all_different_triples(members: list[NamedNode], ns: str = MAP_NS) -> list[Triple]:
    """One owl:AllDifferent over ``members`` as an RDF list (linear size)."""
    group = NamedNode(SKOLEM_PREFIX + "mapgen-alldifferent")
    nodes = [NamedNode(f"{SKOLEM_PREFIX}mapgen-list-{i}") for i in range(len(members))]
    out = [Triple(group, TYPE, owl("AllDifferent")), Triple(group, owl("distinctMembers"), nodes[0] if nodes else NIL)]
    for i, (node, m) in enumerate(zip(nodes, members)):
        out.append(Triple(node, FIRST, m))
        out.append(Triple(node, REST, nodes[i + 1] if i + 1 < len(nodes) else NIL))
    return out


def generate(n_locations: int, rooms_per_corridor: int = 4, seed: int = 0, robots: int = 1,
             now: int = 1665579740, threshold: int = 7) -> TopoMap:
    """A map of ``n_locations`` locations: corridors C1..Ck in a row joined by doors,
    each with up to ``rooms_per_corridor`` rooms behind a door of their own.

    Corridors have two or more doors (so they are CORRIDORs), rooms one (ROOMs).
    Visit times are spread over the last minute so some locations are URGENT.
    """
    if n_locations < 1:
        raise ValueError("a map needs at least one location")
    rng = random.Random(seed)
    m = TopoMap(now=now, threshold=threshold)
    n_corr = max(1, round(n_locations / (rooms_per_corridor + 1)))
    m.corridors = [f"C{i + 1}" for i in range(n_corr)]
    m.rooms = [f"R{i + 1}" for i in range(n_locations - n_corr)]
    doors = 0

    def new_door() -> str:
        nonlocal doors
        doors += 1
        name = f"D{doors}"
        m.doors.append(name)
        return name

    for a, b in zip(m.corridors, m.corridors[1:]):
        d = new_door()
        m.has_door += [(a, d), (b, d)]
    for i, room in enumerate(m.rooms):
        corridor = m.corridors[i % n_corr]
        d = new_door()
        m.has_door += [(corridor, d), (room, d)]
    # a corridor needs two doors to be a CORRIDOR: give lone corridors an extra exit
    door_count = Counter(loc for loc, _ in m.has_door)  # counted once: maps go to 100,000 locations
    for c in m.corridors:
        if door_count[c] < 2:
            m.has_door.append((c, new_door()))
    for loc in m.locations:
        m.visited_at[loc] = now - rng.randint(0, 60)
    for r in range(robots):
        m.robots[f"Robot{r + 1}"] = m.corridors[r % n_corr]
    return m
