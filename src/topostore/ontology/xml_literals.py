"""rdf:XMLLiteral values in canonical form, so that equal XML compares equal.

Two XML literals are the same value when their XML is the same (attribute order,
``<a/>`` against ``<a></a>``, quoting, unused namespace declarations do not
matter), but the store compares literals by their text.  A document's XML literals
are therefore rewritten on load to their canonical form (Canonical XML 2.0, the
standard library's :func:`xml.etree.ElementTree.canonicalize`, comments kept).

Safe by construction: the literal is parsed as the content of a wrapper element,
where no document type declaration can occur, so no entity is ever defined, let
alone expanded, and nothing is fetched.  A literal that is not well-formed XML
content stays as written and is named (a notice): it is compared by its text.
"""

from __future__ import annotations

from collections.abc import Iterable
from xml.etree.ElementTree import ParseError, canonicalize

from pyoxigraph import Literal, NamedNode, Triple

from ..compile.notices import INCOMPLETE, Notice
from ..compile.profile import UNSUPPORTED
from ..rdf.vocab import RDF

XML_LITERAL = RDF + "XMLLiteral"
_OPEN, _CLOSE = "<topostore-xml-literal>", "</topostore-xml-literal>"


def canonical(text: str) -> str | None:
    """The canonical form of XML content ``text``; None when it is not well-formed."""
    try:
        out = canonicalize(_OPEN + text + _CLOSE, with_comments=True)
    except (ParseError, ValueError):
        return None
    if not (out.startswith(_OPEN) and out.endswith(_CLOSE)):  # pragma: no cover - canonicalize keeps the root
        return None
    return out[len(_OPEN):-len(_CLOSE)]


def canonical_xml_literal(p: NamedNode, o: Literal) -> tuple[Literal, Notice | None]:
    """An rdf:XMLLiteral object of predicate ``p`` in canonical form; the notice naming it when it is not
    well-formed XML (then it is kept as written)."""
    text = canonical(o.value)
    if text is None:
        shown = o.value if len(o.value) <= 40 else o.value[:40] + "…"
        return o, Notice(INCOMPLETE, f"{p.value.rsplit('#', 1)[-1]} {shown!r}",
                         "an rdf:XMLLiteral that is not well-formed XML: compared as written", UNSUPPORTED)
    return (o if text == o.value else Literal(text, datatype=o.datatype)), None


def canonical_xml_literals(triples: Iterable[Triple]) -> tuple[list[Triple], list[Notice]]:
    """The triples with every rdf:XMLLiteral object in canonical form, and a notice per
    literal that is not well-formed XML (kept as written)."""
    out: list[Triple] = []
    notices: list[Notice] = []
    for t in triples:
        o = t.object
        if isinstance(o, Literal) and o.datatype.value == XML_LITERAL:
            p = t.predicate
            written, notice = canonical_xml_literal(p, o)
            if notice is not None:
                notices.append(notice)
            elif written is not o:
                t = Triple(t.subject, p, written)
        out.append(t)
    return out, notices


__all__ = ["XML_LITERAL", "canonical", "canonical_xml_literal", "canonical_xml_literals"]
