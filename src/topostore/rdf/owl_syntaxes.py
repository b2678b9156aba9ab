"""OWL's own syntaxes (OWL/XML, Manchester, Functional), recognised so a load refuses them by name.

Protégé and the OWL API read and write these besides RDF; topostore reads RDF only.  Given to an RDF
parser, such a document fails with a text about RDF ("XML namespaces are required in RDF/XML") that
hides the cause, so the start of every document is looked at first: one in an OWL syntax is refused
with what it is and what to save it as, before a byte is parsed.
"""

from __future__ import annotations

import re

from ..errors import LoadError
from .vocab import OWL

#: the syntaxes a document may be read in, as a refusal names them
READABLE = "RDF/XML (Protégé's default), Turtle, N-Triples, N3 or JSON-LD"
#: how much of a document's start is looked at: the root element or the first statement is there
_HEAD = 8192
_XML_PREAMBLE = re.compile(rb"\s*(?:<\?.*?\?>|<!--.*?-->|<!DOCTYPE[^\[>]*(?:\[.*?\])?\s*>|\s+)*", re.S)
_ROOT = re.compile(rb"<(?:[\w.-]+:)?Ontology\b[^>]*>", re.S)
_RDF_NODE_ATTRIBUTE = re.compile(rb"\s[\w.-]+:(?:about|ID|nodeID)\s*=")
#: an element only OWL/XML has (an RDF/XML document whose root is an ``owl:Ontology`` node has none)
_OWL_XML_AXIOM = re.compile(rb"<(?:[\w.-]+:)?(?:Prefix|Import|Declaration|SubClassOf|EquivalentClasses|ClassAssertion|"
                            rb"ObjectPropertyAssertion|DataPropertyAssertion|AnnotationAssertion|DLSafeRule)\b")
_FIRST_LINE = re.compile(rb"\A(?:\s*(?:#[^\n]*)?\n)*\s*(\S[^\n]*)")
_MANCHESTER = re.compile(rb"(?:Prefix|Ontology|Import|Class|ObjectProperty|DataProperty|Individual):(?:\s|$)")
_FUNCTIONAL = re.compile(rb"(?:Prefix|Ontology|Import)\s*\(")


def owl_syntax(data: bytes) -> str | None:
    """The name of the OWL syntax ``data`` starts in (``"OWL/XML"``, ``"Manchester OWL"``, ``"OWL Functional"``), or
    None for anything else (an RDF document, or one no parser reads, which the RDF parser then refuses)."""
    head = data[:_HEAD].lstrip(b"\xef\xbb\xbf")
    root = _ROOT.match(head, _XML_PREAMBLE.match(head).end())  # type: ignore[union-attr]
    if (root and OWL.encode() in root.group() and not _RDF_NODE_ATTRIBUTE.search(root.group())
            and (b"ontologyIRI" in root.group() or _OWL_XML_AXIOM.search(head, root.end()))):
        return "OWL/XML"
    first = _FIRST_LINE.match(head)
    if first is None:
        return None
    if _MANCHESTER.match(first.group(1)):
        return "Manchester OWL"
    if _FUNCTIONAL.match(first.group(1)):
        return "OWL Functional"
    return None


def refuse_owl_syntaxes(data: bytes, source: str) -> None:
    """LoadError naming the OWL syntax ``data`` is in, and the syntaxes topostore reads; nothing if it is in none."""
    syntax = owl_syntax(data)
    if syntax is not None:
        raise LoadError(f"{source}: the document is in the {syntax} syntax, which topostore does not read; "
                        f"save it as {READABLE} (in Protégé: File > Save as... > RDF/XML Syntax)")


__all__ = ["READABLE", "owl_syntax", "refuse_owl_syntaxes"]
