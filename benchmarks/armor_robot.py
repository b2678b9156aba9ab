"""topostore's side of a step: aRMOR commands through ``ArmorService.call``, in this process.

The reference is loaded with a buffering reasoner and unbuffered manipulations, the way aRMOR
clients run the tutorial loop: the REPLACEs change the ontology at once and REASON brings the
inferences up to date.  Answers are compared as local names.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from pathlib import Path

from topostore.armor import ArmorService
from topostore.armor.types import ArmorRequest, ArmorResponse
from topostore.demo.mapgen import MAP_NS

from .maps import ROBOT
from .walk import Answers, Move

REFERENCE = "bench"
IRI = MAP_NS.rstrip("#")


class ArmorRobot:
    """One ArmorService with the map loaded as one reference."""

    def __init__(self, map_file: Path, store: str | None = None,
                 observe: Callable[[str], None] | None = None) -> None:
        """LOAD ``map_file``; ``store``: where the reference lives (None: memory; a SPARQL server's URL);
        ``observe`` is called with each command's name after it answered (the remote benchmark counts
        each command's requests with it)."""
        self.service = ArmorService(store=store)
        self.observe = observe
        start = time.perf_counter()
        # LOAD parses the file and runs the first (full) REASON
        self._call("LOAD", "FILE", "", [str(map_file), IRI, "false", "PELLET", "true"])
        self.load_s = time.perf_counter() - start

    @property
    def ontology(self):  # noqa: ANN201 - topostore.Ontology, for the full-REASON measurement
        return self.service.reference(REFERENCE).ontology

    def answers(self) -> Answers:
        """QUERY OBJECTPROP IND canReach Robot1 and QUERY IND CLASS URGENT."""
        return _answers(*self._replies())

    def _replies(self) -> tuple[list[str], list[str]]:
        """The two queries' ``queried_objects``, as a client receives them."""
        reach = self._call("QUERY", "OBJECTPROP", "IND", ["canReach", ROBOT]).queried_objects
        urgent = self._call("QUERY", "IND", "CLASS", ["URGENT"]).queried_objects
        return reach, urgent

    def step(self, move: Move) -> tuple[float, Answers]:
        """One robot step (three REPLACEs, REASON, two queries); its seconds and its answers."""
        start = time.perf_counter()
        self.moved(move)
        reasoned = self._call("REASON", "", "", [])
        replies = self._replies()
        elapsed = time.perf_counter() - start  # the replies received: reading them into names is the checker's
        answers = _answers(*replies)
        if not reasoned.is_consistent:
            raise RuntimeError(f"topostore found the map inconsistent after moving to {move.to}")
        return elapsed, answers

    def moved(self, move: Move) -> None:
        """The step's three changes before its REASON: the robot's place and clock, the new place's visit time."""
        self._call("REPLACE", "OBJECTPROP", "IND", ["isIn", ROBOT, move.to, move.frm])
        self._call("REPLACE", "DATAPROP", "IND", ["now", ROBOT, "LONG", str(move.now), str(move.old_now)])
        if move.old_visit is None:
            self._call("ADD", "DATAPROP", "IND", ["visitedAt", move.to, "LONG", str(move.now)])
        else:
            self._call("REPLACE", "DATAPROP", "IND", ["visitedAt", move.to, "LONG", str(move.now), str(move.old_visit)])

    def close(self) -> None:
        """Release the service's stores (a remote store's HTTP client)."""
        self.service.close()

    def _call(self, command: str, primary: str, secondary: str, args: list[str]) -> ArmorResponse:
        reply = self.service.call(ArmorRequest("bench", REFERENCE, command, primary, secondary, args))
        if self.observe is not None:
            self.observe(" ".join(w for w in (command, primary, secondary, args[0] if args else "") if w))
        if not reply.success:
            raise RuntimeError(f"{command} {primary} {secondary} {args[:3]} failed: "
                               f"{reply.exit_code} {reply.error_description}")
        return reply


def _answers(reach: list[str], urgent: list[str]) -> Answers:
    return Answers(_names(reach), _names(urgent))


def _names(objects: list[str]) -> tuple[str, ...]:
    """'<http://…#R1>' → 'R1', sorted (the aRMOR reply wraps IRIs in angle brackets)."""
    return tuple(sorted(o.strip("<>").removeprefix(MAP_NS) for o in objects))
