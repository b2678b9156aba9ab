"""The demo's world: a map loaded into an aRMOR reference, and robots placed on it.

Everything after loading goes through :class:`ArmorClient`, as robot code
would (the client can point at ``topostore serve`` with the same calls).
The map files are merged into one Turtle file because aRMOR's LOAD FILE takes
one document; the merged file lives in a private data directory that also
confines the service's file access.
"""

from __future__ import annotations

import os
import tempfile
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path

from ..armor import ArmorService
from ..armor_api.armor_client import ArmorClient
from ..armor_api.armor_query_client import lexical_form
from ..errors import TopostoreError
from ..ontology.facade import Ontology
from ..resources import default_ontology, ontology_dir

REFERENCE = "surveillance"
CLIENT = "surveillance_demo"
DEFAULT_THRESHOLD = 7


def default_map_files() -> list[Path]:
    """The project's topological map: TBox with the SWRL rules, then the example environment."""
    return [default_ontology(), ontology_dir() / "topological_map_abox.ttl"]


@dataclass
class World:
    """A loaded map: the client to talk to it, the robots and the static facts of the map."""

    client: ArmorClient
    service: ArmorService
    robots: list[str]
    locations: list[str]
    corridors: set[str]
    workdir: tempfile.TemporaryDirectory = field(repr=False)

    @property
    def reference(self):
        """The service's reference (for drawing the reasoned map)."""
        return self.service.reference(REFERENCE)

    def close(self) -> None:
        self.service.close()
        self.workdir.cleanup()

    def robot_client(self, robot: str) -> ArmorClient:
        """A client of its own for one robot of a fleet (named after the robot)."""
        return ArmorClient(robot, REFERENCE, transport=self.service)


def open_world(map_files: Sequence[str | os.PathLike[str]] | None = None, robots: int = 1,
               store: str | None = None) -> World:
    """Load the map, declare locations and doors different (as the seed tutorial does), place ``robots`` robots.

    With a durable ``store`` that already holds the map, the stored map (robots where they were,
    clocks and visits as they were) is reused and only missing robots are placed.
    """
    if robots < 1:
        raise TopostoreError("the demo needs at least one robot (--robots 1 or more)")
    files = [Path(f) for f in (map_files or default_map_files())]
    onto = Ontology.from_file(*files)
    prefix = onto.prefix
    if not prefix.endswith("#"):
        raise TopostoreError(f"the map's namespace {prefix!r} does not end with '#': aRMOR names entities as IRI#name")
    workdir = tempfile.TemporaryDirectory(prefix="topostore-demo-")
    try:
        onto.save(Path(workdir.name) / "map.ttl")
        service = ArmorService(data_dir=workdir.name, store=store)
        client = ArmorClient(CLIENT, REFERENCE, transport=service)
        stored = REFERENCE in service.reference_names()
        if not stored:
            client.utils.load_ref_from_file("map.ttl", prefix[:-1], buffered_manipulation=False, reasoner="PELLET",
                                            buffered_reasoner=True)
            # no unique name assumption: corridors, connectedTo and canReach need declared differences
            client.manipulation.disj_inds_of_class("LOCATION")
            client.manipulation.disj_inds_of_class("DOOR")
        if not client.utils.sync_buffered_reasoner():
            raise TopostoreError(f"the map {', '.join(map(str, files))} is inconsistent; check it with `topostore reason`")
        locations = sorted(client.query.ind_b2_class("LOCATION"))
        if not locations:
            raise TopostoreError("the map has no LOCATION individuals (locations need hasDoor or visitedAt facts)")
        corridors = set(client.query.ind_b2_class("CORRIDOR"))
        names = _place_robots(client, robots, locations, corridors)
        if not client.utils.sync_buffered_reasoner():
            raise TopostoreError("placing the robots made the map inconsistent")
    except BaseException:
        if "service" in locals():
            service.close()
        workdir.cleanup()
        raise
    return World(client, service, names, locations, corridors, workdir)


def _place_robots(client: ArmorClient, count: int, locations: list[str], corridors: set[str]) -> list[str]:
    """Use the map's robots first, then create Robot2, Robot3, ... in corridors (round robin)."""
    query = client.query
    existing = sorted(query.ind_b2_class("ROBOT"))
    clocks = [int(lexical_form(v)) for r in existing for v in query.dataprop_b2_ind("now", r)]
    visits = [int(lexical_form(v)) for loc in locations for v in query.dataprop_b2_ind("visitedAt", loc)]
    start_time = max(clocks or visits or [0])
    thresholds = [lexical_form(v) for r in existing for v in query.dataprop_b2_ind("urgencyThreshold", r)]
    threshold = thresholds[0] if thresholds else str(DEFAULT_THRESHOLD)
    starts = sorted(corridors) or locations
    names: list[str] = []
    k = 1
    for i in range(count):
        if i < len(existing):
            name = existing[i]
        else:
            while f"Robot{k}" in existing or f"Robot{k}" in names:
                k += 1
            name = f"Robot{k}"
        names.append(name)
        manip = client.manipulation
        if not query.objectprop_b2_ind("isIn", name):
            manip.add_objectprop_to_ind("isIn", name, starts[i % len(starts)])
        if not query.dataprop_b2_ind("now", name):
            manip.add_dataprop_to_ind("now", name, "LONG", str(start_time))
        if not query.dataprop_b2_ind("urgencyThreshold", name):
            manip.add_dataprop_to_ind("urgencyThreshold", name, "LONG", threshold)
    return names


__all__ = ["World", "open_world", "default_map_files", "REFERENCE", "CLIENT"]
