"""Two source trees, the same robot step, measured in turns: ``python -m benchmarks.paired TREE_A TREE_B``.

On a shared machine the CPU time of one step moves by ±0.1 ms from one run to the next, as the
other processes come and go; a change worth 0.05 ms cannot be seen by running each tree once.
Here each tree gets one long-lived process (its ``src`` and its ``benchmarks`` first on the path: a
tree from before this file existed can be measured), both load the same map
and walk the same planned moves, and they take turns: in each round one runs ``--steps`` steps, then
the other (the first alternates), and each reports the median CPU time of its steps.  The
difference of the two medians in the same round sees the same load; their median over the rounds
is the figure to quote, its standard error says whether it is one.  Run a tree against itself for
the noise floor.

``--map`` is a benchmark map (``example``, or a number of locations, see :mod:`benchmarks.maps`).
"""

from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

READY = "ready"


def worker(map_name: str, total: int) -> None:
    """The side of one tree: load the map, then run the steps asked for on standard input, one
    line ``N`` per round, answering ``median mean`` (ms of CPU time) per round."""
    # the tree's own benchmark package (this file runs as a script there, whatever the tree holds)
    from benchmarks import maps
    from benchmarks.armor_robot import ArmorRobot
    from benchmarks.limits import lift_time_limit
    from benchmarks.walk import plan

    lift_time_limit()
    path, bench = maps.write(map_name, Path(tempfile.mkdtemp()))
    moves = iter(plan(bench, total))
    robot = ArmorRobot(path)
    for _ in range(10):  # warm-up: the first steps compile the step programs
        robot.step(next(moves))
    print(READY, flush=True)
    for line in sys.stdin:
        cpu = []
        for _ in range(int(line)):
            start = time.process_time()
            robot.step(next(moves))
            cpu.append(time.process_time() - start)
        print(f"{statistics.median(cpu) * 1e3:.4f} {statistics.mean(cpu) * 1e3:.4f}", flush=True)


class Side:
    """One tree's worker process."""

    def __init__(self, tree: Path, map_name: str, total: int) -> None:
        env = dict(os.environ, PYTHONPATH=f"{tree / 'src'}{os.pathsep}{tree}")
        self.process = subprocess.Popen(
            [sys.executable, str(Path(__file__).resolve()), "--worker", "--map", map_name, "--total", str(total)],
            cwd=tree, env=env, text=True, stdin=subprocess.PIPE, stdout=subprocess.PIPE)
        if self._line() != READY:
            raise RuntimeError(f"the worker of {tree} did not start")

    def _line(self) -> str:
        line = self.process.stdout.readline().strip()
        if not line:
            raise RuntimeError("a worker stopped (see its error output above)")
        return line

    def run(self, steps: int) -> tuple[float, float]:
        """Median and mean CPU ms of ``steps`` more steps."""
        self.process.stdin.write(f"{steps}\n")
        self.process.stdin.flush()
        median, mean = (float(x) for x in self._line().split())
        return median, mean

    def close(self) -> None:
        self.process.stdin.close()
        self.process.wait()


def compare(a: Path, b: Path, map_name: str, rounds: int, steps: int) -> str:
    """The paired comparison of two trees, as one line of text."""
    total = 10 + rounds * steps + 1
    sides = Side(a, map_name, total), Side(b, map_name, total)
    results: tuple[list, list] = ([], [])
    try:
        for r in range(rounds):
            for k in ((0, 1) if r % 2 == 0 else (1, 0)):
                results[k].append(sides[k].run(steps))
    finally:
        for side in sides:
            side.close()
    diff = [x[0] - y[0] for x, y in zip(*results, strict=True)]
    medians = [statistics.median(m for m, _ in side) for side in results]
    means = [statistics.mean(mean for _, mean in side) for side in results]
    spread = statistics.stdev(diff) / len(diff) ** 0.5 if len(diff) > 1 else float("nan")
    return (f"{map_name}: A {medians[0]:.3f} ms, B {medians[1]:.3f} ms (medians of round medians; means "
            f"{means[0]:.3f} / {means[1]:.3f}); A - B per round: median {statistics.median(diff):.3f}, "
            f"mean {statistics.mean(diff):.3f} ± {spread:.3f} ms ({rounds} rounds of {steps} steps)")


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("trees", nargs="*", type=Path, help="two source trees (each with src/ and benchmarks/)")
    parser.add_argument("--map", default="example")
    parser.add_argument("--rounds", type=int, default=30)
    parser.add_argument("--steps", type=int, default=30, help="steps per tree and round")
    parser.add_argument("--worker", action="store_true", help=argparse.SUPPRESS)
    parser.add_argument("--total", type=int, default=0, help=argparse.SUPPRESS)
    args = parser.parse_args(argv)
    if args.worker:
        worker(args.map, args.total)
        return
    if len(args.trees) != 2:
        parser.error("give two source trees")
    print(compare(args.trees[0].resolve(), args.trees[1].resolve(), args.map, args.rounds, args.steps))


if __name__ == "__main__":
    main()
