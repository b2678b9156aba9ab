"""Triples as users write them (``R1``, ``rdf:type``/``a``, ``URGENT``, ``1665579710``), read against an ontology."""

from __future__ import annotations

import shlex
from typing import TYPE_CHECKING

from pyoxigraph import Literal, NamedNode, Triple

from ...errors import InvalidNameError
from ...rdf.terms import Term, value_key
from ...rdf.vocab import ASSERTED, AUX, ENTAILED, INFERRED, TYPE
from .search import SHORT_PREFIXES

if TYPE_CHECKING:  # pragma: no cover
    from ..facade import Ontology


def resolve_triple(onto: Ontology, s: str | Term, p: str | Term, o: object) -> Triple:
    """A triple from names as users write them (``R1``, ``rdf:type``/``a``, ``URGENT``, ``1665579710``).

    A value of a data property is matched by data value against the stored
    facts, so ``7`` finds a stored ``"7"^^xsd:long``.
    """
    subject = _name(onto, s)
    predicate = TYPE if p in ("a", "rdf:type") else _name(onto, p)
    if isinstance(o, (Literal, NamedNode)):
        obj: Term = o
    elif isinstance(o, str) and not _looks_like_value(o) and predicate not in onto.rules.data_properties:
        obj = _name(onto, o)
    else:
        obj = onto.value(_strip_quotes(o)) if isinstance(o, str) else onto.value(o)
        if isinstance(o, str) and _strip_quotes(o) == o and o.lstrip("+-").isdigit():
            obj = onto.value(int(o))
    if isinstance(obj, Literal):
        key = value_key(obj)
        for g in (ASSERTED, INFERRED, ENTAILED, AUX):
            for t in onto.store.triples(subject, predicate, None, g):
                if isinstance(t.object, Literal) and value_key(t.object) == key:
                    return t
    return Triple(subject, predicate, obj)


def _looks_like_value(text: str) -> bool:
    return text.startswith('"') or text.lstrip("+-").replace(".", "", 1).isdigit() or text in ("true", "false")


def _strip_quotes(text: str) -> str:
    return text[1:-1] if len(text) >= 2 and text[0] == text[-1] == '"' else text


def _name(onto: Ontology, name: str | Term) -> NamedNode:
    if isinstance(name, NamedNode):
        return name
    if not isinstance(name, str):
        raise InvalidNameError(f"expected a name, got {name!r}")
    if ":" in name and not name.startswith("<"):
        prefix, local = name.split(":", 1)
        for ns, known in SHORT_PREFIXES.items():
            if known == prefix + ":":
                return NamedNode(ns + local)
    return onto.iri(name)


def parse_triple_text(onto: Ontology, text: str) -> Triple:
    """``"R1 rdf:type URGENT"`` (three whitespace-separated parts; a quoted value may hold spaces)."""
    try:
        parts = shlex.split(text, posix=False)
    except ValueError as exc:
        raise InvalidNameError(f"cannot read {text!r} as 'SUBJECT PREDICATE OBJECT': {exc}") from None
    if len(parts) != 3:
        raise InvalidNameError(f"expected 'SUBJECT PREDICATE OBJECT' (e.g. \"R1 rdf:type URGENT\"), got {len(parts)} part(s) in {text!r}")
    return resolve_triple(onto, *parts)


__all__ = ["resolve_triple", "parse_triple_text"]
