"""Named SPARQL queries, safe parameter binding and ``QueryItem`` results.

A named query is a ``.rq`` file in ``queries/`` with ``# key: value`` headers::

    # name: can-reach
    # description: locations a robot can reach
    # param: robot iri
    SELECT ?location WHERE { ?robot <...#canReach> ?location }

Parameters are bound by pyoxigraph's ``substitutions=`` (SPARQL-dev SEP-0007:
the variable is replaced by the RDF term in the parsed query), so a parameter
value is never spliced into the query text and cannot change its structure.
pyoxigraph binds projected variables only, so a named query projects its
parameters; :meth:`topostore.Ontology.query` leaves their columns out.  Results are ``QueryItem(key, value)``
lists, one item per projected variable per row (``""`` when unbound), in the
shape of aRMOR's ``sparql_queried_objects``.
"""

from __future__ import annotations

import re
import time
from collections.abc import Callable
from dataclasses import dataclass
from functools import cache
from pathlib import Path

from pyoxigraph import BlankNode, Literal, NamedNode, QuerySolutions, Variable

from ..errors import QueryError, QueryTimeout
from ..rdf.lexer import IRIREF, skip_non_code  # noqa: F401 - the tokenizer's home is lexer.py; kept importable here
from ..rdf.terms import Term
from ..rdf.vocab import XSD
from ..resources import queries_dir
from ..stores.base import unskolem


@dataclass(frozen=True)
class QueryItem:
    """One variable of one result row: ``key`` without ``?``, ``value`` rendered as text."""

    key: str
    value: str

    def to_dict(self) -> dict[str, str]:
        return {"key": self.key, "value": self.value}


@dataclass(frozen=True)
class NamedQuery:
    name: str
    description: str
    params: dict[str, str]  # name -> kind ("iri" or "literal")
    text: str
    path: Path | None = None


def parse_query_file(path: Path) -> NamedQuery:
    text = path.read_text()
    headers = re.findall(r"^#\s*([a-z]+):\s*(.*)$", text, re.M)
    info = {k: v.strip() for k, v in headers if k != "param"}
    params: dict[str, str] = {}
    for k, v in headers:
        if k == "param":
            parts = v.split()
            params[parts[0]] = parts[1] if len(parts) > 1 else "iri"
    return NamedQuery(info.get("name", path.stem), info.get("description", ""), params, text, path)


@cache
def named_queries(folder: Path | None = None) -> dict[str, NamedQuery]:
    folder = folder or queries_dir()
    queries = (parse_query_file(p) for p in sorted(folder.glob("*.rq")))
    return {q.name: q for q in queries}


def get_named_query(name_or_path: str) -> NamedQuery:
    """A named query by name, or any ``.rq`` file by path."""
    queries = named_queries()
    if name_or_path in queries:
        return queries[name_or_path]
    path = Path(name_or_path)
    if path.suffix == ".rq" and path.is_file():
        return parse_query_file(path)
    raise QueryError(f"unknown query {name_or_path!r}; named queries: {', '.join(sorted(queries))}")


# --------------------------------------------------------------------------- binding

def substitutions(bindings: dict[str, Term]) -> dict[Variable, Term]:
    """pyoxigraph's ``substitutions=`` argument: each variable name fixed to its term."""
    return {Variable(name): term for name, term in bindings.items()}


# --------------------------------------------------------------------------- rendering

def render_jena(term: Term | None, restore: Callable[[Term], Term] = lambda t: t) -> str:
    """Value text as aRMOR's SPARQL answers show it: IRI bare, ``lex^^datatypeIRI``,
    plain strings bare, ``text@lang``; ``""`` for unbound."""
    if term is None:
        return ""
    term = unskolem(restore(term))
    if isinstance(term, NamedNode):
        return term.value
    if isinstance(term, BlankNode):
        return "_:" + term.value
    if isinstance(term, Literal):
        if term.language:
            return f"{term.value}@{term.language}"
        if term.datatype.value == XSD + "string":
            return term.value
        return f"{term.value}^^{term.datatype.value}"
    return str(term)


def collect(solutions: QuerySolutions, timeout: float | None) -> tuple[list[str], list[list[Term | None]], bool]:
    """Rows of a SELECT result; stops after ``timeout`` seconds with the rows so far.

    Rows are read on the calling thread (pyoxigraph results are bound to the
    thread that made them); the deadline is checked between rows.
    """
    variables = [v.value for v in solutions.variables]
    rows: list[list[Term | None]] = []
    deadline = time.monotonic() + timeout if timeout and timeout > 0 else None
    try:
        for s in solutions:
            rows.append([s[v] for v in variables])
            if deadline is not None and time.monotonic() > deadline:
                return variables, rows, True
    except OSError as exc:
        raise QueryError(f"SPARQL evaluation failed: {exc}") from exc
    return variables, rows, False


def to_items(variables: list[str], rows: list[list[Term | None]], render: Callable[[Term | None], str]) -> list[QueryItem]:
    return [QueryItem(v, render(value)) for row in rows for v, value in zip(variables, row)]


__all__ = ["QueryItem", "NamedQuery", "named_queries", "get_named_query", "substitutions", "render_jena", "collect",
           "to_items", "QueryTimeout"]
