"""The compiled step: an incremental REASON as one update request, made once per kind of change.

Why this exists
---------------
A robot step changes the same few predicates every time (where it is, the
clock, when it visited a place).  The general maintenance of :mod:`.incremental`
decides what to evaluate next from what the previous phase produced, so it
reads the store between phases and re-plans long, generic SPARQL texts every
step.  But which rules a change can reach, in which order, and what each of
them must do, depends only on *which keys changed* (the predicates and classes
of the added and removed asserted facts), not on the facts themselves.  So the
whole maintenance is compiled once per such *signature* into a fixed sequence
of small SPARQL operations, sent as one update request; data-dependent
decisions (is a fact still derivable?) are made inside the operations.

The algorithm (keys in topological order of the rule dependency graph)
-----------------------------------------------------------------------
For a key no rule derives from itself (non-recursive), once everything it
reads is final:

* **candidates**: heads present before that a rule derived with a removed fact
  (one operation per rule and removed body atom; the other atoms read the old
  state, approximated from above by the new state plus the removed facts);
* **flips**: a rule that sees replaced values only through comparisons (the
  clock) is evaluated with old and new values paired (:mod:`.flip`): heads whose
  comparison turned false become candidates, those turned true are added;
* **recheck**: a candidate stays when some rule still derives it from the new
  state (``KEEP``) or it is asserted; the others are deleted and become the
  key's removed facts for the keys downstream.  A removed asserted fact that
  a rule still derives is put back as inferred;
* **additions**: heads a rule derives with an added fact (one operation per
  rule and added body atom) that are not already known.

No over-deletion and no rederivation: the recheck is exact because the key's
inputs are final.  On a store where a request costs microseconds (in memory),
:class:`StagedRun` sends the program key by key and leaves out the operations
that start from a key the step did not change after all (two index look-ups
per key tell); where each request is a round trip, the program goes as one.

A *recursive* component of keys (a key derived, through other keys, from
itself) cannot be rechecked that way: a fact could confirm itself around the
cycle.  It runs DRed inside the component instead (:mod:`.component`): round
by round in the key-by-key run, with a fixed number of rounds unrolled in the
one request (and a full run when they were not enough).

What is not compiled (the general path runs instead; ``stats.program`` says
which ran and why): rules over any predicate or any class that a change
reaches (owl:sameAs replacement), rules whose filters read changed graph
patterns, and keys whose derivations go to different graphs.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Collection
from dataclasses import dataclass, field
from typing import NamedTuple

from ..compile.condition import TEST
from ..compile.owl_restrictions import term_before
from ..compile.rule import ReadKey, Rule
from ..rdf.vocab import DIFFERENT, TYPE
from . import delta_texts as texts
from .component import COMPONENT_SCRATCH, UNSETTLED, whole_ops
from .direct import FEW

PROGRAM_SCRATCH = (texts.KEEP, texts.FLIP_LOST, UNSETTLED, *COMPONENT_SCRATCH)

#: tags of operations every run needs, and of those that seed a key's candidates (see :class:`.staged.StagedRun`)
ALWAYS, SEEDS = ("always",), ("seeds",)

_TYPE = str(TYPE)
#: ``!sameTerm(?a, ?b)`` at the start of a test or after ``&&``
_APART = re.compile(r"(?:^|&&)\s*!sameTerm\((\?\w+), (\?\w+)\)")


class Signature(NamedTuple):
    """What kind of change a REASON maintains: read keys of the added and removed asserted facts,
    and the predicates all of whose changes are clean replacements (see :func:`.flip.clean_replacements`).

    A named tuple: a REASON hashes and compares its signature four or five times (the programs, the last
    runs, the unsettled ones), a tuple's hash and equality in C where a frozen dataclass's are Python calls."""

    added: frozenset
    removed: frozenset
    clean: frozenset


@dataclass
class StepProgram:
    """The compiled maintenance of one :class:`Signature`."""

    #: the operations, each tagged with when a key-by-key run needs it (see :class:`.staged.StagedRun`);
    #: a recursive component is one entry, tagged ``("component", Component)``
    ops: list
    #: keys whose absence let the compiler leave rules out: the program holds while none has a fact
    needs_absent: frozenset
    #: keys the program may add facts to (for the reasoner's record of keys with facts)
    heads: frozenset
    #: the clean predicates whose flips the program evaluates (their old values go to CHANGE_OLD)
    flipped: frozenset = field(default_factory=frozenset)
    #: rules evaluated as flips (replaced values only compared)
    flips: int = 0
    #: the cleanly replaced predicates no rule derives (see :meth:`.emit.Emitter.idle`)
    clean: frozenset = field(default_factory=frozenset)
    #: keys whose absence from the asserted graph let rechecks be left out (see :meth:`.emit.Emitter.recheck`)
    needs_unasserted: frozenset = field(default_factory=frozenset)
    #: by position in ``ops``: the operation's equivalent through index look-ups (see :mod:`.direct`),
    #: ``run(store)`` answering False where its text must run instead
    direct: dict = field(default_factory=dict)
    #: by position of a flip in ``ops``: per compared predicate (IRI text), the flip as the one branch
    #: seeded by that predicate's atom, for a run where every fact of it was replaced
    seeded: dict = field(default_factory=dict)
    #: by position in ``ops``: the key whose part of the program the operation belongs to (None: the
    #: first operation and recursive components); every operation of a key's part writes facts of it only
    part: list = field(default_factory=list)
    #: what Python reads of the store before a part's operation (see :class:`.staged.StagedRun`): by
    #: key with a part, the keys its rules read and itself; by position of an operation in ``direct``,
    #: the keys its look-ups read
    reads: dict = field(default_factory=dict)
    #: by position of a flip in ``ops``: the keys of its rule's atoms it does not compare, without whose
    #: facts in the new state it finds nothing (see :class:`.staged.StagedRun`)
    needs: dict = field(default_factory=dict)
    #: by position: an operation a regrouped candidates operation (at the position it maps to) does where its
    #: look-up answers :data:`.regroup.REGROUPED` (its part's deletion and its atom's additions: :mod:`.regroup`)
    covered: dict = field(default_factory=dict)
    #: the operations grouped by part once, for key-by-key runs (:func:`.staged.segments`; built at the first run)
    segments: list | None = field(default=None, compare=False, repr=False)
    #: those parts as one generated function (:func:`.staged_code.generate`; made at the first run)
    fused: Callable | None = field(default=None, compare=False, repr=False)


    @property
    def whole(self) -> bool:
        """Whether the program as one request is exact whatever the data (no recursive component,
        whose unrolled rounds may not be enough)."""
        return not any(tag[0] == "component" for tag, _ in self.ops)

    def text(self, flip_text: Callable[[int, tuple, str], str]) -> str:
        """Every operation as one update request (for stores where each request is a round trip), a
        recursive component's rounds unrolled (:func:`.component.whole_ops`); ``flip_text(rule,
        order, text)`` gives a flip operation's text for this run."""
        ops: list[str] = []
        for tag, text in self.ops:
            if tag[0] == "component":
                ops += whole_ops(tag[1], flip_text)
            elif text:
                ops.append(flip_text(tag[2], tag[3], text) if tag[0] == "flip" else text)
        return " ;\n".join(op for op in ops if op)

    @property
    def operations(self) -> int:
        return sum(1 for _, text in self.ops if text)


def pair_atom(rule: Rule, j: int) -> bool:
    """Whether atom ``j`` only ever matches beside a second, different value of its subject: another
    atom on the same predicate and subject whose object a test keeps apart from it (a cardinality's
    pair of fillers, in the compiler's two forms of that test: ``!sameTerm(?a, ?b)`` as a conjunct,
    or the strict term order :func:`~..compile.owl_restrictions.term_before`).

    Where every changed subject of the predicate has exactly one value before and after the change
    (a clean replacement, see :func:`.flip.clean_replacements`), such an atom cannot match a change.
    """
    atom = rule.body[j]
    if not atom.o.startswith("?"):
        return False
    others = [o.o for k, o in enumerate(rule.body) if k != j and o.p == atom.p and o.s == atom.s and o.o.startswith("?")]
    return any(_apart(rule, atom.o, other) for other in others)


def check_pair_atom(check: Rule, j: int) -> bool:
    """:func:`pair_atom` for a consistency check, where the two values may also be kept apart by the
    check's own difference atom: a value different from itself is a violation of its own (the
    different-self check), so the two values of a clean replacement's subject cannot match anew."""
    if pair_atom(check, j):
        return True
    atom = check.body[j]
    if not atom.o.startswith("?"):
        return False
    linked = {(a.s, a.o) for a in check.body if a.p == f"<{DIFFERENT.value}>"}
    return any(o.p == atom.p and o.s == atom.s and o.o.startswith("?") and o.o != atom.o
               and ((atom.o, o.o) in linked or (o.o, atom.o) in linked)
               for k, o in enumerate(check.body) if k != j)


def _apart(rule: Rule, a: str, b: str) -> bool:
    for c in rule.conditions:
        if c.kind != TEST or a not in c.variables or b not in c.variables:
            continue
        if any({x, y} == {a, b} for x, y in _APART.findall(c.expression)):
            return True
        if c.expression in (term_before(a, b), term_before(b, a)):
            return True
    return False


def general_head(rule: Rule, key: ReadKey) -> bool:
    """Whether the rule's head matches every fact of ``key`` (variables where the key has none), each
    of its variables bound by a body atom (a BIND's result could not be asked inside NOT EXISTS, where
    the head's value is already bound)."""
    head = rule.head
    bound = set().union(*(a.variables() for a in rule.body))
    return head.s.startswith("?") and (key[0] == "t" or (head.o.startswith("?") and head.o != head.s)) \
        and head.variables() <= bound and not any(c.binds in head.variables() for c in rule.conditions if c.binds)


class Refused(Exception):
    """The signature cannot be compiled; the message says why (reported in ``stats.program``)."""


#: the tag of the program's first operation: the asserted changes are the first lost and gained facts
CHANGES = ("changes",)
_WHEN = {"always": "always", "changes": "always (the asserted changes are the first lost and gained facts)",
         "seeds": "always (seeds the key's candidates)", "recheck": "when {} has candidates",
         "keep": "when {} has candidates not kept yet", "delete": "when {} has candidates not all kept",
         "minus": "when {} lost facts", "plus": "when {} gained facts"}


def describe(program: StepProgram) -> str:
    """The program as commented SPARQL: each operation with when it runs (``topostore rules --step``)."""
    out = [f"# {program.operations} operations outside recursive components; flips of "
           + (", ".join(sorted(program.flipped)) or "none")]
    for index, (tag, text) in enumerate(program.ops):
        if index in program.seeded:
            out.append(f"# where every fact of {' or '.join(program.seeded[index])} was replaced: only the "
                       "branch seeded by its atom")
        if tag[0] == "flip":
            tag = tag[1]
        if tag[0] == "end":
            out.append(f"# ---- {tag[1][1]} done: did it lose or gain facts? (two look-ups)")
        elif tag[0] == "component":
            comp = tag[1]
            out.append(f"# ---- recursive component: {', '.join(k[1] for k in comp.keys)}\n"
                       f"#   DRed inside it: {len(comp.seeds)} seed, {sum(map(len, comp.confirm.values()))} "
                       f"confirmation, {sum(map(len, comp.inner_candidates.values()))} over-deletion, "
                       f"{sum(map(len, comp.rederive.values()))} rederivation and "
                       f"{len(comp.additions) + sum(map(len, comp.inner_additions.values()))} addition operations, "
                       "run round by round")
        else:
            when = _WHEN.get(tag[0], tag[0]).format(tag[1][1] if len(tag) > 1 else "")
            if index in program.direct:
                when += f" (by index look-ups where up to {FEW} facts are in play, in memory)"
            out.append(f"# runs {when}\n{text} ;")
    return "\n".join(out)


def signature(added_keys: tuple[dict, dict], removed_keys: tuple[dict, dict], clean: Collection[str]) -> Signature:
    """The signature of a change from the read keys of its facts (:func:`~..stores.base.key_census`)."""
    return Signature(_keys(added_keys), _keys(removed_keys), frozenset(clean))


def _keys(census: tuple[dict, dict]) -> frozenset:
    preds, classes = census
    keys = {("t", c) for c in classes}
    keys |= {("p", p) for p in preds if p != _TYPE}
    return frozenset(keys)


__all__ = ["ALWAYS", "CHANGES", "PROGRAM_SCRATCH", "Refused", "SEEDS", "Signature", "StepProgram",
           "check_pair_atom", "describe", "general_head", "pair_atom", "signature"]
