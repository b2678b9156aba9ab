"""The SPARQL 1.1 Protocol side of the server, kept apart from the web framework.

:mod:`.guard` refuses operations that would reach outside the service
(``SERVICE``, ``LOAD``), :mod:`.results` turns rows and triples into the
standard result formats, :mod:`.execute` runs queries and updates on a
reference with its lock and a time limit.  :mod:`topostore.http.app` only maps
HTTP requests onto these functions.
"""

from .execute import QueryOutcome, SparqlTimeout, run_query, run_update
from .guard import UnsafeOperationError, check_safe
from .results import NotAcceptable, choose_format

__all__ = [
    "QueryOutcome", "SparqlTimeout", "run_query", "run_update", "UnsafeOperationError", "check_safe",
    "NotAcceptable", "choose_format",
]
