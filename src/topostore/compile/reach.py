"""What a start reaches through a successor relation: the one walk behind every closure the compiler
takes (datatype ancestors, sub-properties, implied classes, a schema table's hierarchy rows)."""

from __future__ import annotations

from collections.abc import Callable, Hashable, Iterable
from typing import TypeVar

T = TypeVar("T", bound=Hashable)


def reachable(start: T, successors: Callable[[T], Iterable[T]]) -> set[T]:
    """``start`` and everything reachable from it by ``successors`` (depth first; cycles end the walk)."""
    return reachable_all((start,), successors)


def reachable_all(starts: Iterable[T], successors: Callable[[T], Iterable[T]]) -> set[T]:
    """The ``starts`` and everything reachable from any of them by ``successors``: one walk, each node
    visited once however many starts reach it."""
    seen = set(starts)
    todo = list(seen)
    while todo:
        for nxt in successors(todo.pop()):
            if nxt not in seen:
                seen.add(nxt)
                todo.append(nxt)
    return seen


__all__ = ["reachable", "reachable_all"]
