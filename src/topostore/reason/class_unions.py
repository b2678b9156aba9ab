"""Several rules concluding one class, evaluated as one: the first pass of a full REASON unions them.

Why
---
A class is often concluded by many one-atom rules of the schema: the domain of each property whose
subjects are LOCATIONs, the range of each whose objects are.  Evaluated one by one, each projects its
matches on the member, looks every member up in the class's facts (``MINUS``) and writes the new ones;
the second and later rules find every member known already and pay the anti-join for nothing
(10,000 locations: LOCATION by hasDoor's domain 26 ms, then by visitedAt's 15 ms and isIn's range
6 ms, against 29 ms for the three as one ``SELECT DISTINCT`` over a ``UNION``).

When it holds
-------------
The rules of a group are singletons of the ordered first stratum (no cycle through them), write the
same class key into the same graph, project on their one head variable (:func:`.insert_text.distinct_pays`),
and read only keys whose every fact is asserted while the ordered pass runs (``graphs`` maps them to
the asserted graph: no rule of the pass writes them).  Their inputs are then complete before the pass
starts, so each may run at the place of the first of them; every reader of the class comes after all
of its writers in the order, so none of them reads the class earlier than before.  Rules with a form
of their own (a first pass on asserted facts, left-out atoms, a count per group, a deferred ask) stay
apart.
"""

from __future__ import annotations

from collections.abc import Callable, Collection, Mapping, Sequence

from pyoxigraph import NamedNode

from ..compile.rule import ReadKey, Rule
from ..compile.schema import schema_dataset


def class_unions(rules: Sequence[Rule], ordered: Sequence[Sequence[int]], back: Collection[int],
                 graphs: Mapping[ReadKey, NamedNode], asserted: NamedNode, projected: Callable[[Rule], bool],
                 apart: Collection[int]) -> dict[int, tuple[int, ...]]:
    """By the first rule of each group of two or more (in the order of ``ordered``), the others."""
    groups: dict[tuple, list[int]] = {}
    for component in ordered:
        if len(component) != 1:
            continue
        i = component[0]
        rule = rules[i]
        if i in back or i in apart or not _joinable(rule, graphs, asserted, projected):
            continue
        groups.setdefault((rule.writes(), rule.head_aux(), schema_dataset(rule)), []).append(i)
    return {members[0]: tuple(members[1:]) for members in groups.values() if len(members) > 1}


def _joinable(rule: Rule, graphs: Mapping[ReadKey, NamedNode], asserted: NamedNode,
              projected: Callable[[Rule], bool]) -> bool:
    """A class head on one variable, projected, read from asserted-only keys, no graph in its conditions."""
    head = rule.head
    if head is None or rule.writes()[0] != "t" or not head.s.startswith("?") or not projected(rule):
        return False
    if rule.conditions_read_graph or any(a.aux for a in rule.body):
        return False
    return all(graphs.get(key) == asserted for key in rule.reads())


def lead_first(rules: Sequence[Rule], members: Sequence[int]) -> list[int]:
    """``members`` with those concluding the most common head variable first: the first one's head
    is written, and each rule concluding another variable is renamed (a projection more)."""
    counts: dict[str, int] = {}
    for m in members:
        counts[rules[m].head.s] = counts.get(rules[m].head.s, 0) + 1
    return sorted(members, key=lambda m: -counts[rules[m].head.s])


def union_where(rules: Sequence[Rule], graphs: Mapping[ReadKey, NamedNode] | None) -> str:
    """The members the rules conclude, once each, as one projected ``UNION`` on the first rule's head
    variable.  A rule concluding another variable is projected on its own first, then renamed:
    the first rule's variable may occur in its body with another meaning (``?x`` of a range)."""
    target = rules[0].head.s
    branches = []
    for rule in rules:
        where = rule.where(None, "", graphs)
        own = rule.head.s
        if own == target:
            branches.append(f"{{ {where} }}")
        else:
            branches.append(f"{{ SELECT ({own} AS {target}) WHERE {{ {{ SELECT {own} WHERE {{ {where} }} }} }} }}")
    return f"{{ SELECT DISTINCT {target} WHERE {{\n  {' UNION '.join(branches)}\n  }} }}"


__all__ = ["class_unions", "lead_first", "union_where"]
