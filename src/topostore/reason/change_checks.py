"""Whether a maintained change may make a consistency check or a rule with a negated premise match.

After maintenance the state is consistent and quiet (no negated premise matched) unless a check or
a negated-premise rule matches with at least one body atom on a fact the change made new (or, for
a negated premise, a key that lost facts): these are semi-naive ASKs, one group per such atom, made
once per shape of change (:func:`.changed.shape`).  Groups that cannot match after a compiled step
are left out: a pair of values of one subject on a cleanly replaced predicate, and range checks whose
new values surely lie in the range.  The reasoner asks here after the general phases; the compiled
step's after-step query (:mod:`.after`) takes the same groups as branches.
"""

from __future__ import annotations

from collections.abc import Collection

from pyoxigraph import Literal, Triple

from ..compile.datatypes import text_surely_in
from ..compile.generic import PREFIXES
from ..compile.rule import Rule
from ..rdf.vocab import ASSERTED, AUX, INFERRED, TYPE
from ..stores.base import Store
from .changed import ChangedGraphs, shape
from .kinds import Decisions
from .plan import is_small, plan_where
from .program import check_pair_atom, pair_atom
from .scratch import NEW_FACTS, OVERDELETED
from .triggers import Present, Triggers, key_sets, matches

#: rdf:type as a read key's text
_TYPE_KEY = str(TYPE)


class ChangeChecks:
    """The semi-naive reads after maintenance: may a check or a negated-premise rule match now?

    Holds the texts of the groups (rules never change) and, per REASON, what the compiled step
    settled: the cleanly replaced predicates no rule derives and the asserted additions.  The
    reasoner sets :attr:`state` to the state of the last full run, and :attr:`step_clean` and
    :attr:`added_now` per REASON.
    """

    def __init__(self, store: Store, negated: list[Rule], checks: list[Rule], check_triggers: Triggers,
                 changed: ChangedGraphs, decided: Decisions) -> None:
        self.store = store
        self.negated = negated
        self.negated_triggers = Triggers(negated)
        self.checks = checks
        self.check_triggers = check_triggers
        self.changed = changed
        #: what the reads decided, by the shape of the change (shared with the reasoner, which clears it)
        self._decided = decided
        #: the maintenance state of the reasoner (set by it after every full run)
        self.state = None
        #: the cleanly replaced predicates no rule derives, when the compiled step ran (else empty)
        self.step_clean: frozenset = frozenset()
        #: the asserted triples the REASON under way adds (range checks decide known values without a query)
        self.added_now: Collection[Triple] = ()
        #: what :meth:`_after` decided for the REASON under way, and its added values by predicate
        self._now: tuple | None = None
        self._added_values: dict[str, list[tuple[str, str | None]]] | None = None
        #: :func:`~..compile.datatypes.surely_in` of an added value (its texts) and a range, decided once per REASON
        self._in_range: dict[tuple, bool] = {}
        #: the predicates (IRI) range checks read
        self._ranged: frozenset[str] | None = None
        #: SPARQL texts of the groups made once
        self._texts: dict[tuple, str] = {}
        #: :func:`.program.pair_atom` of a check's or negated rule's atom, by (kind, rule index, atom): rules never change
        self._pairs: dict[tuple[str, int, int], bool] = {}
        #: what the keys the staged compiled step of the REASON under way changed decide (:meth:`after_step`):
        #: (a negated-premise group may match, a check group other than a range check's may, the range
        #: checks' (check, atom) pairs); None: the reads decide from the changed graphs
        self._step: tuple[bool, bool, list[tuple]] | None = None

    def begin(self, added: Collection[Triple]) -> None:
        """A REASON adding the asserted triples ``added`` begins: forget what the last one settled."""
        self.step_clean = frozenset()
        self.added_now = added
        self._now = None
        self._added_values = None
        self._in_range = {}
        self._step = None

    def after_step(self, gained: set, lost: set) -> None:
        """A staged compiled step ran whose facts new in the closure are of the keys ``gained`` at most,
        and those it lost of ``lost`` (:meth:`.staged.StagedRun.gained`, :meth:`~.staged.StagedRun.lost`:
        its index look-ups tell them, supersets of the keys of NEW_FACTS and OVERDELETED).  The groups those
        keys start are a superset of those the changed graphs' keys start; where that superset holds no
        negated-premise group, or no check group but range checks, :meth:`negated_match` and
        :meth:`violation_possible` say so without counting the changed graphs.  Decided once per such
        keys, cleanly replaced predicates and keys with facts (a robot repeats a few)."""
        present = self.state.present
        key = ("step", frozenset(gained), frozenset(lost), self.step_clean, len(present[0]), len(present[1]))
        self._step = self._decided.get(key, lambda: self._step_groups(step_keys(gained), step_keys(lost)))

    def _step_groups(self, new: tuple[set, set] | None,
                     lost: tuple[set, set] | None) -> tuple[bool, bool, list[tuple]] | None:
        """:attr:`_step` of a step that may have made facts of ``new`` and lost facts of ``lost`` (as
        (predicates, classes), :func:`step_keys`; None: any, nothing is decided)."""
        if new is None or lost is None:
            return None
        negated = bool(self.negated_branches(new, lost, lambda i, j: False))
        pairs = self._check_pairs(*new)
        ranged = [(c, j) for c, j in pairs if self.checks[c].value_range is not None]
        return negated, len(ranged) < len(pairs), ranged
    def _after(self) -> tuple[str, list[str], list[tuple]]:
        """What the shape of this REASON's change decides (once per REASON, once per shape): the negated
        rules' ASK text ("" when none may match), the checks' groups and apart the range checks' pairs."""
        if self._now is None:
            counts = self.changed.keys(NEW_FACTS, OVERDELETED)
            self._now = self._decided.get(("after", *shape(counts, self.step_clean, self.state.present)),
                                          lambda: (self._negated_ask(*counts) if self.negated else "",
                                                   *self._violation_groups(counts[0])))
        return self._now

    def negated_match(self) -> bool:
        """Whether a rule with a negated premise matches after this maintenance (one semi-naive ASK,
        made once per shape of change; none when the change cannot make one match)."""
        if not self.negated or (self._step is not None and not self._step[0]):
            return False
        text = self._after()[0]
        return bool(text) and bool(self.store.query(text, prefixes=PREFIXES))

    def _negated_ask(self, new: Present, lost: Present) -> str:
        """The ASK of :meth:`negated_branches` ("" when there is none)."""
        branches = self.negated_branches(new, lost, lambda i, j: self.store.supports_lateral
                                          and is_small(new, self.negated[i].body[j].read_key()))
        if not branches:
            return ""
        head = f"FROM {ASSERTED} FROM {INFERRED} FROM {AUX} FROM NAMED {AUX} FROM NAMED {NEW_FACTS}"
        return f"ASK {head} WHERE {{\n" + "\nUNION\n".join(branches) + "\n}"

    def negated_branches(self, new: Present, lost: Present, lateral) -> list[str]:
        """The groups of the negated-premise rules that may match now, when none matched before (the
        state is quiet): a rule whose filters read a key that gained or lost facts, whole; else one
        group per body atom on a key that gained facts, that atom on NEW_FACTS (a lost positive
        premise cannot make a rule match), except a pair of values of one subject on a cleanly
        replaced predicate (:func:`.program.pair_atom`)."""
        if not self.negated:
            return []
        preds = set(new[0]) | set(lost[0])
        classes = set(new[1]) | set(lost[1])
        out = []
        for i, j in self.negated_triggers.evaluations(preds, classes, range(len(self.negated)), self.state.present):
            rule = self.negated[i]
            if j is None:
                out.append(f"{{\n  {rule.where()}\n}}")
                continue
            key = rule.body[j].read_key()
            if key != ("*",) and not matches(key, *new) or self._on_clean_pair("negated", i, rule, j):
                continue
            text_key = ("negated", i, j, lateral(i, j))
            text = self._texts.get(text_key)
            if text is None:
                text = self._texts[text_key] = f"{{\n  {plan_where(rule, j, NEW_FACTS, lateral=lateral(i, j))}\n}}"
            out.append(text)
        return out

    def _on_clean_pair(self, kind: str, i: int, rule: Rule, j: int) -> bool:
        """Whether atom ``j`` of ``rule`` (``kind`` "check" or "negated", index ``i``) is a pair atom
        (:func:`.program.pair_atom`) on a predicate the compiled step cleanly replaced: it cannot match a
        change, since every changed subject has one value before and after."""
        if rule.body[j].p not in self.step_clean:
            return False
        key = (kind, i, j)
        pair = self._pairs.get(key)
        if pair is None:  # a check's pair may also be kept apart by its difference atom
            pair = self._pairs[key] = check_pair_atom(rule, j) if kind == "check" else pair_atom(rule, j)
        return pair

    def violation_possible(self) -> bool:
        """A check matches with at least one atom on a fact new in the closure (one semi-naive ASK)."""
        step = self._step
        if step is not None and not step[1] and all(self._values_in_range(c, j) for c, j in step[2]):
            return False  # the step's keys start range checks only, and its new values lie in their ranges
        _, fixed, ranged = self._after()
        # the same few shapes return: the groups are made once; range checks of known values are decided per run
        left = [(c, j) for c, j in ranged if not self._values_in_range(c, j)] if ranged else ranged
        if left:
            lateral = self._lateral(self.changed.keys(NEW_FACTS)[0])
            branches = fixed + [self._check_text(c, j, lateral(c, j)) for c, j in left]
        else:
            branches = fixed
        if not branches:
            return False
        head = f"FROM {ASSERTED} FROM {INFERRED} FROM {AUX} FROM NAMED {AUX} FROM NAMED {NEW_FACTS}"
        return bool(self.store.query(f"ASK {head} WHERE {{\n" + "\nUNION\n".join(branches) + "\n}",
                                     prefixes=PREFIXES))

    def _lateral(self, counts: tuple[dict[str, int], dict[str, int]]):
        return lambda c, j: j is not None and self.store.supports_lateral \
            and is_small(counts, self.checks[c].body[j].read_key())

    def _violation_groups(self, counts: tuple[dict[str, int], dict[str, int]]) -> tuple[list[str], list[tuple]]:
        """The semi-naive groups of the checks a change of ``counts``' keys may make match, and apart the
        (check, atom) pairs of range checks, whose values each run may decide (:meth:`_values_in_range`)."""
        preds, classes = counts
        pairs = self._check_pairs(preds, classes)
        lateral = self._lateral(counts)
        fixed = [self._check_text(c, j, lateral(c, j)) for c, j in pairs if self.checks[c].value_range is None]
        return fixed, [(c, j) for c, j in pairs if self.checks[c].value_range is not None]

    def check_branches(self, preds: Collection[str], classes: Collection[str], lateral) -> list[str]:
        """The semi-naive groups of the checks a change of ``preds``/``classes`` may make match (one per
        check and changed atom), those that cannot match after the compiled step left out;
        ``lateral(c, j)``: whether the group of check ``c`` on atom ``j`` runs per solution."""
        return [self._check_text(c, j, lateral(c, j)) for c, j in self._check_pairs(preds, classes)
                if not self._values_in_range(c, j)]

    def _check_pairs(self, preds: Collection[str], classes: Collection[str]) -> list[tuple[int, int | None]]:
        return [(c, j) for c, j in
                self.check_triggers.evaluations(preds, classes, range(len(self.checks)), self.state.present)
                if not self._cannot_match(c, j)]

    def _cannot_match(self, c: int, j: int | None) -> bool:
        """Whether check ``c`` with atom ``j`` on the new facts cannot match after the compiled step: a
        pair of values of one subject on a cleanly replaced predicate (:func:`.program.pair_atom`)."""
        return j is not None and self._on_clean_pair("check", c, self.checks[c], j)

    def _values_in_range(self, c: int, j: int | None) -> bool:
        """Whether a range check cannot match this run: its property was cleanly replaced by the compiled
        step (no rule that can fire derives it), so its new facts are the asserted additions, and each
        surely lies in the range (:func:`~..compile.datatypes.surely_in`)."""
        check = self.checks[c]
        if check.value_range is None or j != 0:
            return False
        p, datatype = check.value_range
        if f"<{p}>" not in self.step_clean:
            return False
        values = self._added_values
        if values is None:  # the added values of range-checked predicates, read once per REASON
            values = self._added_values = self._ranged_values()
        decided = self._in_range  # a robot's clock and visit time: one value, two range checks
        for text, own in values.get(p, ()):
            if own is None:
                return False  # not a literal
            key = (text, own, datatype)
            known = decided.get(key)
            if known is None:
                known = decided[key] = text_surely_in(text, own, datatype)
            if not known:
                return False
        return True

    def _ranged_values(self) -> dict[str, list[tuple[str, str | None]]]:
        """The added values of the predicates range checks read, by predicate IRI, each as its lexical
        form and datatype IRI (None: not a literal): each value's terms are made once, and the answers
        kept by these texts (a term's hash is a call)."""
        ranged = self._ranged
        if ranged is None:  # a property of the checks: found once
            ranged = self._ranged = frozenset(c.value_range[0] for c in self.checks if c.value_range is not None)
        values: dict[str, list[tuple[str, str | None]]] = {}
        for t in self.added_now:
            p = t.predicate.value
            if p in ranged:
                o = t.object
                values.setdefault(p, []).append((o.value, o.datatype.value) if type(o) is Literal else ("", None))
        return values

    def _check_text(self, c: int, j: int | None, lateral: bool) -> str:
        key = ("check", c, j, lateral)
        text = self._texts.get(key)
        if text is None:
            rule = self.checks[c]
            where = rule.where() if j is None else plan_where(rule, j, NEW_FACTS, lateral=lateral)
            text = self._texts[key] = f"{{\n  {where}\n}}"
        return text


def step_keys(keys: Collection[tuple]) -> tuple[set[str], set[str]] | None:
    """(predicates, classes) of a staged run's read keys as the changed graphs' census counts them: a class's
    facts are rdf:type facts, so rdf:type is among the predicates where a class is; None where a key
    stands for any predicate (nothing is decided from such keys)."""
    if any(len(key) != 2 for key in keys):  # ("*",): any predicate
        return None
    preds, classes = key_sets(keys)
    if len(preds) + len(classes) < len(keys):
        return None
    if classes:
        preds.add(_TYPE_KEY)
    return preds, classes
