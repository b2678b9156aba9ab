"""A body or head atom of a look-up operation resolved once: its read pattern and the bindings a fact gives.

Why this exists
---------------
The look-up operations of the compiled step (:mod:`.direct`, :mod:`.look_join`, :mod:`.look_flip`) read an
atom's facts by pattern and bind its variables from each fact read, a few dozen times a robot step.  Done
generically, per fact, that is a loop over the atom's three positions
with a type test each, a dictionary for the fact and another to merge it into the solution.  Here each
atom is resolved once, when its operation is compiled, into small functions for its positions: the
pattern for a solution, the fact's bindings, and a solution extended by a fact, in one dictionary.

A fact given to :meth:`Shape.bind` or :meth:`Shape.extend` must have been read by the atom's own pattern
(:meth:`Shape.read` or :attr:`Shape.free`): the index matched its constants and bound values, so only a
variable the atom repeats is checked (and such an atom keeps the generic path).
"""

from __future__ import annotations

from collections.abc import Callable

from pyoxigraph import Triple

#: the fact's term at each position of a triple
_GET = (lambda t: t.subject, lambda t: t.predicate, lambda t: t.object)


class Shape:
    """One atom's terms (:func:`.direct._terms`: a variable's name, or the named term), resolved once."""

    __slots__ = ("bind", "extend", "free", "read", "terms")

    def __init__(self, terms: tuple) -> None:
        self.terms = terms
        #: the pattern with no variable bound (None at each variable)
        self.free = tuple(None if isinstance(x, str) else x for x in terms)
        names = [x for x in terms if isinstance(x, str)]
        #: the pattern for a solution (its values at the atom's variables, None where one is free)
        self.read: Callable[[dict], tuple] = _reader(terms)
        if len(set(names)) != len(names):
            self.bind, self.extend = _checked(terms)
        else:
            self.bind, self.extend = _binder(terms)


def _reader(terms: tuple) -> Callable[[dict], tuple]:
    s, p, o = terms
    vs, vp, vo = (isinstance(x, str) for x in terms)
    if vp:
        return lambda b: tuple(b.get(x) if isinstance(x, str) else x for x in terms)
    if vs and vo:
        return lambda b: (b.get(s), p, b.get(o))
    if vs:
        return lambda b: (b.get(s), p, o)
    if vo:
        return lambda b: (s, p, b.get(o))
    pattern = tuple(terms)
    return lambda b: pattern


def _binder(terms: tuple) -> tuple[Callable[[Triple], dict], Callable[[dict, Triple], dict]]:
    """The fact's bindings, and a solution extended by them, for an atom whose variables are distinct."""
    s, p, o = terms
    vs, vp, vo = (isinstance(x, str) for x in terms)
    if not vp:
        if vs and vo:
            return (lambda t: {s: t.subject, o: t.object}), (lambda b, t: {**b, s: t.subject, o: t.object})
        if vs:
            return (lambda t: {s: t.subject}), (lambda b, t: {**b, s: t.subject})
        if vo:
            return (lambda t: {o: t.object}), (lambda b, t: {**b, o: t.object})
        return (lambda t: {}), (lambda b, t: dict(b))
    slots = tuple((x, _GET[i]) for i, x in enumerate(terms) if isinstance(x, str))

    def bind(t: Triple) -> dict:
        return {x: get(t) for x, get in slots}

    return bind, (lambda b, t: {**b, **bind(t)})


def _checked(terms: tuple) -> tuple[Callable[[Triple], dict | None], Callable[[dict, Triple], dict | None]]:
    """:func:`_binder` for an atom repeating a variable: a fact whose repeated positions differ binds nothing."""
    slots = tuple((x, _GET[i]) for i, x in enumerate(terms) if isinstance(x, str))

    def bind(t: Triple) -> dict | None:
        found: dict = {}
        for x, get in slots:
            value = get(t)
            if found.setdefault(x, value) != value:
                return None
        return found

    def extend(b: dict, t: Triple) -> dict | None:
        found = bind(t)
        return None if found is None else {**b, **found}

    return bind, extend


__all__ = ["Shape"]
