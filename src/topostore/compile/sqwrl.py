"""SQWRL queries (Protégé SWRLTab): a SWRL rule whose head holds ``sqwrl:`` built-ins is a query.

``Person(?p) ^ hasAge(?p, ?a) -> sqwrl:select(?p, ?a) ^ sqwrl:orderByDescending(?a)``
is not a rule (it concludes nothing): it asks for rows.  Such a rule is compiled
to a SPARQL SELECT over what is known after reasoning, kept apart from the rules
(:attr:`RuleSet.queries`), and run by name like the named queries of
``queries/*.rq`` (:meth:`topostore.Ontology.query`), returning ``QueryItem`` s.

Head built-ins translated:

* ``select``/``selectDistinct`` (columns), ``columnNames`` (their names);
* ``count``/``countDistinct``, ``min``, ``max``, ``sum``, ``avg`` (aggregates; the
  selected columns are grouped on, as in SQWRL);
* ``orderBy``/``orderByDescending`` (by a selected column, or by an aggregate's
  argument, which orders by the aggregate);
* ``limit``.

Other SQWRL operators (sets, ``makeBag``, ``groupBy``, ``nth``, ...) and non-SQWRL
atoms beside them in a head are not translated: the query is set aside with a
notice naming the operator, and the file still loads (Pellet ignores SQWRL).
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field

from pyoxigraph import Literal

from ..errors import RuleCompileError
from ..rdf.terms import Term
from ..rdf.vocab import SQWRL_PREFIX

_AGGREGATES = {"count": "COUNT", "countDistinct": "COUNT", "min": "MIN", "max": "MAX", "sum": "SUM", "avg": "AVG"}
_SUPPORTED = {"select", "selectDistinct", "columnNames", "orderBy", "orderByDescending", "limit", *_AGGREGATES}


def is_sqwrl(iri: Term | str | None) -> bool:
    value = getattr(iri, "value", iri)
    return isinstance(value, str) and value.startswith(SQWRL_PREFIX)


def operator(iri: Term) -> str:
    """``sqwrl:select`` → ``select``."""
    return iri.value.rsplit("#", 1)[-1].rsplit("/", 1)[-1]


@dataclass(frozen=True)
class SqwrlQuery:
    """A SQWRL query: its name (the rule's label), its SPARQL SELECT text, its columns."""

    name: str
    text: str
    columns: tuple[str, ...]
    description: str = ""


@dataclass
class _Head:
    """A SQWRL head as read: projections, aggregates, order, limit, column names."""

    select: list[str]
    distinct: bool = False
    aggregates: list[tuple[str, str]] = field(default_factory=list)  # (operator, argument text)
    order: list[tuple[str, bool]] = field(default_factory=list)  # (argument text, descending)
    limit: int | None = None
    names: list[str] = field(default_factory=list)


def _column(text: str, k: int) -> str:
    return text[1:] if text.startswith("?") else f"c{k + 1}"


def _safe_name(name: str) -> str:
    return re.sub(r"[^A-Za-z0-9_]", "_", name) or "column"


def read_head(atoms: list[tuple[str, list[str], list[Term]]]) -> _Head:
    """The head from (operator, argument texts, argument terms); RuleCompileError for what is not translated."""
    head = _Head(select=[])
    for op, args, terms in atoms:
        if op not in _SUPPORTED:
            raise RuleCompileError(f"sqwrl:{op} is not supported (supported: sqwrl:{', sqwrl:'.join(sorted(_SUPPORTED))})")
        if op in ("select", "selectDistinct"):
            head.select += args
            head.distinct |= op == "selectDistinct"
        elif op in _AGGREGATES:
            if len(args) != 1:
                raise RuleCompileError(f"sqwrl:{op} takes 1 argument, got {len(args)}")
            head.aggregates.append((op, args[0]))
        elif op in ("orderBy", "orderByDescending"):
            head.order += [(a, op == "orderByDescending") for a in args]
        elif op == "columnNames":
            head.names += [t.value if isinstance(t, Literal) else a for a, t in zip(args, terms, strict=True)]
        elif op == "limit":
            if len(terms) != 1 or not isinstance(terms[0], Literal) or not terms[0].value.strip().isdigit():
                raise RuleCompileError("sqwrl:limit takes one non-negative integer")
            head.limit = int(terms[0].value)
    if not head.select and not head.aggregates:
        raise RuleCompileError("a SQWRL query needs sqwrl:select or an aggregate such as sqwrl:count")
    return head


def select_text(head: _Head, where: str) -> tuple[str, tuple[str, ...]]:
    """(SPARQL SELECT, column names) for a head over the WHERE group ``where``."""
    columns, projections, alias = [], [], {}
    items = [(a, None) for a in head.select] + [(a, op) for op, a in head.aggregates]
    for k, (arg, op) in enumerate(items):
        name = head.names[k] if k < len(head.names) else (f"{op}_{_column(arg, k)}" if op else _column(arg, k))
        name = _safe_name(name)
        while name in columns:
            name += "_"
        columns.append(name)
        expr = f"{_AGGREGATES[op]}({'DISTINCT ' if op == 'countDistinct' else ''}{arg})" if op else arg
        projections.append(f"({expr} AS ?{name})" if op or arg != f"?{name}" else arg)
        if op:
            alias[arg] = f"?{name}"  # ordering by a counted variable orders by the count
        else:
            alias.setdefault(arg, f"?{name}")
    lines = [f"SELECT {'DISTINCT ' if head.distinct else ''}{' '.join(projections)}", f"WHERE {{\n  {where}\n}}"]
    if head.aggregates and head.select:
        lines.append("GROUP BY " + " ".join(a for a in head.select if a.startswith("?")))
    if head.order:
        order = []
        for arg, desc in head.order:
            target = alias.get(arg, arg)
            order.append(f"DESC({target})" if desc else f"ASC({target})")
        lines.append("ORDER BY " + " ".join(order))
    if head.limit is not None:
        lines.append(f"LIMIT {head.limit}")
    return "\n".join(lines), tuple(columns)


__all__ = ["SQWRL_PREFIX", "SqwrlQuery", "is_sqwrl", "operator", "read_head", "select_text"]
