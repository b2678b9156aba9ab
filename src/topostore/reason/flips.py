"""What a replaced value flips: the rule heads gained or lost when a compared value changes.

A robot step replaces values that rules only compare (the clock ``now``, a
location's ``visitedAt``); re-proving every conclusion built on them would cost
the whole map.  :class:`Flips` evaluates, per rule, only the heads whose
comparison gives a different answer with the new value than with the old one
(texts in :mod:`.flip`), reading the compared facts through a value window
(:mod:`.window`) where the change is narrow.  The heads found lost go to the
deletion phase, those found gained are rechecked and propagated.
"""

from __future__ import annotations

import time
from collections.abc import Collection
from itertools import islice

from pyoxigraph import NamedNode, Quad, Triple

from ..compile.generic import PREFIXES
from ..compile.rule import Rule
from ..rdf.vocab import ASSERTED, AUX, INFERRED
from ..stores.base import key_census
from . import flip, window
from .direct import FEW
from .equal_values import EqualityIndex, difference_pairs, may_equal
from .kinds import replaced_in
from .plan import KeyCounts
from .requests import RequestQueue
from .scratch import FLIP_GAINED, target
from .stats import ReasonStats
from .triggers import Triggers, matches

#: a flip window is used from this many facts of the compared predicate on, up to this many bindings
#: of the seed and this many facts inside (else: a scan)
WINDOW_MIN, WINDOW_ROWS, WINDOW_FACTS = 256, 64, 4096
#: a look-up flip (:mod:`.look_flip`) reads its window from this many facts of the compared predicate on:
#: past :data:`.direct.FEW` its scan gives up to the SPARQL text, and below it keeping the index at every
#: step costs about what the window saves (8 locations: +10 µs in :meth:`Flips.note`, −5 µs in the flip)
LOOKUP_WINDOW_MIN = FEW + 1


class Flips:
    """Finds the flips of one REASON's replacements; keeps the value indexes of compared predicates."""

    def __init__(self, requests: RequestQueue, triggers: Triggers, monotone: set[int]) -> None:
        self.requests = requests
        self.store = requests.store
        self.rules: list[Rule] = requests.rules
        self.triggers = triggers
        self._monotone_set = monotone
        #: the previous REASON's state (what has facts), set by :meth:`find`
        self.state = None
        self._texts: dict[tuple, str] = {}
        #: what the rules' flips need that does not change between REASONs (atom orders, window tests)
        self._plans: dict[tuple, object] = {}
        #: sorted indexes of compared predicates (IRI text) for flip windows, kept from the asserted changes
        self._indexes: dict[str, window.ValueIndex] = {}
        #: indexes of compared predicates' values by equality, for difference flips (see :mod:`.equal_values`)
        self._equal: dict[str, EqualityIndex] = {}
        #: asserted facts of a compared predicate without a value index yet (counted up to
        #: :data:`WINDOW_MIN` once, then kept by :meth:`note`; see :meth:`_fewer_than`)
        self._counts: dict[str, int] = {}
        #: predicates by IRI text, for the fact counts of :meth:`_fewer_than`
        self._nodes: dict[str, NamedNode] = {}
        # per rule: the variables its filters mention
        self._filter_vars = [flip.filter_variables(r) for r in self.rules]

    def note(self, added: Collection[Triple], removed: Collection[Triple]) -> None:
        """Keep the value indexes and the fact counts up to date with the asserted changes."""
        if not (self._indexes or self._equal or self._counts):
            return
        for facts, sign in ((removed, -1), (added, 1)):
            for t in facts:
                p = f"<{t.predicate.value}>"
                for indexes in (self._indexes, self._equal):
                    if (index := indexes.get(p)) is not None:
                        index.add(t) if sign > 0 else index.discard(t)
                if p in self._counts:
                    self._counts[p] += sign

    def forget(self) -> None:
        """Drop the value indexes and the fact counts (after a full run or a failed REASON: made again
        when next needed)."""
        self._indexes.clear()
        self._equal.clear()
        self._counts.clear()

    def quiet(self, i: int, order: tuple[int, ...], replaced: dict[str, list[flip.Replacement]]) -> bool:
        """Whether rule ``i``'s flip over its changed atoms ``order`` surely finds nothing: its tests on
        the replaced values are differences of values (:func:`.equal_values.difference_pairs`), and no
        partner value may equal an old or a new value of a replacement (an index look-up per value)."""
        key = ("difference", i, order)
        compared = self._plans.get(key, key)
        if compared is key:  # a property of the rule: the (predicate, partner's predicate) pairs, once
            pairs = difference_pairs(self.rules[i], order)
            body = self.rules[i].body
            compared = self._plans[key] = None if pairs is None else tuple(sorted(
                {(body[seed].p, body[partner].p) for x, y in pairs for seed, partner in ((x, y), (y, x))}))
        if compared is None:
            return False
        return not any(self._may_equal(p, q, replaced) for p, q in compared if p in replaced)

    def _may_equal(self, p: str, q: str, replaced: dict[str, list[flip.Replacement]]) -> bool:
        """Whether an old or new value of a replacement of ``p`` may equal a value of ``q`` held by
        another fact (now, or before this change for a replaced fact of ``q``)."""
        replacements = replaced.get(p, ())
        if not replacements:
            return False
        if self.derivable(q):
            return True  # derived values are not in the index
        index = self._equality_index(q)
        partners = replaced.get(q, ())
        for r in replacements:
            own = r.old.subject if p == q else None  # a subject's one value is not its own partner
            # the values the replaced facts of q held before this change
            before = [o.old.object for o in partners if own is None or o.old.subject != own]
            for value in (r.old.object, r.new.object):
                if index.other_subject(value, None if own is None else str(own)) \
                        or (before and any(may_equal(value, old) for old in before)):
                    return True
        return False

    def _equality_index(self, p: str) -> EqualityIndex:
        """The equality index of predicate ``p``'s asserted facts (built once, kept by :meth:`note`)."""
        index = self._equal.get(p)
        if index is None:
            index = self._equal[p] = EqualityIndex(self.store.triples(None, NamedNode(p[1:-1]), None, ASSERTED))
        return index

    def find(self, state, added: Collection[Triple], removed: Collection[Triple], added_keys: KeyCounts,
             stats: ReasonStats, replaced: dict | None = None) -> tuple[set[tuple[int, int]], list[Triple], set[int]]:
        """Evaluate the rules that see replaced values only through comparisons (see :mod:`.flip`).

        Returns the (rule, atom) evaluations the ordinary path must skip, the
        heads that lost their derivation by such a rule, and the rules with
        heads that may have gained one (put in FLIP_GAINED, checked later).
        ``replaced``: the change's clean replacements when the caller has read them already.
        """
        self.state = state
        if replaced is None:
            replaced = replaced_in(self.store, added, removed, ASSERTED)
        clean = {p: pairs for p, pairs in replaced.items() if not self.derivable(p)}
        skip: set[tuple[int, int]] = set()
        lost: list[Triple] = []
        gained_rules: set[int] = set()
        if not clean:
            return skip, lost, gained_rules
        preds, classes = added_keys
        removed_preds, removed_classes = key_census(removed)
        changed = (set(preds) | set(removed_preds), set(classes) | set(removed_classes))
        self.requests.scratch([r.old for pairs in clean.values() for r in pairs], flip.CHANGE_OLD)
        self.requests.flush()
        wanted: list[tuple[int, tuple[int, ...]]] = []
        for i in self.triggers.rules_reading(clean, self._monotone_set):
            handled = flip.flip_atoms(self.rules[i], clean, lambda key: matches(key, *changed))
            if handled is None:
                continue
            skip.update((i, j) for j in handled)
            compared = tuple(j for j in handled if self.rules[i].body[j].o[1:] in self._filter_vars[i])
            if compared and self.triggers.feasible(i, self.state.present):
                wanted.append((i, compared))
        stats.flipped = len(skip)
        for row in self._flip_rows(tuple(wanted), stats):
            i = int(row["rule"].value)
            head = flip.head_triple(row)
            if flip.gained(row):
                self.store.add_scratch([head], FLIP_GAINED)
                gained_rules.add(i)
            elif self.store.contains_terms([Quad(head.subject, head.predicate, head.object, target(self.rules[i]))])[0]:
                lost.append(head)  # by term: a derived graph holds each spelling a rule derived
        return skip, lost, gained_rules

    def _flip_rows(self, wanted: tuple[tuple[int, tuple[int, ...]], ...], stats: ReasonStats) -> list:
        """One query for the flips of all ``wanted`` (rule, compared atoms).

        A branch that would scan every value of a compared predicate reads only the
        values in its window instead, when :mod:`.window` can give one.
        """
        if not wanted:
            return []
        lateral = self.store.supports_lateral
        branches: list[str] = []
        for i, atoms in wanted:
            order = self._by_frequency(i, atoms)
            windows = self._windows(i, order)
            if windows:
                branches += flip.flip_branches(self.rules[i], order, lateral, i, windows)
                continue
            key = ("flip", i, order)
            cached = self._texts.get(key)
            if cached is None:
                cached = self._texts[key] = "\nUNION\n".join(flip.flip_branches(self.rules[i], order, lateral, i))
            branches.append(cached)
        stats.evaluations += len(wanted)
        start = time.perf_counter()
        rows = list(self.store.query(flip.flip_query(branches), prefixes=PREFIXES, graphs=[ASSERTED, INFERRED, AUX],
                                     named=[AUX, flip.CHANGE_OLD]))
        if self.requests.profile:
            stats.per_rule["flip"] = stats.per_rule.get("flip", 0.0) + time.perf_counter() - start
        return rows

    def _windows(self, i: int, order: tuple[int, ...]) -> dict[int, dict[int, list[Triple]]]:
        """For the branch seeded by the last changed atom (all others read settled), the facts of each
        other compared atom that lie in its window (see :mod:`.window`); {} where there is none."""
        k = order[-1]
        found: dict[int, list[Triple]] = {}
        for m, p in self._window_atoms(i, k):
            if self.derivable(p):
                continue
            facts = self._window_facts(i, k, m)
            if facts is not None:
                found[m] = facts
        return {k: found} if found else {}

    def _window_atoms(self, i: int, k: int) -> list[tuple[int, str]]:
        """The atoms of rule ``i`` (with their predicates) that a window may narrow when atom ``k`` seeds
        the flip: compared only, not bound by the seed (a look-up already; only an enumeration needs a
        window), and whose tests are linear in the seed's value.  A property of the rule: decided once."""
        key = ("window-atoms", i, k)
        found = self._plans.get(key)
        if found is None:
            rule = self.rules[i]
            seed = rule.body[k]
            tests = self._window_tests(i)
            found = self._plans[key] = [
                (m, atom.p) for m, atom in enumerate(rule.body)
                if m != k and flip.compared_only(rule, m) and atom.s not in seed.variables()
                and window.possible(tests, seed.o[1:])]
        return found

    def _window_tests(self, i: int) -> list:
        """Rule ``i``'s tests as :func:`.window.tests` reads them (once per rule)."""
        tests = self._plans.get(("window-tests", i))
        if tests is None:
            tests = self._plans[("window-tests", i)] = window.tests(self.rules[i])
        return tests

    def _window_facts(self, i: int, k: int, m: int) -> list[Triple] | None:
        """The facts of atom ``m`` that a change of seed atom ``k``'s value may flip (None: no window)."""
        rule = self.rules[i]
        tests = self._window_tests(i)
        seed, atom = rule.body[k], rule.body[m]
        t, v = seed.o[1:], atom.o[1:]
        if self._fewer_than(atom.p, WINDOW_MIN):
            return None  # so few values that scanning them is as cheap (a linear test: :meth:`_window_atoms`)
        rest = sorted({n for test in tests if test.form for n in test.form[0]} - {t, v})
        text = self._texts.get(("window", i, k, m))
        if text is None:
            text = self._texts[("window", i, k, m)] = self._window_query(rule, k, m, rest)
        rows = list(self.store.query(text, prefixes=PREFIXES, graphs=[ASSERTED, INFERRED, AUX],
                                     named=[AUX, flip.CHANGE_OLD]))
        if len(rows) > WINDOW_ROWS:
            return None
        facts: dict[Triple, None] = {}
        index = self._value_index(atom.p)
        for row in rows:
            terms = [row[f"{t}__o"], row[f"{t}__n"], *(row[n] for n in rest)]
            if not index.exact_for(terms):
                return None
            values = [window.number(term) for term in terms]
            if any(x is None for x in values):
                return None
            span = window.interval(tests, v, t, values[0], values[1], dict(zip(rest, values[2:])),
                                   window.margin(terms, values))
            if span is None:
                return None
            if span is False:
                continue
            inside = index.between(span[0], span[1], WINDOW_FACTS)
            if inside is None:
                return None
            facts.update(dict.fromkeys(inside))
            if len(facts) > WINDOW_FACTS:
                return None
        return list(facts)

    def _window_query(self, rule: Rule, k: int, m: int, rest: list[str]) -> str:
        """The old and new seed values with the bindings of ``rest``: the seed atom and the atoms that do
        not depend on atom ``m`` (leaving atoms out only widens the window)."""
        seed, atom = rule.body[k], rule.body[m]
        t = seed.o[1:]
        lines = [f"GRAPH {flip.CHANGE_OLD} {{ {seed.s} {seed.p} ?{t}__o }}", f"{seed.s} {seed.p} ?{t}__n ."]
        own = atom.variables() - seed.variables()
        lines += [rule.atom_text(j) for j, other in enumerate(rule.body)
                  if j not in (k, m) and not (other.variables() & own)]
        head = " ".join([f"?{t}__o", f"?{t}__n", *(f"?{n}" for n in rest)])
        return f"SELECT DISTINCT {head} WHERE {{\n  " + "\n  ".join(lines) + f"\n}} LIMIT {WINDOW_ROWS + 1}"

    def _fewer_than(self, p: str, n: int) -> bool:
        """Whether predicate ``p`` has fewer than ``n`` numeric values in its index.  Until its index is
        built, fewer than ``n`` asserted facts of ``p`` (a superset of the indexed ones) answer without
        building it: a small map then keeps no index up to date at every step (:meth:`note`), only the
        count, read from the store once.  Not on a
        store where each look-up is a round trip: the index, built once, answers there without one."""
        if p not in self._indexes and not self.store.round_trips:  # a count there is a request per step
            count = self._counts.get(p)
            if count is None:
                facts = self.store.triples(None, self._node(p), None, ASSERTED)
                count = self._counts[p] = sum(1 for _ in islice(facts, n))
            if count < n:
                return True
            del self._counts[p]  # the index is built now, and answers from here on
        return len(self._value_index(p)) < n

    def sorted_values(self, p: str) -> window.ValueIndex | None:
        """The sorted index of predicate ``p``'s facts, for a look-up flip's window
        (:class:`.look_flip.Flipped`); None below :data:`LOOKUP_WINDOW_MIN` facts (a scan of so few
        costs what keeping the index at every step costs) and where a rule that can fire may derive
        ``p`` (the index holds asserted facts only).  Built once, then kept by :meth:`note`."""
        if self.state is None or self._fewer_than(p, LOOKUP_WINDOW_MIN) or self.derivable(p):
            return None
        return self._value_index(p)

    def _node(self, p: str) -> NamedNode:
        """The predicate of IRI text ``p`` (made once: the rules' few compared predicates)."""
        node = self._nodes.get(p)
        if node is None:
            node = self._nodes[p] = NamedNode(p[1:-1])
        return node

    def _value_index(self, p: str) -> window.ValueIndex:
        """The sorted index of predicate ``p``'s facts (built once, kept by :meth:`_maintain`)."""
        index = self._indexes.get(p)
        if index is None:
            index = self._indexes[p] = window.ValueIndex(self.store.triples(None, NamedNode(p[1:-1]), None, ASSERTED))
        return index

    def _by_frequency(self, i: int, atoms: tuple[int, ...]) -> tuple[int, ...]:
        """The rule's atoms, those of predicates with the most asserted facts first (see flip.flip_branches)."""
        key = ("order", i, atoms)
        if key not in self._plans:
            self._plans[key] = self._order_by_size(i, atoms)
        return self._plans[key]

    def _order_by_size(self, i: int, atoms: tuple[int, ...]) -> tuple[int, ...]:
        def size(j: int) -> int:
            p = self.rules[i].body[j].p
            rows = self.store.query(f"SELECT (COUNT(*) AS ?n) WHERE {{ ?s {p} ?o }}", graphs=[ASSERTED])
            return int(next(iter(rows))["n"].value)
        sizes = {j: size(j) for j in atoms}
        return tuple(sorted(atoms, key=lambda j: (-sizes[j], j)))

    def derivable(self, p: str) -> bool:
        """Whether a rule that can fire may derive facts of predicate ``p`` (IRI text)."""
        return any(self.triggers.feasible(i, self.state.present) for i in self.triggers.writers(("p", p)))


__all__ = ["LOOKUP_WINDOW_MIN", "Flips", "WINDOW_FACTS", "WINDOW_MIN", "WINDOW_ROWS"]
