"""The first schema change after a REASON: ``python -m benchmarks.schema_change [MAP] [--rounds N]``.

A buffered reasoner answers QUERY CLASS CLASS with the classification of its last REASON until the next one
(spec §2.5).  Each round, on a reference with a buffered reasoner (as the bench's step loads it): REASON (not
timed), ``ADD CLASS CLASS [PANTRY, ROOM]`` (the first schema change after that REASON), ``QUERY CLASS CLASS
[ROOM]`` (the first hierarchy answer since), ``REMOVE CLASS CLASS [PANTRY, ROOM]`` (a second change).  Prints
the median CPU milliseconds of each command over the rounds: where the classification of the last REASON is
made shows in which column grows.  ``--tbox N`` runs it on the tutorial-style TBox of N classes instead
(``benchmarks.tbox``: ``ADD CLASS CLASS [NewPizza, Pizza]``).
"""

from __future__ import annotations

import argparse
import statistics
import tempfile
import time
import warnings
from pathlib import Path

from topostore import OntologyWarning
from topostore.armor import ArmorService
from topostore.armor.types import ArmorRequest

from . import maps, tbox
from .armor_robot import IRI
from .limits import lift_time_limit
from .report import machine

COMMANDS = ("first schema change", "first QUERY CLASS CLASS", "second schema change")


def _reference(size: str, classes: int | None) -> tuple[ArmorService, str, str]:
    """A service holding the map (or the TBox) as reference "bench" with a buffered reasoner; the class the
    rounds put a new subclass under, and its new subclass."""
    folder = Path(tempfile.mkdtemp())
    if classes is None:
        path, iri, under, new = maps.write(size, folder)[0], IRI, "ROOM", "PANTRY"
    else:
        path, iri, under, new = tbox.write(classes, folder), tbox.NS.rstrip("#"), "Pizza", "NewPizza"
    service = ArmorService()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", OntologyWarning)
        reply = service.call(ArmorRequest("bench", "bench", "LOAD", "FILE", "", [str(path), iri, "false", "PELLET",
                                                                                 "true"]))
    if not reply.success:
        raise RuntimeError(reply.error_description)
    return service, under, new


def run(size: str, rounds: int, classes: int | None = None) -> dict[str, list[float]]:
    """The CPU milliseconds of each of :data:`COMMANDS`, one per round."""
    service, under, new = _reference(size, classes)
    times: dict[str, list[float]] = {name: [] for name in COMMANDS}
    clock = time.process_time_ns

    def call(*command: str) -> float:
        start = clock()
        reply = service.call(ArmorRequest("bench", "bench", command[0], command[1], command[2], list(command[3:])))
        spent = (clock() - start) / 1e6
        if not reply.success:
            raise RuntimeError(f"{command}: {reply.error_description}")
        return spent

    for _ in range(rounds):
        call("REASON", "", "")
        times[COMMANDS[0]].append(call("ADD", "CLASS", "CLASS", new, under))
        times[COMMANDS[1]].append(call("QUERY", "CLASS", "CLASS", under))
        times[COMMANDS[2]].append(call("REMOVE", "CLASS", "CLASS", new, under))
    service.close()
    return times


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("size", nargs="?", default=maps.EXAMPLE, help="map: example or a number of locations")
    parser.add_argument("--rounds", type=int, default=50, help="REASON + three commands, this many times")
    parser.add_argument("--tbox", type=int, default=None, help="the tutorial-style TBox of this many classes instead")
    args = parser.parse_args()
    lift_time_limit()
    for key, value in machine().items():
        print(f"{key}: {value}")
    times = run(args.size, args.rounds, args.tbox)
    name = f"tbox:{args.tbox}" if args.tbox else args.size
    print(f"\n| input | rounds | {' (ms) | '.join(COMMANDS)} (ms) |\n|---|---|---|---|---|")
    print(f"| {name} | {args.rounds} | " + " | ".join(f"{statistics.median(times[c]):.2f}" for c in COMMANDS) + " |")


if __name__ == "__main__":
    main()
