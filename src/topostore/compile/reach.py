"""What a start reaches through a successor relation: the one walk behind every closure the compiler
takes (datatype ancestors, sub-properties, implied classes, a schema table's hierarchy rows)."""

from __future__ import annotations

from collections.abc import Callable, Hashable, Iterable
from typing import TypeVar

T = TypeVar("T", bound=Hashable)


def reachable(start: T, successors: Callable[[T], Iterable[T]]) -> set[T]:
    """``start`` and everything reachable from it by ``successors`` (depth first; cycles end the walk)."""
    seen, todo = {start}, [start]
    while todo:
        for nxt in successors(todo.pop()):
            if nxt not in seen:
                seen.add(nxt)
                todo.append(nxt)
    return seen


__all__ = ["reachable"]
