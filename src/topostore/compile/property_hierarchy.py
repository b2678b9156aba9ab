"""The property hierarchy over property expressions: each property and its inverse.

Told sub-properties are not the whole hierarchy: ``p ⊑ q`` also gives ``p⁻ ⊑ q⁻``, ``p owl:inverseOf q``
makes ``p`` and ``q⁻`` the same, a symmetric ``p`` is its own inverse.  So ``p ⊑ q`` with ``p owl:inverseOf q``
makes ``q ⊑ p`` too, and the domain of ``p`` the domain of ``q``.  The compile steps that reason about a
value no one named (an existential's) read the hierarchy from here, so that no such combination is lost:
:mod:`.owl_extras` (restrictions subsumed through properties, the domain of an existential's subject) and
the profile report.
"""

from __future__ import annotations

from pyoxigraph import NamedNode

from ..rdf.vocab import THING
from .model import Expr, Prop, TBox


def inverse(p: Prop) -> Prop:
    return Prop(p.iri, not p.inverse)


def _edges(tb: TBox) -> dict[Prop, set[Prop]]:
    """Direct sub-property edges between property expressions, both directions of each axiom."""
    edges: dict[Prop, set[Prop]] = {}

    def edge(a: Prop, b: Prop) -> None:
        if a != b:
            edges.setdefault(a, set()).add(b)
            edges.setdefault(inverse(a), set()).add(inverse(b))

    for a, b in tb.subproperty:
        edge(a, b)
    for p, q in tb.inverse:
        if isinstance(q, NamedNode):
            edge(Prop(p), Prop(q, True))
            edge(Prop(q, True), Prop(p))
    for p in tb.characteristics.get("SymmetricProperty", ()):
        edge(Prop(p), Prop(p, True))
    return edges


def super_expressions(tb: TBox) -> dict[Prop, frozenset[Prop]]:
    """Each property expression's strict super-property expressions (the equivalent ones included,
    itself not), closed under sub-properties, inverses and symmetry; expressions with none are absent."""
    edges = _edges(tb)
    closure: dict[Prop, frozenset[Prop]] = {}
    for start in edges:
        seen: set[Prop] = set()
        todo = [start]
        while todo:
            for nxt in edges.get(todo.pop(), ()):
                if nxt not in seen and nxt != start:
                    seen.add(nxt)
                    todo.append(nxt)
        closure[start] = frozenset(seen)
    return closure


def single_valued(tb: TBox) -> dict[Prop, Prop]:
    """Each property expression that has at most one value, with the told one that says so (itself or a
    super-expression): a sub-property of a functional property is functional, and so is the inverse of an
    inverse-functional one (``q ⊑ p`` and ``p`` functional: ``q`` has at most one value, OWL 2 and Pellet)."""
    ch = tb.characteristics
    told = {Prop(p) for p in ch.get("FunctionalProperty", ())} | {
        Prop(p, True) for p in ch.get("InverseFunctionalProperty", ())}
    out = {p: p for p in told}
    for p, supers in super_expressions(tb).items():
        found = sorted(supers & told, key=name)
        if p not in out and found:
            out[p] = found[0]
    return out


def subject_classes(tb: TBox, supers: dict[Prop, frozenset[Prop]], p: Prop) -> list[tuple[str, Expr]]:
    """The classes every subject of ``p`` is in, each with the axiom it comes from ("domain of q"): the
    domain of each of ``p``'s super-expressions (itself included), the range of an inverse one; owl:Thing
    left out."""
    wanted = {p, *supers.get(p, ())}
    out = [(f"domain of {name(q)}", c) for q, c in tb.domain if q in wanted and c.node != THING]
    out += [(f"range of {name(q)}", c) for q, c in tb.range if inverse(q) in wanted and c.node != THING]
    return out


def name(p: Prop) -> str:
    """``p`` as the notices and rule origins write it (``inverse q`` for an inverse expression)."""
    v = p.iri.value
    short = v.rsplit("#", 1)[-1] if "#" in v else v.rsplit("/", 1)[-1]
    return f"inverse {short}" if p.inverse else short


__all__ = ["inverse", "name", "subject_classes", "super_expressions"]
