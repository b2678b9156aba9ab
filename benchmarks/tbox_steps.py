"""Robot-like steps on the tutorial-style TBox: ``python -m benchmarks.tbox_steps tbox:N --steps S`` prints JSON.

A map has few axioms and many individuals; the tutorial-style TBox (:mod:`benchmarks.tbox`) is the other
way round, and a step on it once ran for minutes where a full REASON took a fraction of a second.  This
row times what an ontology user does between two questions on such a file, after ``Ontology.from_file``
and a first full REASON:

* type a new pizza individual with a named pizza class and a new topping individual with one of that
  pizza's leaf topping classes (and the spiciness value its class implies),
* add a property value (the pizza ``hasTopping`` the topping) and remove one (the previous step's; on
  the first step ``pizzaA hasTopping salami1`` from the file, which takes a defined class away),
* REASON (``mode="auto"``, as the aRMOR REASON command does).

The first step is reported apart (it builds what the later ones reuse); the median and p95 are over the
others.  After the timed walk every step's answers (consistency and every triple about a named
individual whose object is not a blank node, asserted ∪ inferred) are held against those of a full
REASON from scratch: a new ontology of that step's asserted triples.  Any difference is a mismatch
(exit 3).
"""

from __future__ import annotations

import argparse
import json
import logging
import statistics
import sys
import tempfile
import time
import warnings
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from pyoxigraph import NamedNode

from . import tbox
from .limits import lift_time_limit

#: steps per size when none are asked for
STEPS = 20
OWL_NAMED = "http://www.w3.org/2002/07/owl#NamedIndividual"
ANSWERS = """SELECT ?s ?p ?o WHERE { ?s a <http://www.w3.org/2002/07/owl#NamedIndividual> . ?s ?p ?o .
                                  FILTER(!isBlank(?o)) }"""


@dataclass(frozen=True)
class Step:
    """The manipulations of one step, as (subject, predicate, object) local names in :data:`tbox.NS`."""

    types: list[tuple[str, str]]
    add: list[tuple[str, str, str]]
    remove: list[tuple[str, str, str]]


def plan(classes: int, steps: int) -> list[Step]:
    """The ``steps`` steps on the TBox of ``classes`` classes: each on a named pizza class in turn."""
    toppings = tbox.pizza_toppings(classes)
    names = sorted(toppings, key=lambda n: int(n.removeprefix("Pizza")))
    leaf_spice = tbox.leaf_spiciness(classes)
    out = []
    for i in range(steps):
        pizza_cls = names[i % len(names)]
        leaf = toppings[pizza_cls][i % len(toppings[pizza_cls])]
        pizza, topping = f"stepPizza{i}", f"stepTopping{i}"
        previous = ("pizzaA", "hasTopping", "salami1") if i == 0 else \
            (f"stepPizza{i - 1}", "hasTopping", f"stepTopping{i - 1}")
        out.append(Step(types=[(pizza, "NamedIndividual"), (pizza, pizza_cls), (topping, "NamedIndividual"),
                               (topping, leaf)],
                        add=[(pizza, "hasTopping", topping), (topping, "hasSpiciness", f"{leaf_spice[leaf]}Value")],
                        remove=[previous]))
    return out


def apply(onto: Any, step: Step) -> None:
    """The step's manipulations through the public API (owl:NamedIndividual is in the OWL namespace)."""
    def node(name: str) -> NamedNode:
        return NamedNode(OWL_NAMED if name == "NamedIndividual" else tbox.NS + name)

    for name, cls in step.types:
        onto.add_type(node(name), node(cls))
    for s, p, o in step.add:
        onto.add_fact(node(s), node(p), node(o))
    for s, p, o in step.remove:
        onto.remove_fact(node(s), node(p), node(o))


def answers(onto: Any) -> dict[str, Any]:
    """Consistency and the triples about named individuals (no blank objects), as sorted strings."""
    _, rows, _ = onto.select(ANSWERS)
    return {"consistent": onto.is_consistent, "triples": sorted({" ".join(str(t) for t in row) for row in rows})}


def from_scratch(asserted: bytes) -> dict[str, Any]:
    """The answers of a full REASON of a new ontology holding ``asserted`` (N-Triples) only."""
    from topostore import Ontology

    fresh = Ontology()
    fresh.load_data(asserted, fmt="ntriples")
    fresh.reason(mode="full")
    return answers(fresh)


def differences(step: int, mine: dict[str, Any], full: dict[str, Any]) -> list[str]:
    """What the step answered that the full REASON did not (+) and the other way round (-)."""
    if mine == full:
        return []
    extra, missing = sorted(set(mine["triples"]) - set(full["triples"])), sorted(set(full["triples"]) - set(mine["triples"]))
    what = [f"consistent {mine['consistent']} != {full['consistent']}"] if mine["consistent"] != full["consistent"] else []
    what += [f"+{t}" for t in extra[:3]] + [f"-{t}" for t in missing[:3]]
    return [f"step {step + 1}: {len(extra)} extra, {len(missing)} missing: " + "; ".join(what)]


@contextmanager
def quiet() -> Iterator[None]:
    """The TBox's LOAD notices (what is not reasoned completely) are warned and logged: said, not measured."""
    notices = logging.getLogger("topostore.load")
    level = notices.level
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        notices.setLevel(logging.ERROR)
        try:
            yield
        finally:
            notices.setLevel(level)


def run(classes: int, steps: int, folder: Path, progress: bool = False) -> dict[str, Any]:
    """Time ``steps`` steps on the TBox of ``classes`` classes, then check each against a full REASON;
    with ``progress``, the row so far is printed before each step (what a killed run leaves)."""
    from topostore import Ontology

    if steps < 2:
        raise ValueError(f"at least 2 steps (the first is reported apart), not {steps}")
    row: dict[str, Any] = {"kind": "tbox_steps", "engine": "topostore", "size": f"tbox:{classes}", "classes": classes,
                           "label": f"tutorial-style TBox ({classes} classes)", "steps": steps, "mismatches": []}
    with quiet():
        start = time.perf_counter()
        onto = Ontology.from_file(tbox.write(classes, folder))
        onto.reason(mode="full")
        row["load_and_full_s"] = time.perf_counter() - start
        times, modes, seen = [], [], []
        for step in plan(classes, steps):
            row["doing"] = f"step {len(times) + 1}"
            _progress(row, progress)
            start = time.perf_counter()
            apply(onto, step)
            report = onto.reason()
            times.append(time.perf_counter() - start)
            modes.append(report.stats.mode)
            seen.append((answers(onto), onto.serialize("ntriples")))
        row["doing"] = "the check against full REASONs from scratch"
        _progress(row, progress)
        for i, (mine, asserted) in enumerate(seen):
            row["mismatches"] += differences(i, mine, from_scratch(asserted))
    row.pop("doing")
    rest = sorted(t * 1000 for t in times[1:])
    row.update(first_ms=times[0] * 1000, median_ms=statistics.median(rest), p95_ms=rest[-(-95 * len(rest) // 100) - 1],
               max_ms=rest[-1], modes={m: modes.count(m) for m in sorted(set(modes))},
               answers=len(seen[-1][0]["triples"]))
    return row


def _progress(row: dict[str, Any], show: bool) -> None:
    if show:
        print(json.dumps(row), flush=True)


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("input", help="tbox:N (N named classes)")
    parser.add_argument("--steps", type=int, default=STEPS, help=f"steps (default {STEPS})")
    args = parser.parse_args(argv)
    if not args.input.startswith("tbox:"):
        parser.error(f"the input is tbox:N, not {args.input!r}")
    lift_time_limit()  # the suite's timeout bounds the run
    with tempfile.TemporaryDirectory(prefix="topostore-bench-") as tmp:
        row = run(int(args.input.removeprefix("tbox:")), args.steps, Path(tmp), progress=True)
    print(json.dumps(row))
    sys.exit(3 if row["mismatches"] else 0)


if __name__ == "__main__":
    main()
