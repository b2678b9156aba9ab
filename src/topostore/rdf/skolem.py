"""Skolemisation: blank nodes as IRIs inside the store, blank nodes again outside.

The rule compiler must name class expressions and SWRL atoms inside SPARQL
text, which is impossible for blank nodes; so every blank node is renamed to an
IRI under :data:`~topostore.rdf.vocab.SKOLEM_PREFIX` on load and back on save.
"""

from __future__ import annotations

import uuid

from pyoxigraph import BlankNode, NamedNode, Triple

from .terms import Term
from .vocab import SKOLEM_PREFIX, is_skolem


def skolem(term: Term) -> Term:
    """A blank node as its skolem IRI; any other term unchanged."""
    if isinstance(term, BlankNode):
        return NamedNode(SKOLEM_PREFIX + term.value)
    return term


def skolemize(t: Triple) -> Triple:
    return Triple(skolem(t.subject), t.predicate, skolem(t.object))


def unskolem(term: Term) -> Term:
    """A skolem IRI as the blank node it stands for; any other term unchanged."""
    if is_skolem(term):
        return BlankNode(term.value[len(SKOLEM_PREFIX):])
    return term


def unskolemize(t: Triple) -> Triple:
    return Triple(unskolem(t.subject), t.predicate, unskolem(t.object))


def fresh_skolem() -> NamedNode:
    """A new skolem IRI, standing for a fresh blank node (e.g. a new AllDifferent axiom)."""
    return NamedNode(SKOLEM_PREFIX + "n" + uuid.uuid4().hex)


__all__ = ["SKOLEM_PREFIX", "skolem", "skolemize", "unskolem", "unskolemize", "fresh_skolem"]
