"""The floor of a robot step's REASON on pyoxigraph's quad API: ``python -m benchmarks.step_floor [MAP] [STEPS]``.

What a REASON of the bench's step must do at least, written by hand for the tutorial's map: the robot's
``canReach`` facts made those of its new location's ``connectedTo`` (read, compared, the difference
removed and added), and the URGENT type facts made those of the locations whose last visit is older
than the robot's threshold by its new clock (every visit time read).  No rule, no scratch graph, no
check: the store writes the step's change needs and the reads that find them.  It runs beside the
bench's own robot on a copy of its store, each step's asserted change written to the copy untimed, and
its answers are compared with topostore's after every step (a floor that gives other answers is none).

The figure beside topostore's REASON (``prof.py``'s per-command time, or ``benchmarks.paired``) splits
REASON's time into what the change costs on this store and what the design adds.
"""

from __future__ import annotations

import argparse
import statistics
import tempfile
import time
from pathlib import Path

import pyoxigraph as ox
from pyoxigraph import Literal, NamedNode, Quad

from topostore.demo.mapgen import MAP_NS

from . import maps
from .armor_robot import ArmorRobot
from .limits import lift_time_limit
from .maps import ROBOT
from .walk import Move, plan

_GRAPH = "urn:topostore:graph:"
ASSERTED, INFERRED = NamedNode(_GRAPH + "asserted"), NamedNode(_GRAPH + "inferred")
TYPE = NamedNode("http://www.w3.org/1999/02/22-rdf-syntax-ns#type")
LONG = NamedNode("http://www.w3.org/2001/XMLSchema#long")
IS_IN, NOW, VISITED_AT, CAN_REACH, CONNECTED_TO, THRESHOLD, URGENT = (
    NamedNode(MAP_NS + name) for name in
    ("isIn", "now", "visitedAt", "canReach", "connectedTo", "urgencyThreshold", "URGENT"))


def _node(name: str) -> NamedNode:
    return NamedNode(MAP_NS + name)


def reason(store: ox.Store, robot: NamedNode, to: NamedNode) -> None:
    """The REASON of a move to ``to`` (the clock and the visit time already replaced in ``store``)."""
    old = {q.object for q in store.quads_for_pattern(robot, CAN_REACH, None, INFERRED)}
    new = {q.object for q in store.quads_for_pattern(to, CONNECTED_TO, None, INFERRED)}
    for x in old - new:
        store.remove(Quad(robot, CAN_REACH, x, INFERRED))
    if added := [Quad(robot, CAN_REACH, x, INFERRED) for x in new - old]:
        store.extend(added)
    now = int(next(store.quads_for_pattern(robot, NOW, None, ASSERTED)).object.value)
    threshold = int(next(store.quads_for_pattern(robot, THRESHOLD, None, ASSERTED)).object.value)
    urgent = {q.subject for q in store.quads_for_pattern(None, VISITED_AT, None, ASSERTED)
              if now - int(q.object.value) > threshold}
    was = {q.subject for q in store.quads_for_pattern(None, TYPE, URGENT, INFERRED)}
    for location in was - urgent:
        store.remove(Quad(location, TYPE, URGENT, INFERRED))
    if added := [Quad(location, TYPE, URGENT, INFERRED) for location in urgent - was]:
        store.extend(added)


def assert_move(store: ox.Store, robot: NamedNode, move: Move) -> None:
    """The step's three REPLACEs, written to the floor's store (not timed)."""
    store.remove(Quad(robot, IS_IN, _node(move.frm), ASSERTED))
    store.add(Quad(robot, IS_IN, _node(move.to), ASSERTED))
    for subject, predicate in ((robot, NOW), (_node(move.to), VISITED_AT)):
        for q in list(store.quads_for_pattern(subject, predicate, None, ASSERTED)):
            store.remove(q)
        store.add(Quad(subject, predicate, Literal(str(move.now), datatype=LONG), ASSERTED))


def answers(store: ox.Store, robot: NamedNode) -> tuple[list[str], list[str]]:
    """The robot's canReach and the URGENT locations, as sorted IRIs."""
    reach = sorted(q.object.value for q in store.quads_for_pattern(robot, CAN_REACH, None, INFERRED))
    urgent = sorted(q.subject.value for q in store.quads_for_pattern(None, TYPE, URGENT, INFERRED))
    return reach, urgent


def measure(map_name: str, steps: int, warm: int = 60) -> list[float]:
    """Per step, the floor's REASON in µs (thread CPU), each after the bench robot's step on its own store
    (so that the floor runs between other code, as a REASON does); raises where the answers differ."""
    path, bench = maps.write(map_name, Path(tempfile.mkdtemp()))
    moves = plan(bench, warm + steps)
    robot = ArmorRobot(path)
    for move in moves[:warm]:
        robot.step(move)
    floor = ox.Store()
    floor.extend(robot.ontology.store._ox)
    me = _node(ROBOT)
    times = []
    for k, move in enumerate(moves[warm:]):
        assert_move(floor, me, move)
        if k % 50 == 49:  # a rebuild, as topostore's in-memory store does (removed quads stay until then)
            fresh = ox.Store()
            fresh.extend(floor)
            floor = fresh
        start = time.thread_time_ns()
        reason(floor, me, _node(move.to))
        times.append((time.thread_time_ns() - start) / 1e3)
        robot.step(move)
        theirs = answers(robot.ontology.store._ox, me)
        if answers(floor, me) != theirs:
            raise AssertionError(f"the floor's answers differ from topostore's after {move}")
    return times


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("map", nargs="?", default="8", help="a benchmark map (example, or a number of locations)")
    parser.add_argument("steps", nargs="?", type=int, default=400)
    args = parser.parse_args(argv)
    lift_time_limit()
    times = measure(args.map, args.steps)
    print(f"{args.map}: the REASON floor on the quad API, median {statistics.median(times):.1f} µs, "
          f"minimum {min(times):.1f} µs ({args.steps} steps, each after the bench's own step)")


if __name__ == "__main__":
    main()
