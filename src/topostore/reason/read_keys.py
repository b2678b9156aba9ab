"""Which keys an evaluation reads, and whether the writers of a run may have written one of them.

The early reads of a full run (:mod:`.early_reads`: deferred asks, checks; :mod:`.early_rules`: first-pass
evaluations) are started in the worker thread once what they read is final, and dropped when a later
writer may have changed it: both ask these questions of the rules' read and written keys.
"""

from __future__ import annotations

from collections.abc import Collection, Sequence

from ..compile.rule import ReadKey, Rule
from .order import TYPE_KEY
from .triggers import may_write

#: a key standing for every key (a rule of a variable predicate reads or writes any)
ANY = ("*",)


def evaluation_reads(rule: Rule) -> frozenset[ReadKey]:
    """Every key an evaluation of ``rule`` reads: its body, its filters, its known conclusion."""
    keys = set(rule.reads())
    if rule.conditions_read_graph and not rule.filter_reads:
        keys.add(ANY)
    if rule.unless_known is not None:
        keys.add(rule.unless_known.read_key())
    return frozenset(keys)


def touches(written: ReadKey | None, reads: Collection[ReadKey]) -> bool:
    """Whether a rule writing ``written`` may have written a key among ``reads`` (:func:`.triggers.may_write`;
    a rule of a variable predicate touches every read)."""
    if written is None:
        return False
    return written[0] == "*" or any(may_write(written, key) for key in reads)


class Writes:
    """Which keys a list of writers (each a written key, or None) may write, indexed so that asking whether
    one of them may have written a key among a read's keys costs that read's keys, not the writers
    (the same answer as :func:`touches` over every writer: a TBox of 400 classes has 11,000 checks)."""

    def __init__(self, written: Sequence[tuple[int, ReadKey | None]] = ()) -> None:
        #: key -> the last position writing it; the last position writing any key, any class, rdf:type, "*"
        self.last_by_key: dict[ReadKey, int] = {}
        self.last_any = self.last_class = self.last_star = -1
        for position, key in written:
            self.add(position, key)

    def add(self, position: int, key: ReadKey | None) -> None:
        """A writer of ``key`` (None: nothing) at ``position``."""
        if key is None:
            return
        self.last_any = max(self.last_any, position)
        if key[0] == "*":
            self.last_star = max(self.last_star, position)
        elif key[0] == "t":
            self.last_class = max(self.last_class, position)
        self.last_by_key[key] = max(self.last_by_key.get(key, -1), position)

    def last(self, reads: Collection[ReadKey]) -> int:
        """The last position whose writer may write a key among ``reads`` (-1: none)."""
        if ANY in reads:
            return self.last_any
        found = self.last_star
        for key in reads:
            found = max(found, self.last_by_key.get(key, -1))
            if key[0] == "t":
                found = max(found, self.last_by_key.get(("p", TYPE_KEY), -1))
        if ("p", TYPE_KEY) in reads:
            found = max(found, self.last_class)
        return found


__all__ = ["ANY", "Writes", "evaluation_reads", "touches"]
