"""The operations of one compiled step program, written key by key: candidates, flips, rechecks and
additions as SPARQL texts, with their look-up equivalents where a store offers cheap look-ups
(the algorithm: :mod:`.program`)."""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING

from pyoxigraph import NamedNode

from ..compile.rule import ReadKey
from . import delta_texts as texts
from . import flip
from .component import compile_component
from .direct import Gained, Lost, OneAtom, Relaxed, one_atom, relaxable
from .look_flip import Flipped, flippable
from .look_join import Joined, joinable
from .program import (
    CHANGES,
    SEEDS,
    Refused,
    Signature,
    StepProgram,
    general_head,
    pair_atom,
)
from .regroup import Regroup, regroupable
from .restate import restates
from .scratch import ADDED, CANDIDATES, NEW_FACTS, OVERDELETED, REMOVED, target
from .triggers import Present, matches

if TYPE_CHECKING:
    from .step_compiler import StepCompiler


class Emitter:
    """Writes the operations of one program, key by key (a recursive component as one entry)."""

    def __init__(self, compiler: StepCompiler, sig: Signature, active: list[int],
                 writers: dict[ReadKey, list[int]], clean: frozenset, asserted: Present | None) -> None:
        self.c = compiler
        self.rules = compiler.rules
        self.sig = sig
        self.active = active
        #: every rule that can fire, by written key (the recheck's provers)
        self.writers = writers
        #: the graphs a look-up operation reads an atom from: those of the rules that can have written it
        #: (:meth:`.step_compiler._Writers.graphs_of`), else those of every rule writing it
        self.graphs_of = getattr(writers, "graphs_of", compiler.state_graphs.of)
        self.clean = clean
        self.asserted = asserted
        self._restated: dict[int, bool] = {}
        self._by_head: dict[ReadKey, list[int]] | None = None
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
        #: by position of a flip, the keys of its rule's atoms it does not compare (see :attr:`StepProgram.needs`)
        self.needs: dict[int, frozenset] = {}
        #: the (rule, atom) of each candidates and additions operation, by position (see :meth:`_regroup`)
        self._atom_of: dict[int, tuple[int, int]] = {}
        #: operations a regrouped candidates operation does, by position (see :attr:`StepProgram.covered`)
        self.covered: dict[int, int] = {}

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
            writers = self._active_writers().get(item, [])
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
                           self.seeded, self.part, self.reads, self.needs, covered=self.covered)

    def _active_writers(self) -> dict[ReadKey, list[int]]:
        """The active rules by the key they write, in rule order (found once: a program has a few
        hundred keys and as many active rules on a large TBox)."""
        if self._by_head is None:
            self._by_head = {}
            for i in self.active:
                self._by_head.setdefault(self.rules[i].writes(), []).append(i)
        return self._by_head

    def _plain(self, key: ReadKey, writers: list[int]) -> None:
        """A key no rule derives from itself: candidates, flips, recheck, additions."""
        graph = self.graphs[key] = self.target(key, writers)
        start = len(self.ops)
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
            if len(keeps) == 1 and key not in self.sig.removed and general_head(self.rules[keeps[0][0]], key):
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
        self._regroup(start, key, graph)

    def _regroup(self, start: int, key: ReadKey, graph: NamedNode) -> None:
        """Where the key's part (its operations from ``start``) has one candidates operation, of a rule
        :func:`.regroup.regroupable` at that atom, whose recheck is the rule's own deletion, and nothing
        else that makes candidates (no flip, no removed asserted fact of the key): that operation's look-up
        diffs the rule's heads (:class:`.regroup.Regroup`), and the deletion and the atom's additions are
        recorded as done by it where it does (:attr:`StepProgram.covered`)."""
        part = range(start, len(self.ops))
        kinds = [self.ops[n][0][0] for n in part]
        if kinds.count("minus") != 1 or kinds.count("delete") != 1 or \
                any(k not in ("minus", "delete", "plus", "end") for k in kinds):
            return
        minus = start + kinds.index("minus")
        delete = start + kinds.index("delete")
        if minus not in self._atom_of or delete not in self.direct:
            return
        i, j = self._atom_of[minus]
        plus = [n for n in part if kinds[n - start] == "plus" and self._atom_of.get(n) == (i, j)]
        if len(plus) != 1 or getattr(self.direct[delete].__self__, "rule", None) is not self.rules[i]:
            return
        if not regroupable(self.rules[i], j, self.clean,
                           lambda k: bool(self.writers.get(k)) or bool(self.writers.get(("*",)))):
            return
        regroup = Regroup(self.rules[i], j, graph, self.graphs_of)
        self.direct[minus], self.reads[minus] = regroup.run, regroup.reads
        self.covered[delete] = self.covered[plus[0]] = minus

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
                    self._atom_of[len(self.ops)] = (i, j)
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
            if ops is self.ops:
                self.needs[len(ops)] = frozenset(a.read_key() for m, a in enumerate(rule.body) if m not in order)
            if ops is self.ops and flippable(rule, order):
                flipped = Flipped(rule, order, self.graphs_of, self.c.values)
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
                    self._atom_of[len(self.ops)] = (i, j)
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
        return getattr(Joined(rule, graph, j, self.graphs_of), what)


__all__ = ["Emitter"]
