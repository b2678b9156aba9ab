"""What the SPARQL side needs of a reference: an ontology plus the lock that orders its changes.

``sparql/`` serves the SPARQL protocols over any such target and knows nothing
of aRMOR; :class:`topostore.armor.reference.Reference` is the one the service
hands it (it satisfies both protocols structurally).
"""

from __future__ import annotations

from contextlib import AbstractContextManager
from typing import TYPE_CHECKING, Protocol

from pyoxigraph import Triple

if TYPE_CHECKING:  # pragma: no cover - ontology/ sits above sparql/ in docs/architecture.md
    from ..ontology.facade import Ontology


class LockedOntology(Protocol):
    """An ontology and its lock: a query started under the lock sees no half-done manipulation."""

    @property
    def ontology(self) -> Ontology: ...

    @property
    def lock(self) -> AbstractContextManager: ...


class WritableOntology(LockedOntology, Protocol):
    """A target SPARQL updates may change: one all-or-nothing manipulation, then reasoning."""

    @property
    def name(self) -> str: ...

    @property
    def owner(self) -> str | None:
        """The client that mounted it (only that client may change it), None when unmounted."""
        ...

    @property
    def is_consistent(self) -> bool: ...

    def manipulate(self, description: str, add: list[Triple],
                   remove: list[Triple]) -> tuple[list[Triple], list[Triple], list[str]]:
        """Add and remove asserted triples as one manipulation (undone whole if reasoning fails): the triples
        the store took (added, removed: a value held in another spelling is neither) and its warnings."""
        ...


__all__ = ["LockedOntology", "WritableOntology"]
