"""A pair of values different by AllDifferent keys, evaluated by a full run as one count per group.

Why
---
A minimum of two values (``hasDoor min 2 DOOR``) compiles, for the difference by
``owl:AllDifferent`` groups, to a pairwise rule: two values ``?y1 ?y2`` of the subject, each
value's group key (``?k ts:differentKeyOf ?y``), two keys of one group and two different values.
Evaluated as written, the store enumerates every ordered pair of values and looks up two keys
per pair (at 10,000 locations 50,000 pairs, 0.2 s, the biggest OWL rule of a full REASON).
The rule stays as it is (explanations show its two values; the robot step maintains it as any
other rule); only a full run's evaluation without delta asks the same question as a count: per
binding of the rest of the body and per group, at least two different values *and* at least
two different keys among the values' (value, key) pairs (0.1 s at 10,000).

Same matches
------------
The pairwise body holds for a binding of the rest iff some (value, key) pairs ``(a, ka)`` and
``(b, kb)`` of one group have ``a ≠ b`` and ``ka ≠ kb``.  Such pairs exist iff the pairs of that
group hold two different values and two different keys: a set of (value, key) pairs in which any
two share their value or their key all share one value or all share one key (a bipartite graph
has no triangle).  The rule's order test on the two values (:func:`~..compile.owl_restrictions.term_before`)
only picks one of the two orders of a pair of IRIs: it is replaced by ``isIRI`` on the value, since
the order is undefined (an error, so no match) for blank nodes, and a literal holds no key.

Only rules of exactly this shape are rewritten (:func:`grouped_form`); any other keeps its text.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, replace

from ..compile import condition as cond
from ..compile.counting import group_of
from ..compile.owl_restrictions import term_before
from ..compile.rule import Atom, Rule
from ..rdf.vocab import DIFFERENT_KEY_OF

_KEY = f"<{DIFFERENT_KEY_OF.value}>"


@dataclass(frozen=True)
class GroupedPair:
    """The count form of a rule: ``rule`` holds the body on one value ``value`` with its ``key``;
    matches are grouped by the other variables ``shared`` and the key's group."""

    rule: Rule
    value: str
    key: str
    shared: tuple[str, ...]

    def where(self, graphs=None, one_group: bool = False) -> str:
        """The WHERE group: the head's variables of the bindings with two values and two keys of one group.

        ``one_group``: every key is of one group (:mod:`.one_group`), so the bindings are grouped by the
        other variables alone, without reading each key's group part (when there are other variables)."""
        head = " ".join(sorted(self.rule.head.variables()))
        inner = self.rule.where(None, "", graphs)
        group = "?pair_group"
        bind = f"\n  BIND({group_of(self.key)} AS {group})"
        if one_group and self.shared:
            bind, group = "", ""
        return (f"{{ SELECT DISTINCT {head} WHERE {{\n  {inner}{bind}\n  }}"
                f" GROUP BY {' '.join((*self.shared, group)).strip()}"
                f" HAVING (COUNT(DISTINCT {self.key}) > 1 && COUNT(DISTINCT {self.value}) > 1) }}")


def grouped_form(rule: Rule) -> GroupedPair | None:
    """The count form of ``rule`` when it is a pair of values different by group keys, else None.

    The shape: two helper atoms ``?ka ts:differentKeyOf ?a`` and ``?kb ts:differentKeyOf ?b``, the
    condition "two keys of one group" on them, ``!sameTerm(?a, ?b)`` or the order test; every other
    atom and condition mentions at most one of ``?a``, ``?b``, and those of ``?b`` are those of ``?a``
    renamed; a plain head (a class of variables of the rest), no BIND, no graph pattern in a condition.
    """
    if rule.head is None or rule.stratum or any(c.kind != cond.TEST or c.reads_graph or c.negated
                                                  for c in rule.conditions):
        return None
    keys = [a for a in rule.body if a.aux and a.p == _KEY and a.s.startswith("?") and a.o.startswith("?")]
    for first in keys:
        for second in keys:
            if first is not second:
                found = _pair(rule, first, second)
                if found is not None:
                    return found
    return None


def _pair(rule: Rule, ka: Atom, kb: Atom) -> GroupedPair | None:
    """:func:`grouped_form` with ``ka`` the first value's key atom and ``kb`` the second's."""
    a, b, k1, k2 = ka.o, kb.o, ka.s, kb.s
    if len({a, b, k1, k2}) < 4:
        return None
    pair_tests = {f"!sameTerm({k1}, {k2}) && {group_of(k1)} = {group_of(k2)}"}
    distinct = {f"!sameTerm({a}, {b})", f"!sameTerm({b}, {a})"}
    ordered = {term_before(a, b), term_before(b, a)}
    tests = [c.expression for c in rule.conditions]
    if not pair_tests & set(tests) or not (distinct | ordered) & set(tests):
        return None
    pair_vars = {a, b, k1, k2}
    if rule.head.variables() & pair_vars:
        return None
    atoms = [x for x in rule.body if x is not ka and x is not kb]
    if any(x.variables() & {k1, k2} for x in atoms):
        return None
    shared = [x for x in atoms if not x.variables() & {a, b}]
    on_a = [x for x in atoms if a in x.variables()]
    on_b = [x for x in atoms if b in x.variables()]
    if any(a in x.variables() and b in x.variables() for x in atoms):
        return None
    if sorted(map(_key, on_a)) != sorted(_key(_rename_atom(x, b, a)) for x in on_b):
        return None
    rest = [t for t in tests if t not in pair_tests | distinct | ordered]
    if any(_mentions(t, k1) or _mentions(t, k2) for t in rest):
        return None
    tests_a = [t for t in rest if _mentions(t, a)]
    tests_b = [t for t in rest if _mentions(t, b)]
    if any(_mentions(t, a) and _mentions(t, b) for t in rest):
        return None
    if sorted(tests_a) != sorted(_rename(t, b, a) for t in tests_b):
        return None
    common = [t for t in rest if not _mentions(t, a) and not _mentions(t, b)]
    kept = tests_a + common + (["isIRI(" + a + ")"] if ordered & set(tests) else [])
    body = tuple(shared + on_a + [ka])
    outer = sorted({v for x in shared + on_a for v in x.variables()} - {a})
    if not rule.head.variables() <= set(outer):
        return None
    lean = replace(rule, body=body, conditions=tuple(cond.test(t) for t in kept), filter_reads=frozenset(),
                   written=rule.premises)
    return GroupedPair(lean, a, k1, tuple(outer))


def _key(atom: Atom) -> tuple:
    return atom.s, atom.p, atom.o, atom.aux


def _rename_atom(atom: Atom, old: str, new: str) -> Atom:
    return Atom(*(new if t == old else t for t in (atom.s, atom.p, atom.o)), aux=atom.aux)


def _mentions(text: str, var: str) -> bool:
    return re.search(re.escape(var) + r"(?!\w)", text) is not None


def _rename(text: str, old: str, new: str) -> str:
    return re.sub(re.escape(old) + r"(?!\w)", new, text)


__all__ = ["GroupedPair", "grouped_form"]
