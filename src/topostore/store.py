"""The one store interface every other module talks to.

All reasoning goes through :meth:`Store.query` and :meth:`Store.update` with
graphs named explicitly, so the same rules can later run against an on-disk
Oxigraph store or a remote SPARQL 1.1 server.  Today's implementation is
pyoxigraph, in memory or on disk.

Two details of the store are handled here so that nobody else has to know them:

* Blank nodes are *skolemised* on load (``urn:topostore:bnode:…``): the rule
  compiler must name class expressions and SWRL atoms inside SPARQL text, which
  is impossible for blank nodes.  They become blank nodes again on save.
* Oxigraph keeps numbers in canonical form (``"7"^^xsd:long`` is stored as
  ``"7"^^xsd:integer``).  The asserted lexical form and datatype of every
  literal is remembered so that answers and saved files show what the user wrote.
"""

from __future__ import annotations

import os
import uuid
from collections.abc import Iterable, Iterator
from dataclasses import dataclass
from pathlib import Path

import pyoxigraph as ox
from pyoxigraph import BlankNode, DefaultGraph, Literal, NamedNode, Quad, RdfFormat, Triple

from .errors import LoadError, QueryError
from .safeio import check_xml_entities, read_regular_file
from .terms import Term, value_key
from .vocab import AUX, ASSERTED, INFERRED, INTERNAL, NIL, FIRST, REST

SKOLEM_PREFIX = INTERNAL + "bnode:"
_XSD = "http://www.w3.org/2001/XMLSchema#"


#: largest integer result swrlb:pow computes (bits); beyond it the built-in gives no value
_POW_MAX_BITS = 4096


def _pow(base: Term, exponent: Term) -> Literal | None:
    """swrlb:pow for a non-constant exponent (SPARQL 1.1 has no power function).

    Integers with a non-negative integer exponent stay integers; anything else
    is computed as a double.  Non-numbers give no value (the rule does not fire).
    """
    if not isinstance(base, Literal) or not isinstance(exponent, Literal):
        return None
    try:
        if base.datatype.value.startswith(_XSD) and "." not in base.value and "e" not in base.value.lower() \
                and exponent.value.lstrip("+").isdigit():
            b, e = int(base.value), int(exponent.value)
            if abs(b) > 1 and e * abs(b).bit_length() > _POW_MAX_BITS:
                return None  # a number this large is not a measurement; computing it would freeze the service
            return Literal(str(b ** e), datatype=NamedNode(_XSD + "integer"))
        return Literal(repr(float(base.value) ** float(exponent.value)), datatype=NamedNode(_XSD + "double"))
    except (ValueError, OverflowError, ZeroDivisionError):
        return None


#: Extension functions the compiled rules may call (see compile/builtins.py).
CUSTOM_FUNCTIONS = {NamedNode(INTERNAL + "fn:pow"): _pow}

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
    except Exception:  # pragma: no cover - only used to locate an error
        return None
    return None


@dataclass(frozen=True)
class Graphs:
    """The names of the graphs of one reference (several references may share a store)."""

    asserted: NamedNode = ASSERTED
    inferred: NamedNode = INFERRED
    aux: NamedNode = AUX

    @classmethod
    def for_prefix(cls, prefix: str) -> "Graphs":
        return cls(NamedNode(prefix + "asserted"), NamedNode(prefix + "inferred"), NamedNode(prefix + "aux"))


class Store:
    """pyoxigraph behind a small interface: quads in, SPARQL in, results out."""

    def __init__(self, path: str | os.PathLike[str] | None = None) -> None:
        self._ox = ox.Store(str(path)) if path is not None else ox.Store()
        self._in_memory = path is None
        self._writes = 0  # write operations since the last compaction
        self._live_at_compaction = 0
        # (graph, subject, predicate, value key) -> literal as the user wrote it
        self._literal_forms: dict[tuple, Literal] = {}
        # value key -> {literal as written: number of asserted triples using it}
        self._value_forms: dict[tuple, dict[Literal, int]] = {}

    # ------------------------------------------------------------ parsing
    def parse_file(
        self, path: str | os.PathLike[str], fmt: str | RdfFormat | None = None, base_iri: str | None = None
    ) -> list[Triple]:
        """Parse a document into skolemised triples without touching the store."""
        data = read_regular_file(path)  # regular files only, size-limited (LoadError otherwise)
        return self.parse_bytes(data, guess_format(path, fmt), base_iri, source=str(path))

    def parse_bytes(
        self, data: bytes | str, fmt: RdfFormat, base_iri: str | None = None, source: str = "<input>"
    ) -> list[Triple]:
        if isinstance(data, str):
            data = data.encode("utf-8", errors="surrogatepass")
        if fmt == RdfFormat.RDF_XML:
            check_xml_entities(data, source)
        try:
            quads = list(ox.parse(data, format=fmt, base_iri=base_iri, rename_blank_nodes=True))
        except SyntaxError as exc:
            raise LoadError(_syntax_error_message(source, exc, data, fmt)) from exc
        except ValueError as exc:
            raise LoadError(f"{source}: {exc}") from exc
        return [skolemize(Triple(q.subject, q.predicate, q.object)) for q in quads]

    # ------------------------------------------------------------ quads
    def add(self, triples: Iterable[Triple], graph: NamedNode) -> int:
        """Add triples to ``graph``; returns how many were new."""
        added = 0
        self._writes += 1
        for t in triples:
            quad = Quad(t.subject, t.predicate, t.object, graph)
            if quad not in self._ox:
                self._ox.add(quad)
                added += 1
                if isinstance(t.object, Literal):
                    key = value_key(t.object)
                    self._literal_forms[(graph.value, t.subject, t.predicate, key)] = t.object
                    forms = self._value_forms.setdefault(key, {})
                    forms[t.object] = forms.get(t.object, 0) + 1
        return added

    def add_scratch(self, triples: Iterable[Triple], graph: NamedNode) -> None:
        """Bulk-add to a reasoner's scratch graph (no literal forms recorded, no counting)."""
        self._writes += 1
        self._ox.extend(Quad(t.subject, t.predicate, t.object, graph) for t in triples)

    def remove(self, triples: Iterable[Triple], graph: NamedNode) -> int:
        removed = 0
        self._writes += 1
        for t in triples:
            quad = Quad(t.subject, t.predicate, t.object, graph)
            if quad in self._ox:
                self._ox.remove(quad)
                removed += 1
                if isinstance(t.object, Literal):
                    key = value_key(t.object)
                    original = self._literal_forms.pop((graph.value, t.subject, t.predicate, key), t.object)
                    forms = self._value_forms.get(key, {})
                    if original in forms:
                        forms[original] -= 1
                        if forms[original] <= 0:
                            del forms[original]
        return removed

    def contains(self, t: Triple, graph: NamedNode) -> bool:
        return Quad(t.subject, t.predicate, t.object, graph) in self._ox

    def triples(
        self, s: Term | None = None, p: NamedNode | None = None, o: Term | None = None, graph: NamedNode | None = None
    ) -> Iterator[Triple]:
        for q in self._ox.quads_for_pattern(s, p, o, graph):
            yield Triple(q.subject, q.predicate, q.object)

    def objects(self, s: Term, p: NamedNode, graph: NamedNode) -> list[Term]:
        return [q.object for q in self._ox.quads_for_pattern(s, p, None, graph)]

    def subjects(self, p: NamedNode, o: Term, graph: NamedNode) -> list[Term]:
        return [q.subject for q in self._ox.quads_for_pattern(None, p, o, graph)]

    def list_items(self, head: Term, graph: NamedNode) -> list[Term]:
        """Members of an RDF collection (rdf:first/rdf:rest), in order."""
        items: list[Term] = []
        seen = set()
        node = head
        while node != NIL and node not in seen:
            seen.add(node)
            firsts = self.objects(node, FIRST, graph)
            if not firsts:
                break
            items.append(firsts[0])
            rests = self.objects(node, REST, graph)
            if not rests:
                break
            node = rests[0]
        return items

    def count(self, graph: NamedNode) -> int:
        result = self._ox.query(f"SELECT (COUNT(*) AS ?n) WHERE {{ GRAPH {graph} {{ ?s ?p ?o }} }}")
        return int(next(iter(result))["n"].value)

    def is_empty(self, graph: NamedNode) -> bool:
        return not bool(self._ox.query(f"ASK {{ GRAPH {graph} {{ ?s ?p ?o }} }}"))

    def clear(self, graph: NamedNode) -> None:
        self._ox.update(f"DROP SILENT GRAPH {graph}")
        self._literal_forms = {k: v for k, v in self._literal_forms.items() if k[0] != graph.value}
        self._value_forms = {}
        for (_, _, _, key), lit in self._literal_forms.items():
            forms = self._value_forms.setdefault(key, {})
            forms[lit] = forms.get(lit, 0) + 1

    def original_literal(self, graph: NamedNode, s: Term, p: NamedNode, o: Literal) -> Literal:
        """The literal as the user asserted it (lexical form and datatype)."""
        found = self._literal_forms.get((graph.value, s, p, value_key(o)))
        return found if found is not None else self.restore(o)

    def restore(self, term: Term) -> Term:
        """A literal as users wrote it, when that value was written in one form only."""
        if not isinstance(term, Literal):
            return term
        forms = self._value_forms.get(value_key(term))
        if forms and len(forms) == 1:
            return next(iter(forms))
        return term

    # ------------------------------------------------------------ SPARQL
    def update(self, text: str, **kwargs) -> None:
        self._writes += 1
        try:
            self._ox.update(text, custom_functions=CUSTOM_FUNCTIONS, **kwargs)
        except SyntaxError as exc:
            raise QueryError(f"malformed SPARQL update: {exc}") from exc
        except (OSError, RuntimeError) as exc:
            raise QueryError(f"SPARQL update failed: {exc}") from exc

    def query(self, text: str, graphs: list[NamedNode] | None = None, **kwargs):
        """Run a query whose default graph is the union of ``graphs``."""
        kwargs.setdefault("custom_functions", CUSTOM_FUNCTIONS)
        try:
            if graphs is not None:
                return self._ox.query(text, default_graph=list(graphs), named_graphs=list(graphs), **kwargs)
            return self._ox.query(text, **kwargs)
        except SyntaxError as exc:
            raise QueryError(f"malformed SPARQL query: {exc}") from exc
        except (OSError, RuntimeError) as exc:  # evaluation errors reported by Oxigraph
            raise QueryError(f"SPARQL evaluation failed: {exc}") from exc

    # ------------------------------------------------------------ housekeeping
    def maybe_compact(self) -> bool:
        """Rebuild the in-memory store once enough writes have piled up.

        Oxigraph's in-memory store keeps removed quads around (for its
        transactions), so a long-running reasoner that derives and drops the same
        facts step after step gets slower and bigger.  Copying the live quads into
        a fresh store resets that; it is done when the writes since the last
        compaction outnumber a fiftieth of the live quads (at least 200), which
        keeps its amortised cost small.  On-disk stores compact themselves.
        """
        if not self._in_memory or self._writes < max(200, self._live_at_compaction // 50):
            return False
        fresh = ox.Store()
        fresh.extend(self._ox)
        self._ox = fresh
        self._writes = 0
        self._live_at_compaction = len(fresh)
        return True

    # ------------------------------------------------------------ output
    def dump(self, graphs: list[NamedNode], restore_literals_from: NamedNode | None = None) -> list[Triple]:
        """Triples of ``graphs`` (deduplicated), blank nodes and literal forms restored."""
        out: dict[Triple, None] = {}
        for g in graphs:
            for t in self.triples(graph=g):
                if isinstance(t.object, Literal):
                    t = Triple(t.subject, t.predicate, self.original_literal(restore_literals_from or g, t.subject, t.predicate, t.object))
                out[unskolemize(t)] = None
        return list(out)


def skolem(term: Term) -> Term:
    if isinstance(term, BlankNode):
        return NamedNode(SKOLEM_PREFIX + term.value)
    return term


def skolemize(t: Triple) -> Triple:
    return Triple(skolem(t.subject), t.predicate, skolem(t.object))


def unskolem(term: Term) -> Term:
    if isinstance(term, NamedNode) and term.value.startswith(SKOLEM_PREFIX):
        return BlankNode(term.value[len(SKOLEM_PREFIX):])
    return term


def unskolemize(t: Triple) -> Triple:
    return Triple(unskolem(t.subject), t.predicate, unskolem(t.object))


def fresh_skolem() -> NamedNode:
    """A new skolem IRI, standing for a fresh blank node (e.g. a new AllDifferent axiom)."""
    return NamedNode(SKOLEM_PREFIX + "n" + uuid.uuid4().hex)


def serialize(triples: Iterable[Triple], fmt: RdfFormat, prefixes: dict[str, str] | None = None) -> bytes:
    return ox.serialize(list(triples), format=fmt, prefixes=prefixes or None)


__all__ = [
    "Store", "Graphs", "guess_format", "skolemize", "unskolemize", "skolem", "unskolem", "fresh_skolem",
    "serialize", "DefaultGraph", "SKOLEM_PREFIX",
]
