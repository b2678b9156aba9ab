"""Facade methods that hand a call to one of the ontology's named parts, as the part's method is.

:class:`~topostore.ontology.facade.Ontology` delegates most of its API to parts (``reads``, ``files``):
where a method only calls the part's method of the same name with the same arguments,
:func:`forward` writes it, with the part's signature and the facade's own docstring, instead of a
body that repeats the part's parameters.
"""

from __future__ import annotations

import inspect
from collections.abc import Callable
from operator import attrgetter
from typing import Any


def forward(part: str, method: Callable[..., Any], doc: str | None = None) -> Callable[..., Any]:
    """A method calling ``self.<part>.<method's name>`` with its arguments: the signature is ``method``'s
    (the part's), the docstring ``doc`` (the facade's; None for none)."""
    name = method.__name__
    bound = attrgetter(f"{part}.{name}")  # the part's bound method, read in one call

    def call(self: Any, *args: Any, **kwargs: Any) -> Any:
        return bound(self)(*args, **kwargs)

    call.__name__ = name
    call.__qualname__ = f"Ontology.{name}"
    call.__doc__ = doc
    call.__signature__ = inspect.signature(method)  # type: ignore[attr-defined]
    return call


__all__ = ["forward"]
