"""Non-simple properties where OWL 2 DL wants simple ones, read as Pellet 2.3.1 reads them.

OWL 2 DL (Structural Specification §11.2) allows only *simple* object properties as functional,
inverse-functional, irreflexive, asymmetric, disjoint properties and in cardinality and hasSelf
restrictions.  A property is non-simple when it is transitive, the super-property of a chain, or a
super-property of a non-simple one (inverses included).  An ontology using a non-simple property there is
outside OWL 2 DL: the Direct Semantics say nothing of it, and a rule reasoner applying everything (the
RDF-Based Semantics) finds it inconsistent or merges individuals where Pellet does not.

Pellet keeps such a property simple and ignores what makes it non-simple: its OWL API loader marks the
named property of every simple position (an inverse counts as its property), the marking goes down to every
sub-property (through inverses, equivalences and ``owl:inverseOf`` alike), and each marked property loses
its transitivity and the chains it is the super-property of (the warning ``Ignoring transitivity and/or
complex subproperty axioms for p``).  A super-property of a marked property keeps its axioms.  This module
computes the same set and drops the same axioms from the TBox before it is compiled, with a notice naming
each property, the axioms left out and why; a change of the schema recompiles, so an axiom added at run
time takes the decision a fresh load takes.
"""

from __future__ import annotations

from collections import defaultdict

from pyoxigraph import NamedNode

from .model import Expr, Prop, TBox
from .notices import NON_SIMPLE

#: the characteristics that want a simple property (OWL 2 Structural Specification §11.2), by their text
SIMPLE_CHARACTERISTICS = {
    "FunctionalProperty": "functional",
    "InverseFunctionalProperty": "inverse functional",
    "IrreflexiveProperty": "irreflexive",
    "AsymmetricProperty": "asymmetric",
}

#: the restrictions that want a simple property, by their text
SIMPLE_RESTRICTIONS = {"min": "a minimum cardinality", "max": "a maximum cardinality",
                       "exact": "an exact cardinality", "self": "a hasSelf restriction"}

#: a property expression as a node of the hierarchy: the named property and whether it is its inverse
Node = tuple[NamedNode, bool]


def simple_uses(tb: TBox, expressions: list[Expr]) -> dict[NamedNode, list[str]]:
    """The named object properties used where a simple one is wanted, each with the uses (as text)."""
    uses: dict[NamedNode, list[str]] = defaultdict(list)
    for name, text in SIMPLE_CHARACTERISTICS.items():
        for p in sorted(tb.characteristics.get(name, ()), key=str):
            if p not in tb.data_properties:
                uses[p].append(text)
    for a, b in tb.disjoint_props:
        for p, other in ((a, b), (b, a)):
            if isinstance(p, NamedNode) and p not in tb.data_properties:
                uses[p].append(f"disjoint with {_short(other)}")
    for e in expressions:
        if e.kind in SIMPLE_RESTRICTIONS and e.prop is not None and not e.is_data and not e.prop.data \
                and e.prop.iri not in tb.data_properties:
            uses[e.prop.iri].append(f"in {SIMPLE_RESTRICTIONS[e.kind]}")
    return {p: list(dict.fromkeys(texts)) for p, texts in uses.items()}


def _sub_properties(tb: TBox) -> dict[Node, set[Node]]:
    """Each property expression's direct sub-properties, with the inverse of every axiom too."""
    subs: dict[Node, set[Node]] = defaultdict(set)

    def below(sub: Node, sup: Node) -> None:
        subs[sup].add(sub)
        subs[(sup[0], not sup[1])].add((sub[0], not sub[1]))

    for p, q in tb.subproperty:
        below((p.iri, p.inverse), (q.iri, q.inverse))
    for p, q in tb.inverse:
        if isinstance(q, NamedNode):
            below((p, False), (q, True))
            below((q, True), (p, False))
    return subs


def kept_simple(tb: TBox, expressions: list[Expr]) -> dict[NamedNode, list[str]]:
    """The named properties Pellet keeps simple, each with why: the simple uses of the property or of the
    property it is a sub-property of."""
    uses = simple_uses(tb, expressions)
    subs = _sub_properties(tb)
    kept: dict[NamedNode, list[str]] = {}
    for used in sorted(uses, key=str):
        what = " and ".join(uses[used])
        seen: set[Node] = set()
        todo: list[Node] = [(used, False)]
        while todo:
            node = todo.pop()
            if node in seen:
                continue
            seen.add(node)
            name, inverse = node
            kept.setdefault(name, []).append(
                f"{_short(used)} is {what}" if node == (used, False) else
                f"{'the inverse of ' if inverse else ''}{_short(name)} is a sub-property of {_short(used)}, which is {what}")
            todo.extend(subs.get(node, ()))
    return kept


def ignore_non_simple(tb: TBox, expressions: list[Expr]) -> None:
    """Drop the transitivity and the chains of the properties kept simple from ``tb``, each property's with a
    notice in ``tb.partial``."""
    kept = kept_simple(tb, expressions)
    transitive = tb.characteristics.get("TransitiveProperty", set())
    dropped: dict[NamedNode, list[str]] = defaultdict(list)
    for p in sorted(transitive & kept.keys(), key=str):
        transitive.discard(p)
        dropped[p].append(f"{_short(p)} is transitive")
    chains = []
    for q, chain in tb.chains:
        if q in kept:
            dropped[q].append(f"{_short(q)} chain of {' o '.join(_text(p) for p in chain)}")
        else:
            chains.append((q, chain))
    tb.chains = chains
    for p in sorted(dropped, key=str):
        why = "; ".join(dict.fromkeys(kept[p]))
        tb.partial.append((", ".join(dropped[p]), NON_SIMPLE,
                           f"ignored, as Pellet ignores it: {why}; OWL 2 DL allows only a simple property there, one "
                           "neither transitive nor the super-property of a chain, nor above such a property"))


def _text(p: Prop) -> str:
    return f"inverse {_short(p.iri)}" if p.inverse else _short(p.iri)


def _short(t: object) -> str:
    v = t.value if hasattr(t, "value") else str(t)
    return v.rsplit("#", 1)[-1] if "#" in v else v.rsplit("/", 1)[-1]


__all__ = ["ignore_non_simple", "kept_simple", "simple_uses"]
