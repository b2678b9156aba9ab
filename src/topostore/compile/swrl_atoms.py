"""A SWRL rule's atoms as the RDF graph writes them, and the SPARQL names of their arguments.

Read as written, whatever they hold: an atom of no known kind, or one missing its predicate or arguments, is
read too, so that the compiler (:mod:`.swrl`) names what is wrong with it where it sets the rule aside.
"""

from __future__ import annotations

import re
from dataclasses import dataclass

from pyoxigraph import NamedNode

from ..rdf.terms import Term, sparql
from ..rdf.vocab import SWRL, TYPE, swrl
from ..stores.base import Store


@dataclass(frozen=True)
class SwrlAtom:
    kind: str  # ClassAtom, IndividualPropertyAtom, ... ("?" when the atom has no SWRL type)
    predicate: Term | None
    args: tuple[Term, ...]
    node: Term

    def describe(self, rule_name: str) -> str:
        def short(t: Term | None) -> str:
            if t is None:
                return ""
            v = getattr(t, "value", str(t))
            return v.rsplit("#", 1)[-1].rsplit("/", 1)[-1]

        args = ", ".join(short(a) for a in self.args)
        return f"{self.kind}({short(self.predicate)}{', ' if self.predicate else ''}{args})"


def read_atoms(store: Store, graph: NamedNode, head: Term | None) -> list[SwrlAtom]:
    """The atoms of the atom list ``head`` (a rule's body or head; none when it is missing)."""
    if head is None:
        return []

    def one(s: Term, p: NamedNode) -> Term | None:
        v = store.objects(s, p, graph)
        return v[0] if v else None

    out = []
    for node in store.list_items(head, graph):
        kinds = [t.value[len(SWRL):] for t in store.objects(node, TYPE, graph) if t.value.startswith(SWRL)]
        kind = kinds[0] if kinds else "?"
        pred = (one(node, swrl("classPredicate")) or one(node, swrl("propertyPredicate"))
                or one(node, swrl("dataRange")) or one(node, swrl("builtin")))
        if kind == "BuiltinAtom":
            lst = one(node, swrl("arguments"))
            args = tuple(store.list_items(lst, graph)) if lst is not None else ()
        else:
            args = tuple(a for a in (one(node, swrl("argument1")), one(node, swrl("argument2"))) if a is not None)
        out.append(SwrlAtom(kind, pred, args, node))
    return out


class Names:
    """SPARQL text of a rule's arguments: ``?local`` for each SWRL variable (unique per rule), terms rendered."""

    def __init__(self, variables: set[Term]) -> None:
        self.variables = variables
        self.names: dict[Term, str] = {}

    def __call__(self, t: Term) -> str:
        if t not in self.variables:
            return sparql(t)
        if t not in self.names:
            local = re.sub(r"[^A-Za-z0-9_]", "_", t.value.rsplit("#", 1)[-1].rsplit("/", 1)[-1]) or "v"
            candidate = f"?{local}"
            while candidate in self.names.values():
                candidate += "_"
            self.names[t] = candidate
        return self.names[t]


__all__ = ["Names", "SwrlAtom", "read_atoms"]
