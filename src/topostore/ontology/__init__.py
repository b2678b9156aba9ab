"""An ontology reference: the :class:`Ontology` facade over a store, its rules and its reasoner.

The package holds the facade (``facade``) and its parts: the rules, the reasoner and the report
(``reasoning``), values and changes by names (``values``), the namespace (``namespace``), loading and
saving (``files``), the read API (``reads``) and named queries (``named_queries``), the manipulation
path (``changes``), the change ledger and rollback (``ledger``), events, explanations (``explain``),
class views and n-ary axioms.
"""

from .facade import Ontology, ReasonReport

__all__ = ["Ontology", "ReasonReport"]
