"""Skolemisation: blank nodes as IRIs inside the store, blank nodes again outside.

The rule compiler must name class expressions and SWRL atoms inside SPARQL
text, which is impossible for blank nodes; so every blank node is renamed to an
IRI under :data:`~topostore.rdf.vocab.SKOLEM_PREFIX` on load and back on save.
"""

from __future__ import annotations

import uuid
from collections.abc import Iterable

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


def named(triples: Iterable[Triple]) -> tuple[Triple, ...]:
    """``triples`` with their blank nodes as the skolem IRIs a load gives them: a triple a user adds with a
    blank node names the same node as a loaded document's (and as :func:`unskolemize` gave it back)."""
    return tuple(skolemize(t) if isinstance(t.subject, BlankNode) or isinstance(t.object, BlankNode) else t
                 for t in triples)


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


__all__ = ["SKOLEM_PREFIX", "named", "skolem", "skolemize", "unskolem", "unskolemize", "fresh_skolem"]
