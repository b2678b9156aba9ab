"""A picture of a topological map as the reasoner sees it.

Everything drawn comes from the *reasoned* ontology: which locations are
CORRIDORs or ROOMs, which are URGENT, which are connectedTo each other, where
each robot isIn.  So the picture shows the reasoner's conclusions, not the
input file, and is a quick way to check them.  networkx places the nodes;
matplotlib draws them (through ``Figure`` directly, no global pyplot state,
so pictures can be made from any thread).
"""

from __future__ import annotations

import os
from dataclasses import dataclass, field
from pathlib import Path

import networkx as nx
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure
from matplotlib.lines import Line2D

from ..errors import TopostoreError
from ..ontology import Ontology

#: Output formats matplotlib writes that make sense for a map.
PICTURE_FORMATS = (".png", ".svg", ".pdf")


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
    def from_ontology(cls, onto: Ontology) -> "MapView":
        """Read the map from ``onto``, reasoning first if it changed since the last reasoning."""
        if onto.dirty or onto.report is None:
            onto.reason()
        names = lambda cls_name: sorted(onto.short(t) for t in onto.instances(cls_name))  # noqa: E731
        corridors = names("CORRIDOR")
        rooms = [r for r in names("ROOM") if r not in corridors]
        others = [loc for loc in names("LOCATION") if loc not in corridors and loc not in rooms]
        view = cls(corridors=corridors, rooms=rooms, other_locations=others, doors=names("DOOR"),
                   urgent=set(names("URGENT")))
        for loc in view.locations:
            for door in onto.object_values("hasDoor", loc):
                view.has_door.append((loc, door))
            for other in onto.object_values("connectedTo", loc):
                view.connected.add(frozenset((loc, other)))
        for robot in names("ROBOT"):
            where = onto.object_values("isIn", robot)
            view.robots[robot] = sorted(where)[0] if where else None
        return view

    def graph(self) -> nx.Graph:
        g = nx.Graph()
        for loc in self.locations:
            g.add_node(loc, kind="location")
        for door in self.doors:
            g.add_node(door, kind="door")
        for loc, door in self.has_door:
            g.add_edge(loc, door)
        return g


def draw(view: MapView, path: str | os.PathLike[str], title: str = "", seed: int = 0) -> Path:
    """Write the picture to ``path`` (.png, .svg or .pdf); returns the path."""
    path = Path(path)
    if path.suffix.lower() not in PICTURE_FORMATS:
        raise TopostoreError(f"cannot draw {str(path)!r}: use a {', '.join(PICTURE_FORMATS)} file name")
    g = view.graph()
    if g.number_of_nodes() == 0:
        raise TopostoreError("nothing to draw: the ontology has no LOCATION or DOOR individuals")
    pos = nx.kamada_kawai_layout(g) if _has_scipy() and g.number_of_nodes() > 2 else nx.spring_layout(g, seed=seed)
    size = max(6.0, min(24.0, 2.0 + g.number_of_nodes() ** 0.5 * 1.6))
    fig = Figure(figsize=(size, size * 0.75), dpi=110)
    FigureCanvasAgg(fig)
    ax = fig.add_subplot()
    ax.set_axis_off()
    # doors on the walls between locations, connectedTo as the paths a robot may take
    nx.draw_networkx_edges(g, pos, ax=ax, edge_color="#999999", width=1.0)
    connections = [tuple(pair) for pair in view.connected if len(pair) == 2 and all(p in pos for p in pair)]
    nx.draw_networkx_edges(nx.Graph(connections), pos, ax=ax, edge_color="#4a90d9", style="dashed", width=1.6,
                           alpha=0.8)
    kinds = (
        (view.corridors, "s", "#f5d76e", 1500, "CORRIDOR"),
        (view.rooms, "o", "#a8d8a8", 1100, "ROOM"),
        (view.other_locations, "o", "#dddddd", 900, "LOCATION"),
    )
    for nodes, shape, colour, node_size, _ in kinds:
        if nodes:
            edge = ["#d62728" if n in view.urgent else "#333333" for n in nodes]
            width = [3.5 if n in view.urgent else 1.0 for n in nodes]
            nx.draw_networkx_nodes(g, pos, nodelist=nodes, node_shape=shape, node_color=colour, node_size=node_size,
                                   edgecolors=edge, linewidths=width, ax=ax)
    if view.doors:
        nx.draw_networkx_nodes(g, pos, nodelist=view.doors, node_shape="D", node_color="#8c564b", node_size=120, ax=ax)
    nx.draw_networkx_labels(g, pos, labels={n: n for n in view.locations}, font_size=9, ax=ax)
    door_label_pos = {d: (pos[d][0], pos[d][1] + 0.045) for d in view.doors}
    nx.draw_networkx_labels(g, door_label_pos, labels={d: d for d in view.doors}, font_size=7, font_color="#5a3a2a",
                            verticalalignment="bottom", ax=ax)
    here: dict[str, list[str]] = {}
    for robot, loc in view.robots.items():
        if loc in pos:
            here.setdefault(loc, []).append(robot)
    for loc, robots in here.items():
        x, y = pos[loc]
        ax.annotate("\n".join(sorted(robots)), (x, y), xytext=(14, 14), textcoords="offset points", fontsize=8,
                    color="white", bbox={"boxstyle": "round", "fc": "#1f3b73", "ec": "none"})
    legend = [
        Line2D([], [], marker="s", ls="", color="#f5d76e", markeredgecolor="#333333", markersize=11, label="CORRIDOR"),
        Line2D([], [], marker="o", ls="", color="#a8d8a8", markeredgecolor="#333333", markersize=11, label="ROOM"),
        Line2D([], [], marker="o", ls="", color="white", markeredgecolor="#d62728", markeredgewidth=3, markersize=11,
               label="URGENT"),
        Line2D([], [], marker="D", ls="", color="#8c564b", markersize=6, label="DOOR"),
        Line2D([], [], color="#4a90d9", ls="--", label="connectedTo"),
        Line2D([], [], marker="s", ls="", color="#1f3b73", markersize=9, label="robot (isIn)"),
    ]
    ax.margins(0.12)
    ax.legend(handles=legend, loc="upper center", bbox_to_anchor=(0.5, 0.0), ncol=len(legend), fontsize=8,
              frameon=False)
    if title:
        ax.set_title(title, fontsize=10)
    fig.tight_layout()
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path)
    return path


def draw_ontology(onto: Ontology, path: str | os.PathLike[str], title: str = "") -> Path:
    """Reason if needed, then draw ``onto``'s map to ``path``."""
    return draw(MapView.from_ontology(onto), path, title)


def _has_scipy() -> bool:
    try:
        import scipy  # noqa: F401  (kamada_kawai_layout needs it)
    except ImportError:
        return False
    return True


__all__ = ["MapView", "draw", "draw_ontology", "PICTURE_FORMATS"]
