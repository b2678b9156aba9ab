"""Which rule evaluations a change triggers, looked up instead of scanned.

Every delta round asks: for the predicates and classes that changed, which
(rule, body atom) pairs can match something new, and can the rest of the rule
match at all?  Scanning every rule and atom for that costs more Python time
than the SPARQL it saves on small maps, so the answer comes from an index
built once per rule set.
"""

from __future__ import annotations

from collections.abc import Collection, Iterable

from ..compile.rule import ReadKey, Rule
from ..rdf.vocab import TYPE

#: Predicates and classes that have (or may have) facts, as SPARQL text.
Present = tuple[set[str], set[str]]

#: One evaluation: rule index, and the body atom on the delta (None: the whole rule).
Evaluation = tuple[int, int | None]


class Triggers:
    """An index from read keys to the rule evaluations they trigger."""

    def __init__(self, rules: list[Rule]) -> None:
        self.rules = rules
        self._atoms: dict[ReadKey, list[tuple[int, int]]] = {}
        self._filters: dict[ReadKey, list[int]] = {}
        self._writers: dict[ReadKey, list[int]] = {}
        #: per rule, per body atom: the key that must have facts for the atom to match (None: any may)
        self._needs: list[tuple[ReadKey | None, ...]] = []
        # one pass with the lookups bound locally: a large TBox gives tens of thousands of rules (one
        # per pair of disjoint classes), all indexed by a robot's first step
        atoms, filters, writers, needs = self._atoms, self._filters, self._writers, self._needs.append
        for i, rule in enumerate(rules):
            body = rule.body
            keys = [a.read_key() for a in body]
            for j, key in enumerate(keys):
                found = atoms.get(key)
                if found is None:
                    atoms[key] = [(i, j)]
                else:
                    found.append((i, j))
            for key in rule.filter_reads:
                filters.setdefault(key, []).append(i)
            needs(tuple([key if a.p[0] == "<" else None for a, key in zip(body, keys)]))
            if rule.head is not None:
                writers.setdefault(rule.writes(), []).append(i)

    def evaluations(self, preds: Collection[str], classes: Collection[str], active: Collection[int],
                    present: Present | None = None, skip: Collection[tuple[int, int]] = ()) -> list[Evaluation]:
        """The evaluations a change of ``preds``/``classes`` triggers among the ``active`` rules.

        A rule whose filters read a changed key is evaluated whole; otherwise
        once per body atom on a changed key (that atom on the delta), unless the
        pair is in ``skip``.  With ``present``, evaluations where another atom
        reads a key without any fact are left out: they cannot match.
        """
        keys = [("p", p) for p in preds] + [("t", c) for c in classes] + ([("*",)] if preds else [])
        whole = {i for k in keys for i in self._filters.get(k, ())}
        pairs = {pair for k in keys for pair in self._atoms.get(k, ())}
        out: list[Evaluation] = [(i, None) for i in sorted(whole)
                                 if i in active and self.feasible(i, present)]
        out += [(i, j) for i, j in sorted(pairs)
                if i not in whole and i in active and (i, j) not in skip and self.feasible(i, present, j)]
        return out

    def rules_reading(self, preds: Collection[str], among: Collection[int]) -> list[int]:
        """The rules in ``among`` with a body atom on one of the predicates ``preds``."""
        found = {i for p in preds for i, _ in self._atoms.get(("p", p), ())}
        return sorted(i for i in found if i in among)

    def writers(self, key: ReadKey) -> list[int]:
        """The rules whose head may produce facts of ``key`` (those writing any predicate included)."""
        return self._writers.get(key, []) + self._writers.get(("*",), [])

    def needed_keys(self) -> set[ReadKey]:
        """Every key some body atom needs facts of (see :meth:`feasible`)."""
        return {need for needs in self._needs for need in needs if need is not None}

    def feasible(self, i: int, present: Present | None, skip: int | None = None) -> bool:
        """False when a body atom of rule ``i`` other than ``skip`` reads a key without any fact.

        Such an evaluation cannot match; skipping it saves a SPARQL update, which
        costs about 0.1 ms even when nothing matches.
        """
        if present is None:
            return True
        preds, classes = present
        for j, need in enumerate(self._needs[i]):
            if need is None or j == skip:
                continue
            if need[0] == "t":
                if need[1] not in classes:
                    return False
            elif need[0] == "p" and need[1] not in preds:
                return False
        return True

    def unknown_atoms(self, i: int, known: Present) -> list[int]:
        """Body atoms of rule ``i`` on a predicate or class without any fact in ``known``
        (atoms with a variable predicate or a path may match anything, so they are never unknown)."""
        preds, classes = known
        return [j for j, need in enumerate(self._needs[i])
                if need is not None and need[1] not in (classes if need[0] == "t" else preds)]


def matches(key: ReadKey, changed_preds: Collection[str], changed_classes: Collection[str]) -> bool:
    """Whether a change of ``changed_preds``/``changed_classes`` touches read key ``key``."""
    if key[0] == "*":
        return bool(changed_preds)
    if key[0] == "t":
        return key[1] in changed_classes
    return key[1] in changed_preds


#: the read key of an rdf:type atom whose class is a variable (``?x a ?c``)
_ANY_CLASS = ("p", str(TYPE))


def may_write(written: ReadKey, key: ReadKey) -> bool:
    """Whether facts a rule writes under ``written`` may be facts read under ``key``: the same key, either
    standing for any key (``*``: a variable predicate), or a class membership against an rdf:type of a
    variable class, either way round (a class's facts are rdf:type facts; an rdf:type head of a variable
    class writes every class's)."""
    if written == key or written[0] == "*" or key[0] == "*":
        return True
    if written[0] == "t":
        return key == _ANY_CLASS
    return written == _ANY_CLASS and key[0] == "t"


def may_hold(written: Collection[ReadKey | None], key: ReadKey) -> bool:
    """Whether evaluations writing the keys ``written`` may have written a fact of ``key``, a predicate or
    a class: :func:`may_write` against each, by set look-ups (the keys standing for many are few)."""
    return key in written or ("*",) in written or (key[0] == "t" and _ANY_CLASS in written)


def may_write_any(queued: Collection[ReadKey | None], keys: Iterable[ReadKey]) -> bool:
    """Whether evaluations writing the keys ``queued`` (None among them: a key not known, so any) may have
    written a fact of one of ``keys`` (:func:`may_hold` of each)."""
    return None in queued or any(may_hold(queued, k) for k in keys)


def key_sets(keys: Collection[tuple[str, str]]) -> tuple[set[str], set[str]]:
    """(predicates, classes) of read keys ``("p", iri)`` / ``("t", class)``."""
    return {k for kind, k in keys if kind == "p"}, {k for kind, k in keys if kind == "t"}

__all__ = ["key_sets", "Evaluation", "Present", "Triggers", "matches", "may_hold", "may_write", "may_write_any"]
