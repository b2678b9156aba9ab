"""The robot's walk: which moves a benchmark makes, and what the answers after each must be.

The walk is planned before any reasoner runs, from the map alone, so every reasoner gets the
very same moves: the robot goes to the neighbour it visited longest ago (ties: by name), its
clock advances 5 s per move, and it stamps the new place's ``visitedAt`` with the new clock.

The expected answers follow the three SWRL rules on a map where every location and door is
declared different: the robot can reach the locations sharing a door with where it is, and a
location is URGENT when ``now - visitedAt > urgencyThreshold``.  They are a third opinion
beside topostore and Pellet, and the only one on the sizes Pellet cannot run.
"""

from __future__ import annotations

from dataclasses import dataclass

from .maps import BenchMap

#: seconds the robot's clock advances per move (as in aRMOR's tutorial loop)
TICK = 5


@dataclass(frozen=True)
class Move:
    """One step's REPLACE arguments: isIn new/old, now new/old, visitedAt new (= now)/old."""

    to: str
    frm: str
    now: int
    old_now: int
    old_visit: int | None


@dataclass(frozen=True)
class Answers:
    """What a reasoner says after a step: QUERY canReach Robot1 and QUERY IND CLASS URGENT."""

    can_reach: tuple[str, ...]
    urgent: tuple[str, ...]

    def differences(self, other: Answers) -> str:
        """'' when equal, else what differs (for a loud report)."""
        out = []
        for name, mine, theirs in (("canReach", self.can_reach, other.can_reach), ("URGENT", self.urgent, other.urgent)):
            only_mine, only_theirs = sorted(set(mine) - set(theirs)), sorted(set(theirs) - set(mine))
            if only_mine or only_theirs:
                out.append(f"{name}: only in the first {only_mine[:8]}, only in the second {only_theirs[:8]}")
        return "; ".join(out)


def plan(bench: BenchMap, steps: int) -> list[Move]:
    """``steps`` moves from the map's initial state (nothing is changed in ``bench``)."""
    visited = dict(bench.visited)
    where, now, moves = bench.start, bench.now, []
    for _ in range(steps):
        options = bench.neighbours[where]
        if not options:
            raise ValueError(f"map {bench.name!r}: {where} has no neighbour to move to")
        to = min(options, key=lambda loc: (visited.get(loc, -(2 ** 63)), loc))
        moves.append(Move(to, where, now + TICK, now, visited.get(to)))
        where, now = to, now + TICK
        visited[to] = now
    return moves


def expected(bench: BenchMap, moves: list[Move]) -> list[Answers]:
    """The answers before the first move and after each move."""
    visited = dict(bench.visited)
    out = [_answers(bench, bench.start, bench.now, visited)]
    for m in moves:
        visited[m.to] = m.now
        out.append(_answers(bench, m.to, m.now, visited))
    return out


def _answers(bench: BenchMap, where: str, now: int, visited: dict[str, int]) -> Answers:
    urgent = sorted(loc for loc, t in visited.items() if now - t > bench.threshold)
    return Answers(tuple(bench.neighbours[where]), tuple(urgent))
