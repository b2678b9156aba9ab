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

from ..errors import TopostoreError
from .fleet import run_fleet
from .step import Move, describe, take_step
from .world import World, open_world


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
            run_fleet(world, steps, seed, time_scale, emit, result)
        for step in in_turn:
            emit(f"Step {step}")
            for robot in world.robots:
                move = take_step(world, robot, step, rng)
                result.moves.append(move)
                for line in describe(move):
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


def _numbered(path: Path, step: int) -> Path:
    return path.with_name(f"{path.stem}-{step:03d}{path.suffix}")


def _draw(world: World, path: Path, title: str) -> Path:
    from .mapview import draw_ontology  # matplotlib is the [viz] extra: imported only when drawing

    ref = world.reference
    with ref.lock:
        return draw_ontology(ref.ontology, path, title)


__all__ = ["run_demo", "DemoResult", "Move"]
