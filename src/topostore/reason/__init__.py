"""Reasoning: the fixpoint of the compiled rules, consistency checks, classification.

Rules and the loop that runs them are kept apart: :mod:`.materialize` only
needs a :class:`~topostore.compile.RuleSet` and a :class:`~topostore.store.Store`;
:mod:`.incremental` maintains its result after asserted changes.
"""

from .consistency import Violation, check_consistency
from .materialize import Materializer, ReasonStats
from .classify import classify
from .incremental import IncrementalReasoner

__all__ = ["IncrementalReasoner", "Materializer", "ReasonStats", "Violation", "check_consistency", "classify"]
