"""Join plans for evaluations that start from a small graph (a delta, candidates).

Semi-naive and DRed evaluations restrict one body atom (or the head) to a graph
of a few facts; the plan binds that first and evaluates the rest once per
solution, so their cost follows the change, not the map.
"""

from __future__ import annotations

from pyoxigraph import NamedNode

from ..compile.rule import Rule, join_order

#: Up to this many facts in the start graph, per-solution (LATERAL) evaluation
#: wins; above, Oxigraph's hash joins do (measured on generated maps).
LATERAL_MAX = 100


#: How many facts of each predicate and of each class (rdf:type objects) a graph holds.
KeyCounts = tuple[dict[str, int], dict[str, int]]


def key_counts(store, graph: NamedNode) -> KeyCounts:
    """Facts per predicate and per class in ``graph``: which read keys it changes, and how much.

    Tells whether the graph is empty, which rules it can trigger and whether
    evaluations starting from it should run per solution (:func:`is_small`).
    """
    return store.census(graph)


def is_small(counts: KeyCounts, key: tuple = ("*",)) -> bool:
    """Whether the facts of read key ``key`` (all facts for ``("*",)``) are at most :data:`LATERAL_MAX`."""
    preds, classes = counts
    if key[0] == "t":
        n = classes.get(key[1], 0)
    elif key[0] == "p":
        n = preds.get(key[1], 0)
    else:
        n = sum(preds.values())
    return n <= LATERAL_MAX


def plan_where(rule: Rule, delta: int | None = None, delta_graph: NamedNode | None = None,
               head_graph: NamedNode | None = None, lateral: bool = True) -> str:
    """The WHERE group of ``rule`` for incremental evaluation.

    With ``delta``, that atom reads only ``delta_graph``; with ``head_graph``,
    the head must be a fact of that graph, matched first so that it binds the
    head's variables from a small graph (see :func:`goal_match` for a head
    variable a filter BINDs).  Filters follow the atoms, as in :meth:`Rule.where`.

    With ``lateral`` (for a small start graph), each further atom is evaluated under its own LATERAL, i.e. once per
    solution so far, in the order of :func:`~topostore.compile.rule.join_order`: Oxigraph's own join
    ordering (also inside one LATERAL group, where it does not know which
    variables are bound) often starts with a large class membership, and an
    evaluation over an empty delta then still costs tens of milliseconds on a
    map of 1,000 locations.  For a large start graph, per-solution
    evaluation costs more than Oxigraph's hash joins, so ``lateral=False``
    gives a flat group (start patterns first).
    """
    head_line, same = goal_match(rule, head_graph) if head_graph is not None else ("", "")
    bound = rule.head.variables() - rule.binds if head_line else set()
    lead, lead_bound, own = rule.placed  # a generic rule's schema rows start the group
    filters = "\n  ".join(f for f in (own, same) if f)
    start = [line for line in (head_line, lead) if line]
    rest: list[str] = []
    for k in join_order(rule.body, delta, bound | lead_bound):
        (start if k == delta else rest).append(rule.atom_text(k, delta, str(delta_graph)))
    if not start:
        return "\n  ".join(rest + ([filters] if filters else []))
    if not lateral:
        return "\n  ".join(start + rest + ([filters] if filters else []))
    return "\n  ".join(start) + nested(rest, filters)


def goal_match(rule: Rule, graph: NamedNode) -> tuple[str, str]:
    """The head as a fact of ``graph`` (a pattern to match first), and the FILTER that ties it to the body.

    A head variable that a filter BINDs cannot be bound before its BIND (SPARQL
    forbids binding it twice), so in the pattern it gets a name of its own and the
    FILTER, placed after the BINDs, requires the bound value to be that same term.
    Without that condition the evaluation would range over every derivation of
    the rule instead of the facts of ``graph`` (a DRed proof would never finish).
    """
    head = rule.head
    bind = rule.binds & head.variables()
    if not bind:
        return f"GRAPH {graph} {{ {head.text()} }}", ""
    taken = {v for atom in (*rule.body, head) for v in atom.variables()}
    taken.update(v for c in rule.conditions for v in c.variables)
    names: dict[str, str] = {}
    for var in sorted(bind):
        name = f"{var}_goal"
        while name in taken:
            name += "_"
        names[var] = name
        taken.add(name)
    s, p, o = (names.get(t, t) for t in (head.s, head.p, head.o))
    same = " && ".join(f"sameTerm({var}, {name})" for var, name in names.items())
    return f"GRAPH {graph} {{ {s} {p} {o} . }}", f"FILTER({same})"


def nested(patterns: list[str], filters: str) -> str:
    """Each pattern in its own LATERAL level, the filters innermost: a strict nested-loop order."""
    text = f"\n  {filters}" if filters else ""
    for pattern in reversed(patterns):
        text = f"\n  LATERAL {{ {pattern}{text} }}"
    return text


__all__ = ["KeyCounts", "LATERAL_MAX", "goal_match", "is_small", "key_counts", "nested", "plan_where"]
