"""A keyed conclusion's first pass without its key atoms, where the census shows the keys one to one.

Why
---
Connectability (``connectedTo`` of two doors' holders that are different) is joined with the two holders'
AllDifferent keys (:mod:`..compile.inline_difference`): at 100,000 locations its first pass reads 0.88 s,
of which the two key look-ups per match cost 0.45 s.  Where the census of :mod:`.keyed_asks` shows the
keys one to one with their holders, every holder of the body's pair holding one, and one group, two
different holders hold two different keys of that group: the key atoms decide nothing and are left out.

Same answer
-----------
Let ``J`` be a keyed conclusion of the deferred rule ``R`` (:func:`.keyed_asks.keyed_conclusion`: ``J``'s
body is ``R``'s with ``?k1 ts:differentKeyOf x`` and ``?k2 ts:differentKeyOf y``; its conditions are
``R``'s with the group test and ``!sameTerm(?k1, ?k2)``), with ``!sameTerm(x, y)`` among its conditions,
and ``L`` the lean rule: ``J`` without the two key atoms and the conditions naming ``?k1`` or ``?k2``.  A
match of ``J`` is a match of ``L``.  Conversely, on data where the census covers ``R``
(:func:`.keyed_asks.covered`: one group; key facts, distinct keys and distinct holders as many; every
term one of ``R``'s body atoms binds to ``x`` or ``y`` a holder), take a match of ``L``: ``x`` and ``y``
hold keys ``k1`` and ``k2``, ``x ≠ y`` gives ``k1 ≠ k2`` (one key per holder, one holder per key), both of
the one group: the match extends to one of ``J`` with the same head.  ``L``'s body reads its atoms in the
default dataset or in one of its graphs, a subset of what the census counts, so what the census covers
covers ``L``.

So at ``J``'s first-pass turn, the census taken on the data of that turn lets the pass send ``L``'s text.
The census is started in the worker (:class:`.early_rules.EarlyRules`) once the components writing what
it reads are done (an early writer counted at its start: the worker runs its reads in the order they were
started), and awaited at ``J``'s turn; any evaluation since writing a key it reads (sent, queued, or
started early after it) drops it, and the pass sends ``J`` as before.  The rounds with a delta always
evaluate ``J`` itself.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, replace

from ..compile import condition as cond
from ..compile.rule import ReadKey, Rule
from ..rdf.vocab import DIFFERENT_KEY_OF
from .keyed_asks import GROUP_READS, KeyCensus, keyed_conclusion
from .read_keys import evaluation_reads

_KEY = f"<{DIFFERENT_KEY_OF.value}>"


@dataclass(frozen=True)
class KeyedPass:
    """A keyed conclusion's lean first pass: the census that allows it, its key variables, and what the
    census reads (the rule's own reads, the deferred rule's, the group's)."""

    census: KeyCensus
    keys: frozenset[str]
    reads: frozenset[ReadKey]

    def lean(self, rule: Rule) -> Rule:
        """``rule`` (the keyed conclusion, or its first pass's form without implied atoms) without the key
        atoms and the conditions naming a key variable."""
        body = tuple(a for a in rule.body if not (a.aux and a.p == _KEY and a.s in self.keys))
        conditions = tuple(c for c in rule.conditions if not (c.variables & self.keys))
        return replace(rule, body=body, conditions=conditions, written=rule.premises,
                       written_conditions=rule.written_conditions if rule.written_conditions is not None
                       else rule.conditions)


def keyed_passes(rules: Sequence[Rule], censuses: Mapping[int, KeyCensus]) -> dict[int, KeyedPass]:
    """By rule, the keyed conclusions whose first pass may leave their keys out (see the module)."""
    out = {}
    for i, census in censuses.items():
        asked = rules[i]
        for j, other in enumerate(rules):
            if j in out or not keyed_conclusion(asked, other):
                continue
            keys = _key_variables(asked, other)
            if keys is not None:
                out[j] = KeyedPass(census, keys, evaluation_reads(asked) | evaluation_reads(other) | GROUP_READS)
    return out


def _key_variables(asked: Rule, keyed: Rule) -> frozenset[str] | None:
    """The key variables of ``keyed`` (a keyed conclusion of ``asked``), where its lean rule is ``asked``'s
    body with ``x ≠ y`` and a head of the body's variables; else None."""
    x, y = asked.head.s, asked.head.o
    extra = list(keyed.body)
    for atom in asked.body:
        extra.remove(atom)
    keys = frozenset(a.s for a in extra)
    distinct = cond.test(f"!sameTerm({x}, {y})")
    if not any((c.kind, c.expression, c.binds, c.negated) == (distinct.kind, distinct.expression, None, False)
               for c in keyed.conditions):
        return None
    kept = {v for a in asked.body for v in a.variables()}
    if keyed.head is None or not keyed.head.variables() <= kept:
        return None
    if any(c.variables & keys and not c.plain for c in keyed.conditions) or any(
            c.binds in keys for c in keyed.conditions if c.binds):
        return None
    return keys


__all__ = ["KeyedPass", "keyed_passes"]
