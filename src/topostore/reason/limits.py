"""Limits on one REASON: rounds, inferred facts, seconds.

A rule whose built-ins produce new values (``counter(?x, ?v) ^ swrlb:add(?w, ?v, 1)
-> counter(?x, ?w)``) has no finite closure, so reasoning would never end and
would hold the reference's lock forever.  Every REASON therefore runs under a
:class:`Budget`: the reasoning loops call :func:`tick` once per semi-naive round
with the number of facts the round derived and the rules that derived them; past
a limit :class:`ReasonLimitExceeded` is raised naming those rules, and
:meth:`topostore.ontology.facade.Ontology.reason` rolls the change back.

The budget travels in a context variable, so the loops need no extra
parameters: ``with limits.budget(ReasonLimits()): ...`` around a REASON, and
``limits.tick(...)`` inside.  Outside a ``budget`` block :func:`tick` does
nothing.  The time limit is checked between rounds; one SPARQL evaluation
cannot be interrupted inside Oxigraph, so a single enormous round can overrun
it by that round's duration.
"""

from __future__ import annotations

import contextlib
import contextvars
import time
from collections.abc import Callable, Iterable, Iterator
from dataclasses import dataclass

from ..errors import TopostoreError


@dataclass(frozen=True)
class ReasonLimits:
    """Bounds on one REASON (``topostore serve --reason-max-*``; ``Ontology.limits`` in Python)."""

    #: semi-naive rounds (a terminating ontology of a robot's map needs tens)
    max_rounds: int = 10_000
    #: facts derived by one REASON (also bounds memory)
    max_inferred: int = 5_000_000
    #: wall-clock seconds of one REASON
    max_seconds: float = 120.0

    def check(self) -> None:
        if self.max_rounds < 1 or self.max_inferred < 1 or not self.max_seconds > 0:
            raise ValueError("reasoning limits must be positive")


#: limits new ontologies start with; ``topostore serve --reason-max-*`` changes them (:func:`set_defaults`)
DEFAULTS = ReasonLimits()


def set_defaults(limits: ReasonLimits) -> None:
    """Replace the limits every new :class:`~topostore.ontology.facade.Ontology` starts with."""
    global DEFAULTS
    limits.check()
    DEFAULTS = limits


#: what a failed REASON left, as the error's text says it (:attr:`ReasonLimitExceeded.outcome`)
OUTCOMES = {
    "undone": "The change was rolled back",
    "cleared": "There was no reasoned state to return to: the asserted facts were kept and the inferred ones "
               "cleared",
}
#: the text's last words, whatever the outcome
RAISE = "(raise the limit with --reason-max-rounds/-inferred/-seconds if the ontology really needs more)"


class ReasonLimitExceeded(TopostoreError):
    """A REASON ran past one of its limits; what that left (the change rolled back, or the inferred facts
    cleared where no reasoned state could be returned to) is set by the REASON that caught it."""

    def __init__(self, message: str, rules: list[str], cause: str = "") -> None:
        super().__init__(message)
        self.rules = rules
        #: why it may have happened ("" where nothing was deriving)
        self.cause = cause
        #: "undone" or "cleared" once the failed REASON has restored what it could ("" before)
        self.outcome = ""

    def __str__(self) -> str:
        parts = [super().__str__(), self.cause, OUTCOMES.get(self.outcome, "")]
        return ". ".join(p for p in parts if p) + " " + RAISE


class Budget:
    """What one REASON has used so far, against its :class:`ReasonLimits`."""

    def __init__(self, limits: ReasonLimits) -> None:
        self.limits = limits
        self.deadline = time.monotonic() + limits.max_seconds
        self.rounds = 0
        self.inferred = 0
        #: what the REASON is doing now (set by :func:`doing`), named when a limit stops it
        self.activity = "semi-naive rounds"

    def round(self, rules: Callable[[], Iterable[str]] | Iterable[str] = ()) -> None:
        """Count one round; ``rules`` (or a function giving them) names who derived its facts."""
        self.rounds += 1
        if self.rounds > self.limits.max_rounds:
            self._stop(f"more than {self.limits.max_rounds} rounds", rules)
        self.check(rules)

    def derived(self, n: int, rules: Callable[[], Iterable[str]] | Iterable[str] = ()) -> None:
        """Count ``n`` newly derived facts."""
        self.inferred += n
        if self.inferred > self.limits.max_inferred:
            self._stop(f"more than {self.limits.max_inferred} inferred facts", rules)

    def check(self, rules: Callable[[], Iterable[str]] | Iterable[str] = ()) -> None:
        """Stop when the deadline has passed."""
        if time.monotonic() > self.deadline:
            self._stop(f"more than {self.limits.max_seconds:g} s", rules)

    def _stop(self, what: str, rules: Callable[[], Iterable[str]] | Iterable[str]) -> None:
        names = sorted(set(rules() if callable(rules) else rules))
        shown = ", ".join(names[:5]) + (f" and {len(names) - 5} more" if len(names) > 5 else "")
        blame = f"; still deriving: {shown}" if names else ""
        # only rounds that keep deriving facts point at a rule without a finite closure
        cause = "A rule that creates new values (e.g. with swrlb:add) may have no finite closure" if names else ""
        raise ReasonLimitExceeded(
            f"reasoning stopped after {what} while running {self.activity} "
            f"({self.rounds} rounds, {self.inferred} facts){blame}", names, cause)


_CURRENT: contextvars.ContextVar[Budget | None] = contextvars.ContextVar("topostore_reason_budget", default=None)


class _Block:
    """The block of :func:`budget`: a class, not a generator (a REASON enters one per robot step)."""

    __slots__ = ("limits", "token")

    def __init__(self, limits: ReasonLimits) -> None:
        self.limits = limits
        self.token: contextvars.Token | None = None

    def __enter__(self) -> Budget:
        outer = _CURRENT.get()
        if outer is not None:
            return outer
        fresh = Budget(self.limits)
        self.token = _CURRENT.set(fresh)
        return fresh

    def __exit__(self, *exc: object) -> None:
        if self.token is not None:
            _CURRENT.reset(self.token)
            self.token = None


def budget(limits: ReasonLimits) -> _Block:
    """Run the block under a fresh budget (nested blocks keep the outer one: one REASON, one budget)."""
    return _Block(limits)


@contextlib.contextmanager
def doing(activity: str) -> Iterator[None]:
    """Name what the running REASON does inside the block, for the message of a limit that stops it."""
    current = _CURRENT.get()
    if current is None:
        yield
        return
    outer, current.activity = current.activity, activity
    try:
        yield
    finally:
        current.activity = outer


def tick(derived: int = 0, rules: Callable[[], Iterable[str]] | Iterable[str] = ()) -> None:
    """One round of the running REASON derived ``derived`` facts (no-op outside :func:`budget`)."""
    current = _CURRENT.get()
    if current is not None:
        current.round(rules)
        current.derived(derived, rules)


def check() -> None:
    """Stop the running REASON if its deadline has passed (loops that derive nothing new)."""
    current = _CURRENT.get()
    if current is not None:
        current.check()


def writers(rules: Iterable, preds: dict[str, int], classes: dict[str, int]) -> list[str]:
    """Names of the rules whose conclusions are among the facts just derived (for the error message)."""
    out = []
    for rule in rules:
        key = rule.writes()
        if key is None:
            continue
        if key[0] == "*" or (key[0] == "t" and key[1] in classes) or (key[0] == "p" and key[1] in preds):
            out.append(rule.name)
    return out


__all__ = ["DEFAULTS", "set_defaults", "ReasonLimits", "ReasonLimitExceeded", "Budget", "budget", "doing", "tick", "check", "writers"]
