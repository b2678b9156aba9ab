"""The rows an axiom contributes to the schema tables of ``rules/owl/`` (see :mod:`.schema`).

Each function reads one kind of axiom and gives its row, the SPARQL terms in the order the file's
schema atoms bind them, or None where the axiom has no row (a shape the file does not have: an
inverse property expression, owl:Thing, a chain of another length), whose rule the compiler then
writes directly.
"""

from __future__ import annotations

from collections.abc import Sequence

from pyoxigraph import NamedNode

from ..rdf.terms import sparql
from ..rdf.vocab import THING
from .model import Expr, Prop
from .schema import Row


def class_row(a: Expr, b: Expr) -> Row | None:
    """``a ⊑ b`` (or one direction of ``a ≡ b``); None when it says nothing (a class of itself, owl:Thing)."""
    if a.node == b.node or THING in (a.node, b.node):
        return None
    return a.term, b.term


def disjoint_row(a: Expr, b: Expr) -> Row | None:
    """Disjoint ``a`` and ``b`` (in this order); None when one is owl:Thing (its rules read one class)."""
    if THING in (a.node, b.node):
        return None
    return a.term, b.term


def filler_row(e: Expr, data: bool) -> Row | None:
    """(restriction, property, filler) of a some/all restriction ``e`` on a named object property with a
    class filler other than owl:Thing; None otherwise (a data or inverse property, an unqualified
    filler: those rules have other shapes and stay as the compiler writes them)."""
    if data or e.prop is None or e.prop.inverse or e.datatype is not None or e.filler is None \
            or e.filler.node == THING:
        return None
    return e.term, sparql(e.prop.iri), e.filler.term


def value_row(e: Expr) -> Row | None:
    """(restriction, property, value) of a hasValue restriction on a named property; None otherwise."""
    if e.prop is None or e.prop.inverse or e.value is None:
        return None
    return e.term, sparql(e.prop.iri), sparql(e.value)


def member_row(e: Expr, m: Expr) -> Row | None:
    """(intersection or union, member): a row per member; None for owl:Thing (it says nothing)."""
    if m.node == THING:
        return None
    return e.term, m.term


def chain_row(q: NamedNode, chain: Sequence[Prop]) -> Row | None:
    """(first, second, super-property) of a chain of two named properties; None for another length
    or an inverse link (a row has a fixed number of terms: a longer chain keeps a rule of its own)."""
    if len(chain) != 2 or any(p.inverse for p in chain):
        return None
    return sparql(chain[0].iri), sparql(chain[1].iri), sparql(q)


def typing_row(p: Prop, c: Expr) -> Row | None:
    """A domain or range ``c`` of ``p``; None for owl:Thing or an inverse property expression."""
    if c.node == THING or p.inverse:
        return None
    return sparql(p.iri), c.term


def subproperty_row(p: Prop, q: Prop) -> Row | None:
    """``p ⊑ q`` of two named properties; None otherwise."""
    if p == q or p.inverse or q.inverse:
        return None
    return sparql(p.iri), sparql(q.iri)


__all__ = ["chain_row", "class_row", "disjoint_row", "filler_row", "member_row", "subproperty_row", "typing_row",
           "value_row"]
