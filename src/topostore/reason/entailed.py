"""Publishing the conclusions drawn with entailed-only difference.

A SWRL rule whose DifferentIndividuals atom holds only by entailment (the two
individuals are not declared different, but equating them would be
inconsistent) still has an entailed conclusion, which Pellet reports; Pellet
finds it by refutation and never uses it to fire other rules.  The compiler
derives such conclusions in the helper graph under an internal predicate (so no
rule reads them); this step copies them, under their real predicate, into the
ENTAILED graph that queries see, leaving out those already asserted or inferred.

After a full run the graph is rebuilt: one indexed scan per such predicate.
After incremental maintenance only the triples the maintenance touched can
have changed their standing, so only those are looked at: a triple is in
ENTAILED exactly when its internal twin is in the helper graph and the triple
is neither asserted nor inferred, and each of those three facts changes only
for triples in the graphs of facts new in the closure or deleted from it.
"""

from __future__ import annotations

import functools
from collections.abc import Callable, Collection, Iterable, Sequence

from pyoxigraph import NamedNode, Quad, Triple

from ..compile.rule import RuleSet
from ..rdf.vocab import ASSERTED, AUX, ENTAILED, ENTAILED_PREFIX, INFERRED, TYPE
from ..stores.base import Store


def publish_entailed(store: Store, rules: RuleSet) -> None:
    """Rebuild the ENTAILED graph from the helper graph (after a full run)."""
    ops = [f"DROP SILENT GRAPH {ENTAILED}"]
    for p in sorted(rules.entailed_predicates, key=lambda t: t.value):
        ops.append(f"INSERT {{ GRAPH {ENTAILED} {{ ?s {p} ?o }} }} WHERE {{ GRAPH {AUX} {{ ?s {internal(p)} ?o }} "
                   f"FILTER NOT EXISTS {{ GRAPH {INFERRED} {{ ?s {p} ?o }} }} "
                   f"FILTER NOT EXISTS {{ GRAPH {ASSERTED} {{ ?s {p} ?o }} }} }}")
    store.update(" ; ".join(ops))


def refresh_entailed(store: Store, rules: RuleSet, changed: Sequence[NamedNode],
                     quads_in: Callable[[NamedNode], Sequence[tuple] | None] | None = None) -> None:
    """Bring ENTAILED up to date after maintenance; ``changed``: graphs holding every triple whose
    presence in the asserted, inferred or helper graph changed (in either form, real or internal);
    ``quads_in(graph)``: every fact of such a graph as its (subject, predicate, object) when the caller
    has read it (else None).

    The few touched triples are found (index reads in memory, one query where reads are round trips)
    and decided one by one (index look-ups); a set-at-a-time update over them let the planner scan
    every internal triple instead.
    """
    predicates = sorted(rules.entailed_predicates, key=lambda t: t.value)
    if not predicates:
        return
    touched = _touched(store, predicates, changed, quads_in)
    _publish(store, touched, _standings(store, touched))


def refresh_touched(store: Store, touched: list[Triple], twin_changed: Collection[Triple]) -> None:
    """:func:`refresh_entailed` of the touched triples a caller found (real triples of the entailed-only
    predicates; ``twin_changed``: those whose internal twin was among the changed facts).

    A triple whose twin was not changed and is absent now was absent before the maintenance too, so
    the triple was not in ENTAILED and is not wanted there: one look-up decides it (the twin's), the
    other three are asked only of the triples left."""
    if not touched:
        return
    if store.round_trips:  # one batch of four look-ups each: one request
        _publish(store, touched, _standings(store, touched))
        return
    if not twin_changed and not _any_twin(store, touched):
        return  # no twin changed and none is there: each triple's twin look-up would answer absent
    twins = store.contains_terms([Quad(t.subject, internal(t.predicate), t.object, AUX)
                                  for t in touched if t not in twin_changed])
    found = iter(twins)
    left = [t for t in touched if t in twin_changed or next(found)]
    if left:
        _publish(store, left, _standings(store, left))


def _any_twin(store: Store, touched: list[Triple]) -> bool:
    """Whether the helper graph holds an internal fact of any touched triple's predicate: one index read
    per predicate (a robot's step touches a few triples of one or two) in place of one per triple."""
    return any_twin(store, dict.fromkeys(t.predicate for t in touched))


def any_twin(store: Store, predicates: Iterable[NamedNode]) -> bool:
    """Whether the helper graph holds an internal fact of any of ``predicates`` (one index read each)."""
    for p in predicates:
        if next(iter(store.triples(None, internal(p), None, AUX)), None) is not None:
            return True
    return False


def _publish(store: Store, touched: list[Triple], standings: list[bool | None]) -> None:
    """Add to ENTAILED and drop from it the touched triples whose :func:`standing` says so."""
    add: list[Triple] = []
    drop: list[Triple] = []
    for t, change in zip(touched, standings, strict=True):
        if change is not None:
            (add if change else drop).append(t)
    if add:
        store.add_scratch(add, ENTAILED)
    if drop:
        store.discard(drop, (ENTAILED,))


def watched_forms(rules: RuleSet) -> dict[NamedNode, NamedNode]:
    """Real and internal form of each entailed-only predicate of ``rules`` → the real one (what
    :class:`.changed.ChangedGraphs` watches for :func:`refresh_touched`)."""
    return dict(_forms(tuple(sorted(rules.entailed_predicates, key=lambda t: t.value))))


def _standings(store: Store, touched: list[Triple]) -> list[bool | None]:
    """:func:`standing` of each touched triple, from its four look-ups, all in one batch (one request
    where reads are round trips; in memory one pass over the index for the step's few triples).  By term:
    ENTAILED holds each spelling of a value its rule derived, as a REASON from scratch's SPARQL writes it,
    and two spellings asked by value would take one answer (the second's twin gone drops the first)."""
    def quads(t: Triple) -> tuple[Quad, ...]:
        s, p, o = t.subject, t.predicate, t.object
        return Quad(s, internal(p), o, AUX), Quad(s, p, o, INFERRED), Quad(s, p, o, ASSERTED), Quad(s, p, o, ENTAILED)

    found = store.contains_terms([q for t in touched for q in quads(t)])  # by term, as a REASON from scratch
    return [standing(*found[4 * n:4 * n + 4]) for n in range(len(touched))]


def internal(p: NamedNode) -> NamedNode:
    """The internal predicate of ``p``'s entailed-only conclusions (in the helper graph)."""
    found = _INTERNAL.get(p)
    if found is None:
        if len(_INTERNAL) >= _INTERNAL_MAX:  # a long-lived service loads many rule sets
            _INTERNAL.clear()
        found = _INTERNAL[p] = NamedNode(ENTAILED_PREFIX + p.value)
    return found


#: internal predicates made so far (the entailed-only predicates of the rules loaded: a few)
_INTERNAL: dict[NamedNode, NamedNode] = {}
_INTERNAL_MAX = 1024


#: the internal form of an rdf:type conclusion whose individuals are different by entailment only
ENTAILED_TYPE = internal(TYPE)


def standing(internal_fact: bool, inferred: bool, asserted: bool, shown: bool) -> bool | None:
    """Whether a triple must be added to ENTAILED (True), dropped from it (False) or neither (None): it
    belongs there exactly when its internal twin holds and it is neither inferred nor asserted."""
    wanted = internal_fact and not inferred and not asserted
    return None if wanted == shown else wanted


def _touched(store: Store, predicates: Sequence[NamedNode], changed: Sequence[NamedNode],
             quads_in: Callable[[NamedNode], Sequence[tuple] | None] | None) -> list[Triple]:
    """The triples of ``predicates`` (real or internal form, as the real triple) in the ``changed`` graphs,
    without duplicates: from the facts the caller read (each a (subject, predicate, object) sequence:
    :meth:`.Store.small_terms`' tuples or triples), or an index read per predicate, form and graph (in
    memory, microseconds where parsing and planning the UNION query costs a tenth of a millisecond)."""
    if store.round_trips:
        return [Triple(row["s"], row["p"], row["o"]) for row in store.query(_touched_query(predicates, changed))]
    real = _forms(tuple(predicates))
    found: dict[Triple, None] = {}
    for g in changed:
        quads = quads_in(g) if quads_in is not None else None
        if quads is None:
            quads = [q for form in real for q in store.triples(None, form, None, g)]
        for subject, predicate, obj in quads:
            p = real.get(predicate)
            if p is not None:
                found[Triple(subject, p, obj)] = None
    return list(found)


@functools.lru_cache(maxsize=64)
def _forms(predicates: tuple[NamedNode, ...]) -> dict[NamedNode, NamedNode]:
    """Real and internal form of each of ``predicates`` → the real one (made once per rule set)."""
    return {form: p for p in predicates for form in (p, internal(p))}


def _touched_query(predicates: Sequence[NamedNode], changed: Sequence[NamedNode]) -> str:
    """?s ?p ?o of the triples of ``predicates`` (real or internal form) in the ``changed`` graphs."""
    patterns = [f"{{ GRAPH {g} {{ ?s {q} ?o }} BIND({p} AS ?p) }}"
                for p in predicates for g in changed for q in (p, internal(p))]
    return f"SELECT DISTINCT ?s ?p ?o WHERE {{ {' UNION '.join(patterns)} }}"
