"""The service's resource limits as ``topostore serve`` options, applied process-wide.

Each limit lives beside the code it protects (:mod:`topostore.sparql.guard`,
:mod:`topostore.rdf.safeio`, :mod:`topostore.reason.limits`,
``ArmorService.max_query_seconds``); this module only turns command-line
options into those settings, so the limits table of docs/reliability.md has one place to
point to.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import click

from ..armor import service as armor_service
from ..rdf import safeio
from ..reason import limits as reason_limits
from ..sparql import guard

_SPARQL, _FILES, _REASON = guard.SparqlLimits(), safeio.FileLimits(), reason_limits.ReasonLimits()

OPTIONS = [
    click.option("--sparql-max-length", default=_SPARQL.max_length, show_default=True, type=click.IntRange(1),
                 help="Most characters of a SPARQL query or update."),
    click.option("--sparql-max-depth", default=_SPARQL.max_depth, show_default=True, type=click.IntRange(1),
                 help="Deepest nesting of (, { and [ in SPARQL (the parser crashes near 900)."),
    click.option("--sparql-max-tokens", default=_SPARQL.max_tokens, show_default=True, type=click.IntRange(1),
                 help="Most tokens of a SPARQL text (operator chains crash the parser near 3,000)."),
    click.option("--query-max-seconds", default=armor_service.DEFAULT_MAX_QUERY_SECONDS, show_default=True,
                 type=click.FloatRange(min=0, min_open=True),
                 help="Longest an aRMOR QUERY SPARQL may run, also when the client asks for no limit."),
    click.option("--max-file-size", default=_FILES.max_file_bytes, show_default=True, type=click.IntRange(1),
                 help="Largest ontology file LOAD reads (bytes)."),
    click.option("--max-entity-expansion", default=_FILES.max_entity_expansion, show_default=True,
                 type=click.IntRange(0), help="Most characters the XML entities of one RDF/XML file may expand to."),
    click.option("--reason-max-rounds", default=_REASON.max_rounds, show_default=True, type=click.IntRange(1),
                 help="Most semi-naive rounds of one REASON."),
    click.option("--reason-max-inferred", default=_REASON.max_inferred, show_default=True, type=click.IntRange(1),
                 help="Most facts one REASON may derive."),
    click.option("--reason-max-seconds", default=_REASON.max_seconds, show_default=True,
                 type=click.FloatRange(min=0, min_open=True), help="Longest one REASON may run (seconds)."),
]


def limit_options(command: Callable[..., Any]) -> Callable[..., Any]:
    """Decorate a click command with every limit option."""
    for option in reversed(OPTIONS):
        command = option(command)
    return command


def apply_limits(sparql_max_length: int, sparql_max_depth: int, sparql_max_tokens: int, query_max_seconds: float,
                 max_file_size: int, max_entity_expansion: int, reason_max_rounds: int, reason_max_inferred: int,
                 reason_max_seconds: float) -> None:
    """Install the limits for this process (before the service is created)."""
    guard.set_limits(guard.SparqlLimits(sparql_max_length, sparql_max_depth, sparql_max_tokens))
    safeio.set_limits(safeio.FileLimits(max_file_size, max_entity_expansion))
    reason_limits.set_defaults(reason_limits.ReasonLimits(reason_max_rounds, reason_max_inferred, reason_max_seconds))
    armor_service.DEFAULT_MAX_QUERY_SECONDS = query_max_seconds


__all__ = ["limit_options", "apply_limits", "OPTIONS"]
