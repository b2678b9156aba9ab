"""An ontology reference: the :class:`Ontology` facade over a store, its rules and its reasoner.

The package holds the facade (``facade``), loading and saving (``files``), the read API
(``reads``) and named queries (``named_queries``), the record of asserted changes and rollback
(``journal``), events, explanations, class views and n-ary axioms.
"""

from .facade import Ontology, ReasonReport

__all__ = ["Ontology", "ReasonReport"]
