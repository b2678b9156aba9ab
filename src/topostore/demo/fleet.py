"""A fleet on one shared map: one client and one thread per robot, all through one store.

Each robot patrols as in the single-robot demo (:func:`.step.take_step`), but
with a client of its own (its name is the client name) and in a thread of its
own; the store (a directory or a SPARQL server) holds the one shared map.  A
step reads the map, decides and writes (a location's ``visitedAt`` is shared
by every robot visiting it), so steps take turns under one fleet lock: two
robots writing the same location's visit time from stale reads would
otherwise leave it two values, which the map's cardinality makes inconsistent.  Each move is
printed whole, prefixed by its robot, so interleaved robots stay readable.
"""

from __future__ import annotations

import random
import threading
import time
from collections.abc import Callable

from ..errors import TopostoreError
from .step import describe, take_step
from .world import World


def run_fleet(world: World, steps: int, seed: int, time_scale: float, emit: Callable[[str], None], result) -> None:
    """Run ``steps`` steps of every robot concurrently; moves are appended to ``result`` as they happen."""
    lock = threading.Lock()  # the trace: one move printed whole
    step_lock = threading.Lock()  # one robot's read-decide-write step at a time
    failures: list[BaseException] = []

    def patrol(index: int, robot: str) -> None:
        rng = random.Random(seed * 1000 + index)
        client = world.robot_client(robot)
        try:
            for number in range(1, steps + 1):
                with step_lock:
                    move = take_step(world, robot, number, rng, client)
                with lock:
                    result.moves.append(move)
                    for i, line in enumerate(describe(move)):
                        emit(f"[{robot} step {number}] {line.strip()}" if i == 0 else f"[{robot}]   {line.strip()}")
                if not move.consistent:
                    raise TopostoreError(f"the ontology became inconsistent after {robot} moved; stopping")
                if time_scale:
                    time.sleep(time_scale * move.elapsed)
        except BaseException as exc:  # reported by the caller
            failures.append(exc)

    threads = [threading.Thread(target=patrol, args=(i, r), name=f"robot-{r}") for i, r in enumerate(world.robots)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    if failures:
        raise failures[0]


__all__ = ["run_fleet"]
