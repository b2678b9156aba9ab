"""The in-memory Oxigraph store's reads for the reasoner's look-ups, straight from its index and its held graphs.

Why this exists
---------------
A robot step's REASON makes some fifty look-ups of a few facts each (:mod:`topostore.reason.staged`): the
facts of a pattern in one graph or a few, whether a scratch graph holds one, whether each head is in the
new state.  The general reads (:mod:`.reads`) answer them through the open transaction's pending writes
and the literal forms' listings; with neither in play these read the engine's index (and the scratch
graphs held in Python, :mod:`.held`) directly, with as few Python objects per fact as the caller needs.
Each falls back to the general read where a transaction is open or literal forms are listed.  They are
methods of :class:`~.oxigraph.OxigraphStore` (bound there), kept here as one concept apart from the
store's writes.
"""

from __future__ import annotations

from collections.abc import Collection, Iterator
from itertools import chain, islice
from operator import attrgetter
from typing import TYPE_CHECKING

from pyoxigraph import Literal, NamedNode, Quad, Triple

from ..rdf.terms import Term
from . import reads
from .base import Store

if TYPE_CHECKING:
    from .oxigraph import OxigraphStore

#: a quad's triple (read in C by :func:`map`)
_TRIPLE = attrgetter("triple")


def triples(store: OxigraphStore, s=None, p=None, o=None, graph=None) -> Iterator[Triple]:
    """:func:`.reads.triples` without its layers where no transaction is open (the reasoner's
    look-ups, each a few facts): a held graph's matches, or the index's quads mapped to their
    triples in C, instead of a generator over :meth:`.OxigraphStore._match`'s iterator."""
    if store._pending is not None or store.listings is not None:
        return reads.triples(store, s, p, o, graph)
    if type(s) is Literal:
        return iter(())  # a literal is no subject (:func:`few_facts`)
    held = store._held.graphs
    if held:
        if graph is None:
            # the held graphs' matches listed now, as the general read does: a write made while
            # the caller iterates neither shows up nor breaks the iteration
            return chain(map(_TRIPLE, store._ox.quads_for_pattern(s, p, o, None)),
                         [t for g in held.values() for t in store._held.triples(s, p, o, g)])
        found = held.get(graph)
        if found is not None:
            return iter(store._held.triples(s, p, o, found))
    return map(_TRIPLE, store._ox.quads_for_pattern(s, p, o, graph))


def few_facts(store: OxigraphStore, s, p, o, graphs, limit: int) -> list[Triple] | None:
    """:func:`.reads.few_facts` read here directly where no transaction is open: a held graph's
    matches, or the index's first ``limit + 1`` quads mapped to their triples in C; one graph's
    facts are distinct as read (no dictionary between the index and the caller)."""
    if store._pending is not None or store.listings is not None:
        return reads.few_facts(store, s, p, o, graphs, limit)
    if type(s) is Literal:
        return []  # a value bound by a rule's join is no subject: no fact has it (as in SPARQL)
    held = store._held.graphs
    found: list[Triple] | dict[Triple, None] | None = None
    for g in graphs:
        kept = held.get(g) if held else None
        facts = store._held.triples(s, p, o, kept) if kept is not None \
            else list(islice(map(_TRIPLE, store._ox.quads_for_pattern(s, p, o, g)), limit + 1))
        if found is None:
            found = facts
        elif facts:
            if type(found) is list:
                found = dict.fromkeys(found)
            found.update(dict.fromkeys(facts))
        if len(found) > limit:
            return None
    if found is None:
        return []
    return found if type(found) is list else list(found)


def matches(store: OxigraphStore, s, p, o, graph: NamedNode, limit: int) -> list | None:
    """:func:`few_facts` of one graph as the index gives them, quads (a held graph's triples): a look-up
    join reads only their terms, and a triple made of each quad costs pyoxigraph a copy of its terms."""
    if store._pending is not None or store.listings is not None:
        return reads.few_facts(store, s, p, o, (graph,), limit)
    if type(s) is Literal:
        return []  # a literal is no subject (:func:`few_facts`)
    held = store._held.graphs
    kept = held.get(graph) if held else None
    facts = store._held.triples(s, p, o, kept) if kept is not None \
        else list(islice(store._ox.quads_for_pattern(s, p, o, graph), limit + 1))
    return facts if len(facts) <= limit else None


def has_match(store: OxigraphStore, s, p, o, graph: NamedNode) -> bool:
    """Whether ``graph`` holds a fact of the pattern: a held graph's first match, or the index's first
    quad, with no list and no triple made (a staged run asks it of its scratch graphs a dozen times)."""
    if store._pending is not None or store.listings is not None or graph is None:
        return Store.has_match(store, s, p, o, graph)
    if type(s) is Literal:
        return False  # a literal is no subject (:func:`few_facts`)
    held = store._held.graphs
    kept = held.get(graph) if held else None
    if kept is not None:
        return store._held.any_match(s, p, o, kept)
    return next(store._ox.quads_for_pattern(s, p, o, graph), None) is not None


def match_in(store: OxigraphStore, s, p, o, graphs: frozenset, limit: int) -> list | None:
    """The distinct triples of ``(s, p, o)`` in any of ``graphs``, at most ``limit + 1`` of them: one
    index read over every graph, filtered here, instead of one read per graph (each read costs its
    call and its iterator).  Only where the subject or the object is bound, so that the quads of other
    graphs are few; None where that does not hold (or a transaction is open): read each graph then."""
    if (s is None and o is None) or store._pending is not None or store.listings is not None \
            or (store._held.graphs and not graphs.isdisjoint(store._held.graphs)):
        return None
    if type(s) is Literal:
        return []  # a literal is no subject (:func:`few_facts`)
    found: dict = {}
    seen = 0
    for q in store._ox.quads_for_pattern(s, p, o, None):
        seen += 1
        if q.graph_name in graphs:
            found[q.triple] = None
            if len(found) > limit:
                break
        elif seen > 4 * limit:
            return None  # other graphs hold many: the per-graph reads are cheaper
    return list(found)


def objects_by_graph(store: OxigraphStore, s: Term, p: NamedNode, graphs: list[NamedNode]) -> dict[NamedNode, list[Term]]:
    """:meth:`Store.objects` of (s, p) in each of ``graphs`` by one index read over every graph, sorted
    out here (a query's answer, e.g. the asserted, inferred and entailed values of a property, is
    three reads otherwise, each its call and its iterator); per graph where a transaction is open,
    literal forms are listed or a held graph is among ``graphs``."""
    if type(s) is Literal or not _one_read(store, graphs):
        return Store.objects_by_graph(store, s, p, graphs)
    found: dict[NamedNode, list[Term]] = {g: [] for g in graphs}
    for q in store._ox.quads_for_pattern(s, p, None, None):
        values = found.get(q.graph_name)
        if values is not None:
            values.append(q.object)
    return found


def known_in(store: OxigraphStore, triples: list[Triple], graphs: Collection[NamedNode]) -> list[bool]:
    """Whether each triple is in one of ``graphs``, as :func:`.presence.present` answers it: one index
    read per triple over every graph (a fact is in a few), where the presence batch makes a quad per
    triple and graph; that batch (:func:`.reads.known_in`) where the one read does not hold
    (:func:`_one_read`) or a triple's object is a literal (presence is then by value)."""
    if not _one_read(store, graphs):
        return reads.known_in(store, triples, graphs)
    match = store._ox.quads_for_pattern
    out = []
    for t in triples:
        o = t.object
        if type(o) is Literal:
            return reads.known_in(store, triples, graphs)
        found = False
        for q in match(t.subject, t.predicate, o, None):  # a loop, not any() over a generator: a fact is in one or two
            if q.graph_name in graphs:
                found = True
                break
        out.append(found)
    return out


def contains_each(store: OxigraphStore, triples: list[Triple], graph: NamedNode) -> list[bool]:
    """Whether each triple is in ``graph``, as :func:`.reads.contains_each` answers it: where no
    transaction is open and no literal forms are listed, one membership test per triple (the held
    graph's dictionary, or the index), not a quad batch through the presence layers; that batch for a
    literal (presence is then by value)."""
    if store._pending is not None or store.listings is not None:
        return reads.contains_each(store, triples, graph)
    held = store._held.graphs.get(graph) if store._held.graphs else None
    ox = store._ox
    out = []
    for t in triples:
        o = t.object
        if type(o) is Literal:
            return reads.contains_each(store, triples, graph)
        out.append((t.subject, t.predicate, o) in held if held is not None
                   else Quad(t.subject, t.predicate, o, graph) in ox)
    return out


def _one_read(store: OxigraphStore, graphs: Collection[NamedNode]) -> bool:
    """Whether one index read over every graph answers for ``graphs`` as the per-graph reads do: no
    transaction open, no literal forms listed, no held graph among them."""
    held = store._held.graphs
    return store._pending is None and store.listings is None and not (held and not held.keys().isdisjoint(graphs))


__all__ = ["contains_each", "few_facts", "has_match", "known_in", "match_in", "matches", "objects_by_graph", "triples"]
