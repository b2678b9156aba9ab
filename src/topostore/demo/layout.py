"""Where to put each location of a topological map in a picture, from the map's own structure.

A general graph layout (force-directed, Kamada-Kawai) needs SciPy beyond a
few hundred nodes and turns a building into a hairball.  A topological map
already says how to draw it: corridors form the spine, every room hangs off
the corridor it opens onto.  So:

* corridors are ordered by walking the corridor graph depth-first from the
  end of a chain (adjacent corridors come out next to each other) and are laid
  out in rows, snaking left-right then right-left, so consecutive corridors
  stay neighbours in the picture;
* each room is placed on a ring (or rings) around its corridor; a room that
  opens only onto other rooms joins the corridor of its neighbour; a location
  reachable from no corridor goes into a group of its own;
* a door sits between the locations that have it.

Above ``cluster_above`` locations single rooms are unreadable whatever the
layout, so consecutive corridor groups are merged into clusters (at most
``max_clusters``), drawn as one node each.  Pure Python, linear in the size
of the map: 10,000 locations are laid out in well under a second.
"""

from __future__ import annotations

import math
import re
from collections import defaultdict
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field

Point = tuple[float, float]

#: Map size from which rooms are merged into clusters.
CLUSTER_ABOVE = 400
#: Most clusters drawn in a clustered picture.
MAX_CLUSTERS = 150
_RING_CAPACITY = 8  # rooms on the first ring; ring k holds 8k
_RING_STEP = 1.0


def natural_key(name: str) -> list[object]:
    """Sort key putting R2 before R10."""
    return [int(p) if p.isdigit() else p for p in re.split(r"(\d+)", name)]


@dataclass
class Group:
    """One corridor (``None`` for locations reachable from no corridor) and the rooms placed around it."""

    corridor: str | None
    rooms: list[str] = field(default_factory=list)

    @property
    def members(self) -> list[str]:
        return ([self.corridor] if self.corridor else []) + self.rooms


@dataclass
class Cluster:
    """Consecutive groups drawn as one node in a clustered picture."""

    groups: list[Group]
    position: Point = (0.0, 0.0)

    @property
    def members(self) -> list[str]:
        return [m for g in self.groups for m in g.members]

    @property
    def label(self) -> str:
        corridors = [g.corridor for g in self.groups if g.corridor]
        if not corridors:
            return "unattached"
        return corridors[0] if len(corridors) == 1 else f"{corridors[0]}–{corridors[-1]}"


@dataclass
class Layout:
    """Positions of locations and doors; ``clusters`` is set when the map is drawn clustered."""

    positions: dict[str, Point]
    doors: dict[str, Point]
    groups: list[Group]
    clusters: list[Cluster] | None = None
    cluster_of: dict[str, int] = field(default_factory=dict)

    @property
    def clustered(self) -> bool:
        return self.clusters is not None

    def bounds(self) -> tuple[float, float, float, float]:
        """(x0, y0, x1, y1) of what is drawn, at least one ring around the centre in each direction."""
        points = [c.position for c in self.clusters] if self.clusters is not None else list(self.positions.values())
        xs, ys = [p[0] for p in points] or [0.0], [p[1] for p in points] or [0.0]
        cx, cy = (min(xs) + max(xs)) / 2, (min(ys) + max(ys)) / 2
        return min(min(xs), cx - 1), min(min(ys), cy - 1), max(max(xs), cx + 1), max(max(ys), cy + 1)


def adjacency(has_door: Iterable[tuple[str, str]]) -> tuple[dict[str, list[str]], dict[str, set[str]]]:
    """(door → locations having it, location → locations sharing a door with it)."""
    members: dict[str, list[str]] = defaultdict(list)
    for loc, door in has_door:
        if loc not in members[door]:
            members[door].append(loc)
    neighbours: dict[str, set[str]] = defaultdict(set)
    for locs in members.values():
        for a in locs:
            neighbours[a].update(b for b in locs if b != a)
    return members, neighbours


def corridor_order(corridors: Sequence[str], neighbours: dict[str, set[str]]) -> list[str]:
    """Corridors in depth-first order over corridor-to-corridor doors, each walk starting at a chain end."""
    corridor_set = set(corridors)
    links = {c: sorted((n for n in neighbours.get(c, ()) if n in corridor_set), key=natural_key) for c in corridors}
    seen: set[str] = set()
    order: list[str] = []
    for start in sorted(corridors, key=lambda c: (len(links[c]) > 1, natural_key(c))):
        if start in seen:
            continue
        stack = [start]
        while stack:
            c = stack.pop()
            if c in seen:
                continue
            seen.add(c)
            order.append(c)
            stack.extend(reversed([n for n in links[c] if n not in seen]))
    return order


def group_locations(corridors: Sequence[str], others: Sequence[str], neighbours: dict[str, set[str]]) -> list[Group]:
    """Each corridor with the rooms opening onto it; rooms reached only through rooms join their neighbour's corridor."""
    order = corridor_order(corridors, neighbours)
    rank = {c: i for i, c in enumerate(order)}
    groups = [Group(c) for c in order]
    home: dict[str, int] = {c: rank[c] for c in order}
    frontier = []
    for loc in sorted(others, key=natural_key):
        near = [rank[n] for n in neighbours.get(loc, ()) if n in rank]
        if near:
            home[loc] = min(near)
            frontier.append(loc)
    while frontier:  # breadth-first through room-to-room doors
        nxt = []
        for loc in frontier:
            for n in sorted(neighbours.get(loc, ()), key=natural_key):
                if n not in home:
                    home[n] = home[loc]
                    nxt.append(n)
        frontier = nxt
    lonely = Group(None)
    for loc in sorted(others, key=natural_key):
        if loc in home:
            groups[home[loc]].rooms.append(loc)
        else:
            lonely.rooms.append(loc)
    if lonely.rooms:
        groups.append(lonely)
    return groups


def ring_offsets(count: int) -> list[Point]:
    """Offsets of ``count`` rooms around their corridor: rings of 8, 16, 24 ... away from the horizontal spine."""
    out: list[Point] = []
    ring = 1
    while len(out) < count:
        here = min(count - len(out), _RING_CAPACITY * ring)
        radius = _RING_STEP * ring
        for j in range(here):
            angle = math.pi / 4 + 2 * math.pi * j / here  # diagonals first: the spine runs horizontally
            out.append((radius * math.cos(angle), radius * math.sin(angle)))
        ring += 1
    return out


def snake(count: int, spacing: float, aspect: float = 1.4) -> list[Point]:
    """``count`` cell centres in rows, left-to-right then right-to-left, about ``aspect`` times wider than tall."""
    cols = max(1, math.ceil(math.sqrt(count * aspect)))
    out = []
    for i in range(count):
        row, col = divmod(i, cols)
        if row % 2:
            col = cols - 1 - col
        out.append((col * spacing, -row * spacing))
    return out


def _ring_radius(rooms: int) -> float:
    ring, placed = 0, 0
    while placed < rooms:
        ring += 1
        placed += _RING_CAPACITY * ring
    return ring * _RING_STEP


def layout(corridors: Sequence[str], others: Sequence[str], has_door: Iterable[tuple[str, str]],
           cluster_above: int = CLUSTER_ABOVE, max_clusters: int = MAX_CLUSTERS) -> Layout:
    """Positions for every location and door; clustered when there are more than ``cluster_above`` locations."""
    members, neighbours = adjacency(has_door)
    groups = group_locations(corridors, others, neighbours)
    largest = max((len(g.rooms) for g in groups), default=0)
    spacing = 2 * _ring_radius(largest) + 1.2
    positions: dict[str, Point] = {}
    for group, (cx, cy) in zip(groups, snake(len(groups), spacing)):
        if group.corridor:
            positions[group.corridor] = (cx, cy)
        for room, (dx, dy) in zip(group.rooms, ring_offsets(len(group.rooms))):
            positions[room] = (cx + dx, cy + dy)
    doors = door_positions(members, positions)
    result = Layout(positions, doors, groups)
    if len(positions) > cluster_above:
        cluster(result, max_clusters)
    return result


def door_positions(members: dict[str, list[str]], positions: dict[str, Point]) -> dict[str, Point]:
    """A door between the locations that have it; a door of one location just outside it."""
    out: dict[str, Point] = {}
    for door, locs in members.items():
        placed = [positions[loc] for loc in locs if loc in positions]
        if len(placed) >= 2:
            out[door] = (sum(p[0] for p in placed) / len(placed), sum(p[1] for p in placed) / len(placed))
        elif placed:
            out[door] = (placed[0][0] + 0.35, placed[0][1] - 0.35)
    return out


def cluster(result: Layout, max_clusters: int) -> None:
    """Merge consecutive groups into at most ``max_clusters`` clusters laid out on their own snake."""
    groups = result.groups
    size = max(1, math.ceil(len(groups) / max(1, max_clusters)))
    clusters = [Cluster(groups[i:i + size]) for i in range(0, len(groups), size)]
    for c, pos in zip(clusters, snake(len(clusters), 1.0)):
        c.position = pos
    result.clusters = clusters
    result.cluster_of = {m: i for i, c in enumerate(clusters) for m in c.members}


def cluster_links(result: Layout, has_door: Iterable[tuple[str, str]]) -> set[tuple[int, int]]:
    """Pairs of clusters joined by a door."""
    members, _ = adjacency(has_door)
    links: set[tuple[int, int]] = set()
    for locs in members.values():
        ids = sorted({result.cluster_of[loc] for loc in locs if loc in result.cluster_of})
        links.update((a, b) for i, a in enumerate(ids) for b in ids[i + 1:])
    return links


__all__ = ["Layout", "Group", "Cluster", "layout", "cluster_links", "natural_key", "CLUSTER_ABOVE", "MAX_CLUSTERS"]
