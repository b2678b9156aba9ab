"""Anonymous class expressions written alike are compiled once.

Why
---
An ontology edited in Protégé writes a restriction afresh in every axiom that uses it: the
tutorial's pizzas each say ``hasBase some ThinBase`` with a blank node of their own, every topping
``hasSpiciness some Hot``.  Each such node is its own class to the compiler: its own rules
(cls-svf1, the negation rules), and, because restrictions written alike subsume each other, a rule
per ordered pair of them (ext-card-sub).  Eighty copies of ``hasSpiciness some Hot`` gave 6,400
rules; on the 400-class tutorial-style TBox most of the 64,800 compiled rules were such pairs, and
the LOAD's time grew with them.

Here every anonymous expression is replaced by the first one written alike (the same kind, property,
number, filler, members, individuals or value, compared after their own parts were replaced), in the
axioms the compiler reads (:class:`.model.TBox`), before any rule is made.

Same closure
------------
Two expressions written alike have the same instances in every model, and the compiler makes the
same rules for each, differing only in the node; with one node, the rules that read or wrote the
other read and write this one.  What is no longer derived is the membership of the replaced node, a
helper fact no query answers (anonymous classes are not answered; see :mod:`.fold` for the same
reasoning).  An expression an individual is typed with in the data, or a SWRL rule names
(:attr:`.model.TBox.typed_expressions`), is kept as it is, with every part of it: facts and rules
outside the axioms name those nodes.  What the notices say is unchanged: they describe an axiom by
its text, which is the same for expressions written alike.
"""

from __future__ import annotations

from dataclasses import replace

from pyoxigraph import NamedNode

from .model import Expr, TBox


class Alike:
    """Replaces each anonymous expression by the first one written alike (see the module)."""

    def __init__(self, kept: set[NamedNode]) -> None:
        #: nodes never replaced (those named outside the axioms), though they may stand for others
        self.kept = kept
        #: the expression each node became
        self.done: dict[NamedNode, Expr] = {}
        #: the first expression of each shape
        self.first: dict[tuple, Expr] = {}

    def __call__(self, e: Expr) -> Expr:
        """``e``, or the expression written alike that stands for it (its parts replaced alike)."""
        found = self.done.get(e.node)
        if found is not None:
            return found
        if e.is_named:
            return e
        self.done[e.node] = e  # a cyclic structure (set aside by the reader) meets itself unchanged
        members = tuple(self(m) for m in e.members)
        filler = self(e.filler) if e.filler is not None else None
        if members != e.members or filler is not e.filler:
            e = replace(e, members=members, filler=filler)
        shape = (e.kind, e.prop, e.n, e.datatype, e.value, e.individuals, tuple(m.node for m in members),
                 filler.node if filler is not None else None)
        if e.node in self.kept:
            self.first.setdefault(shape, e)
            chosen = e
        else:
            chosen = self.first.setdefault(shape, e)
        self.done[e.node] = chosen
        return chosen


def _parts(e: Expr, found: set[NamedNode]) -> set[NamedNode]:
    """The nodes of ``e`` and of every expression inside it."""
    todo = [e]
    while todo:
        x = todo.pop()
        if x.node in found:
            continue
        found.add(x.node)
        todo += list(x.members) + ([x.filler] if x.filler is not None else [])
    return found


def kept_nodes(tb: TBox) -> set[NamedNode]:
    """The nodes named outside the axioms: the typed expressions' and every part of them."""
    kept: set[NamedNode] = set()
    for e in tb.typed_expressions:
        _parts(e, kept)
    return kept


def merge_alike(tb: TBox) -> TBox:
    """``tb`` with its axioms' anonymous expressions written alike made one (see the module).

    The TBox is changed in place (its axiom lists replaced) and returned."""
    kept = kept_nodes(tb)
    one = Alike(kept)
    for e in tb.typed_expressions:
        one(e)  # a kept expression is the one its copies in the axioms become
    tb.subclass = [(one(a), one(b)) for a, b in tb.subclass]
    tb.equivalent = [(one(a), one(b)) for a, b in tb.equivalent]
    tb.disjoint = [(one(a), one(b)) for a, b in tb.disjoint]
    tb.domain = [(p, one(c)) for p, c in tb.domain]
    tb.range = [(p, one(c)) for p, c in tb.range]
    tb.keys = [(one(c), props) for c, props in tb.keys]
    return tb


__all__ = ["merge_alike"]
