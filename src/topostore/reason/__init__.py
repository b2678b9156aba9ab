"""Reasoning: the fixpoint of the compiled rules, consistency checks, classification.

Rules and the loop that runs them are kept apart: :mod:`.materialize` only
needs a :class:`~topostore.compile.RuleSet` and a :class:`~topostore.stores.base.Store`;
:mod:`.incremental` maintains its result after asserted changes.
"""

from .classify import classify
from .consistency import Violation, check_consistency
from .incremental import IncrementalReasoner
from .materialize import Materializer
from .stats import ReasonStats

__all__ = ["IncrementalReasoner", "Materializer", "ReasonStats", "Violation", "check_consistency", "classify"]
