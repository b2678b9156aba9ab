"""Run SPARQL queries and updates on an aRMOR reference, safely under concurrency.

Queries: the reference lock is held only while the query is *started*.
Oxigraph evaluates every query on a snapshot of the store taken at that
moment, and the reference lock guarantees the moment is between two
manipulations (never half-way through a REASON), so the reader sees one
consistent state while writers carry on.  Rows are read on the calling thread
(pyoxigraph result objects must stay on the thread that created them) and
the deadline is checked between rows, so a long result stops at the limit.

Updates are evaluated on a scratch copy of the asserted graph; the difference
is applied as one all-or-nothing manipulation through the target's
``manipulate`` (:class:`~topostore.sparql.target.WritableOntology`), which
re-reasons (or undoes everything if reasoning fails), exactly like an aRMOR
manipulation.
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable
from dataclasses import dataclass, field

import pyoxigraph as ox
from pyoxigraph import DefaultGraph, Literal, Quad, QueryBoolean, QuerySolutions, Triple

from ..errors import QueryError
from ..rdf.terms import Term
from ..rdf.vocab import ASSERTED, OWL, RDF, RDFS, XSD
from ..stores.base import skolemize
from ..stores.language_tags import literal_tags
from . import evaluated
from .guard import check_user_sparql
from .results import ResultFormat, boolean_json, choose_format, render_graph, render_table, solutions_json
from .target import LockedOntology, WritableOntology
from .written import as_written, may_respell


class SparqlTimeout(QueryError):
    """A query or update ran past the server's time limit."""


class ResultTooLarge(QueryError):
    """A result with more rows (or triples) than the server's limit."""


class ReferenceMounted(QueryError):
    """A SPARQL update on a reference mounted by an aRMOR client (only that client may change it)."""


@dataclass
class TripleDelta:
    """What an update changes in the asserted graph."""

    add: list[Triple]
    remove: list[Triple]


@dataclass
class QueryOutcome:
    """A serialized query result and the format it is in."""

    body: bytes
    format: ResultFormat
    kind: str  # "solutions", "boolean" or "graph"
    rows: int = 0


@dataclass
class Job:
    """Shared between the waiting request and the worker: who gets to decide the outcome.

    A request that gives up at the deadline *expires* the job; a worker about
    to commit an update *claims* it.  Whichever comes first wins, so a client
    told "timed out" can rely on nothing having changed.
    """

    deadline: float
    _state: str = "running"
    _lock: threading.Lock = field(default_factory=threading.Lock)

    def expire(self) -> bool:
        with self._lock:
            if self._state == "running":
                self._state = "expired"
            return self._state == "expired"

    def claim(self) -> bool:
        with self._lock:
            if self._state == "running":
                self._state = "claimed"
            return self._state == "claimed"

    @property
    def expired(self) -> bool:
        return self._state == "expired" or time.monotonic() > self.deadline


def timeout_message(limit: float) -> str:
    return (f"the SPARQL request ran past the time limit of {limit:g} s and was stopped; "
            "narrow it (LIMIT, more specific patterns) or start the server with a larger --sparql-timeout")


def too_large_message(max_rows: int) -> str:
    return (f"the result has more than {max_rows} rows; page through it with LIMIT/OFFSET "
            "or start the server with a larger --sparql-max-rows")


def run_query(ref: LockedOntology, text: str, accept: str | None, explicit_format: str | None, job: Job,
              limit: float, max_rows: int = 500_000) -> QueryOutcome:
    """Evaluate a query over the reference's asserted ∪ inferred graphs and serialize it.

    Results are held in memory to be serialized, so more than ``max_rows``
    rows or triples is refused rather than risking the robot's memory.
    Raises QueryError (malformed), UnsafeOperationError, NotAcceptable,
    SparqlTimeout or ResultTooLarge.
    """
    onto = ref.ontology  # onto.sparql passes the text through the SPARQL guard
    with ref.lock:
        result = onto.sparql(text)  # the snapshot is taken here
    try:
        return _serialize(ref, onto, result, accept, explicit_format, job, limit, max_rows)
    finally:
        # pyoxigraph results must be freed on this thread, not where a traceback holding them ends up
        result = None  # noqa: F841


def _serialize(ref: LockedOntology, onto, result, accept: str | None, explicit_format: str | None, job: Job,
               limit: float, max_rows: int) -> QueryOutcome:
    """Read the rows (or triples) under the deadline and serialize them."""
    try:
        return _read(ref, onto, result, accept, explicit_format, job, limit, max_rows)
    except Exception as exc:  # a fresh exception: no traceback may keep the result alive
        try:
            error = type(exc)(str(exc))
        except TypeError:  # an exception class that takes other arguments
            error = QueryError(str(exc))
    result = None  # noqa: F841
    raise error


def _read(ref: LockedOntology, onto, result, accept: str | None, explicit_format: str | None, job: Job,
          limit: float, max_rows: int) -> QueryOutcome:
    if isinstance(result, QueryBoolean):
        fmt = choose_format(accept, graph=False, explicit=explicit_format)
        return QueryOutcome(render_table(boolean_json(bool(result)), fmt), fmt, "boolean", 1)
    if isinstance(result, QuerySolutions):
        fmt = choose_format(accept, graph=False, explicit=explicit_format)
        variables = [v.value for v in result.variables]
        rows: list[list[object | None]] = []
        for solution in result:
            rows.append([solution[v] for v in variables])
            if job.expired:
                raise SparqlTimeout(timeout_message(limit))
            if len(rows) > max_rows:
                raise ResultTooLarge(too_large_message(max_rows))
        with ref.lock:  # literal forms and tag spellings are bookkeeping shared with writers
            rows = [[_restore(onto, t) for t in row] for row in rows]
            tags = onto.store.forms.tags
            table = render_table(solutions_json(variables, rows, tags.spelled if tags else str), fmt)
            table = tags.respell_results(table, fmt.ox_format)  # what pyoxigraph wrote again, lowered
        return QueryOutcome(table, fmt, "solutions", len(rows))
    fmt = choose_format(accept, graph=True, explicit=explicit_format)
    triples: list[Triple] = []
    for t in result:
        triples.append(t)
        if job.expired:
            raise SparqlTimeout(timeout_message(limit))
        if len(triples) > max_rows:
            raise ResultTooLarge(too_large_message(max_rows))
    with ref.lock:
        triples = [Triple(t.subject, t.predicate, _restore(onto, t.object)) for t in triples]
        tags = onto.store.forms.tags
    prefixes = {"owl": OWL, "rdf": RDF, "rdfs": RDFS, "xsd": XSD, "": onto.prefix}
    return QueryOutcome(tags.respell(render_graph(triples, fmt, prefixes), fmt.ox_format), fmt, "graph", len(triples))


def _restore(onto, term):
    """A literal in the form the user asserted (Oxigraph canonicalises xsd:long to xsd:integer)."""
    return onto.store.restore(term) if isinstance(term, Literal) else term


@dataclass
class UpdateOutcome:
    added: int
    removed: int
    consistent: bool
    warnings: list[str]

    def to_dict(self) -> dict[str, object]:
        return {"added": self.added, "removed": self.removed, "is_consistent": self.consistent,
                "warnings": self.warnings}


def update_delta(asserted: list[Triple], text: str, held: Callable[[Literal], Term] | None = None) -> TripleDelta:
    """What ``text`` adds to and removes from ``asserted``, computed on a scratch store; each added literal
    spelled as the text wrote it at its position, else as ``held`` gives its value (:func:`.written.as_written`).
    Where the text may respell a literal, the update runs one operation at a time and each value takes the first
    spelling its evaluation wrote at its position, the others following it for the change to say them, and so do
    the spellings written of a value the graph holds (:mod:`.evaluated`)."""
    scratch = _scratch(asserted)
    respell = may_respell(text)
    seen = evaluated.run(scratch, text) if respell else None
    if seen is None:
        if respell:  # an operation that does not run alone: the whole text, with its own error
            scratch = _scratch(asserted)
        try:
            scratch.update(text)
        except SyntaxError as exc:
            raise QueryError(f"malformed SPARQL update: {exc}") from exc
        except (OSError, RuntimeError) as exc:
            raise QueryError(f"SPARQL update failed: {exc}") from exc
    named = {q.graph_name.value for q in scratch.quads_for_pattern(None, None, None) if not isinstance(q.graph_name, DefaultGraph)}
    if named:
        raise QueryError(f"the update writes to the named graph(s) {', '.join(sorted(named))}; a reference has one "
                         "writable graph, the default graph (leave out GRAPH and WITH)")
    after = {skolemize(Triple(q.subject, q.predicate, q.object)) for q in scratch.quads_for_pattern(None, None, None, DefaultGraph())}
    before = set(asserted)
    added, removed = sorted(after - before, key=str), sorted(before - after, key=str)
    if seen is None or not seen.followed:
        return TripleDelta(add=as_written(added, text, held), remove=removed)

    def present(s: object, p: object) -> list[Triple]:
        return [skolemize(Triple(q.subject, q.predicate, q.object))
                for q in scratch.quads_for_pattern(s, p, None, DefaultGraph())]  # type: ignore[arg-type]

    add, held_removed = evaluated.added_as_written(added, seen, text, held, present)
    return TripleDelta(add=add, remove=removed + held_removed)


def _scratch(asserted: list[Triple]) -> ox.Store:
    """A store holding ``asserted`` in its default graph, for an update to run on."""
    scratch = ox.Store()
    scratch.extend([Quad(t.subject, t.predicate, t.object, DefaultGraph()) for t in asserted])
    return scratch


def run_update(ref: WritableOntology, text: str, job: Job, limit: float) -> UpdateOutcome:
    """Apply a SPARQL update to the reference's asserted graph, then reason as a manipulation would.

    Updates see and change asserted knowledge only; inferences follow from reasoning.
    """
    check_user_sparql(text)
    with ref.lock:
        if ref.owner is not None:
            raise ReferenceMounted(f"reference {ref.name!r} is mounted by client {ref.owner!r}; "
                                   "only that client may change it")
        asserted = list(ref.ontology.store.triples(graph=ASSERTED))
        delta = update_delta(asserted, text, ref.ontology.store.restore)
        if not job.claim():
            raise SparqlTimeout(timeout_message(limit))
        added, removed, warnings = ref.manipulate("SPARQL update", delta.add, delta.remove)
        # the tags of the literals it added, as the update's text spells them (pyoxigraph lowered them)
        ref.ontology.values.learned(text, None, only=literal_tags(added))
        if "@" in text and (document := evaluated.data_document(text)):  # a tag spelled otherwise, said
            notes = ref.ontology.values.data_tag_notes(document, set(added))
            warnings = [*warnings, "; ".join(dict.fromkeys(notes))] if notes else warnings
        return UpdateOutcome(len(added), len(removed), ref.is_consistent, warnings)


__all__ = ["QueryOutcome", "UpdateOutcome", "SparqlTimeout", "ResultTooLarge", "ReferenceMounted", "Job", "run_query", "run_update",
           "update_delta", "timeout_message"]
