"""The greedy join order of a rule body: which atom a SPARQL text or an index walk joins next.

Kept apart from the :class:`~.rule.Rule` value: the store evaluates a basic graph pattern largely in the
order it is written, and the reasoner's look-up joins, flips and explanations walk a body in the same
order, so every evaluation of a rule asks it (kept per body).
"""

from __future__ import annotations

from collections.abc import Iterable
from functools import lru_cache
from typing import TYPE_CHECKING

from ..rdf.vocab import TYPE

if TYPE_CHECKING:
    from .rule import Atom

_TYPE_TEXT = str(TYPE)


def _atom_score(atom: Atom, bound: set[str]) -> int:
    """Higher is cheaper to evaluate next, given the variables already bound."""
    if atom._vars <= bound:
        return 100  # a pure check on bound values
    s_known = not atom.s.startswith("?") or atom.s in bound
    o_known = not atom.o.startswith("?") or atom.o in bound
    is_type = atom.p == _TYPE_TEXT
    if atom.p.startswith("?"):
        return 20 if s_known else (15 if o_known else 0)
    if s_known and not is_type:
        return 60
    if o_known and not is_type:
        return 55
    if is_type:
        return 10  # enumerate the instances of a class
    return 30  # enumerate a property


def join_order(atoms: tuple[Atom, ...], first: int | None = None, bound: Iterable[str] = ()) -> list[int]:
    """A greedy join order: start from ``first`` (or the most selective atom), then
    always take the atom that is cheapest given what is bound (``bound``: variables
    bound before the body), so that no rule starts from a cross product of class
    extensions."""
    if len(atoms) <= 1 and first in (None, 0):
        return list(range(len(atoms)))
    return list(_join_order(tuple(atoms), first, frozenset(bound)))


@lru_cache(maxsize=1 << 16)
def _join_order(atoms: tuple[Atom, ...], first: int | None, bound: frozenset[str]) -> tuple[int, ...]:
    """:func:`join_order`, kept per body: a compilation merges and a full REASON renders the same
    bodies again and again (every round, every delta atom)."""
    remaining = list(range(len(atoms)))
    order: list[int] = []
    known = set(bound)
    if first is not None:
        order.append(first)
        remaining.remove(first)
        known |= atoms[first]._vars
    while remaining:
        best = max(remaining, key=lambda i: (_atom_score(atoms[i], known), -i))
        order.append(best)
        remaining.remove(best)
        known |= atoms[best]._vars
    return tuple(order)


__all__ = ["join_order"]
