"""SPARQL results in the formats clients ask for, chosen by content negotiation.

The format is negotiated with python-mimeparse (q-values, wildcards,
specificity); ``?format=`` (as SPARQLWrapper, Virtuoso and Fuseki clients
send it) is honoured when it names an offered format that the Accept header
also allows, so a client sending both is never refused for the pair.

Rows are first written as SPARQL JSON with :mod:`json` (where every term is an
explicit object, so nothing needs escaping by hand), and converted to XML, CSV
and TSV by pyoxigraph's own result serializers.  Graph results (CONSTRUCT,
DESCRIBE) are serialized by pyoxigraph as Turtle, N-Triples, RDF/XML or JSON-LD.
Going through pyoxigraph means no hand-written escaping for any format.
"""

from __future__ import annotations

import json
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import mimeparse
import pyoxigraph as ox
from pyoxigraph import BlankNode, Literal, NamedNode, QueryResultsFormat, RdfFormat, Triple

from ..errors import TopostoreError
from ..rdf.vocab import RDF, XSD

_XSD_STRING = XSD + "string"
_RDF_LANG_STRING = RDF + "langString"


@dataclass(frozen=True)
class ResultFormat:
    """One output format: short name (for ``?format=``), media type, pyoxigraph format."""

    name: str
    media_type: str
    ox_format: QueryResultsFormat | RdfFormat
    aliases: tuple[str, ...] = ()

    @property
    def content_type(self) -> str:
        text = self.media_type.startswith("text/") or self.media_type.endswith(("+json", "+xml", "n-triples"))
        return f"{self.media_type}; charset=utf-8" if text else self.media_type


#: Formats for SELECT and ASK results; the first is the default.
SOLUTION_FORMATS: tuple[ResultFormat, ...] = (
    ResultFormat("json", "application/sparql-results+json", QueryResultsFormat.JSON, ("application/json",)),
    ResultFormat("xml", "application/sparql-results+xml", QueryResultsFormat.XML, ("application/xml", "text/xml")),
    ResultFormat("csv", "text/csv", QueryResultsFormat.CSV),
    ResultFormat("tsv", "text/tab-separated-values", QueryResultsFormat.TSV, ("tab-separated-values",)),
)

#: Formats for CONSTRUCT and DESCRIBE results; the first is the default.
GRAPH_FORMATS: tuple[ResultFormat, ...] = (
    # Turtle is N3 without N3's extensions: what N3 clients (SPARQLWrapper's N3) ask for
    ResultFormat("turtle", "text/turtle", RdfFormat.TURTLE,
                 ("application/x-turtle", "application/turtle", "ttl", "n3", "text/n3", "text/rdf+n3", "application/n3")),
    ResultFormat("ntriples", "application/n-triples", RdfFormat.N_TRIPLES, ("text/plain", "nt", "n-triples")),
    ResultFormat("rdfxml", "application/rdf+xml", RdfFormat.RDF_XML, ("application/xml", "text/xml", "xml", "rdf+xml")),
    ResultFormat("jsonld", "application/ld+json", RdfFormat.JSON_LD, ("json-ld", "json", "application/x-json+ld")),
)


class NotAcceptable(TopostoreError):
    """No format the client accepts can carry this kind of result (HTTP 406)."""


def _named(offered: Sequence[ResultFormat], name: str) -> ResultFormat | None:
    key = name.strip().lower()
    return next((f for f in offered if key in (f.name, f.media_type, *f.aliases)), None)


def _media_types(offered: Sequence[ResultFormat]) -> list[str]:
    """Every media type (and alias that is one) of ``offered``, least preferred first (mimeparse's tie order)."""
    types = [m for f in offered for m in (f.media_type, *f.aliases) if "/" in m]
    return list(reversed(types))


def _quality(media: str, accept: str) -> float:
    try:
        return mimeparse.quality(media, accept)
    except (mimeparse.MimeTypeParseException, ValueError):
        return 0.0


def choose_format(accept: str | None, graph: bool, explicit: str | None = None) -> ResultFormat:
    """The format for a result: ``explicit`` (``?format=``) if it fits the Accept header, else the best Accept match.

    ``graph`` selects the CONSTRUCT/DESCRIBE formats.  Raises
    :class:`NotAcceptable` naming the formats on offer.
    """
    offered = GRAPH_FORMATS if graph else SOLUTION_FORMATS
    header = (accept or "").strip() or "*/*"
    named = _named(offered, explicit) if explicit else None
    if named is not None and any(_quality(m, header) > 0 for m in (named.media_type, *named.aliases) if "/" in m):
        return named
    if explicit and named is None and header in ("*/*", "*"):
        raise NotAcceptable(f"format {explicit!r} cannot carry this result; use one of "
                            f"{', '.join(f.name for f in offered)}")
    try:
        best = mimeparse.best_match(_media_types(offered), "*/*" if header == "*" else header)
    except (mimeparse.MimeTypeParseException, ValueError):
        raise NotAcceptable(f"cannot read the Accept header {accept!r}") from None
    found = next((f for f in offered if best and best in (f.media_type, *f.aliases)), None)
    if found is None:
        raise NotAcceptable(f"none of the accepted media types ({accept}) can carry this result; this endpoint offers "
                            f"{', '.join(f.media_type for f in offered)}")
    return found


# --------------------------------------------------------------------------- SELECT / ASK

def term_json(term: object, spelled: Callable[[str], str] = str) -> dict[str, object]:
    """A term as an object of the SPARQL 1.1 JSON results format; ``spelled`` gives a language tag's
    spelling (the store lowers tags: :class:`~topostore.stores.language_tags.LanguageTags`)."""
    if isinstance(term, NamedNode):
        return {"type": "uri", "value": term.value}
    if isinstance(term, BlankNode):
        return {"type": "bnode", "value": term.value}
    if isinstance(term, Literal):
        out: dict[str, object] = {"type": "literal", "value": term.value}
        if term.language:
            out["xml:lang"] = spelled(term.language)
        elif term.datatype.value not in (_XSD_STRING, _RDF_LANG_STRING):
            out["datatype"] = term.datatype.value
        return out
    if isinstance(term, Triple):
        return {"type": "triple", "value": {"subject": term_json(term.subject, spelled),
                                            "predicate": term_json(term.predicate, spelled),
                                            "object": term_json(term.object, spelled)}}
    raise TypeError(f"not an RDF term: {term!r}")


def solutions_json(variables: Sequence[str], rows: Sequence[Sequence[object | None]],
                   spelled: Callable[[str], str] = str) -> bytes:
    """SPARQL JSON for a SELECT result; unbound values are left out of their row."""
    bindings = [{v: term_json(t, spelled) for v, t in zip(variables, row) if t is not None} for row in rows]
    return json.dumps({"head": {"vars": list(variables)}, "results": {"bindings": bindings}},
                      ensure_ascii=False).encode("utf-8")


def boolean_json(value: bool) -> bytes:
    return json.dumps({"head": {}, "boolean": bool(value)}).encode("utf-8")


def render_table(json_results: bytes, fmt: ResultFormat) -> bytes:
    """SPARQL JSON results re-serialized in ``fmt`` (identity for JSON)."""
    if fmt.ox_format == QueryResultsFormat.JSON:
        return json_results
    parsed = ox.parse_query_results(json_results, format=QueryResultsFormat.JSON)
    return parsed.serialize(format=fmt.ox_format)


def render_graph(triples: Sequence[Triple], fmt: ResultFormat, prefixes: dict[str, str] | None = None) -> bytes:
    """Triples in an RDF syntax; prefixes only where the syntax has them."""
    use_prefixes = prefixes if fmt.ox_format in (RdfFormat.TURTLE, RdfFormat.RDF_XML, RdfFormat.JSON_LD) else None
    return ox.serialize(list(triples), format=fmt.ox_format, prefixes=use_prefixes or None)


__all__ = [
    "ResultFormat", "SOLUTION_FORMATS", "GRAPH_FORMATS", "NotAcceptable", "choose_format", "term_json",
    "solutions_json", "boolean_json", "render_table", "render_graph",
]
