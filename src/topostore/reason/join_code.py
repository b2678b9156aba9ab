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

import functools
from collections.abc import Callable, Collection, Iterator
from types import CodeType
from typing import NamedTuple

from .atom_shape import Shape

_POSITION = ("subject", "predicate", "object")

#: a join over given variables: ``join(store, bound)`` yields each solution extending ``bound``
Join = Callable[[object, dict], Iterator[dict]]

#: the most loops one generated function nests: Python refuses more than 20 statically nested blocks
#: (a rule of 21 atoms), so a longer join or flip is interpreted (:func:`interpreted`) instead
MAX_LOOPS = 18


class JoinDecision(NamedTuple):
    """What a generated join decides each solution with, in place of yielding it: ``holds``, the rule's
    conditions as a function of the values of ``names`` in that order (True, False, or None where not
    decided: :meth:`.look_join.Conditions.holds_over`), and, for additions, the head's terms,
    ``instance(s, p, o)`` (the head fact, None where none is written, False where the caller's text must
    write it) and the most heads the look-up writes."""

    holds: Callable
    names: tuple[str, ...]
    head: tuple | None = None
    instance: Callable | None = None
    limit: int = 0


def compile_join(terms: list[tuple], order: list[int], given: Collection[str], graphs: list[tuple],
                 read: Callable, decision: JoinDecision | None = None) -> Callable | None:
    """The join of the atoms ``order`` (each atom's terms: a variable's name, or the term itself, as
    :func:`.direct._terms` gives them), starting from a solution binding exactly ``given``;
    ``graphs[k]``: the extra arguments ``read(store, pattern, *graphs[k])`` takes for atom ``k``.
    None where the join nests more than :data:`MAX_LOOPS` loops (the caller interprets it).

    With a ``decision`` its solutions are decided where they are found (the conditions called with the
    loop's locals, no dictionary per solution): without a head, ``prove(store, bound)`` answers whether
    one holds (True at the first, None where none does and one is not decided, else False), as
    :meth:`.look_join.Joined._proven`; with a head, ``derive(store, bound, heads)`` appends the head of
    each solution that holds to ``heads`` and answers False (the caller's text runs) where one is not
    decided, a head holds a literal or the heads grow past ``decision.limit``, as
    :meth:`.look_join.Joined.additions`."""
    if len(order) > MAX_LOOPS:
        return None
    deriving = decision is not None and decision.head is not None
    code = _Code("def join(store, bound, heads):" if deriving else "def join(store, bound):", read)
    if decision is not None and decision.head is None:
        code.line("answer = False")
    for var in sorted(given):
        code.line(f"{code.local(var)} = bound[{var!r}]")
    for k in order:
        code.read_atom(terms[k], code.const(graphs[k]))
    if decision is None:
        code.line(f"yield {code.solution()}")
        return code.function("join")
    holds = code.const(decision.holds)
    code.line(f"b = {holds}({', '.join(code.names.get(name, 'None') for name in decision.names)})")
    if decision.head is None:
        code.line("if b is True:")
        code.line("    return True")
        code.line("if b is None:")
        code.line("    answer = None")
        code.close_all()
        code.line("return answer")
    else:
        head = ", ".join(code.names[x] if isinstance(x, str) else code.const(x) for x in decision.head)
        code.line("if b is None:")
        code.line("    return False")
        code.line("if b:")
        code.line(f"    head = {code.const(decision.instance)}({head})")
        code.line("    if head is False:")
        code.line("        return False")
        code.line("    if head is not None:")
        code.line("        heads.append(head)")
        code.line(f"        if len(heads) > {int(decision.limit)}:")
        code.line("            return False")
        code.close_all()
        code.line("return True")
    return code.function("join")


class FlipDecision(NamedTuple):
    """What a generated flip branch decides each solution with, in place of yielding it: ``exact``, the
    rule's conditions as a function of the values of ``names`` in that order (each test a boolean, else
    None: :meth:`.look_join.Conditions.exact_over`), the head's terms, ``instance(s, p, o)`` (the head
    fact, None where none is written, False where the caller's text must write it) and the exception
    that hands the flip to its text."""

    exact: Callable
    names: tuple[str, ...]
    head: tuple
    instance: Callable
    fallback: type[Exception]


def compile_flip(terms: list[tuple], seed: int, plan: list[int], paired: Collection[int], graphs: list[tuple],
                 old_graphs: tuple, read: Callable, decision: FlipDecision | None = None) -> Callable | None:
    """One branch of a flip (see :mod:`.look_flip`) as a flat function: ``branch(store)`` yields each
    solution with the new values and, apart, the old values of its compared variables; with a
    ``decision``, ``branch(store, gained, lost)`` decides each solution where it is found instead (the
    conditions called with the loop's locals, no dictionary per solution), putting a head whose answer
    differs into ``gained`` (true now) or ``lost``, and raising ``decision.fallback`` where one is not
    decided or its head holds a literal (as :meth:`.look_flip.Flipped._decide`).

    The seed atom ``seed``'s replaced facts are read from ``old_graphs`` (their old value), and its new
    facts by their subject and predicate; the atoms ``plan`` are joined after it, each from its
    ``graphs``; an atom of ``paired`` (a changed atom after the seed) takes, besides its new value, each
    old value its fact had (or the new one where it was not replaced).  Every changed atom's object
    must be a variable (the value compared).  None where it nests more than :data:`MAX_LOOPS` loops."""
    if 2 + len(plan) + len(set(plan) & set(paired)) > MAX_LOOPS:
        return None
    code = _Code("def branch(store, gained, lost):" if decision else "def branch(store):", read)
    old = code.const(old_graphs)
    s, p, value = terms[seed]
    code.read_atom((s, p, value), old, fresh=True, name="f")
    subject = s if not isinstance(s, str) else None
    predicate = p if not isinstance(p, str) else None
    code.read_atom(terms[seed], code.const(graphs[seed]), fresh=True,
                   pattern=(code.term(s, subject), code.term(p, predicate), "None"))
    olds = {value: "w0"}
    code.line("w0 = f.object")
    for m in plan:
        code.read_atom(terms[m], code.const(graphs[m]))
        if m in paired:
            local = f"w{len(code.lines)}"  # unique even where a paired atom's variable is bound twice
            code.line(f"for {local} in ([o.object for o in read(store, (t.subject, t.predicate, None), *{old})]"
                      " or (t.object,)):")
            code.open()
            olds[terms[m][2]] = local
    if decision is None:
        code.line(f"yield {code.solution()}, {{{', '.join(f'{var!r}: {w}' for var, w in olds.items())}}}")
    else:
        code.decide(decision, olds)
    return code.function("branch")


class _Code:
    """The text of one generated function: nested loops, their locals and constants."""

    def __init__(self, header: str, read: Callable) -> None:
        self.lines = [header]
        self.depth = 1
        #: variable name -> local name, in the order they are bound
        self.names: dict[str, str] = {}
        self.namespace: dict[str, object] = {"read": read}
        #: local name -> the depth of the loop body that binds it (1: bound before any loop)
        self.levels: dict[str, int] = {}
        #: per depth, the line where the body of its loop starts, after the loop's bindings and checks
        #: (where a read that does not depend on deeper loops is forgotten: see :meth:`read_atom`)
        self.starts: dict[int, int] = {1: 1}
        self.hoisted = 0

    def line(self, text: str) -> None:
        self.lines.append("    " * self.depth + text)

    def local(self, var: str) -> str:
        """A variable's local (made at its first binding, at the current depth)."""
        if var not in self.names:
            self.names[var] = f"v{len(self.names)}"
            self.levels[self.names[var]] = self.depth
        return self.names[var]

    def open(self) -> None:
        """A loop's body starts here (its header written, its bindings not yet)."""
        self.depth += 1
        self.starts[self.depth] = len(self.lines)

    def _insert(self, depth: int, text: str) -> None:
        """A line at the start of the body of the loop at ``depth`` (after its bindings and checks)."""
        at = self.starts[depth]
        self.lines.insert(at, "    " * depth + text)
        for d, start in self.starts.items():
            if start >= at and d != depth:
                self.starts[d] = start + 1
        self.starts[depth] = at + 1

    def const(self, value: object) -> str:
        """A constant's name in the function's namespace (never its text)."""
        name = f"c{len(self.namespace)}"
        self.namespace[name] = value
        return name

    def term(self, term, constant) -> str:
        """A pattern's position: the constant's name, or the bound variable's local."""
        return self.const(constant) if constant is not None else self.names[term]

    def read_atom(self, terms: tuple, graphs: str, fresh: bool = False, name: str = "t",
                  pattern: tuple | None = None) -> None:
        """A loop over the atom's facts (read by the values bound so far, or ``pattern``), binding its
        new variables and checking a variable it repeats; ``fresh``: every variable of the atom is
        bound anew from the fact (its read matched those already bound)."""
        bound = set() if fresh else set(self.names)
        parts, binds, checks = [], [], []
        seen: set[str] = set()
        for position, term in zip(_POSITION, terms):
            if not isinstance(term, str):
                parts.append(self.const(term))
            elif term in seen:
                parts.append("None")
                checks.append((self.names[term], position))
            elif term in bound:
                parts.append(self.names[term])
            else:
                seen.add(term)
                parts.append("None")
                binds.append((self.local(term), position))
        call = f"read(store, ({', '.join(pattern or parts)}), *{graphs})"
        # a read none of whose values the innermost loops bind gives the same facts at each of their
        # turns: made at the first, kept until the loop it depends on moves on (never made sooner,
        # so a read that refuses refuses at the same point)
        home = max((self.levels[x] for x in parts if x in self.levels), default=1)
        if pattern is None and not fresh and home < self.depth:
            self.hoisted += 1
            kept = f"h{self.hoisted}"
            self._insert(home, f"{kept} = None")
            self.line(f"if {kept} is None:")
            self.line(f"    {kept} = {call}")
            call = kept
        self.line(f"for {name} in {call}:")
        self.open()
        for local, position in binds:
            self.levels[local] = self.depth
            self.line(f"{local} = {name}.{position}")
        for local, position in checks:
            self.line(f"if {name}.{position} != {local}:")
            self.line("    continue")
        self.starts[self.depth] = len(self.lines)

    def decide(self, decision: FlipDecision, olds: dict[str, str]) -> None:
        """The innermost statements of a flip branch with ``decision``: the conditions over the new values
        and over the old ones (``olds``: a compared variable's local holding its old value), and the head
        put where its answer went."""
        exact, fallback, instance = self.const(decision.exact), self.const(decision.fallback), \
            self.const(decision.instance)
        now = ", ".join(self.names.get(name, "None") for name in decision.names)
        then = ", ".join(olds.get(name, self.names.get(name, "None")) for name in decision.names)
        head = ", ".join(self.names[x] if isinstance(x, str) else self.const(x) for x in decision.head)
        self.line(f"now = {exact}({now})")
        self.line(f"then = {exact}({then})")
        self.line("if now is None or then is None:")
        self.line(f"    raise {fallback}")
        self.line("if now != then:")
        self.line(f"    head = {instance}({head})")
        self.line("    if head is False:")
        self.line(f"        raise {fallback}")
        self.line("    if head is not None:")
        self.line("        (gained if now else lost)[head] = None")

    def close_all(self) -> None:
        """Back to the function's body, after every loop (its closing statements follow)."""
        self.depth = 1

    def solution(self) -> str:
        return "{" + ", ".join(f"{var!r}: {local}" for var, local in self.names.items()) + "}"

    def function(self, name: str) -> Callable:
        exec(_compiled("\n".join(self.lines), name), self.namespace)  # noqa: S102 - made above
        return self.namespace[name]  # type: ignore[return-value]


@functools.lru_cache(maxsize=4096)
def _compiled(text: str, name: str) -> CodeType:
    """The code object of a generated text, compiled once: the text names no term (constants are the
    namespace's ``c0``, ``c1``, ...), so rules of one shape share it, and Python's compiler is most of
    what a first step spends making its look-ups."""
    return compile(text, f"<topostore {name}>", "exec")


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


__all__ = ["FlipDecision", "Join", "JoinDecision", "compile_flip", "compile_join", "interpreted"]
