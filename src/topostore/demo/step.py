"""One robot's step of the patrol: read where it is, decide, move, stay, REASON; and its trace lines.

Shared by the single-robot loop (:mod:`.patrol`) and the fleet (:mod:`.fleet`), which runs it per robot.
"""

from __future__ import annotations

import random
import time
from dataclasses import dataclass

from ..armor_api.armor_query_client import lexical_form
from .policy import decide
from .world import World

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


def take_step(world: World, robot: str, step: int, rng: random.Random, client=None) -> Move:
    """One robot's read-decide-write step through ``client`` (the world's own client by default), then REASON."""
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


def describe(move: Move) -> list[str]:
    """The trace lines of one move (the first names the robot and what it sees)."""
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


__all__ = ["Move", "take_step", "describe", "TRAVEL_SECONDS", "STAY_SECONDS"]
