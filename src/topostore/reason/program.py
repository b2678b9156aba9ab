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
from dataclasses import dataclass, field, replace

from pyoxigraph import NamedNode

from ..compile.condition import TEST
from ..compile.owl_restrictions import term_before
from ..compile.rule import ReadKey, Rule
from ..rdf.vocab import DIFFERENT, TYPE
from . import delta_texts as texts
from . import flip
from .component import COMPONENT_SCRATCH, UNSETTLED, compile_component, whole_ops
from .direct import FEW, Gained, Lost, OneAtom, Relaxed, one_atom, relaxable
from .look_flip import Flipped, flippable
from .look_join import Joined, joinable
from .order import strongly_connected
from .restate import covering, restates
from .scratch import ADDED, CANDIDATES, NEW_FACTS, OVERDELETED, REMOVED, target
from .triggers import Present, matches

PROGRAM_SCRATCH = (texts.KEEP, texts.FLIP_LOST, UNSETTLED, *COMPONENT_SCRATCH)

#: tags of operations every run needs, and of those that seed a key's candidates (see :class:`.staged.StagedRun`)
ALWAYS, SEEDS = ("always",), ("seeds",)

_TYPE = str(TYPE)
#: ``!sameTerm(?a, ?b)`` at the start of a test or after ``&&``
_APART = re.compile(r"(?:^|&&)\s*!sameTerm\((\?\w+), (\?\w+)\)")


@dataclass(frozen=True)
class Signature:
    """What kind of change a REASON maintains: read keys of the added and removed asserted facts,
    and the predicates all of whose changes are clean replacements (see :func:`.flip.clean_replacements`)."""

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
    #: the cleanly replaced predicates no rule derives (see :meth:`_Emitter.idle`)
    clean: frozenset = field(default_factory=frozenset)
    #: keys whose absence from the asserted graph let rechecks be left out (see :meth:`_Emitter.recheck`)
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


def _general_head(rule: Rule, key: ReadKey) -> bool:
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


class StepCompiler:
    """Compiles signatures into :class:`StepProgram` operations for one rule set.

    ``rules``: the inference rules; ``monotone``: the indexes maintained (stratum 0, no negation);
    ``order``: for a flipped rule and its compared atoms, the order of the flip branches
    (:meth:`.flips.Flips._by_frequency`); ``lateral``: whether the store evaluates LATERAL;
    ``cover``: whether covered rules may be left out (:func:`.restate.covering`).  A store where
    every request is a round trip gets the whole program in one request, and there they are kept:
    one SPARQL server (Virtuoso 7) answered such a long request without them differently from the
    same operations sent one by one.
    """

    def __init__(self, rules: list[Rule], monotone: Collection[int],
                 order: Callable[[int, tuple[int, ...]], tuple[int, ...]], lateral: bool, cover: bool = True) -> None:
        self.rules = rules
        self.monotone = sorted(monotone)
        self.order = order
        self.lateral = lateral
        self._flat: dict[int, Rule] = {}
        self.filter_vars = {i: flip.filter_variables(rules[i]) for i in self.monotone}
        self._cover = cover
        self._covered: dict[int, ReadKey] | None = None

    @property
    def covered(self) -> dict[int, ReadKey]:
        """Rules that add nothing while a premise only matches derived facts (see :func:`.restate.covering`),
        found when the first step is compiled (a full REASON does not need them)."""
        if self._covered is None:
            self._covered = covering(self.rules, self.monotone) if self._cover else {}
        return self._covered

    def compile(self, sig: Signature, present: Present, asserted: Present | None = None) -> StepProgram:
        """The program of ``sig`` given the keys with facts (``present``) and with asserted facts
        (``asserted``, a superset; None: any); raises :class:`Refused`."""
        left_out = self._left_out(sig, asserted)
        active, affected, absent = self._affected(sig, present, left_out)
        writers = self._writers(present, affected, absent, left_out)
        # a replaced value that a rule may also derive is not a clean replacement (see :mod:`.flip`)
        clean = {p for p in sig.clean if not writers.get(("p", p))}
        emitter = _Emitter(self, sig, active, writers, frozenset(clean), asserted)
        emitter.unasserted.update(self.covered[i] for i in left_out)
        return emitter.emit(self._components(active, affected, emitter.idle), absent)

    def _left_out(self, sig: Signature, asserted: Present | None) -> set[int]:
        """The covered rules whose premise has no asserted fact, now or from this change: they add
        nothing (:func:`.restate.covering`).  None known of the asserted facts: none."""
        if asserted is None:
            return set()
        changed = sig.added | sig.removed
        return {i for i, key in self.covered.items() if key not in changed and not matches(key, *asserted)}

    def _writers(self, present: Present, affected: set, absent: set,
                 left_out: Collection[int]) -> dict[ReadKey, list[int]]:
        """Every maintained rule that can fire (its body keys have facts, now or from this change), by
        the key it writes: a recheck must ask all of them, changed premises or not."""
        writers: dict[ReadKey, list[int]] = {}
        for i in self.monotone:
            if i in left_out:
                continue
            rule = self.rules[i]
            missing = self._missing(rule, present, affected)
            if missing:
                absent |= missing
                continue
            writers.setdefault(rule.writes(), []).append(i)
        return writers

    def _affected(self, sig: Signature, present: Present, left_out: Collection[int]) -> tuple[list[int], set, set]:
        """The rules a change of ``sig`` can make fire, the keys they may change, and the keys whose
        absence left rules out."""
        affected = set(sig.added | sig.removed)
        active: dict[int, None] = {}
        absent: set = set()
        grew = True
        while grew:
            grew = False
            for i in self.monotone:
                rule = self.rules[i]
                if i in active or i in left_out or not self._reaches(rule, affected):
                    continue
                missing = self._missing(rule, present, affected)
                if missing:
                    absent |= missing
                    continue
                self._check_compilable(rule, affected)
                active[i] = None
                if rule.writes() not in affected:
                    affected.add(rule.writes())
                    grew = True
        return list(active), affected, absent

    @staticmethod
    def _reaches(rule: Rule, affected: set) -> bool:
        reads = rule.reads()
        if ("*",) in reads or ("p", _TYPE) in reads:
            return bool(affected)
        return bool(reads & affected)

    @staticmethod
    def _missing(rule: Rule, present: Present, affected: set) -> set:
        """Body keys without any fact, now or from this change (the rule cannot match)."""
        preds, classes = present
        missing = set()
        for atom in rule.body:
            key = atom.read_key()
            if not atom.p.startswith("<") or key in affected:
                continue  # a variable predicate or a path may match anything
            if key[1] not in (classes if key[0] == "t" else preds):
                missing.add(key)
        return missing

    @staticmethod
    def _check_compilable(rule: Rule, affected: set) -> None:
        if ("*",) in rule.reads() or rule.writes() == ("*",):
            raise Refused(f"rule {rule.name} reads or writes any predicate")
        if ("p", _TYPE) in rule.reads() or rule.writes() == ("p", _TYPE):
            raise Refused(f"rule {rule.name} reads or writes any class")
        if rule.filter_reads & affected or rule.conditions_read_graph:
            raise Refused(f"rule {rule.name} has a filter reading facts")

    def _components(self, active: list[int], affected: set,
                    idle: Callable[[int, int], bool]) -> list[list[ReadKey]]:
        """The strongly connected components of the affected keys, in topological order, without the
        edges of atoms whose changes cannot change the rule's conclusions (``idle``)."""
        keys = sorted(affected)
        number = {k: n for n, k in enumerate(keys)}
        succ: dict[int, set[int]] = {n: set() for n in range(len(keys))}
        for i in active:
            rule = self.rules[i]
            head = number[rule.writes()]
            in_body = {atom.read_key() for atom in rule.body}
            live = {atom.read_key() for j, atom in enumerate(rule.body) if not idle(i, j)}
            for key in live | (rule.reads() - in_body):
                if key in number:
                    succ[number[key]].add(head)
        found = strongly_connected(list(range(len(keys))), {n: sorted(s) for n, s in succ.items()})
        return [[keys[n] for n in comp] if len(comp) > 1 or comp[0] in succ[comp[0]] else keys[comp[0]]
                for comp in found]

    def flat(self, i: int) -> Rule:
        """Rule ``i`` with its helper-graph atoms read from the dataset's default graph (for the old
        state, whose removed helper facts are in OVERDELETED, not in the helper graph)."""
        rule = self._flat.get(i)
        if rule is None:
            rule = self.rules[i]
            if any(a.aux for a in rule.body):
                rule = replace(rule, body=tuple(replace(a, aux=False) for a in rule.body))
            self._flat[i] = rule
        return rule


class _Emitter:
    """Writes the operations of one program, key by key (a recursive component as one entry)."""

    def __init__(self, compiler: StepCompiler, sig: Signature, active: list[int],
                 writers: dict[ReadKey, list[int]], clean: frozenset, asserted: Present | None) -> None:
        self.c = compiler
        self.rules = compiler.rules
        self.sig = sig
        self.active = active
        #: every rule that can fire, by written key (the recheck's provers)
        self.writers = writers
        self.clean = clean
        self.asserted = asserted
        self._restated: dict[int, bool] = {}
        #: keys whose absence from the asserted graph let a recheck be left out
        self.unasserted: set[ReadKey] = set()
        #: keys that may have lost facts / gained facts so far (their changes are in OVERDELETED / NEW_FACTS)
        self.minus: set = set(sig.removed)
        self.plus: set = set(sig.added)
        self.ops: list[tuple[tuple, object]] = [(CHANGES, f"ADD SILENT {REMOVED} TO {OVERDELETED} ; "
                                                           f"ADD SILENT {ADDED} TO {NEW_FACTS}")]
        self.flipped: set[str] = set()
        self.flip_rules = 0
        #: the keys the program may change, with the graph their derived facts live in
        self.graphs: dict[ReadKey, NamedNode] = {}
        #: operations with an equivalent through index look-ups, by position (see :mod:`.direct`)
        self.direct: dict[int, Callable] = {}
        #: flips as one branch, by position and seed predicate (see :attr:`StepProgram.seeded`)
        self.seeded: dict[int, dict[str, str]] = {}
        #: the key of each operation's part, and what each part reads (see :attr:`StepProgram.part`)
        self.part: list[ReadKey | None] = []
        self.reads: dict[ReadKey, frozenset] = {}

    def op(self, ops: list, tag: tuple, text: str, direct: Callable | None = None) -> None:
        """Append an operation to ``ops`` (the program's own: with its look-up equivalent, if any, a
        method of an object of :mod:`.direct` that tells the keys it ``reads``)."""
        if direct is not None and ops is self.ops:
            self.direct[len(ops)] = direct
            self.reads[len(ops)] = direct.__self__.reads
        ops.append((tag, text))

    def emit(self, components: list, absent: set) -> StepProgram:
        for item in components:
            if isinstance(item, list):
                self.ops.append((("component", compile_component(self, item)), ""))
                self.part += [None] * (len(self.ops) - len(self.part))
                continue
            writers = [i for i in self.active if self.rules[i].writes() == item]
            # a removed asserted fact that some rule still derives stays, as inferred
            if writers or (item in self.sig.removed and self.writers.get(item)):
                start = len(self.ops)
                self.part += [None] * (start - len(self.part))
                self._plain(item, writers)
                self.part += [item] * (len(self.ops) - start)
                self.reads[item] = frozenset({item}.union(
                    *(self.rules[i].reads() for i in {*writers, *self.writers.get(item, ())})))
        self.part += [None] * (len(self.ops) - len(self.part))
        return StepProgram(self.ops, frozenset(absent), frozenset(self.graphs), frozenset(self.flipped),
                           self.flip_rules, self.clean, frozenset(self.unasserted), self.direct,
                           self.seeded, self.part, self.reads)

    def _plain(self, key: ReadKey, writers: list[int]) -> None:
        """A key no rule derives from itself: candidates, flips, recheck, additions."""
        graph = self.graphs[key] = self.target(key, writers)
        seeded = self._candidates(writers)
        flipped = self.flip_ops(writers, self.ops, SEEDS)
        # the flipped-true heads before the recheck, where each is proven by its flip's rule in the new
        # state (no recheck deletes it): the recheck then goes out with what follows, not alone
        early = flipped and not any(self.restated(i) for i in flipped)
        if early:
            self._gained(key, graph)
        if key in self.sig.removed:
            self.ops.append((SEEDS, texts.copy(key, REMOVED, (CANDIDATES,))))
        if seeded or flipped or key in self.sig.removed:
            recheck = ("recheck", key)
            # provers whose premises the step left alone first: the likeliest to keep every candidate
            provers = sorted(self.writers.get(key, []), key=lambda i: bool(self.rules[i].reads() & (self.minus | self.plus)))
            keeps = [(i, text) for i, text in ((i, self.recheck(i)) for i in provers) if text]
            if len(keeps) == 1 and key not in self.sig.removed and _general_head(self.rules[keeps[0][0]], key):
                i = keeps[0][0]  # one prover, whose head matches every fact of the key: ask it inside the deletion
                self.op(self.ops, ("delete", key), texts.recheck_one(self.rules[i], graph, self.restated(i)),
                        self._joined(i, graph, "delete"))
            else:
                for i, text in keeps:
                    self.op(self.ops, ("keep", key), text,
                            self._one_atom(i, graph, "keep") or self._joined(i, graph, "keep"))
                self.ops.append((("delete", key), texts.recheck(key, graph)))
            if key in self.sig.removed:
                self.ops.append((recheck, texts.restore(key, graph)))
            self.minus.add(key)
        added = self._additions(writers, graph)
        if flipped and not early:
            self._gained(key, graph)
        if added or flipped:
            self.plus.add(key)
        self.ops.append((("end", key), ""))

    def _gained(self, key: ReadKey, graph: NamedNode) -> None:
        """The key's flipped-true heads not known yet, into its graph and NEW_FACTS."""
        self.op(self.ops, ("gained", key), texts.gained(key, (graph, NEW_FACTS)), Gained(key, graph).run)

    def target(self, key: ReadKey, writers: list[int]) -> NamedNode:

        """The graph the key's derived facts live in (one for all its rules, else :class:`Refused`)."""
        graphs = {target(self.rules[i]) for i in self.writers.get(key, writers)}
        if len(graphs) != 1:
            raise Refused(f"facts of {key[1]} are derived into different graphs")
        return graphs.pop()

    def idle(self, i: int, j: int) -> bool:
        """Whether a change of atom ``j``'s facts cannot change what rule ``i`` concludes in this step:

        * the atom is on a cleanly replaced predicate and only matches beside a second value of its
          subject (:func:`pair_atom`): it cannot match a change;
        * the rule only restates a premise of every derivation of the atom's facts, and no asserted
          fact of the atom's key changed (:func:`.restate.restates`): a derived fact's premise held
          before it, so the rule never supports anything else.
        """
        rule = self.rules[i]
        if rule.body[j].p in self.clean and pair_atom(rule, j):
            return True
        return self.restated(i)

    def restated(self, i: int) -> bool:
        """Whether rule ``i`` only restates a premise (see :mod:`.restate`), decided once per program."""
        found = self._restated.get(i)
        if found is None:
            found = self._restated[i] = restates(self.rules, i, self.writers, self.sig.added | self.sig.removed,
                                                 self.asserted, self.unasserted)
        return found

    def recheck(self, i: int) -> str:
        """Rule ``i``'s recheck of its key's candidates: from the new state, or, for a rule that only
        restates a premise, from the asserted facts of its premise ("" when there are none)."""
        rule = self.rules[i]
        if not self.restated(i):
            return texts.keep(rule, self.c.lateral)
        key = rule.body[0].read_key()
        if rule.body[0].aux or (self.asserted is not None and not matches(key, *self.asserted)):
            self.unasserted.add(key)
            return ""
        return texts.keep_asserted(rule)

    def handled(self, i: int) -> tuple[int, ...] | None:
        """Rule ``i``'s changed atoms when all are flips (see :func:`.flip.flip_atoms`)."""
        changed = self.minus | self.plus
        return flip.flip_atoms(self.rules[i], self.clean, changed.__contains__)

    def _candidates(self, writers: list[int]) -> bool:
        """Heads present before that a rule derived with a removed fact go to CANDIDATES."""
        emitted = False
        for i in writers:
            handled = set(self.handled(i) or ())
            for j, atom in enumerate(self.rules[i].body):
                if atom.read_key() in self.minus and j not in handled and not self.idle(i, j):
                    self.op(self.ops, ("minus", atom.read_key()), self.candidates(i, j),
                            self._one_atom(i, target(self.rules[i]), "candidates") or self._relaxed(i, j))
                    emitted = True
        return emitted

    def candidates(self, i: int, j: int) -> str:
        """The candidates of rule ``i`` from the removed facts of atom ``j`` (see :func:`.delta_texts.candidates`)."""
        body = self.rules[i].body
        added_only = [k for k, atom in enumerate(body) if k != j and atom.read_key() in self.sig.added
                      and not self.writers.get(atom.read_key())]
        return texts.candidates(self.c.flat(i), j, OVERDELETED, self.c.lateral, not_added=added_only)

    def flip_ops(self, writers: list[int], ops: list, tag: tuple) -> list[int]:
        """Per rule seeing replaced values only through comparisons, the operation sending the heads
        whose comparison flipped to FLIP_LOST or FLIP_GAINED, then the lost ones present to
        CANDIDATES; appended to ``ops``.  Returns the rules."""
        found = []
        for i in writers:
            rule = self.rules[i]
            compared = tuple(j for j in self.handled(i) or () if rule.body[j].o[1:] in self.c.filter_vars[i])
            if not compared:
                continue  # replaced values the rule does not look at: nothing flips
            self.flipped.update(rule.body[j].p for j in compared)
            self.flip_rules += 1
            order = self.c.order(i, compared)
            # the text is made per run when a value window narrows the flip (see :mod:`.window`)
            if ops is self.ops and len(order) > 1:
                self.seeded[len(ops)] = {
                    rule.body[j].p: texts.flips(rule, (j, *(m for m in order if m != j)), self.c.lateral, i, seeded=True)
                    for j in order}
            if ops is self.ops and flippable(rule, order):
                flipped = Flipped(rule, order)
                self.direct[len(ops)], self.reads[len(ops)] = flipped.run, flipped.reads
            ops.append((("flip", tag, i, order), texts.flips(rule, order, self.c.lateral, i)))
            found.append(i)
        for key in sorted({self.rules[i].writes() for i in found}):
            graph = self.target(key, found)
            self.op(ops, ("lost", key), texts.lost(key, graph), Lost(key, graph).run)
        return found

    def _additions(self, writers: list[int], graph: NamedNode) -> bool:
        """Heads a rule derives with an added fact, not known yet: into their graph and NEW_FACTS."""
        emitted = False
        for i in writers:
            handled = set(self.handled(i) or ())
            for j, atom in enumerate(self.rules[i].body):
                if atom.read_key() in self.plus and j not in handled and not self.idle(i, j):
                    self.op(self.ops, ("plus", atom.read_key()),
                            texts.additions(self.rules[i], j, NEW_FACTS, (graph, NEW_FACTS), self.c.lateral),
                            self._one_atom(i, graph, "additions") or self._joined(i, graph, "additions", j))
                    emitted = True
        return emitted

    def _relaxed(self, i: int, j: int) -> Callable | None:
        """Rule ``i``'s candidates from atom ``j``, widened to look-ups (see :class:`.direct.Relaxed`)."""
        rule = self.rules[i]
        return Relaxed(rule, j, target(rule)).run if relaxable(rule, j) else None

    def _one_atom(self, i: int, graph: NamedNode, what: str) -> Callable | None:
        """Rule ``i``'s ``what`` (candidates, keep, additions) through index look-ups, when it is a
        rule with one atom and no filter whose recheck reads the new state (see :mod:`.direct`)."""
        rule = self.rules[i]
        if not one_atom(rule) or (what == "keep" and self.restated(i)):
            return None
        return getattr(OneAtom(rule, graph), what)

    def _joined(self, i: int, graph: NamedNode, what: str, j: int | None = None) -> Callable | None:
        """Rule ``i``'s ``what`` (keep, delete, additions from atom ``j``) by a look-up join with its
        conditions decided in Python, when every condition is in the evaluated subset and the recheck
        reads the new state (see :mod:`.look_join`)."""
        if self.restated(i) and what != "additions":
            return None
        rule = self.rules[i]
        if not joinable(rule):
            return None
        return getattr(Joined(rule, graph, j), what)


__all__ = ["ALWAYS", "PROGRAM_SCRATCH", "Refused", "SEEDS", "Signature", "StepCompiler", "StepProgram",
           "check_pair_atom", "describe", "pair_atom", "signature"]
