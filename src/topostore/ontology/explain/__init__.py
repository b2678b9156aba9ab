"""Why does a triple hold?  One derivation, as a tree of rules and premises down to asserted facts.

The search runs the compiled rules backwards (:mod:`.search`, where the choice of derivation is
described), the tree it returns is :class:`~.tree.Explanation`, and :mod:`.names` reads a triple
as users write it.  :func:`explain` is what :meth:`Ontology.explain` runs.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from ...rdf.terms import Term
from .names import parse_triple_text, resolve_triple
from .search import Explainer, constant, unify
from .tree import Explanation

if TYPE_CHECKING:  # pragma: no cover
    from ..facade import Ontology


def explain(onto: Ontology, s: str | Term, p: str | Term, o: object) -> Explanation:
    """Why ``s p o`` holds in ``onto`` as of its last REASON (reasons first if it never did)."""
    if onto.report is None:
        onto.reason()
    t = resolve_triple(onto, s, p, o)
    return Explainer(onto.store, onto.rules.all_rules, onto.short).explain(t)


__all__ = ["Explanation", "Explainer", "explain", "parse_triple_text", "resolve_triple", "unify", "constant"]
