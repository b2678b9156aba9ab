"""The compiled step: one program per kind of change, run in place of the general phases.

A robot's steps repeat a few kinds of change (the same predicates and classes added and removed, the
same values replaced); each kind is compiled once into a program of delta rules (see :mod:`.program`
and :mod:`.step_compiler`) and kept until the next full run.  On a store where every request is a
round trip the whole program is one request and the reads after it one query (:mod:`.after`);
elsewhere its rounds run staged (:mod:`.staged`).  A kind of change that cannot be compiled, or whose
program once needed more rounds than one request had, takes the general phases.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Collection
from typing import TYPE_CHECKING

from pyoxigraph import Triple

from ..compile.generic import PREFIXES
from ..compile.rule import RuleSet
from ..stores.base import Store, key_census
from . import after as after_step
from . import delta_texts as texts
from . import flip, staged_code
from .change_checks import ChangeChecks
from .component import WHOLE_ROUNDS
from .flips import Flips
from .program import Refused, Signature, StepProgram, signature
from .requests import RequestQueue
from .staged import StagedRun
from .stats import ReasonStats
from .step_compiler import StepCompiler
from .triggers import key_sets, matches

if TYPE_CHECKING:
    from .maintenance import MaintenanceState

#: Compiled steps kept (one per kind of change seen since the last full run, oldest dropped first).
MAX_PROGRAMS = 256


class CompiledStep:
    """Compiles each kind of change once and runs its program; remembers what the last run may change.

    Shares the reasoner's request queue, flips and after-maintenance reads; the reasoner passes the
    state of its last full run to each :meth:`run` and clears :attr:`programs` at a full run.
    """

    def __init__(self, store: Store, ruleset: RuleSet, monotone: list[int], requests: RequestQueue, flips: Flips,
                 checks: ChangeChecks) -> None:
        self.store = store
        self.ruleset = ruleset
        self.rules = ruleset.inference_rules
        self.requests = requests
        self.flips = flips
        self.checks = checks
        #: False runs the general phases for every change
        self.enabled = True
        self.compiler = StepCompiler(self.rules, monotone, flips._by_frequency, store.supports_lateral,
                                     cover=not store.round_trips, values=flips.sorted_values)
        #: compiled programs (or why a signature cannot be compiled) by signature, until the next full run
        self.programs: dict = {}
        #: signatures whose program in one request needed more rounds than it had: general phases for good
        self.unsettled: set = set()
        #: the last compiled step's signature, whether it had unrolled rounds, and the keys it may change
        self.last_sig = None
        self._settle = False
        #: the clean replacements of the REASON under way, by predicate (see :func:`.flip.clean_replacements`)
        self._clean: dict = {}
        self._heads: set = set()
        #: the keys the last compiled step may have added facts to or removed facts from (its program's heads,
        #: or those a staged run noted: :meth:`.staged.StagedRun.gained` and :meth:`~.staged.StagedRun.lost`)
        self.written: frozenset = frozenset()
        #: the keys that may have lost facts in the last compiled step (the remote negated-premise read),
        #: and as (predicates, classes) (:func:`.triggers.key_sets`, made once per kind of change)
        self.lost: set = set()
        self.lost_keys: tuple[set, set] = (set(), set())
        #: :func:`.flip.kind_tests_only` of a flip (rule index, changed atoms)
        self._kind_only: dict[tuple[int, tuple[int, ...]], bool] = {}
        #: per signature, after its program last ran: (program, state, :func:`_sizes` of the state, the
        #: after-step keys, the lost keys, and those as :func:`.triggers.key_sets`); see :meth:`_unchanged`
        self._ran: dict = {}

    def forget_runs(self) -> None:
        """The keys with facts may have changed outside a compiled step (the general phases, a full run):
        every program's keys are checked and noted again at its next run."""
        self._ran.clear()

    def run(self, added: Collection[Triple], removed: Collection[Triple], clean: dict,
            stats: ReasonStats, state: MaintenanceState, census: tuple | None = None,
            copy_changes: Callable[[], None] = lambda: None, lost: tuple | None = None,
            sig: Signature | None = None) -> bool:
        """Maintain with the compiled program of this kind of change (see :mod:`.program`); False
        (with the reason in ``stats.program``) when it cannot be compiled.  ``clean``: the change's
        clean replacements (:func:`.flip.replaced_in`); ``census``: :func:`key_census` of ``added``
        when the caller made it (``lost``: that of ``removed``); ``copy_changes``: writes the changes to the
        scratch graphs SPARQL text reads them from (called before the first text is sent); ``sig``: the
        change's :func:`.program.signature` when the caller has it."""
        if not self.enabled:
            stats.program = "general: compiled step switched off"
            return False
        if sig is None:
            sig = signature(census if census is not None else key_census(added),
                            lost if lost is not None else key_census(removed), clean)
        self._clean = clean
        ran = self._unchanged(sig, state)
        program = ran[0] if ran is not None else self._program(sig, state)
        if isinstance(program, str):
            stats.program = f"general: {program}"
            return False
        self.requests.scratch([r.old for p in program.flipped for r in clean[p]], flip.CHANGE_OLD)
        start = time.perf_counter()
        self.flips.state = state
        gained = lost_now = None  # the keys that may have gained / lost facts (None: any the program writes)
        if self.store.round_trips and self.store.whole_programs:  # the whole program as one request
            copy_changes()
            self.requests.flush()
            self.requests.defer(program.text(self._flip_text))
            self.requests.flush()
            stats.evaluations += program.operations
            self.last_sig, self._settle = sig, not program.whole
        else:
            self._settle = False  # the rounds run to their end here
            self.requests.flush()
            run = StagedRun(self.store, program, sig, self._flip_text, (added, removed), copy_changes, state.present)
            stats.staged = staged_code.run(run)
            stats.evaluations += run.sent
            gained = run.gained()
            lost_now = run.lost()
        if self.requests.profile:
            stats.per_rule["program"] = time.perf_counter() - start
        stats.flipped = program.flips
        stats.program = "compiled"
        self.written = program.heads if gained is None or lost_now is None else gained | lost_now
        self.checks.step_clean = program.clean
        # the keys with facts stay a superset, and no larger: a head the program never wrote keeps the
        # operations joining it left out (a staged run's ``needs``) and the program that left it out valid
        for kind, key in program.heads if gained is None else gained:
            state.present[0 if kind == "p" else 1].add(key)
        if gained is not None and lost_now is not None:  # what the reads after a staged run may leave out
            self.checks.after_step(gained, lost_now)
        if ran is None:
            #: the keys the after-step reads ask about: the asserted changes' and what the program may add
            written = frozenset(program.heads)
            heads, lost = written | frozenset(sig.added), written | frozenset(sig.removed)
            ran = self._ran[sig] = (program, state, _sizes(state), heads, lost, key_sets(lost))
        else:
            heads, lost = ran[3], ran[4]  # recorded at the program's first run
        self._heads, self.lost, self.lost_keys = heads, lost, ran[5]
        return True

    def _unchanged(self, sig, state: MaintenanceState) -> tuple | None:
        """What the last run of ``sig``'s program noted, when nothing its checks read changed since: the
        same program and state, and the keys with facts (asserted or not) no more than then.  Between
        full runs those sets only grow, in :meth:`run` (by the keys a run gained facts of) and with the
        asserted changes, and the general phases clear this record (:meth:`forget_runs`): the same sizes
        are the same keys.  Then the keys the program left out still have no facts; else None."""
        ran = self._ran.get(sig)
        if ran is None or sig in self.unsettled or ran[1] is not state or ran[0] is not self.programs.get(sig):
            return None
        if ran[2] != _sizes(state):
            return None
        return ran

    def _flip_text(self, i: int, order: tuple[int, ...], text: str, look_up_first: bool = False) -> str:
        """A compiled flip's text for this run: "" when no value changed kind and the rule only tests
        kinds (:func:`.flip.kind_tests_only`), else narrowed to the values in a window where one applies.
        ``look_up_first``: the flip's look-up operation (:mod:`.look_flip`) runs in the text's place and
        this text is asked again only where it gives up: the compiled text is given, no window made
        (finding that none applies costs a step at 8 locations ≈ 6 µs, for a text that does not run)."""
        rule = self.rules[i]
        kinds = self._kind_only.get((i, order))
        if kinds is None:  # a property of the rule: asked once
            kinds = self._kind_only[(i, order)] = flip.kind_tests_only(rule, order)
        if kinds and all(
                flip.same_kind(r) for j in order for r in self._clean.get(rule.body[j].p, ())):
            return ""
        if self.flips.quiet(i, order, self._clean):
            return ""  # a difference of values whose partners none may equal (see :mod:`.equal_values`)
        if look_up_first:
            return text
        windows = self.flips._windows(i, order)
        if not windows:
            return text
        return texts.flips(self.rules[i], order, self.store.supports_lateral, i, windows)

    def read_after(self) -> after_step.After:
        """The reads that follow a compiled step, as one query (see :mod:`.after`)."""
        preds, classes = key_sets(self._heads)
        checks = self.checks.check_branches(preds, classes, lambda c, j: self.store.supports_lateral)
        negated = self.checks.negated_branches((preds, classes), self.lost_keys, lambda i, j: self.store.supports_lateral)
        text = after_step.query(negated, checks, sorted(self.ruleset.entailed_predicates, key=lambda t: t.value),
                                self._settle)
        return after_step.read(self.store.query(text, prefixes=PREFIXES))

    def _program(self, sig, state: MaintenanceState) -> StepProgram | str:
        """The compiled program of a signature, or why there is none (cached until the next full run)."""
        if sig in self.unsettled and self.store.round_trips and self.store.whole_programs:
            return f"a recursive component needed more than {WHOLE_ROUNDS} rounds in one request before"
        program = self.programs.get(sig)
        if isinstance(program, StepProgram) and (
                any(matches(key, *state.present) for key in program.needs_absent)
                or any(matches(key, *state.asserted) for key in program.needs_unasserted)):
            program = None  # a key it left out has facts now
        if program is None:
            try:
                program = self.compiler.compile(sig, state.present, state.asserted)
            except Refused as why:
                program = str(why)
            if len(self.programs) >= MAX_PROGRAMS:  # the oldest kind of change is compiled again if it returns
                oldest = next(iter(self.programs))
                del self.programs[oldest]
                self._ran.pop(oldest, None)  # its run record names the evicted program: never reused
            self.programs[sig] = program
        return program


def _sizes(state: MaintenanceState) -> tuple[int, int, int, int]:
    """How many predicates and classes have facts, and asserted facts (sets that only grow between full runs)."""
    return len(state.present[0]), len(state.present[1]), len(state.asserted[0]), len(state.asserted[1])
