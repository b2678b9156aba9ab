"""A SWRL variable bound only by a ``sameAs`` body atom, compiled as rules without that atom.

``sameAs(?x, ?y)`` with ``?y`` bound by no other atom still binds it (the rule is DL-safe): sameAs is
reflexive, so ``?y`` ranges over ``?x`` itself and its aliases.  The store holds no reflexive
``owl:sameAs``, so such a rule is two: one with ``?y`` replaced by ``?x`` everywhere, one with the atom
read as the graph pattern ``?x owl:sameAs ?y``, a body atom the delta and step forms read like any other.
A SQWRL query's body is the union of the same forms, the variable replaced bound again
(:func:`rebinding`), so that the query selects it under its own name.
"""

from __future__ import annotations

from dataclasses import replace
from typing import Protocol, TypeVar

from ..rdf.terms import Term
from ..rdf.vocab import SAME_AS

#: the body atoms whose arguments a graph pattern binds
BINDING = ("ClassAtom", "IndividualPropertyAtom", "DatavaluedPropertyAtom")


class _Atom(Protocol):
    kind: str
    args: tuple[Term, ...]


A = TypeVar("A", bound=_Atom)


def same_as_forms(body: list[A], head: list[A], variables: set[Term]) -> list[tuple[list[A], list[A]]]:
    """The rule (``body``, ``head`` atoms) as the bodies and heads it stands for, none with a ``sameAs``
    atom that binds a variable; a rule without one is itself."""
    bound = {t for a in body if a.kind in BINDING for t in a.args if t in variables}
    for i, a in enumerate(body):
        if a.kind != "SameIndividualAtom" or len(a.args) != 2:
            continue
        free = [t for t in a.args if t in variables and t not in bound]
        if len(free) != 1:
            continue
        y = free[0]
        x = a.args[1] if a.args[0] == y else a.args[0]

        def put(atoms: list[A], x: Term = x, y: Term = y) -> list[A]:
            return [replace(b, args=tuple(x if t == y else t for t in b.args)) for b in atoms]

        pattern = replace(a, kind="IndividualPropertyAtom", predicate=SAME_AS, args=(x, y))
        return [*same_as_forms(put(body[:i] + body[i + 1:]), put(head), variables),
                *same_as_forms(body[:i] + [pattern] + body[i + 1:], head, variables)]
    return [(body, head)]


def rebinding(body: list[A], form: list[A], variables: set[Term]) -> list[tuple[Term, Term]]:
    """(y, x) for each variable ``y`` of ``body`` that its form ``form`` replaced: ``x`` is the variable of
    ``form`` it stands for, the nearest through ``body``'s sameAs atoms (a chain ``sameAs(?x, ?y) ^ sameAs(?y,
    ?z)`` may have replaced ``?z`` by ``?y``, or both by ``?x``)."""
    kept = {t for a in form for t in a.args if t in variables}
    links: dict[Term, list[Term]] = {}
    for a in body:
        if a.kind == "SameIndividualAtom" and len(a.args) == 2:
            p, q = a.args
            links.setdefault(p, []).append(q)
            links.setdefault(q, []).append(p)
    out = []
    for y in dict.fromkeys(t for a in body for t in a.args if t in variables and t not in kept):
        seen, todo = {y}, [y]
        while todo:
            nearest = [t for t in (n for v in todo for n in links.get(v, ())) if t not in seen]
            found = next((t for t in nearest if t in kept), None)
            if found is not None:
                out.append((y, found))
                break
            seen.update(nearest)
            todo = nearest
    return out
