"""What incremental maintenance keeps between REASONs: the state of the previous one, and the parts it
reads of the rules (indexes, the request queue, flips, deletion, the reads after maintenance, the compiled
step), made by the first REASON that maintains.

Why apart from :mod:`.incremental`: that module decides the mode and runs the phases; this one says what
they share and when it is made.  A full REASON needs none of the parts, and on a TBox of thousands of
disjoint siblings the maintained rules (one per pair of disjoint classes) are hundreds of thousands, so
they are made on the first step, with the cycle collector paused while they are.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from ..compile.rule import Rule, RuleSet
from .change_checks import ChangeChecks
from .changed import ChangedGraphs
from .compiled_step import CompiledStep
from .consistency import Violation
from .dred import Deletion, can_prove
from .early_reads import EARLY_CHECKS
from .entailed import watched_forms
from .flips import Flips
from .negation import Completion, deferred
from .outcome import Outcome
from .requests import RequestQueue
from .triggers import Present, Triggers

if TYPE_CHECKING:
    from .incremental import IncrementalReasoner


def is_monotone(rule: Rule) -> bool:
    """A rule whose matches can only grow when facts are added (DRed needs this)."""
    return rule.stratum == 0 and not rule.negates


@dataclass
class MaintenanceState:
    """What incremental maintenance needs to know about the previous REASON."""

    #: a full run with these rules has happened on this store
    ready: bool = False
    #: no rule with a negated premise (stratum > 0) matched in the previous state
    quiet: bool = False
    asserted_size: int = 0
    violations: list[Violation] = field(default_factory=list)
    #: predicates and classes with facts (a superset of those the rules and checks read: no other
    #: is asked about), to skip evaluations that cannot match
    present: Present = field(default_factory=lambda: (set(), set()))
    #: predicates and classes of asserted facts (a superset), to skip proofs that cannot succeed
    asserted: Present = field(default_factory=lambda: (set(), set()))


class Part:
    """An attribute of the reasoner that is one of its maintenance parts (:class:`MaintenanceParts`): its
    first read makes the parts, which then become the reasoner's own attributes (a step reads them
    as any other)."""

    def __set_name__(self, owner: type, name: str) -> None:
        self.name = name

    def __get__(self, obj: IncrementalReasoner | None, owner: type | None = None):
        return self if obj is None else getattr(obj.parts, self.name)


class MaintenanceParts:
    """What maintenance reads of the rules: the indexes of the maintained rules and checks (the rule
    per pair of disjoint classes among them), the request queue, the flips, the deletion phases, the
    reads after maintenance and the compiled step.

    Made by the first REASON that maintains: a full REASON needs none of it, and on a TBox of
    thousands of disjoint siblings the rules per pair are millions (:mod:`..compile.disjointness`)."""

    def __init__(self, reasoner: IncrementalReasoner) -> None:
        rules = reasoner.ruleset
        store = reasoner.store
        self.rules = rules.inference_rules
        self.monotone = [i for i, r in enumerate(self.rules) if is_monotone(r)]
        self._monotone_set = set(self.monotone)
        #: candidate rules a full REASON evaluates without the pairs whose conclusion is known, and the
        #: keys whose loss (derived; asserted) makes maintenance ask those pairs again (:mod:`.negation`)
        self.deferred = sorted(deferred(self.rules))
        self._completion = Completion(self.rules)
        self.triggers = Triggers(self.rules)
        self.checks = rules.checks
        self.check_triggers = Triggers(self.checks)
        self.negated = [r for r in self.rules if not is_monotone(r)]
        self.provers = [i for i in self.monotone if can_prove(self.rules[i])]
        #: the rules with negated premises in stratum 0, which maintenance cannot keep (a property of the
        #: rules: decided here once, not at every REASON)
        self._unmaintainable = sorted({r.name for r in self.negated if r.stratum == 0}) \
            if len(self.monotone) + len([r for r in self.negated if r.stratum > 0]) < len(self.rules) else []
        self.checks_monotone = all(not c.negates and c.stratum == 0 for c in self.checks)
        self.requests = RequestQueue(store, self.rules)
        self.flips = Flips(self.requests, self.triggers, self._monotone_set)
        self.deletion = Deletion(self.requests, self.triggers, self.monotone, self.provers)
        #: the scratch graphs of the REASON under way, read once by the reads after maintenance
        self.changed = ChangedGraphs(store, self.requests.flush, watched_forms(rules))
        #: whether a change may make a check or a negated-premise rule match (:mod:`.change_checks`)
        self.change_checks = ChangeChecks(store, self.negated, self.checks, self.check_triggers, self.changed,
                                          reasoner.kinds.decided)
        self.change_checks.state = reasoner.state
        #: the compiled step of each kind of change (see :mod:`.compiled_step`)
        self.step = CompiledStep(store, rules, self.monotone, self.requests, self.flips, self.change_checks)
        #: the reads after maintenance: consistency and the entailed-only graph (see :mod:`.outcome`)
        self.outcome = Outcome(store, rules, self.requests, self.changed, self.change_checks, self.step,
                               self.checks_monotone)


def early_checks(rules: RuleSet) -> list[Rule]:
    """The checks a full REASON may start beside its fixpoint (:mod:`.early_reads`): every check when
    they are few, else those other than the told pairs of disjoint classes (which are then checked in
    one query after the fixpoint, and never made one per pair)."""
    table = rules.disjointness
    if table is None or len(table.told) <= EARLY_CHECKS:
        return rules.checks
    return rules.base_checks


def needed_keys(rules: RuleSet) -> set:
    """The keys the maintained rules' and checks' bodies read: the rule set's own rules and the rows of its
    schema tables bound, and for the
    rows of disjoint classes one rule and one check per class (a row's keys are its classes' keys)."""
    table = rules.disjointness
    extra = table.representatives() if table is not None else []
    return Triggers([*rules.rules, *rules.held_rules(), *extra]).needed_keys()


__all__ = ["EARLY_CHECKS", "MaintenanceParts", "MaintenanceState", "Part", "early_checks", "is_monotone", "needed_keys"]
