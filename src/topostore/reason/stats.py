"""What one REASON did: the figures a full run or incremental maintenance reports."""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import lru_cache


@dataclass
class ReasonStats:
    """What one REASON did: rounds, rule evaluations, facts derived, time."""

    rounds: int = 0
    evaluations: int = 0
    derived: int = 0
    seconds: float = 0.0
    mode: str = "full"
    #: why this mode was chosen (e.g. "schema changed", "change of 5000 triples > 10% of ...")
    reason: str = ""
    #: incremental maintenance only: facts over-deleted and put back by rederivation
    overdeleted: int = 0
    rederived: int = 0
    #: incremental only: rule evaluations replaced by one flip query (replaced values only compared)
    flipped: int = 0
    #: incremental only: "compiled" when the compiled step ran (see :mod:`.program`), with what it handed
    #: to the general phases; else why the general phases ran instead
    program: str = ""
    #: incremental only, where the compiled step ran key by key: "generated" (its program as one generated
    #: function, :mod:`.staged_code`), else "interpreted: " and why
    staged: str = ""
    per_rule: dict[str, float] = field(default_factory=dict)


@lru_cache(maxsize=256)
def incremental_reason(added: int, removed: int) -> str:
    """Why a run was incremental, by the sizes of its change (a robot's every step: one text, made once)."""
    return f"{added} added, {removed} removed asserted triples" if added or removed else "no asserted change"
