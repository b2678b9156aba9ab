"""The group test of AllDifferent keys left out of a full run's evaluation while one group exists.

Why
---
Two individuals are different by ``owl:AllDifferent`` when they hold two keys of one group (``?k1
ts:differentKeyOf ?a``, ``?k2 ts:differentKeyOf ?b``, the keys' group parts equal: see
:func:`~..compile.counting.group_of`); a group is one member list of an AllDifferent node (OWL 2 RL
eq-diff2/eq-diff3 read each list apart), so a node with two lists is two groups. Comparing the group
parts decodes both keys' text for every match: at 100,000 locations the connecting rule's 400,000
matches spent 0.33 s of its 1.1 s on it, and the minimum cardinality's grouping decodes each of its
150,000 values' keys once more. A map has one ``owl:AllDifferent`` over every location and door, so
every key is of that one group and the test only repeats ``!sameTerm(?k1, ?k2)``.

Same matches
------------
Keys are written to the helper graph only by the generic rules ``all-different`` (a key of each
member of each member list of an ``owl:AllDifferent`` node, its group part that list's, or empty for
every member where the member is its own key: :mod:`..compile.key_form`) and ``eq-rep-s``
(a key copied as it is to what is the same as its member), and a full run starts with an empty helper
graph and never removes a fact.  So while the store holds at most one node typed ``owl:AllDifferent``,
that node at most one member list, and no evaluation waiting in the queue may type another node or give
a node a list, every key in the helper graph has that list's group part, and the group test holds for
any two keys: left out, the evaluation matches what it matched
with it.  Only a full run's evaluations without delta are rewritten, each checked when it is made
(:func:`one_group`); the delta evaluations and the robot step keep the test.  Any other rule writing
keys (a user's rule of the helper predicate), or a helper rule of any predicate, keeps the test always.
"""

from __future__ import annotations

from collections.abc import Collection
from dataclasses import replace
from itertools import islice

from pyoxigraph import NamedNode

from ..compile import condition as cond
from ..compile.counting import group_of
from ..compile.rule import ReadKey, Rule
from ..rdf.vocab import ASSERTED, AUX, DIFFERENT_KEY_OF, INFERRED, TYPE, owl
from ..stores.base import Store

_KEY = f"<{DIFFERENT_KEY_OF.value}>"
_GROUP = owl("AllDifferent")
#: the rules that write keys (rules/all-different-key.rq, rules/eq-rep-s-key.rq): each key's group is an AllDifferent node's
_KEY_WRITERS = frozenset({"all-different", "eq-rep-s"})
#: the predicates giving an AllDifferent node its member lists (each list is one group)
_LISTS = (owl("distinctMembers"), owl("members"))
#: the read keys whose facts add an AllDifferent node or a member list of one
_TYPING = frozenset({("t", f"<{_GROUP.value}>"), ("p", f"<{TYPE.value}>"), ("*",),
                     *(("p", f"<{p.value}>") for p in _LISTS)})
_GRAPHS = (ASSERTED, INFERRED, AUX)


def group_test(k1: str, k2: str) -> str:
    """The condition "two keys of one group" on key variables ``k1``, ``k2``, as the compiler writes it."""
    return f"!sameTerm({k1}, {k2}) && {group_of(k1)} = {group_of(k2)}"


def without_group_tests(rule: Rule) -> Rule | None:
    """``rule`` with each "two keys of one group" test reduced to ``!sameTerm`` of the keys, or None
    when it has no such test."""
    keys = [a.s for a in rule.body if a.aux and a.p == _KEY and a.s.startswith("?")]
    tests = {group_test(k1, k2): f"!sameTerm({k1}, {k2})" for k1 in keys for k2 in keys if k1 != k2}
    if not any(c.kind == cond.TEST and c.expression in tests for c in rule.conditions):
        return None
    conditions = tuple(cond.test(tests[c.expression]) if c.kind == cond.TEST and c.expression in tests else c
                       for c in rule.conditions)
    return replace(rule, conditions=conditions)


def keys_kept_by_group(rules: list[Rule]) -> bool:
    """Whether every rule writing keys is one of the generic key rules (:data:`_KEY_WRITERS`), so that
    each key's group part names an AllDifferent node; a helper rule of any predicate may write keys too."""
    for rule in rules:
        if rule.head is None or not rule.head_aux():
            continue
        if rule.head.p.startswith("?") or (rule.head.p == _KEY and rule.name not in _KEY_WRITERS):
            return False
    return True


def one_group(store: Store, queued: Collection[ReadKey | None]) -> bool:
    """Whether the store holds at most one node typed ``owl:AllDifferent``, that node at most one member
    list, and no evaluation waiting in the queue (``queued``: the keys they may write) may type another
    node or give one a list (see the module)."""
    if store.round_trips or any(k in queued for k in _TYPING):
        return False
    nodes: set = set()
    for graph in _GRAPHS:
        nodes.update(t.subject for t in islice(store.triples(None, TYPE, _GROUP, graph), 2))
        if len(nodes) > 1:
            return False
    return not nodes or _lists_at_most_one(store, next(iter(nodes)))


def _lists_at_most_one(store: Store, node: NamedNode) -> bool:
    """Whether ``node`` has at most one member list (by either predicate, in any graph)."""
    lists: set = set()
    for graph in _GRAPHS:
        for p in _LISTS:
            lists.update(t.object for t in islice(store.triples(node, p, None, graph), 2))
            if len(lists) > 1:
                return False
    return True


__all__ = ["group_test", "keys_kept_by_group", "one_group", "without_group_tests"]
