"""What a start reaches through a successor relation: the one walk behind every closure the compiler
takes (datatype ancestors, sub-properties, implied classes, a schema table's hierarchy rows)."""

from __future__ import annotations

from collections.abc import Callable, Hashable, Iterable
from typing import Generic, TypeVar

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


class Reach(Generic[T]):
    """What each start reaches by ``successors``, walked only for the starts asked and kept: a walk that
    meets a node already walked takes that node's set whole instead of walking on (each kept set is
    complete, so this holds through cycles too)."""

    def __init__(self, successors: Callable[[T], Iterable[T]]) -> None:
        self._successors = successors
        self._found: dict[T, frozenset[T]] = {}

    def __call__(self, start: T) -> frozenset[T]:
        """``start`` and everything reachable from it."""
        found = self._found.get(start)
        if found is not None:
            return found
        seen: set[T] = {start}
        todo = [start]
        while todo:
            for nxt in self._successors(todo.pop()):
                if nxt in seen:
                    continue
                known = self._found.get(nxt)
                if known is not None:
                    seen |= known
                else:
                    seen.add(nxt)
                    todo.append(nxt)
        found = self._found[start] = frozenset(seen)
        return found


__all__ = ["Reach", "reachable", "reachable_all"]
