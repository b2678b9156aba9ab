"""A picture of a topological map as the reasoner sees it.

Everything drawn comes from the *reasoned* ontology: which locations are
CORRIDORs or ROOMs, which are URGENT, which are connectedTo each other, where
each robot isIn.  So the picture shows the reasoner's conclusions, not the
input file, and is a quick way to check them.  :mod:`.layout` places the
locations from the map's own structure (corridors as spines, rooms around
them, clusters for big maps); matplotlib (the ``[viz]`` extra, imported only
here) draws them through ``Figure`` directly, with no global pyplot state, so
pictures can be made from any thread.
"""

from __future__ import annotations

import os
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from ..errors import TopostoreError
from ..ontology.facade import Ontology
from .layout import CLUSTER_ABOVE, Layout, cluster_links, layout

#: Output formats matplotlib writes that make sense for a map.
PICTURE_FORMATS = (".png", ".svg", ".pdf")
VIZ_HINT = "pip install 'topostore[viz]'"

CORRIDOR_COLOUR, ROOM_COLOUR, OTHER_COLOUR = "#f5d76e", "#a8d8a8", "#dddddd"
DOOR_COLOUR, LINK_COLOUR, URGENT_COLOUR, ROBOT_COLOUR = "#8c564b", "#4a90d9", "#d62728", "#1f3b73"


class VizMissing(TopostoreError):
    """matplotlib, which draws the pictures, is not installed (the ``[viz]`` extra)."""


def require_matplotlib() -> None:
    """Raise :class:`VizMissing` with the install command when matplotlib cannot be imported."""
    try:
        import matplotlib  # noqa: F401
    except ImportError:
        raise VizMissing(f"drawing maps needs matplotlib, which is not installed: {VIZ_HINT}") from None


@dataclass
class MapView:
    """The facts a picture needs, read from a reasoned ontology."""

    corridors: list[str] = field(default_factory=list)
    rooms: list[str] = field(default_factory=list)
    other_locations: list[str] = field(default_factory=list)
    doors: list[str] = field(default_factory=list)
    has_door: list[tuple[str, str]] = field(default_factory=list)
    connected: set[frozenset[str]] = field(default_factory=set)
    urgent: set[str] = field(default_factory=set)
    robots: dict[str, str | None] = field(default_factory=dict)  # robot -> location

    @property
    def locations(self) -> list[str]:
        return self.corridors + self.rooms + self.other_locations

    @classmethod
    def from_ontology(cls, onto: Ontology) -> MapView:
        """Read the map from ``onto``, reasoning first if it changed since the last reasoning."""
        if onto.dirty or onto.report is None:
            onto.reason()
        names = lambda cls_name: sorted(onto.short(t) for t in onto.instances(cls_name))  # noqa: E731
        corridors = names("CORRIDOR")
        corridor_set = set(corridors)
        rooms = [r for r in names("ROOM") if r not in corridor_set]
        known = corridor_set | set(rooms)
        others = [loc for loc in names("LOCATION") if loc not in known]
        view = cls(corridors=corridors, rooms=rooms, other_locations=others, doors=names("DOOR"),
                   urgent=set(names("URGENT")))
        locations = set(view.locations)
        view.has_door = sorted(p for p in _pairs(onto, "hasDoor") if p[0] in locations)
        view.connected = {frozenset(p) for p in _pairs(onto, "connectedTo") if p[0] in locations and p[0] != p[1]}
        where: dict[str, list[str]] = {}
        for robot, loc in _pairs(onto, "isIn"):
            where.setdefault(robot, []).append(loc)
        for robot in names("ROBOT"):
            view.robots[robot] = sorted(where[robot])[0] if where.get(robot) else None
        return view


def _pairs(onto: Ontology, prop: str) -> list[tuple[str, str]]:
    """(subject, object) short names of every ``prop`` fact, asserted or inferred, in one query."""
    rows = onto.sparql(f"SELECT ?s ?o WHERE {{ ?s <{onto.iri(prop).value}> ?o }}")
    return [(onto.short(r["s"]), onto.short(r["o"])) for r in rows]


@dataclass
class Style:
    """What to highlight: robots (isIn) and URGENT locations; ``cluster_above`` switches to clusters."""

    robots: bool = True
    urgent: bool = True
    cluster_above: int = CLUSTER_ABOVE


def draw(view: MapView, path: str | os.PathLike[str], title: str = "", style: Style | None = None) -> Path:
    """Write the picture to ``path`` (.png, .svg or .pdf); returns the path."""
    style = style or Style()
    path = Path(path)
    if path.suffix.lower() not in PICTURE_FORMATS:
        raise TopostoreError(f"cannot draw {str(path)!r}: use a {', '.join(PICTURE_FORMATS)} file name")
    if not view.locations:
        raise TopostoreError("nothing to draw: the ontology has no LOCATION individuals")
    require_matplotlib()
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    placed = layout(view.corridors, view.rooms + view.other_locations, view.has_door, cluster_above=style.cluster_above)
    x0, y0, x1, y1 = placed.bounds()
    scale = 0.55 if placed.clustered else 0.6  # inches per layout unit
    width = min(40.0, max(6.0, (x1 - x0 + 3) * scale * (1.6 if placed.clustered else 1.0)))
    height = min(40.0, max(4.5, (y1 - y0 + 3) * scale * (1.6 if placed.clustered else 1.0) + 1.0))
    fig = Figure(figsize=(width, height), dpi=100)
    FigureCanvasAgg(fig)
    ax = fig.add_subplot()
    ax.set_axis_off()
    ax.set_aspect("equal")
    if placed.clustered:
        _draw_clusters(ax, view, placed, style)
    else:
        _draw_full(ax, view, placed, style)
    ax.margins(0.06)
    if title:
        ax.set_title(title, fontsize=11)
    fig.tight_layout()
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path)
    return path


def _draw_full(ax: Any, view: MapView, placed: Layout, style: Style) -> None:
    """Every location, door and connection, labelled."""
    from matplotlib.collections import LineCollection
    from matplotlib.lines import Line2D

    pos, doors = placed.positions, placed.doors
    ax.add_collection(LineCollection([(pos[loc], doors[d]) for loc, d in view.has_door if loc in pos and d in doors],
                                     colors="#999999", linewidths=1.0, zorder=1))
    links = [tuple(pos[p] for p in pair) for pair in view.connected if len(pair) == 2 and all(p in pos for p in pair)]
    ax.add_collection(LineCollection(links, colors=LINK_COLOUR, linestyles="dashed", linewidths=1.4, alpha=0.7, zorder=2))
    small = len(pos) > 60
    kinds = ((view.corridors, "s", CORRIDOR_COLOUR, 300 if small else 900),
             (view.rooms, "o", ROOM_COLOUR, 260 if small else 700),
             (view.other_locations, "o", OTHER_COLOUR, 260 if small else 600))
    for nodes, marker, colour, size in kinds:
        nodes = [n for n in nodes if n in pos]
        if not nodes:
            continue
        urgent = [style.urgent and n in view.urgent for n in nodes]
        ax.scatter([pos[n][0] for n in nodes], [pos[n][1] for n in nodes], s=size, marker=marker, c=colour,
                   edgecolors=[URGENT_COLOUR if u else "#333333" for u in urgent],
                   linewidths=[2.5 if u else 0.8 for u in urgent], zorder=3)
    door_names = [d for d in view.doors if d in doors]
    if door_names:
        ax.scatter([doors[d][0] for d in door_names], [doors[d][1] for d in door_names], s=14 if small else 40,
                   marker="D", c=DOOR_COLOUR, zorder=4)
    font = 5.5 if small else 9
    for name in view.locations:
        if name in pos:
            ax.annotate(name, pos[name], ha="center", va="center", fontsize=font, zorder=5)
    if not small:
        for d in door_names:
            ax.annotate(d, doors[d], xytext=(0, 5), textcoords="offset points", ha="center", fontsize=7,
                        color="#5a3a2a", zorder=5)
    if style.robots:
        _robots(ax, {r: pos[loc] for r, loc in view.robots.items() if loc in pos}, small)
    legend = [
        Line2D([], [], marker="s", ls="", color=CORRIDOR_COLOUR, markeredgecolor="#333333", markersize=10, label="CORRIDOR"),
        Line2D([], [], marker="o", ls="", color=ROOM_COLOUR, markeredgecolor="#333333", markersize=10, label="ROOM"),
        Line2D([], [], marker="D", ls="", color=DOOR_COLOUR, markersize=6, label="DOOR"),
        Line2D([], [], color=LINK_COLOUR, ls="--", label="connectedTo"),
    ]
    if style.urgent:
        legend.insert(2, Line2D([], [], marker="o", ls="", color="white", markeredgecolor=URGENT_COLOUR,
                                markeredgewidth=3, markersize=10, label="URGENT"))
    if style.robots:
        legend.append(Line2D([], [], marker="s", ls="", color=ROBOT_COLOUR, markersize=9, label="robot (isIn)"))
    ax.legend(handles=legend, loc="upper center", bbox_to_anchor=(0.5, 0.0), ncol=(len(legend) + 1) // 2, fontsize=8,
              frameon=False)


def _draw_clusters(ax: Any, view: MapView, placed: Layout, style: Style) -> None:
    """One node per cluster of consecutive corridors with their rooms: size by locations, red by URGENT share."""
    from matplotlib.collections import LineCollection
    from matplotlib.lines import Line2D

    clusters = placed.clusters or []
    centre = [c.position for c in clusters]
    links = cluster_links(placed, view.has_door)
    ax.add_collection(LineCollection([(centre[a], centre[b]) for a, b in sorted(links)], colors="#777777",
                                     linewidths=2.0, zorder=1))
    sizes = [len(c.members) for c in clusters]
    urgent = [sum(1 for m in c.members if m in view.urgent) if style.urgent else 0 for c in clusters]
    biggest = max(sizes, default=1)
    ax.scatter([p[0] for p in centre], [p[1] for p in centre], s=[250 + 900 * n / biggest for n in sizes],
               c=[(u / n) if n else 0.0 for u, n in zip(urgent, sizes)], cmap="YlOrRd", vmin=0.0, vmax=1.0,
               edgecolors=[URGENT_COLOUR if u else "#333333" for u in urgent],
               linewidths=[2.0 if u else 0.8 for u in urgent], zorder=3)
    for c, n, u in zip(clusters, sizes, urgent):
        text = f"{c.label}\n{n} loc." + (f"\n{u} URGENT" if u else "")
        ax.annotate(text, c.position, xytext=(0, -17), textcoords="offset points", ha="center", va="top",
                    fontsize=5.5, zorder=5)
    if style.robots:
        _robots(ax, {r: centre[placed.cluster_of[loc]] for r, loc in view.robots.items() if loc in placed.cluster_of},
                True, {r: loc for r, loc in view.robots.items()})
    legend = [
        Line2D([], [], marker="o", ls="", color="#ffffcc", markeredgecolor="#333333", markersize=10,
               label=f"corridors with their rooms ({len(view.locations)} locations in {len(clusters)} clusters)"),
        Line2D([], [], color="#777777", lw=2, label="doors between clusters"),
    ]
    if style.urgent:
        legend.insert(1, Line2D([], [], marker="o", ls="", color="#e31a1c", markeredgecolor=URGENT_COLOUR,
                                markersize=10, label=f"share of URGENT locations ({len(view.urgent)} in all)"))
    if style.robots:
        legend.append(Line2D([], [], marker="s", ls="", color=ROBOT_COLOUR, markersize=9, label="robot (isIn)"))
    ax.legend(handles=legend, loc="upper center", bbox_to_anchor=(0.5, 0.0), ncol=2, fontsize=8, frameon=False)


def _robots(ax: Any, at: dict[str, tuple[float, float]], small: bool, where: dict[str, str | None] | None = None) -> None:
    """A dark label next to each robot's location (robots sharing a place share a label)."""
    here: dict[tuple[float, float], list[str]] = {}
    for robot, point in at.items():
        here.setdefault(point, []).append(f"{robot} @ {where[robot]}" if where else robot)
    for point, robots in here.items():
        ax.annotate("\n".join(sorted(robots)), point, xytext=(10, 10), textcoords="offset points",
                    fontsize=6 if small else 8, color="white", zorder=6,
                    bbox={"boxstyle": "round", "fc": ROBOT_COLOUR, "ec": "none"})


def draw_ontology(onto: Ontology, path: str | os.PathLike[str], title: str = "", style: Style | None = None) -> Path:
    """Reason if needed, then draw ``onto``'s map to ``path``."""
    return draw(MapView.from_ontology(onto), path, title, style)


__all__ = ["MapView", "Style", "draw", "draw_ontology", "require_matplotlib", "VizMissing", "PICTURE_FORMATS",
           "VIZ_HINT"]
