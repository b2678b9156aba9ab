"""Store operations per REASON of the bench's robot step, by kind: ``python -m benchmarks.step_ops [MAP] [STEPS]``.

A REASON of the step on a small map costs a few hundred microseconds where the hand-written floor
(:mod:`.step_floor`) costs thirty, and most of the difference is how many times the reasoner goes to
the store: every look-up, presence test and scratch write is a call through two to four Python frames.
This counts them: each method of the store's look-up API (and the index reads beneath it, and the held
scratch graphs' reads and writes) wrapped by a counter while REASON runs, after a warm-up whose steps
compile the step programs.  The table gives each kind's calls per REASON and which function called it,
so a change that removes operations says which and how many.  Counts, not times: the figure is exact
and needs no quiet machine.
"""

from __future__ import annotations

import argparse
import collections
import functools
import sys
import tempfile
from pathlib import Path

from topostore.stores.held import HeldGraphs
from topostore.stores.oxigraph import OxigraphStore

from . import maps
from .armor_robot import ArmorRobot
from .limits import lift_time_limit
from .walk import plan

#: the store's look-up API as the reasoner calls it, and the held scratch graphs beneath it
STORE_METHODS = ("few_facts", "matches", "has_match", "triples", "match_in", "contains_each", "known_in", "add_scratch", "discard",
                 "update")
HELD_METHODS = ("add", "triples")


class _Counter:
    """Calls by (kind, caller) while :attr:`on`."""

    def __init__(self) -> None:
        self.on = False
        self.calls: collections.Counter = collections.Counter()
        #: (owner, name, the method it had) per wrapped method, put back by :meth:`restore`
        self._wrapped: list[tuple] = []

    def wrap(self, owner: type, name: str, kind: str) -> None:
        """``owner.name`` counted as ``kind`` (with the function that called it); nothing where the tree
        measured has no such method."""
        original = getattr(owner, name, None)
        if original is None:
            return

        @functools.wraps(original)
        def counted(*args, **kwargs):
            if self.on:
                frame = sys._getframe(1)
                self.calls[(kind, f"{Path(frame.f_code.co_filename).stem}.{frame.f_code.co_name}")] += 1
            return original(*args, **kwargs)

        self._wrapped.append((owner, name, owner.__dict__.get(name)))  # None: inherited
        setattr(owner, name, counted)

    def restore(self) -> None:
        """Every wrapped method as it was."""
        for owner, name, original in reversed(self._wrapped):
            if original is None:
                delattr(owner, name)
            else:
                setattr(owner, name, original)
        self._wrapped.clear()


class _Index:
    """The engine's store with its pattern reads counted (the native object's methods cannot be wrapped)."""

    def __init__(self, inner, counter: _Counter) -> None:
        self._inner, self._counter = inner, counter

    def quads_for_pattern(self, *args, **kwargs):
        if self._counter.on:
            frame = sys._getframe(1)
            self._counter.calls[("index read", f"{Path(frame.f_code.co_filename).stem}.{frame.f_code.co_name}")] += 1
        return self._inner.quads_for_pattern(*args, **kwargs)

    def __contains__(self, quad) -> bool:
        if self._counter.on:
            self._counter.calls[("index contains", "")] += 1
        return quad in self._inner

    def __len__(self) -> int:
        return len(self._inner)

    def __iter__(self):
        return iter(self._inner)

    def __getattr__(self, name: str):
        return getattr(self._inner, name)


def count(map_name: str, steps: int, warm: int = 50) -> collections.Counter:
    """Operations by (kind, caller) over ``steps`` REASONs of the bench's step on ``map_name``."""
    lift_time_limit()
    path, bench = maps.write(map_name, Path(tempfile.mkdtemp()))
    moves = iter(plan(bench, warm + steps))
    robot = ArmorRobot(path)
    for _ in range(warm):
        robot.step(next(moves))
    counter = _Counter()
    for name in STORE_METHODS:
        counter.wrap(OxigraphStore, name, name)
    for name in HELD_METHODS:
        counter.wrap(HeldGraphs, name, f"held.{name}")
    try:
        for _ in range(steps):
            _reason(robot, next(moves), counter)
    finally:
        counter.restore()
    return counter.calls


def _reason(robot: ArmorRobot, m, counter: _Counter) -> None:
    """One step of the bench's robot, its REASON counted (the index's reads through :class:`_Index`)."""
    robot.moved(m)
    store = robot.ontology.store
    index = store._ox
    store._ox = _Index(index, counter)
    counter.on = True
    try:
        robot._call("REASON", "", "", [])
    finally:
        counter.on = False
        if store._ox.__class__ is _Index:  # a compaction may have put a new index in its place
            store._ox = index


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("map", nargs="?", default="example")
    parser.add_argument("steps", nargs="?", type=int, default=200)
    parser.add_argument("--callers", action="store_true", help="a row per kind and calling function")
    args = parser.parse_args()
    calls = count(args.map, args.steps)
    by_kind: collections.Counter = collections.Counter()
    for (kind, _), n in calls.items():
        by_kind[kind] += n
    rows = sorted(calls.items(), key=lambda x: -x[1]) if args.callers else \
        [((kind, ""), n) for kind, n in by_kind.most_common()]
    print(f"store operations per REASON, map {args.map}, {args.steps} steps")
    print(f"{'kind':<16} {'caller':<34} {'per REASON':>10}")
    for (kind, caller), n in rows:
        print(f"{kind:<16} {caller:<34} {n / args.steps:>10.2f}")
    api = sum(n for k, n in by_kind.items() if k in STORE_METHODS)
    print(f"{'store API':<51} {api / args.steps:>10.2f}")
    print(f"{'all':<51} {sum(by_kind.values()) / args.steps:>10.2f}")


if __name__ == "__main__":
    main()
