"""The namespace an ontology's entity names are read in: given, or its ontology IRI + '#'.

A named part of one :class:`~topostore.ontology.facade.Ontology` (``onto.names``); the ontology's
``prefix``, ``iri`` and ``short`` are these.
"""

from __future__ import annotations

from pyoxigraph import Literal, NamedNode

from ..rdf.terms import Term, entity
from ..rdf.vocab import ASSERTED, DEFAULT_PREFIX, TYPE, owl
from ..stores.base import Store


class Namespace:
    """Reads names into IRIs and IRIs back into names, in one ontology's namespace."""

    def __init__(self, store: Store, given: str | None) -> None:
        self.store = store
        self._given = given
        self._found: str | None = None
        #: the namespace when known without a look-up (given, or found since the last schema change), else None
        self.known = given

    @property
    def given(self) -> str | None:
        """The namespace given (None: found from the asserted owl:Ontology)."""
        return self._given

    @given.setter
    def given(self, value: str | None) -> None:
        self._given = value
        self.known = value if value is not None else self._found

    @property
    def prefix(self) -> str:
        """Namespace for entity names: the ontology IRI + '#' unless given."""
        if self.known is not None:
            return self.known
        found = DEFAULT_PREFIX  # looked up once per schema change (a round trip on a server)
        # kept only once the read succeeded: a read that fails (a remote store's queued writes
        # refused on the way) must not leave the default namespace behind for good
        for t in self.store.triples(None, TYPE, owl("Ontology"), ASSERTED):
            if isinstance(t.subject, NamedNode):
                iri = t.subject.value
                found = iri if iri.endswith(("#", "/")) else iri + "#"
                break
        self._found = self.known = found
        return found

    def forget(self) -> None:
        """The schema changed: the ontology IRI is looked up again."""
        self._found = None
        self.known = self._given

    def iri(self, name: str | NamedNode) -> NamedNode:
        """IRI of a named entity (``<full IRI>`` or a name in :attr:`prefix`)."""
        if not isinstance(name, (str, NamedNode)):
            raise TypeError(f"an entity name must be a string or a NamedNode, not {type(name).__name__}")
        return name if isinstance(name, NamedNode) else entity(name, self.prefix)

    def short(self, term: Term) -> str:
        """Name of a term relative to :attr:`prefix` (full IRI otherwise); literals as text."""
        if isinstance(term, NamedNode):
            v, prefix = term.value, self.prefix
            return v[len(prefix):] if v.startswith(prefix) else v
        if isinstance(term, Literal):
            return term.value
        return str(term)


__all__ = ["Namespace"]
