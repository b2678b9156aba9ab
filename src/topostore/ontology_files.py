"""An ontology's documents: loading (all or nothing, rules compiled first) and saving.

A part of :class:`topostore.ontology.Ontology` (a mixin), apart from the facade
because loading has rules of its own: a document that changes the schema is
compiled on a scratch copy first, so an untranslatable rule leaves the ontology
as it was.
"""

from __future__ import annotations

import os
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING

from pyoxigraph import NamedNode, RdfFormat, Triple

from .compile import RuleSet, compile_ontology
from .safeio import atomic_write
from .store import Store, guess_format, serialize
from .stores import StoreSpec, check_rules
from .vocab import (
    ASSERTED,
    DIFFERENT_FROM,
    FIRST,
    OWL,
    RDF,
    RDFS,
    REST,
    STANFORD_SWRL,
    SWRL,
    SWRLB,
    TYPE,
    XSD,
    owl,
)

if TYPE_CHECKING:  # pragma: no cover
    from .ontology import Ontology

SCHEMA_NAMESPACES = (RDF, RDFS, OWL, SWRL, STANFORD_SWRL)
_ABOX_PREDICATES = {TYPE, owl("sameAs"), DIFFERENT_FROM, FIRST, REST, owl("distinctMembers"), owl("members")}


def is_schema_triple(t: Triple) -> bool:
    """True for triples that change the rules (TBox axioms, SWRL rules), not just facts."""
    p = t.predicate
    if p == TYPE:
        return isinstance(t.object, NamedNode) and t.object.value.startswith(SCHEMA_NAMESPACES) and t.object not in (
            owl("NamedIndividual"), owl("Thing"), owl("AllDifferent"))
    if p in _ABOX_PREDICATES:
        return False
    return p.value.startswith(SCHEMA_NAMESPACES)


class OntologyFiles:
    """Loading and saving (a mixin of :class:`~topostore.ontology.Ontology`).

    Uses the ontology's ``store``, ``add``, ``prefix`` and ``visible_graphs``.
    """

    store: Store
    _rules: RuleSet | None

    @classmethod
    def from_file(cls, *paths: str | os.PathLike[str], prefix: str | None = None, fmt: str | None = None,
                  base_iri: str | None = None, store: Store | StoreSpec = None) -> Ontology:
        onto = cls(prefix=prefix, store=store)
        for p in paths:
            onto.load(p, fmt=fmt, base_iri=base_iri)
        return onto

    def load(self, path: str | os.PathLike[str], fmt: str | None = None, base_iri: str | None = None,
             progress: Callable[[int], None] | None = None) -> int:
        """Add a document's triples to the asserted graph; all or nothing.

        Rules are compiled before anything is added, so a file with a rule that
        cannot be translated is refused and leaves the ontology as it was.
        ``progress(n)`` is told how many triples have been parsed so far.
        """
        triples = self.store.parse_file(path, fmt, base_iri, progress)
        return self._add_checked(triples)

    def load_data(self, data: str | bytes, fmt: str = "turtle", base_iri: str | None = None) -> int:
        triples = self.store.parse_bytes(data, guess_format("x", fmt), base_iri)
        return self._add_checked(triples)

    def _add_checked(self, triples: list[Triple]) -> int:
        """Add loaded triples; when they change the rules, compile first on a copy,
        so that an untranslatable rule leaves the ontology untouched, and keep
        that compilation (it is the one the new asserted graph gives)."""
        if not any(is_schema_triple(t) for t in triples):
            return self.add(*triples)
        scratch = Store()
        scratch.add(self.store.triples(graph=ASSERTED), ASSERTED)
        scratch.add(triples, ASSERTED)
        rules = compile_ontology(scratch, ASSERTED)  # raises RuleCompileError, nothing added
        check_rules(self.store, rules)
        added = self.add(*triples)
        self._rules = rules
        return added

    def triples(self, inferred: bool = False) -> list[Triple]:
        graphs = self.visible_graphs() if inferred else [ASSERTED]
        return self.store.dump(graphs, restore_literals_from=ASSERTED)

    def serialize(self, fmt: str | RdfFormat = "turtle", inferred: bool = False) -> bytes:
        rdf_format = guess_format("x", fmt) if isinstance(fmt, str) else fmt
        prefixes = {"owl": OWL, "rdf": RDF, "rdfs": RDFS, "xsd": XSD, "swrl": SWRL,
                    "swrlb": SWRLB, "": self.prefix}
        return serialize(self.triples(inferred), rdf_format, prefixes)

    def save(self, path: str | os.PathLike[str], fmt: str | None = None, inferred: bool = False) -> Path:
        """Write asserted (or asserted + inferred) triples; the format follows the extension."""
        path = Path(path)
        data = self.serialize(guess_format(path, fmt), inferred)
        return atomic_write(path, data)  # temporary file beside it, never through a symlink, removed on failure


__all__ = ["OntologyFiles", "is_schema_triple"]
