"""Told subsumption between fillers, and which restrictions' fillers subsume a given filler, found
through an index instead of a scan.

Restriction subsumption (``≥n p.C ⊑ ≥m p.D`` when ``C ⊑ D``, :mod:`.owl`; through sub-properties and
for universal restrictions, :mod:`.owl_extras`) compares restrictions pairwise.  A TBox with hundreds
of distinct restrictions on one property made that tens of thousands of told-subsumption tests, of
which a few hundred hold.  Most fillers are named classes, and a named class ``D`` subsumes a filler
``C`` exactly when ``D`` is among :meth:`Subsumption.named_supers` of ``C`` (what
:meth:`Subsumption.classes` decides for a named right-hand side, computed once per filler):
restrictions with a named filler are looked up by it, the others (a class expression, a data range,
no filler) are still tested one by one.
"""

from __future__ import annotations

from collections.abc import Sequence

from pyoxigraph import NamedNode

from .datatypes import implied_ranges
from .model import Expr, TBox
from .range_values import included


class Subsumption:
    """Told subsumption between class expressions and between restrictions' fillers, each pair decided
    once (comparing the unions of a TBox's universal restrictions compares the same members again and
    again), and the named classes an expression is told to be under (for :class:`FillerIndex`)."""

    def __init__(self, told: dict[NamedNode, set[NamedNode]]) -> None:
        #: named class -> its told named superclasses (closed)
        self.told = told
        self._classes: dict[tuple[NamedNode, NamedNode], bool] = {}
        self._fillers: dict[tuple, bool] = {}
        self._supers: dict[NamedNode, frozenset[NamedNode]] = {}
        self._parts: dict[NamedNode, frozenset[NamedNode]] = {}

    def fillers(self, a: Expr, b: Expr) -> bool:
        """Told: every instance of filler ``a`` is an instance of filler ``b`` (None = Thing); data
        ranges by datatype subsumption (``xsd:byte`` values are ``xsd:short`` values)."""
        key = (a.filler.node if a.filler is not None else None, a.datatype,
               b.filler.node if b.filler is not None else None, b.datatype)
        found = self._fillers.get(key)
        if found is None:
            found = self._fillers[key] = self._filler_subsumed(a, b)
        return found

    def _filler_subsumed(self, a: Expr, b: Expr) -> bool:
        if b.filler is None and b.datatype is None:
            return True
        if a.datatype is not None or b.datatype is not None:
            if a.datatype is None or b.datatype is None:
                return False
            if a.datatype == b.datatype or b.datatype in implied_ranges([a.datatype]):
                return True
            # a range built of others on either side: decided structurally where simple (range_values.included;
            # what is not decided is said by a notice, graph_notices.unchecked_datatypes)
            return included(a.datatype, b.datatype) is True
        if a.filler is None:
            return False
        return self.classes(a.filler, b.filler)

    def classes(self, x: Expr, y: Expr) -> bool:
        """Told: ``x ⊑ y`` through named superclasses, a member of a union on the right (``C ⊑ C ⊔ D``)
        or every member of an intersection; on the left, a member of an intersection or every member
        of a union."""
        key = (x.node, y.node)
        found = self._classes.get(key)
        if found is None:
            found = self._classes[key] = self._class_subsumed(x, y)
        return found

    def _class_subsumed(self, x: Expr, y: Expr) -> bool:
        if x.node == y.node or (x.is_named and y.is_named and y.node in self.told.get(x.node, set())):
            return True
        if y.kind == "or" and any(self.classes(x, m) for m in y.members):
            return True
        if y.kind == "and" and y.members and all(self.classes(x, m) for m in y.members):
            return True
        if x.kind == "and" and any(self.classes(m, y) for m in x.members):
            return True
        return x.kind == "or" and bool(x.members) and all(self.classes(m, y) for m in x.members)

    def named_supers(self, x: Expr) -> frozenset[NamedNode]:
        """The named classes ``D`` with ``classes(x, D)``: a named class and its told superclasses; for an
        intersection, those of any member; for a union, those of every member; none otherwise."""
        found = self._supers.get(x.node)
        if found is None:
            if x.is_named:
                found = frozenset({x.node, *self.told.get(x.node, ())})
            elif x.kind == "and":
                found = frozenset().union(*(self.named_supers(m) for m in x.members))
            elif x.kind == "or" and x.members:
                found = frozenset.intersection(*(self.named_supers(m) for m in x.members))
            else:
                found = frozenset()
            self._supers[x.node] = found
        return found

    def named_parts(self, x: Expr) -> frozenset[NamedNode]:
        """:meth:`named_supers` of ``x`` and of the members of its intersections and unions, at any depth:
        a union of named classes subsumes ``x`` only if one of its members is among them (or it is ``x``)."""
        found = self._parts.get(x.node)
        if found is None:
            found = self.named_supers(x)
            if x.kind in ("and", "or"):
                found = found.union(*(self.named_parts(m) for m in x.members))
            self._parts[x.node] = found
        return found


class FillerIndex:
    """The restrictions ``candidates`` (in their order), looked up by what their filler subsumes.

    A named filler is looked up exactly (:meth:`Subsumption.named_supers`).  A union of named classes (a
    closure axiom's ``only (A or B or C)``) can subsume a filler only if it is that very node or one of
    its members is among :meth:`Subsumption.named_parts` of the filler: those are the union's only
    candidates, then tested.  Any other filler is tested against every restriction."""

    def __init__(self, told: Subsumption, candidates: Sequence[Expr]) -> None:
        self.told = told
        self.by_named: dict[NamedNode, list[tuple[int, Expr]]] = {}
        self.by_member: dict[NamedNode, list[tuple[int, Expr]]] = {}
        self.others: list[tuple[int, Expr]] = []
        for i, b in enumerate(candidates):
            f = b.filler
            if f is not None and f.is_named and b.datatype is None:
                self.by_named.setdefault(f.node, []).append((i, b))
            elif f is not None and b.datatype is None and f.kind == "or" and f.members \
                    and all(m.is_named for m in f.members):
                for node in {f.node, *(m.node for m in f.members)}:
                    self.by_member.setdefault(node, []).append((i, b))
            else:
                self.others.append((i, b))

    def subsuming(self, a: Expr) -> list[Expr]:
        """The candidates ``b`` whose filler subsumes ``a``'s (:meth:`Subsumption.fillers`), in order."""
        told = self.told
        found: dict[int, Expr] = {}
        if a.filler is not None and a.datatype is None:
            for node in told.named_supers(a.filler):
                found.update(self.by_named.get(node, ()))
            for node in {a.filler.node, *told.named_parts(a.filler)}:
                found.update((i, b) for i, b in self.by_member.get(node, ()) if i not in found and told.fillers(a, b))
        found.update((i, b) for i, b in self.others if told.fillers(a, b))
        return [found[i] for i in sorted(found)]


def _link(edges: dict[NamedNode, set[NamedNode]], a: Expr, b: Expr) -> None:
    """The told edge a ⊑ b between named classes into ``edges`` (b's named members for an intersection).
    A function of the module, not a closure: a nested function calling itself is a cycle, which would keep
    what it reads alive past the compilation until a full collection (tests/test_compile_cycles.py)."""
    if a.is_named and b.is_named:
        edges.setdefault(a.node, set()).add(b.node)
    elif a.is_named and b.kind == "and":
        for m in b.members:
            _link(edges, a, m)


def told_superclasses(tbox: TBox) -> dict[NamedNode, set[NamedNode]]:
    """Named-class subsumption told by the axioms (closure), for comparing fillers."""
    edges: dict[NamedNode, set[NamedNode]] = {}
    for a, b in tbox.subclass:
        _link(edges, a, b)
    for a, b in tbox.equivalent:
        _link(edges, a, b)
        _link(edges, b, a)
    closure: dict[NamedNode, set[NamedNode]] = {}
    for start in edges:
        seen, todo = set(), [start]
        while todo:
            for nxt in edges.get(todo.pop(), ()):
                if nxt not in seen:
                    seen.add(nxt)
                    todo.append(nxt)
        closure[start] = seen
    return closure


__all__ = ["FillerIndex", "Subsumption", "told_superclasses"]
