"""One fact of a change, with every form and key the layers of a change need, made once.

A manipulation's triple passes through the command (which compares data values), the store (which
keys a pending write by value, so ``1`` and ``"01"^^xsd:int`` are one write), the change ledger (which
keys the net change by the stored form, so an addition and a removal cancel out, and keeps the
written form, so an undo restores what the user wrote) and the literal forms (keyed by value).  Each
of those used to take the triple and compute the keys it needed again: the value key of a literal, the
quad to write, the stored form, the written form of a removed literal.  pyoxigraph terms cache no hash
and a literal argument costs pyoxigraph several attempts to convert, so every one of those was paid
again at every layer.  A :class:`Fact` is made once per triple of a change and read by every layer.
"""

from __future__ import annotations

from pyoxigraph import Literal, NamedNode, Quad, Triple

from ..rdf.terms import quad, value_key


class Fact:
    """A triple of one graph, its forms and its keys.

    ``triple``: as the caller named it (for a fact read from the store, as the store holds it);
    ``quad``: the write of it in ``graph``; ``key``: what identifies it in the store (the quad, or with a
    literal object its subject, predicate, value key and graph, see ``Store._key``); ``value``: the value
    key of the object (None for an IRI or a blank node); ``stored``: the triple as the store holds it once
    added (what the change ledger keys by; None until the ledger asks); ``written``: the triple as the
    user wrote it, where an undo must restore it (None until asked for a removal, see
    ``Store.written_fact``).
    """

    __slots__ = ("triple", "quad", "key", "value", "stored", "written")

    def __init__(self, t: Triple, q: Quad, key: object, value: tuple | None, stored: Triple | None,
                 written: Triple | None) -> None:
        self.triple = t
        self.quad = q
        self.key = key
        self.value = value
        self.stored = stored
        self.written = written

    def __repr__(self) -> str:
        return f"Fact({self.triple})"


def fact_of(t: Triple, graph: NamedNode, written: bool = True) -> Fact:
    """The fact of a triple given by a caller (``written``: its written form is itself; else it is asked
    of the literal forms when it is removed).  Its stored form is asked when the ledger records it."""
    s, p, o = t.subject, t.predicate, t.object
    if not isinstance(o, Literal):
        q = Quad(s, p, o, graph)
        return Fact(t, q, q, None, t, t)
    value = value_key(o)
    return Fact(t, quad(s, p, o, graph), (s, p, value, graph), value, None, t if written else None)


def fact_written(q: Quad) -> Fact:
    """:func:`fact_of` of a quad the caller made for the write: its triple is taken from it (pyoxigraph
    makes it from the quad's terms, where a ``Triple`` given a literal costs ≈ 1.7 µs to make)."""
    t = q.triple
    o = t.object
    if not isinstance(o, Literal):
        return Fact(t, q, q, None, t, t)
    value = value_key(o)
    return Fact(t, q, (t.subject, t.predicate, value, q.graph_name), value, None, t)


def fact_read(q: Quad, canonical: bool) -> Fact:
    """The fact of a quad read from a store (``canonical``: the store holds literals as Oxigraph stores
    them, so the read triple is its own stored form); its written form is asked when it is removed."""
    t = q.triple
    o = t.object
    if not isinstance(o, Literal):
        return Fact(t, q, q, None, t, t)
    value = value_key(o)
    return Fact(t, q, (t.subject, t.predicate, value, q.graph_name), value, t if canonical else None, None)


__all__ = ["Fact", "fact_of", "fact_read", "fact_written"]
