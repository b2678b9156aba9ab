"""Which restrictions' fillers subsume a given filler, found through an index instead of a scan.

Restriction subsumption (``≥n p.C ⊑ ≥m p.D`` when ``C ⊑ D``, :mod:`.owl`; through sub-properties and
for universal restrictions, :mod:`.owl_extras`) compares restrictions pairwise.  A TBox with hundreds
of distinct restrictions on one property made that tens of thousands of told-subsumption tests, of
which a few hundred hold.  Most fillers are named classes, and a named class ``D`` subsumes a filler
``C`` exactly when ``D`` is among :func:`named_supers` of ``C`` (what
:meth:`.owl.OwlCompiler.class_subsumed` decides for a named right-hand side, computed once per
filler): restrictions with a named filler are looked up by it, the others (a class expression, a
data range, no filler) are still tested one by one.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING

from pyoxigraph import NamedNode

from .model import Expr

if TYPE_CHECKING:
    from .owl import OwlCompiler


class FillerIndex:
    """The restrictions ``candidates`` (in their order), looked up by what their filler subsumes.

    A named filler is looked up exactly (:func:`named_supers`).  A union of named classes (a closure
    axiom's ``only (A or B or C)``) can subsume a filler only if it is that very node or one of its
    members is among :func:`named_parts` of the filler: those are the union's only candidates, then
    tested.  Any other filler is tested against every restriction."""

    def __init__(self, owl: OwlCompiler, candidates: Sequence[Expr]) -> None:
        self.owl = owl
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
        """The candidates ``b`` with ``owl.filler_subsumed(a, b)``, in the candidates' order."""
        found: dict[int, Expr] = {}
        if a.filler is not None and a.datatype is None:
            for node in named_supers(self.owl, a.filler):
                found.update(self.by_named.get(node, ()))
            for node in {a.filler.node, *named_parts(self.owl, a.filler)}:
                found.update((i, b) for i, b in self.by_member.get(node, ())
                             if i not in found and self.owl.fillers_subsumed(a, b))
        found.update((i, b) for i, b in self.others if self.owl.fillers_subsumed(a, b))
        return [found[i] for i in sorted(found)]


def named_parts(owl: OwlCompiler, x: Expr) -> frozenset[NamedNode]:
    """:func:`named_supers` of ``x`` and of the members of its intersections and unions, at any depth: a
    union of named classes subsumes ``x`` only if one of its members is among them (or it is ``x``)."""
    found = owl.named_parts.get(x.node)
    if found is None:
        found = named_supers(owl, x)
        if x.kind in ("and", "or"):
            found = found.union(*(named_parts(owl, m) for m in x.members))
        owl.named_parts[x.node] = found
    return found


def named_supers(owl: OwlCompiler, x: Expr) -> frozenset[NamedNode]:
    """The named classes ``D`` with ``owl.class_subsumed(x, D)``: a named class and its told superclasses;
    for an intersection, those of any member; for a union, those of every member; none otherwise."""
    found = owl.named_supers.get(x.node)
    if found is None:
        if x.is_named:
            found = frozenset({x.node, *owl.told.get(x.node, ())})
        elif x.kind == "and":
            found = frozenset().union(*(named_supers(owl, m) for m in x.members))
        elif x.kind == "or" and x.members:
            found = frozenset.intersection(*(named_supers(owl, m) for m in x.members))
        else:
            found = frozenset()
        owl.named_supers[x.node] = found
    return found


__all__ = ["FillerIndex", "named_parts", "named_supers"]
