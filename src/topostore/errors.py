"""Exception hierarchy.

Every error a user can cause derives from :class:`TopostoreError`, so that the
command layer can turn any of them into a reply instead of a traceback.
"""

from __future__ import annotations


class TopostoreError(Exception):
    """Base class of every error raised on purpose by topostore."""


class InvalidNameError(TopostoreError, ValueError):
    """An entity name or IRI that could alter a query or is not a valid IRI."""


class InvalidValueError(TopostoreError, ValueError):
    """A value that is not a valid literal of the requested type."""


class UnknownTypeError(InvalidValueError):
    """A value type name that is not supported (aRMOR exit code 101)."""


class LoadError(TopostoreError):
    """A document could not be read or parsed; the store is left untouched."""


class RuleCompileError(TopostoreError):
    """A SWRL rule or OWL axiom that cannot be translated; names the rule and the atom.

    ``rule``: the ``swrl:Imp`` node when a SWRL rule failed (None otherwise).
    """

    rule: object = None


class IncompleteOntologyError(RuleCompileError):
    """A strict load refused an ontology topostore would not reason completely (the notices say why)."""


class QueryError(TopostoreError):
    """A malformed SPARQL query, an unknown named query or a bad parameter."""


class QueryTimeout(QueryError):
    """A query ran past its time limit; ``partial`` holds the rows obtained so far."""

    def __init__(self, message: str, partial: list | None = None) -> None:
        super().__init__(message)
        self.partial = partial or []


class StoreError(TopostoreError):
    """A store that cannot be opened, reached or written (disk locked, server down, writer lock held)."""


class WritesLostError(StoreError):
    """Changes a store had accepted and queued for the server were refused (or not answered) when sent:
    they were undone in this process too, and the message says how many and why."""


class StoreLockedError(StoreError):
    """Another topostore process holds the writer lock of a reference in a shared store."""
