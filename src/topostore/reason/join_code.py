"""A look-up join compiled once into a flat Python function: one loop per atom, variables as locals.

Why this exists
---------------
The look-up operations of the compiled step (:mod:`.look_join`, :mod:`.look_flip`) join a rule's atoms
by index reads in an order fixed when the step is compiled.  Interpreted, every fact read cost a
pattern built from the solution dictionary, a new dictionary merging the fact's bindings, and a
generator frame per atom that every solution climbs back through.  But what the interpretation
decides — the order, which positions of each atom are bound when it is read, which variable a
position binds and which repeated variable it must agree with — depends only on the rule and the
atom the join starts from.  So it is decided once here and written out as nested ``for`` loops
whose read patterns name local variables; only a finished solution is made a dictionary (the
conditions of :mod:`.look_filters` read one).

The generated text holds no term and no name taken from the ontology: constants are passed in
the function's namespace (``c0``, ``c1``, ...), variables are renamed ``v0``, ``v1``, ..., and a
solution's keys are the variables' names as Python string literals (``repr``).  The solutions and
their order are those of the interpreted join (:func:`interpreted`, kept as the reference the tests
compare against), and so is every read: the same patterns, graphs and limit (``read`` raises when an
atom has too many matches, and the caller's SPARQL text runs).
"""

from __future__ import annotations

from collections.abc import Callable, Collection, Iterator

from .atom_shape import Shape

_POSITION = ("subject", "predicate", "object")

#: a join over given variables: ``join(store, bound)`` yields each solution extending ``bound``
Join = Callable[[object, dict], Iterator[dict]]


def compile_join(terms: list[tuple], order: list[int], given: Collection[str], graphs: list[tuple],
                 read: Callable) -> Join:
    """The join of the atoms ``order`` (each atom's terms: a variable's name, or the term itself, as
    :func:`.direct._terms` gives them), starting from a solution binding exactly ``given``;
    ``graphs[k]``: the extra arguments ``read(store, pattern, *graphs[k])`` takes for atom ``k``."""
    names: dict[str, str] = {}
    consts: list = []
    namespace: dict[str, object] = {"read": read}
    lines = ["def join(store, bound):"]
    for var in sorted(given):
        names[var] = f"v{len(names)}"
        lines.append(f"    {names[var]} = bound[{var!r}]")
    depth = 1
    for level, k in enumerate(order):
        namespace[f"g{level}"] = graphs[k]
        pattern, binds, checks = _atom(terms[k], names, consts)
        pad = "    " * depth
        lines.append(f"{pad}for t in read(store, ({', '.join(pattern)}), *g{level}):")
        pad += "    "
        for local, position in binds:
            lines.append(f"{pad}{local} = t.{position}")
        for local, position in checks:
            lines.append(f"{pad}if t.{position} != {local}:")
            lines.append(f"{pad}    continue")
        depth += 1
    namespace.update((f"c{i}", term) for i, term in enumerate(consts))
    solution = ", ".join(f"{var!r}: {local}" for var, local in names.items())
    lines.append(f"{'    ' * depth}yield {{{solution}}}")
    exec(compile("\n".join(lines), "<topostore join>", "exec"), namespace)  # noqa: S102 - text made above
    return namespace["join"]  # type: ignore[return-value]


def _atom(terms: tuple, names: dict[str, str], consts: list) -> tuple[list[str], list, list]:
    """One atom's read pattern (local names, and constants named by their place in ``consts``), the
    locals its fact binds, and the positions that repeat a variable the same fact binds first
    (checked equal)."""
    pattern, binds, checks = [], [], []
    fresh: set[str] = set()
    for position, term in zip(_POSITION, terms):
        if not isinstance(term, str):
            pattern.append(f"c{len(consts)}")
            consts.append(term)
        elif term in names and term not in fresh:
            pattern.append(names[term])
        elif term in fresh:
            pattern.append("None")
            checks.append((names[term], position))
        else:
            names[term] = f"v{len(names)}"
            fresh.add(term)
            pattern.append("None")
            binds.append((names[term], position))
    return pattern, binds, checks


def interpreted(shapes: list[Shape], order: list[int], graphs: list[tuple], read: Callable) -> Join:
    """The same join interpreted atom by atom (the reference :func:`compile_join` is tested against)."""

    def join(store, bound: dict, at: int = 0) -> Iterator[dict]:
        if at == len(order):
            yield bound
            return
        shape = shapes[order[at]]
        for t in read(store, shape.read(bound), *graphs[order[at]]):
            extended = shape.extend(bound, t)
            if extended is not None:
                yield from join(store, extended, at + 1)

    return join


__all__ = ["Join", "compile_join", "interpreted"]
