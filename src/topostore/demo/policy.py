"""The surveillance policy of the seed scenario, as a pure function of what the robot knows.

A robot stays mostly in corridors; when a location it can reach is URGENT
(not visited for longer than its urgency threshold) it goes there, the most
neglected first.  Kept free of I/O so it can be tested and reused with any
client.
"""

from __future__ import annotations

import random
from collections.abc import Collection, Mapping
from dataclasses import dataclass


@dataclass(frozen=True)
class Decision:
    """Where to go (``None``: stay) and why, in words for the trace."""

    destination: str | None
    reason: str
    urgent: bool = False


def decide(here: str | None, reachable: Collection[str], urgent: Collection[str], corridors: Collection[str],
           visited_at: Mapping[str, int], now: int, rng: random.Random) -> Decision:
    """The next move of a robot in ``here`` that ``canReach`` the locations in ``reachable``."""
    options = sorted(reachable)
    if not options:
        return Decision(None, "nothing reachable: stay and wait")
    urgent_here = [loc for loc in options if loc in urgent]
    if urgent_here:
        # the most neglected first; ties broken by the seeded generator, not by name
        oldest = min(visited_at.get(loc, now) for loc in urgent_here)
        candidates = [loc for loc in urgent_here if visited_at.get(loc, now) == oldest]
        target = rng.choice(candidates)
        age = now - visited_at[target] if target in visited_at else None
        since = f"not visited for {age} s" if age is not None else "never visited"
        return Decision(target, f"{target} is URGENT ({since}): go there", urgent=True)
    corridor_options = [loc for loc in options if loc in corridors]
    if corridor_options:
        fresh = [loc for loc in corridor_options if loc != here] or corridor_options
        target = rng.choice(fresh)
        return Decision(target, f"nothing urgent in reach: patrol corridor {target}")
    target = rng.choice(options)
    return Decision(target, f"nothing urgent and no corridor in reach: move to {target}")


__all__ = ["Decision", "decide"]
