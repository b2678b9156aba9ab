"""The cycle collector on the TBox-heavy robot step: what freezing the settled state would save.

``python -m benchmarks.tbox_gc [--freeze none|load|first-step] [--steps S] [CLASSES]`` (one size and one
policy per process: a collector's state is the whole process's) runs S robot-like steps of
:mod:`benchmarks.tbox_steps` on the tutorial-style TBox and prints one line: each step's CPU time
(median and mean of all steps but the first), the full collections the steps after the first met and
their time, and the tracked and frozen objects after the first step.  ``--freeze load`` applies the policy
measured on 26 Nov 2026 (``gc.collect()`` then ``gc.freeze()`` after LOAD and after the full REASON, as
the Ontology facade would have); ``first-step`` also after the first step, which builds the maintained
rules.  It did not pay (docs/benchmarks-history.md), so topostore does not freeze.
"""

from __future__ import annotations

import argparse
import gc
import statistics
import tempfile
import time
from pathlib import Path
from typing import Any

from benchmarks import tbox
from benchmarks.tbox_steps import apply, plan, quiet


class FullCollections:
    """Counts and times the cycle collector's full (generation 2) collections."""

    def __init__(self) -> None:
        self.count, self.seconds, self._start = 0, 0.0, 0.0

    def __call__(self, phase: str, info: dict[str, Any]) -> None:
        if info["generation"] != 2:
            return
        if phase == "start":
            self._start = time.perf_counter()
        else:
            self.count += 1
            self.seconds += time.perf_counter() - self._start


def settle() -> None:
    """What the measured policy did at each settling point: collect, then freeze what survives."""
    gc.unfreeze()
    gc.collect()
    gc.freeze()


def run(classes: int, steps: int, freeze: str) -> dict[str, Any]:
    """One process's measurement (see the module)."""
    from topostore import Ontology

    full = FullCollections()
    with quiet():
        folder = Path(tempfile.mkdtemp())
        start = time.process_time()
        onto = Ontology.from_file(tbox.write(classes, folder))
        if freeze != "none":
            settle()
        onto.reason(mode="full")
        if freeze != "none":
            settle()
        load_s = time.process_time() - start
        gc.callbacks.append(full)
        cpu: list[float] = []
        for i, step in enumerate(plan(classes, steps)):
            start = time.process_time()
            apply(onto, step)
            onto.reason()
            cpu.append((time.process_time() - start) * 1000)
            if i == 0:
                if freeze == "first-step":
                    settle()
                after_first = {"tracked": len(gc.get_objects()), "frozen": gc.get_freeze_count(),
                               "count": full.count, "seconds": full.seconds}
        gc.callbacks.remove(full)
    rest = cpu[1:]
    return {"classes": classes, "freeze": freeze, "load_and_full_cpu_s": load_s, "first_ms": cpu[0],
            "median_ms": statistics.median(rest), "mean_ms": statistics.mean(rest),
            "tracked": after_first["tracked"], "frozen": after_first["frozen"],
            "full_collections": full.count - after_first["count"],
            "full_collections_ms": (full.seconds - after_first["seconds"]) * 1000}


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(prog="python -m benchmarks.tbox_gc", description=__doc__.split("\n\n")[0])
    parser.add_argument("classes", nargs="?", type=int, default=400)
    parser.add_argument("--steps", type=int, default=20)
    parser.add_argument("--freeze", choices=("none", "load", "first-step"), default="none")
    args = parser.parse_args(argv)
    row = run(args.classes, args.steps, args.freeze)
    print(f"{row['classes']} classes, freeze {row['freeze']}: LOAD + full REASON {row['load_and_full_cpu_s']:.2f} s "
          f"CPU; first step {row['first_ms']:.0f} ms; steps 2-{args.steps} median {row['median_ms']:.1f} ms, mean "
          f"{row['mean_ms']:.1f} ms CPU; {row['full_collections']} full collections, {row['full_collections_ms']:.0f} "
          f"ms; after the first step {row['tracked']:,} tracked + {row['frozen']:,} frozen objects")


if __name__ == "__main__":
    main()
