"""Compilation of an ontology's axioms and SWRL rules into :class:`Rule` values.

The data path reads top-down: :mod:`.rule` defines the value, :mod:`.class_expressions`
reads OWL class expressions and :mod:`.tbox_reader` the axioms using them from the asserted graph into the
values of :mod:`.model`, :mod:`.owl` turns them into rules, :mod:`.swrl` turns SWRL rules into rules (with
:mod:`.builtins` for swrlb), and :func:`compile_ontology` puts them together.
"""

from .pipeline import compile_ontology
from .rule import Atom, Rule, RuleSet

__all__ = ["Atom", "Rule", "RuleSet", "compile_ontology"]
