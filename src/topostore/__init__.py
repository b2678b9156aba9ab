"""topostore: an OWL + SWRL ontology service for robots.

The ontology lives in an Oxigraph store; OWL axioms and SWRL rules are compiled
to SPARQL updates and run to a fixpoint on REASON.
"""

from .compile.notices import Notice, OntologyWarning
from .errors import (
    IncompleteOntologyError,
    InvalidNameError,
    InvalidValueError,
    LoadError,
    QueryError,
    QueryTimeout,
    RuleCompileError,
    TopostoreError,
    UnknownTypeError,
)
from .ontology.facade import Ontology, ReasonReport
from .ontology.named_queries import QueryItem
from .ontology.pellet_values import PelletDifferenceWarning
from .ontology.spellings import SpellingKeptWarning

__version__ = "0.1.0"

__all__ = [
    "Ontology", "ReasonReport", "QueryItem", "TopostoreError", "InvalidNameError", "InvalidValueError",
    "UnknownTypeError", "LoadError", "QueryError", "QueryTimeout", "RuleCompileError", "OntologyWarning", "Notice",
    "IncompleteOntologyError", "SpellingKeptWarning", "PelletDifferenceWarning",
]

from .armor import ArmorRequest, ArmorResponse, ArmorService  # noqa: E402  (aRMOR command interface)

__all__ += ["ArmorService", "ArmorRequest", "ArmorResponse"]
