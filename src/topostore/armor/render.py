"""How query answers are written in ``queried_objects`` (spec §2.4).

Default (aRMOR HEAD, what armor_py_api's ``_strip_URI`` expects): entities as
``<full IRI>``, IRIs of the owl/rdf/rdfs/xsd/xml vocabularies abbreviated
(``owl:Thing``), literals as ``"lexical"^^xsd:long``.  Short-name mode (a
service option, the pre-2019 aRMOR behaviour the public tutorials show):
entities by their local name, literals by their lexical form.
"""

from __future__ import annotations

import functools
from collections.abc import Iterable
from dataclasses import dataclass

from pyoxigraph import BlankNode, Literal, NamedNode

from ..rdf.terms import Term
from ..rdf.vocab import NOTHING, OWL, RDF, RDFS, THING, XML, XSD, is_internal
from ..stores.base import unskolem

_ABBREVIATIONS = (
    ("owl:", OWL),
    ("rdf:", RDF),
    ("rdfs:", RDFS),
    ("xsd:", XSD),
    ("xml:", XML),
)


def abbreviate(iri: str) -> str | None:
    """``owl:Thing`` for a well-known vocabulary IRI, ``None`` otherwise."""
    for prefix, namespace in _ABBREVIATIONS:
        if iri.startswith(namespace) and len(iri) > len(namespace):
            return prefix + iri[len(namespace):]
    return None


def local_name(iri: str) -> str:
    """The text after the last ``#`` (or, without ``#``, after the last ``/``)."""
    if "#" in iri:
        return iri.rsplit("#", 1)[1]
    if "/" in iri:
        return iri.rstrip("/").rsplit("/", 1)[-1]
    return iri


def escape_lexical(text: str) -> str:
    """OWL API literal escaping: backslash and double quote."""
    return text.replace("\\", "\\\\").replace('"', '\\"')


def full_entity(iri: str) -> str:
    """``<IRI>`` or the vocabulary abbreviation, as OWL API 5 ``toString()``."""
    return abbreviate(iri) or f"<{iri}>"


def full_literal(lit: Literal) -> str:
    """``"lex"^^xsd:T``, ``"text"@lang`` or ``"lex"^^<datatype IRI>``."""
    body = f'"{escape_lexical(lit.value)}"'
    if lit.language:
        return f"{body}@{lit.language}"
    return f"{body}^^{full_entity(lit.datatype.value)}"


@dataclass(frozen=True)
class Renderer:
    """Renders terms for ``queried_objects``; ``short_names`` selects the short-name mode."""

    short_names: bool = False

    def term(self, term: Term) -> str:
        return _rendered(term, self.short_names)

    def terms(self, terms: list[Term]) -> list[str]:
        """Render a list, dropping duplicates (aRMOR answers are sets)."""
        return list(dict.fromkeys(self.term(t) for t in terms))

    def member(self, term: Term) -> str | None:
        """A class's member as QUERY IND CLASS answers it, None for one it leaves out (:func:`hidden`)."""
        return _answer_text(term, self.short_names)

    def answer(self, terms: Iterable[Term]) -> set[str]:
        """The terms an answer shows (none :func:`hidden`), rendered, as a set: a term's text or its absence
        is cached, since a robot is answered the same few individuals every step."""
        short = self.short_names
        return {text for t in terms if (text := _answer_text(t, short)) is not None}

    def texts(self, terms: Iterable[Term]) -> set[str]:
        """The terms rendered, as a set (an answer is sorted and has no duplicates: no order to keep)."""
        short = self.short_names
        return {_rendered(t, short) for t in terms}


def hidden(term: object) -> bool:
    """Terms never shown in answers: internal IRIs, owl:Thing and owl:Nothing (spec §7 item 6)."""
    return is_internal(term) or term in (THING, NOTHING)


@functools.lru_cache(maxsize=1 << 16)
def _answer_text(term: Term, short_names: bool) -> str | None:
    """:func:`_rendered` of a term an answer shows, None for one it leaves out (:func:`hidden`)."""
    return None if hidden(term) else _rendered(term, short_names)


@functools.lru_cache(maxsize=1 << 17)
def _rendered(term: Term, short_names: bool) -> str:
    """One term as ``queried_objects`` shows it; cached, since a robot asks for the same big answers every step."""
    term = unskolem(term)
    if isinstance(term, NamedNode):
        return local_name(term.value) if short_names else full_entity(term.value)
    if isinstance(term, Literal):
        return term.value if short_names else full_literal(term)
    if isinstance(term, BlankNode):
        return f"_:{term.value}"
    return str(term)


def short_name(term: Term) -> str:
    """Short name used whatever the mode (bottom types, restriction strings)."""
    term = unskolem(term)
    if isinstance(term, NamedNode):
        # datatypes keep their prefix (``xsd:long``), as in aRMOR's restriction strings
        return "xsd:" + term.value[len(XSD):] if term.value.startswith(XSD) else local_name(term.value)
    if isinstance(term, Literal):
        return term.value
    return str(term)


__all__ = ["Renderer", "hidden", "abbreviate", "local_name", "full_entity", "full_literal", "short_name", "escape_lexical"]
