"""RDF syntaxes: which format a file is in, parsing into skolemised triples, writing.

Parsing is pyoxigraph's; this module adds what users need around it: the format
from a name or an extension, ``file:line: cause`` errors (with the line found by
an XML parser when Oxigraph gives none), refusal of XML entity expansion, progress
reports for big files, and blank nodes skolemised (:mod:`topostore.rdf.skolem`).
"""

from __future__ import annotations

import os
from collections.abc import Callable, Iterable, Iterator
from pathlib import Path

import pyoxigraph as ox
from pyoxigraph import BlankNode, RdfFormat, Triple

from ..errors import LoadError
from .owl_syntaxes import refuse_owl_syntaxes
from .safeio import check_xml_entities
from .skolem import skolem

#: How often (in triples) parsing reports progress.
PROGRESS_EVERY = 5000

_FORMATS = {
    ".owl": RdfFormat.RDF_XML,
    ".rdf": RdfFormat.RDF_XML,
    ".xml": RdfFormat.RDF_XML,
    ".ttl": RdfFormat.TURTLE,
    ".turtle": RdfFormat.TURTLE,
    ".nt": RdfFormat.N_TRIPLES,
    ".ntriples": RdfFormat.N_TRIPLES,
    ".n3": RdfFormat.N3,
    ".jsonld": RdfFormat.JSON_LD,
}
FORMAT_NAMES = {
    "rdfxml": RdfFormat.RDF_XML,
    "rdf/xml": RdfFormat.RDF_XML,
    "xml": RdfFormat.RDF_XML,
    "owl": RdfFormat.RDF_XML,
    "turtle": RdfFormat.TURTLE,
    "ttl": RdfFormat.TURTLE,
    "ntriples": RdfFormat.N_TRIPLES,
    "nt": RdfFormat.N_TRIPLES,
    "n-triples": RdfFormat.N_TRIPLES,
}


def guess_format(path: str | os.PathLike[str], explicit: str | RdfFormat | None = None) -> RdfFormat:
    """The RDF format of a file, from an explicit name or its extension (RDF/XML by default)."""
    if isinstance(explicit, RdfFormat):
        return explicit
    if explicit:
        try:
            return FORMAT_NAMES[explicit.lower()]
        except KeyError:
            raise LoadError(f"unknown RDF format {explicit!r}; use one of {', '.join(FORMAT_NAMES)}") from None
    return _FORMATS.get(Path(path).suffix.lower(), RdfFormat.RDF_XML)


def _syntax_error_message(source: str, exc: SyntaxError, data: bytes, fmt: RdfFormat) -> str:
    """'file:line: cause', finding the line with rdflib when Oxigraph gives none (RDF/XML)."""
    cause = str(exc.msg if hasattr(exc, "msg") and exc.msg else exc)
    line = exc.lineno
    if line is None and fmt == RdfFormat.RDF_XML:
        line = _xml_error_line(data)
    where = f"{source}:{line}" if line else f"{source}:?"
    return f"{where}: not valid {fmt.name}: {cause}"


def _xml_error_line(data: bytes) -> int | None:
    import xml.sax

    class _Handler(xml.sax.handler.ContentHandler):
        pass

    try:
        xml.sax.parseString(data, _Handler())
    except xml.sax.SAXParseException as exc:
        return exc.getLineNumber()
    except (xml.sax.SAXException, ValueError):  # pragma: no cover - other failures locate nothing
        return None
    return None


def parse_triples(
    data: bytes | str, fmt: RdfFormat, base_iri: str | None = None, source: str = "<input>",
    progress: Callable[[int], None] | None = None,
) -> list[Triple]:
    """A document's triples, skolemised; ``progress(n)`` is called every ``PROGRESS_EVERY`` triples parsed."""
    return _skolemised(parsed_quads(data, fmt, base_iri, source), progress)


def parsed_quads(data: bytes | str, fmt: RdfFormat, base_iri: str | None = None,
                 source: str = "<input>") -> Iterator[ox.Quad]:
    """The parser's quads as it makes them (blank nodes renamed apart from every other document's, not yet
    skolemised): RDF/XML refused before a byte is parsed when it declares entities, a syntax error raised
    as :class:`LoadError` ``file:line: cause`` where the parser stops (so a caller writing the quads as they
    come takes them out again)."""
    data = document_bytes(data)
    quads = parser(data, fmt, base_iri, source)
    try:
        yield from quads
    except (SyntaxError, ValueError) as exc:
        raise parse_error(exc, data, fmt, source) from exc


def document_bytes(data: bytes | str) -> bytes:
    """A document as the parser reads it (text as UTF-8, lone surrogates kept for the parser to refuse)."""
    return data.encode("utf-8", errors="surrogatepass") if isinstance(data, str) else data


def parser(data: bytes, fmt: RdfFormat, base_iri: str | None, source: str) -> Iterator[ox.Quad]:
    """pyoxigraph's own iterator over a document's quads (blank nodes renamed apart from every other
    document's), for a caller that hands it to pyoxigraph whole (no Python frame per quad); RDF/XML
    declaring entities refused first.  What it raises midway is turned into the load's error by
    :func:`parse_error`.  A document in one of OWL's own syntaxes is refused by name first."""
    refuse_owl_syntaxes(data, source)
    if fmt == RdfFormat.RDF_XML:
        check_xml_entities(data, source)
    try:
        return ox.parse(data, format=fmt, base_iri=base_iri, rename_blank_nodes=True)
    except (SyntaxError, ValueError) as exc:
        raise parse_error(exc, data, fmt, source) from exc


def parse_error(exc: SyntaxError | ValueError, data: bytes, fmt: RdfFormat, source: str) -> LoadError:
    """What parsing ``data`` raised, as the load's error: ``file:line: cause`` for a syntax error."""
    if isinstance(exc, SyntaxError):
        return LoadError(_syntax_error_message(source, exc, data, fmt))
    return LoadError(f"{source}: {exc}")


def _skolemised(quads: Iterable[ox.Quad], progress: Callable[[int], None] | None) -> list[Triple]:
    """Each quad as its triple, made at once (a big file is never held twice), blank nodes as skolem IRIs.

    A quad's triple is taken whole (one conversion, not three) and rebuilt only when a blank node
    is in it: the term conversions are most of a big load's per-triple cost."""
    triples: list[Triple] = []
    append = triples.append
    blank = BlankNode
    for quad in quads:
        t = quad.triple
        s, o = t.subject, t.object
        if type(s) is blank or type(o) is blank:
            t = Triple(skolem(s), t.predicate, skolem(o))
        append(t)
        if progress is not None and len(triples) % PROGRESS_EVERY == 0:
            progress(len(triples))
    return triples


def serialize(triples: Iterable[Triple], fmt: RdfFormat, prefixes: dict[str, str] | None = None) -> bytes:
    return ox.serialize(list(triples), format=fmt, prefixes=prefixes or None)


__all__ = ["FORMAT_NAMES", "PROGRESS_EVERY", "document_bytes", "guess_format", "parse_error", "parse_triples",
           "parsed_quads", "parser", "serialize"]
