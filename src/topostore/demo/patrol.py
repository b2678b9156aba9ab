"""Run the surveillance scenario and print a readable trace of every decision.

Each step, every robot: asks where it is, what it canReach and which
locations are URGENT; decides (:func:`~.policy.decide`); moves and stays a
while; updates ``isIn``, its own ``now`` and the location's ``visitedAt``
with aRMOR REPLACE commands; and REASONs.  Robots keep their own clocks, so
the Urgency rule judges each robot's visits by that robot's ``now``.
"""

from __future__ import annotations

import os
import random
import time
from collections import Counter
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path

from ..armor_api.armor_query_client import lexical_form
from ..errors import TopostoreError
from .policy import decide
from .world import World, open_world

#: How long (simulated seconds) a move takes and how long the robot stays.
TRAVEL_SECONDS = 1
STAY_SECONDS = {"corridor": (1, 2), "room": (2, 4)}


@dataclass
class Move:
    """One robot's step, as printed in the trace."""

    step: int
    robot: str
    origin: str | None
    reachable: list[str]
    urgent: list[str]
    decision: str
    destination: str | None
    went_urgent: bool
    time: int
    elapsed: int
    reason_ms: float
    consistent: bool


@dataclass
class DemoResult:
    moves: list[Move] = field(default_factory=list)
    pictures: list[Path] = field(default_factory=list)
    robots: list[str] = field(default_factory=list)

    def visits(self) -> Counter:
        return Counter(m.destination for m in self.moves if m.destination)


def run_demo(map_files: Sequence[str | os.PathLike[str]] | None = None, steps: int = 10, seed: int = 0,
             robots: int = 1, time_scale: float = 0.0, picture: str | os.PathLike[str] | None = "out/map.png",
             every_step: bool = False, emit: Callable[[str], None] = print, store: str | None = None) -> DemoResult:
    """Run ``steps`` steps; ``time_scale`` = real seconds slept per simulated second (0: no waiting).

    With ``store`` (a directory or a SPARQL server URL) the map lives there and the robots are a
    fleet: each robot is a client of its own in a thread of its own (:mod:`.fleet`); the
    trace names the robot on every line.
    """
    if steps < 0:
        raise TopostoreError("--steps must be 0 or more")
    if time_scale < 0:
        raise TopostoreError("--time-scale must be 0 or more")
    rng = random.Random(seed)
    world = open_world(map_files, robots, store)
    result = DemoResult(robots=list(world.robots))
    try:
        emit(f"Map: {len(world.locations)} locations ({len(world.corridors)} corridors); robots: {', '.join(world.robots)}")
        in_turn = range(1, steps + 1) if store is None else range(0)  # a fleet runs its own steps
        if store is not None:
            from .fleet import run_fleet

            run_fleet(world, steps, seed, time_scale, emit, result)
        for step in in_turn:
            emit(f"Step {step}")
            for robot in world.robots:
                move = _step(world, robot, step, rng)
                result.moves.append(move)
                for line in _describe(move):
                    emit(line)
                if not move.consistent:
                    raise TopostoreError(f"the ontology became inconsistent after {robot} moved; stopping")
                if time_scale:
                    time.sleep(time_scale * move.elapsed)
            if every_step and picture is not None:
                result.pictures.append(_draw(world, _numbered(Path(picture), step), f"step {step}"))
        if picture is not None and (not every_step or steps == 0):
            result.pictures.append(_draw(world, Path(picture), f"after {steps} steps"))
        if result.pictures:
            emit(f"Picture: {result.pictures[-1]}" if len(result.pictures) == 1 else
                 f"Pictures: {result.pictures[0]} ... {result.pictures[-1]}")
        visits = result.visits()
        if visits:
            emit("Visits: " + ", ".join(f"{loc} {n}" for loc, n in sorted(visits.items())))
    finally:
        world.close()
    return result


def _step(world: World, robot: str, step: int, rng: random.Random, client=None) -> Move:
    client = client or world.client
    query, manip, utils = client.query, client.manipulation, client.utils
    here_list = query.objectprop_b2_ind("isIn", robot)
    here = here_list[0] if here_list else None
    now = int(lexical_form(query.dataprop_b2_ind("now", robot)[0]))
    reachable = sorted(query.objectprop_b2_ind("canReach", robot))
    urgent = sorted(query.ind_b2_class("URGENT"))
    visited = {loc: int(lexical_form(v[0])) for loc in reachable if loc in urgent for v in [query.dataprop_b2_ind("visitedAt", loc)] if v}
    decision = decide(here, reachable, urgent, world.corridors, visited, now, rng)
    target = decision.destination or here
    kind = "corridor" if target in world.corridors else "room"
    elapsed = (TRAVEL_SECONDS if decision.destination else 0) + rng.randint(*STAY_SECONDS[kind])
    new_now = now + elapsed
    if decision.destination and decision.destination != here:
        if here is None:
            manip.add_objectprop_to_ind("isIn", robot, decision.destination)
        else:
            manip.replace_objectprop_b2_ind("isIn", robot, decision.destination, here)
    manip.replace_dataprop_b2_ind("now", robot, "LONG", str(new_now), str(now))
    if target is not None:
        manip.replace_one_dataprop_b2_ind("visitedAt", target, "LONG", str(new_now))
    start = time.perf_counter()
    consistent = utils.sync_buffered_reasoner()
    reason_ms = (time.perf_counter() - start) * 1000
    return Move(step, robot, here, reachable, urgent, decision.reason, decision.destination, decision.urgent, new_now,
                elapsed, reason_ms, consistent)


def _describe(move: Move) -> list[str]:
    where = move.origin or "nowhere"
    if len(move.urgent) <= 8:
        urgent = ", ".join(move.urgent) or "none"
    else:
        in_reach = [loc for loc in move.urgent if loc in move.reachable]
        urgent = f"{len(move.urgent)} locations ({', '.join(in_reach) or 'none'} in reach)"
    lines = [
        f"  {move.robot} in {where}: can reach {', '.join(move.reachable) or 'nothing'}; URGENT {urgent}",
        f"    decision: {move.decision}",
    ]
    moved = move.destination is not None and move.destination != move.origin
    arrived = f"moved to {move.destination}" if moved else f"stayed in {where}"
    state = "consistent" if move.consistent else "INCONSISTENT"
    lines.append(f"    {arrived} (+{move.elapsed} s, clock {move.time}); REASON {move.reason_ms:.1f} ms ({state})")
    return lines


def _numbered(path: Path, step: int) -> Path:
    return path.with_name(f"{path.stem}-{step:03d}{path.suffix}")


def _draw(world: World, path: Path, title: str) -> Path:
    from .mapview import draw_ontology  # matplotlib is the [viz] extra: imported only when drawing

    ref = world.reference
    with ref.lock:
        return draw_ontology(ref.ontology, path, title)


__all__ = ["run_demo", "DemoResult", "Move"]
