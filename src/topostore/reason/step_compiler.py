"""The step compiler: which rules a signature's change reaches, in which order, and the program that
maintains them (:class:`.program.StepProgram`); the operations themselves are written by
:class:`.emit.Emitter`.  The algorithm is described in :mod:`.program`."""

from __future__ import annotations

from collections.abc import Callable, Collection, Iterator, Mapping
from dataclasses import replace

from ..compile.rule import ReadKey, Rule
from ..rdf.collector import collector_paused
from ..rdf.vocab import TYPE
from . import flip
from .emit import Emitter
from .look_join import StateGraphs
from .order import strongly_connected
from .program import (
    Refused,
    Signature,
    StepProgram,
)
from .restate import Covering
from .triggers import Present, matches

_TYPE = str(TYPE)


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
                 order: Callable[[int, tuple[int, ...]], tuple[int, ...]], lateral: bool, cover: bool = True,
                 values: Callable[[str], object] | None = None) -> None:
        """``values``: a compared predicate's sorted value index, or None (see :meth:`.flips.Flips.sorted_values`),
        for the windows of the look-up flips; None: they read every compared fact."""
        self.rules = rules
        self.values = values
        self.monotone = sorted(monotone)
        self.order = order
        self.lateral = lateral
        self._flat: dict[int, Rule] = {}
        self.filter_vars = {i: flip.filter_variables(rules[i]) for i in self.monotone}
        self._cover = cover
        self._covering: Covering | None = None
        #: the graphs a look-up operation reads an atom's facts from (see :class:`.look_join.StateGraphs`)
        self.state_graphs = StateGraphs(rules)
        self._index: _Index | None = None

    @property
    def index(self) -> _Index:
        """The maintained rules indexed for a step's compilation, built by the first (a full REASON
        does not need it)."""
        if self._index is None:
            with collector_paused():  # a rule per pair of disjoint classes indexed: see ..rdf.collector
                self._index = _Index(self.rules, self.monotone)
        return self._index

    @staticmethod
    def _available(key: ReadKey, present: Present, affected: set) -> bool:
        """Whether ``key`` has facts, now or from this change."""
        return key in affected or key[1] in (present[1] if key[0] == "t" else present[0])

    @property
    def covering(self) -> Covering | None:
        """Rules that add nothing while a premise only matches derived facts (see :func:`.restate.covering`),
        asked rule by rule as steps reach them (a full REASON does not need them); None when covered
        rules are kept."""
        if self._covering is None and self._cover:
            with collector_paused():  # every rule indexed (one per pair of disjoint classes): see ..rdf.collector
                self._covering = Covering(self.rules, self.monotone)
        return self._covering

    @property
    def covered(self) -> dict[int, ReadKey]:
        """Every covered rule, by the premise key it is covered at (what the steps ask rule by rule)."""
        found = self.covering
        if found is None:
            return {}
        return {i: key for i in self.monotone if (key := found.key(i)) is not None}

    def compile(self, sig: Signature, present: Present, asserted: Present | None = None) -> StepProgram:
        """The program of ``sig`` given the keys with facts (``present``) and with asserted facts
        (``asserted``, a superset; None: any); raises :class:`Refused`."""
        left_out = _LeftOut(self.covering if asserted is not None else None, sig, asserted)
        active, affected, absent, missed = self._affected(sig, present, left_out)
        writers = _Writers(self, present, affected, absent, left_out, active, missed)
        # a replaced value that a rule may also derive is not a clean replacement (see :mod:`.flip`)
        clean = {p for p in sig.clean if not writers.get(("p", p))}
        emitter = Emitter(self, sig, active, writers, frozenset(clean), asserted)
        # the premises of the rules left out, as they are found (the emitter asks about writers too)
        emitter.unasserted = left_out.unasserted
        return emitter.emit(self._components(active, affected, emitter.idle), absent)

    def _affected(self, sig: Signature, present: Present,
                  left_out: _LeftOut) -> tuple[list[int], set, set, dict[int, set]]:
        """The rules a change of ``sig`` can make fire, the keys they may change, the keys whose
        absence left rules out, and the rules left out by the keys they missed.

        A worklist over the readers of each key as it becomes affected: a rule is looked at again only
        when a key it reads joins (which is also when a key it missed may have), so the work follows
        what the change reaches.  The rules are returned in rule order."""
        affected = set(sig.added | sig.removed)
        active: set[int] = set()
        absent: set = set()
        #: a rule left out, by the body keys it missed: only one of those joining can change that
        missed: dict[int, set] = {}
        # (rule, the key whose joining queued it: None for the change's own keys, looked at in any case)
        todo: list[tuple[int, ReadKey | None]] = []

        def reached(key: ReadKey, joined: ReadKey | None) -> None:
            """Queue the readers of ``key`` whose guard has facts; a guard joining later queues them
            as a key they read (a guard is a body key)."""
            for guard, group in self.index.readers.get(key, {}).items():
                if guard is None or self._available(guard, present, affected):
                    todo.extend((n, joined) for n in group)
                else:
                    absent.add(guard)

        for key in affected:
            reached(key, None)
        if affected:
            todo += [(i, None) for i in self.index.wild]
        while todo:
            i, joined = todo.pop()
            if i in active or (i in missed and joined not in missed[i]):
                continue
            rule = self.rules[i]
            missing = self._missing(i, present, affected)
            if missing:
                absent |= missing
                missed[i] = missing
                continue
            missed.pop(i, None)
            if i in left_out:  # asked of the rules that could fire only (a covering is found per rule)
                continue
            self._check_compilable(rule, affected)
            active.add(i)
            key = rule.writes()
            if key not in affected:
                affected.add(key)
                reached(key, key)
        for i in active:  # a key a filter reads may have joined after its rule did
            self._check_compilable(self.rules[i], affected)
        return sorted(active), affected, absent, missed

    def _missing(self, i: int, present: Present, affected: set) -> set:
        """Body keys of rule ``i`` without any fact, now or from this change (the rule cannot match)."""
        preds, classes = present
        return {key for key in self.index.keys[i]
                if key not in affected and key[1] not in (classes if key[0] == "t" else preds)}

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


class _Index:
    """The maintained rules by the keys they read (and then by a guard), those reading any predicate or
    class apart, and by the key they write (and a guard): a step's compilation then visits the rules
    its change reaches whose guards have facts, not all of them (a 400-class TBox has tens of
    thousands, most on classes without members).

    A rule's guard is a body key other than the one it is found by that must have facts for the rule
    to match, a class first (most classes of a large TBox have no member); None when there is none.
    A rule whose guard has no facts is left out with that key alone as the reason: the rule cannot
    match before the guard has facts, and then a program that named it is compiled again."""

    def __init__(self, rules: list[Rule], monotone: Collection[int]) -> None:
        self.readers: dict[ReadKey, dict[ReadKey | None, list[int]]] = {}
        self.wild: list[int] = []
        self.by_head: dict[ReadKey, dict[ReadKey | None, list[int]]] = {}
        #: per rule, the read keys of its body atoms with a named predicate (a variable predicate or a
        #: path may match anything)
        self.keys: dict[int, tuple[ReadKey, ...]] = {}
        readers, by_head, all_keys = self.readers, self.by_head, self.keys  # bound once: a large TBox
        wild = (("*",), ("p", _TYPE))  # gives tens of thousands of rules, one per pair of disjoint classes
        for i in monotone:
            rule = rules[i]
            keys = all_keys[i] = tuple(dict.fromkeys([a.read_key() for a in rule.body if a.p[0] == "<"]))
            guard = _guard(keys, None)
            reads = rule.reads()
            if wild[0] in reads or wild[1] in reads:
                # reached by any change; looked at again when a key it missed joins (a body key)
                self.wild.append(i)
                for key in keys:
                    readers.setdefault(key, {}).setdefault(None, []).append(i)
            else:
                for key in reads:
                    by_guard = readers.setdefault(key, {})
                    by_guard.setdefault(guard if guard != key else _guard(keys, key), []).append(i)
            by_head.setdefault(rule.writes(), {}).setdefault(guard, []).append(i)


def _guard(keys: tuple[ReadKey, ...], key: ReadKey | None) -> ReadKey | None:
    """The first class key of ``keys`` other than ``key``, else the first other key, else None."""
    first = None
    for k in keys:
        if k != key:
            if k[0] == "t":
                return k
            if first is None:
                first = k
    return first


class _LeftOut:
    """The covered rules whose premise has no asserted fact, now or from this change: they add nothing
    (:func:`.restate.covering`).  Asked rule by rule; the premise keys of those found are collected in
    ``unasserted`` (the program's ``needs_unasserted``: it is compiled again once they have asserted
    facts).  No covering, or none known of the asserted facts: none."""

    def __init__(self, covering: Covering | None, sig: Signature, asserted: Present | None) -> None:
        self._covering, self._asserted = covering, asserted
        self._changed = sig.added | sig.removed
        self._seen: dict[int, bool] = {}
        self.unasserted: set[ReadKey] = set()

    def __contains__(self, i: object) -> bool:
        if self._covering is None or self._asserted is None or not isinstance(i, int):
            return False
        out = self._seen.get(i)
        if out is None:
            key = self._covering.key(i)
            out = self._seen[i] = key is not None and key not in self._changed and not matches(key, *self._asserted)
            if out:
                self.unasserted.add(key)
        return out


class _Writers(Mapping):
    """Every maintained rule that can fire (its body keys have facts, now or from this change), by the
    key it writes: a recheck must ask all of them, changed premises or not.

    Found per key when the emitter first asks: it asks about the keys the change reaches and the
    premises of their rules, a few of the keys the rules write.  A rule :meth:`StepCompiler._affected`
    looked at is known (active, or left out by the keys it missed); the keys whose absence left a
    rule out are added to ``absent`` as found (the program's ``needs_absent``, read when the emitter
    is done)."""

    def __init__(self, compiler: StepCompiler, present: Present, affected: set, absent: set,
                 left_out: _LeftOut, active: Collection[int], missed: dict[int, set]) -> None:
        self._c, self._present, self._affected, self._absent = compiler, present, affected, absent
        self._left_out, self._active, self._missed = left_out, frozenset(active), missed
        self._found: dict[ReadKey, list[int]] = {}

    def __getitem__(self, key: ReadKey) -> list[int]:
        found = self._found.get(key)
        if found is None:
            found = self._found[key] = []
            for guard, group in self._c.index.by_head.get(key, {}).items():
                if guard is None or self._c._available(guard, self._present, self._affected):
                    found += [i for i in group if self._fires(i)]
                else:
                    self._absent.add(guard)
            found.sort()
        if not found:
            raise KeyError(key)
        return found

    def graphs_of(self, atom) -> tuple:
        """The graphs a look-up operation reads ``atom``'s facts from: those of the rules writing its key
        that can have fired (:meth:`.look_join.StateGraphs.firing`; the premises that left a graph out
        join the program's ``needs_absent``)."""
        return self._c.state_graphs.firing(atom, self._present, self._affected, self._absent)

    def _fires(self, i: int) -> bool:
        if i in self._active:
            return True
        missing = self._missed.get(i)
        if missing is None:
            missing = self._c._missing(i, self._present, self._affected)
        self._absent |= missing
        return not missing and i not in self._left_out

    def __iter__(self) -> Iterator[ReadKey]:
        return iter(self._c.index.by_head)

    def __len__(self) -> int:
        return len(self._c.index.by_head)


__all__ = ["StepCompiler"]
