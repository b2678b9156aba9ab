"""The reads of a :class:`~topostore.stores.base.Store`: triples by pattern, objects, subjects, collections,
presence, census, counts and the dump, as the open transaction sees them.

Each is a function of the store over its primitives (``_match``, ``_present``, ``_run_query``) and its parts
(``listings``, ``batched``, ``forms``), bound as its method in :class:`~topostore.stores.base.Store`
(``triples = reads.triples``): the reasoner and a manipulation read through them in their inner loops, where a
delegating method would add a call to each.  An implementation overrides one by defining the method (the
in-memory store counts a small graph from its index).
"""

from __future__ import annotations

from collections.abc import Collection, Iterable, Iterator
from itertools import islice
from typing import TYPE_CHECKING

from pyoxigraph import Literal, NamedNode, Quad, Triple

from ..rdf.skolem import unskolemize
from ..rdf.terms import Term
from ..rdf.vocab import FIRST, NIL, REST, TYPE

if TYPE_CHECKING:
    from .base import Store


def key_census(facts: Iterable[Triple | Quad]) -> tuple[dict[str, int], dict[str, int]]:
    """Facts per predicate and per class (objects of rdf:type), keyed by SPARQL text: the read keys
    a set of facts changes, and how much (see :meth:`Store.census`)."""
    preds: dict[str, int] = {}
    classes: dict[str, int] = {}
    for f in facts:
        p = str(f.predicate)
        preds[p] = preds.get(p, 0) + 1
        if p == _TYPE_TEXT:  # by its text: a pyoxigraph term's equality is a call
            c = str(f.object)
            classes[c] = classes.get(c, 0) + 1
    return preds, classes


_TYPE_TEXT = str(TYPE)


def _matches(q: Quad, s, p, o, graph) -> bool:
    """Whether a pending quad matches a pattern of :func:`triples` (None: any)."""
    return ((s is None or q.subject == s) and (p is None or q.predicate == p)
            and (o is None or q.object == o) and (graph is None or q.graph_name == graph))


def triples(
    store: Store, s: Term | None = None, p: NamedNode | None = None, o: Term | None = None,
    graph: NamedNode | None = None,
) -> Iterator[Triple]:
    """Triples matching a pattern (None: any), with the open transaction's pending writes on top; what it
    reads of the committed store is remembered for the transaction's presence look-ups."""
    if store.listings is not None and s is not None and p is not None and o is None and graph is not None:
        yield from store.batched.listed(s, p, graph)
        return
    pending = store._pending
    if pending is None:
        for q in store._match(s, p, o, graph):
            yield q.triple
        return
    for q in list(store._match(s, p, o, graph)):
        key = store._key(q)
        store._known[key] = True
        entry = pending.get(key)
        if entry is None:  # a pending write of its value stands for it (adding a held value: a respelling)
            yield q.triple
    for q, present in list(pending.values()):
        if present and _matches(q, s, p, o, graph):
            yield q.triple


def few_facts(store: Store, s: Term | None, p: NamedNode | None, o: Term | None, graphs: Iterable[NamedNode],
              limit: int) -> list[Triple] | None:
    """The distinct triples of a pattern (None: any) in any of ``graphs`` (one read per graph), None when
    there are more than ``limit``: what the reasoner's look-ups read before deciding that their few
    facts are few (else their SPARQL text runs)."""
    seen: dict[Triple, None] = {}
    for g in graphs:
        seen.update(dict.fromkeys(islice(store.triples(s, p, o, g), limit + 1)))
        if len(seen) > limit:
            return None
    return list(seen)


def objects(store: Store, s: Term, p: NamedNode, graph: NamedNode) -> list[Term]:
    """Objects of (s, p, ?) in ``graph``, as the open transaction sees them."""
    if store._pending is None and store.listings is None:  # the index as it is: no triple made per value
        return [q.object for q in store._match(s, p, None, graph)]
    return [t.object for t in store.triples(s, p, None, graph)]


def objects_many(store: Store, pairs: list[tuple[Term, NamedNode]], graph: NamedNode) -> dict[tuple, list[Term]]:
    """:meth:`objects` of several (subject, predicate) pairs; one query where reads are round trips."""
    return store.batched.objects_many(pairs, graph)


def subjects(store: Store, p: NamedNode, o: Term, graph: NamedNode) -> list[Term]:
    """Subjects of (?, p, o) in ``graph``, as the open transaction sees them."""
    return [t.subject for t in store.triples(None, p, o, graph)]


def list_items(store: Store, head: Term, graph: NamedNode) -> list[Term]:
    """Members of an RDF collection (rdf:first/rdf:rest), in order."""
    return list_read(store, head, graph)[0]


def list_read(store: Store, head: Term, graph: NamedNode) -> tuple[list[Term], str]:
    """Members of an RDF collection, in order, and what is wrong with its shape ("" when nothing): a list
    that loops back on itself is read once around, a cell with several rdf:first or rdf:rest by the first
    the store gives (a reader that takes it says so, rather than reading a malformed list silently)."""
    items: list[Term] = []
    seen = set()
    faults: list[str] = []
    node = head
    while node != NIL:
        if node in seen:
            faults.append("it loops back on itself (read once around)")
            break
        seen.add(node)
        firsts = store.objects(node, FIRST, graph)
        if not firsts:
            break
        items.append(firsts[0])
        rests = store.objects(node, REST, graph)
        if len(firsts) > 1 or len(rests) > 1:
            faults.append(f"a cell has {len(firsts)} rdf:first and {len(rests)} rdf:rest (one of each read)")
        if not rests:
            break
        node = rests[0]
    return items, "; ".join(dict.fromkeys(faults))


def contains(store: Store, t: Triple, graph: NamedNode) -> bool:
    """Whether ``t`` is in ``graph`` as the open transaction sees it (a literal by its value)."""
    return store._present([Quad(t.subject, t.predicate, t.object, graph)])[0]


def contains_each(store: Store, triples: list[Triple], graph: NamedNode) -> list[bool]:
    """Whether each triple is in ``graph``: one look-up batch (one request on a remote store)."""
    return store._present([Quad(t.subject, t.predicate, t.object, graph) for t in triples])


def contains_quads(store: Store, quads: list[Quad]) -> list[bool]:
    """Whether each quad (triple and graph) is in the store: one look-up batch, as :meth:`contains_each`."""
    return store._present(quads)


def known_in(store: Store, triples: list[Triple], graphs: Collection[NamedNode]) -> list[bool]:
    """Whether each triple is in one of ``graphs`` (a literal by its value, as :meth:`contains_quads`):
    one look-up batch of a quad per triple and graph (one request on a remote store)."""
    order = tuple(graphs)
    n = len(order)
    present = store._present([Quad(t.subject, t.predicate, t.object, g) for t in triples for g in order])
    return [any(present[i * n:(i + 1) * n]) for i in range(len(triples))]


def contains_terms(store: Store, quads: list[Quad]) -> list[bool]:
    """Whether each quad is in the store as that very term, not another spelling of its literal's value.

    For the reasoner's own graphs, which hold each spelling a rule derived (a REASON from scratch keeps
    ``"8"^^xsd:integer`` and ``"8.0"^^xsd:decimal`` apart there): :meth:`contains_quads` answers by value,
    and gives two spellings asked together one answer.  Asked in batches in which no two quads share a
    value (one batch but for such pairs), so that no store's by-value answer mixes them."""
    store._flush_open()
    answers = [False] * len(quads)
    left = list(range(len(quads)))
    while left:
        batch: list[int] = []
        later: list[int] = []
        seen: set = set()
        for i in left:
            k = store._key(quads[i])
            (later if k in seen else batch).append(i)
            seen.add(k)
        for i, found in zip(batch, store._has_many([quads[i] for i in batch]), strict=True):
            answers[i] = found
        left = later
    return answers


def census(store: Store, graph: NamedNode) -> tuple[dict[str, int], dict[str, int]]:
    """Facts per predicate and per class (objects of rdf:type) in ``graph``, keyed by SPARQL text."""
    return store.census_many([graph])[graph]


def census_many(store: Store, graphs: list[NamedNode]) -> dict[NamedNode, tuple[dict[str, int], dict[str, int]]]:
    """:meth:`census` of several graphs, in one query.

    The reasoner reads the size of its scratch graphs after every round; on
    a store reached over HTTP each query is a round trip, so the graphs of
    one round are counted together (an empty graph counts nothing).
    """
    store._flush_open()
    found: dict[NamedNode, tuple[dict[str, int], dict[str, int]]] = {g: ({}, {}) for g in graphs}
    if not graphs:
        return found
    values = " ".join(str(g) for g in found)
    text = (f"SELECT ?g ?p ?c (COUNT(*) AS ?n) WHERE {{ VALUES ?g {{ {values} }} GRAPH ?g {{ ?s ?p ?o }} "
            f"BIND(IF(sameTerm(?p, {TYPE}), ?o, \"\") AS ?c) }} GROUP BY ?g ?p ?c")
    for r in store._run_query(text, None):
        preds, classes = found[store._graph_in(r["g"])]
        p, n = str(r["p"]), int(r["n"].value)
        preds[p] = preds.get(p, 0) + n
        if p == str(TYPE):
            classes[str(r["c"])] = classes.get(str(r["c"]), 0) + n
    return found


def small_graph(store: Store, graph: NamedNode, limit: int = 2000) -> list[Quad] | None:
    """Every quad of ``graph`` when there are at most ``limit`` and reading them is an index scan
    (in memory or on disk), else None: the caller reads by pattern or query instead."""
    return None


def small_terms(store: Store, graph: NamedNode, limit: int = 2000) -> list[tuple] | None:
    """:func:`small_graph` as each quad's (subject, predicate, object): what a reader that goes through a
    scratch graph once needs, each term read once (pyoxigraph makes a new object at every read)."""
    quads = store.small_graph(graph, limit)
    return None if quads is None else [(q.subject, q.predicate, q.object) for q in quads]


def count(store: Store, graph: NamedNode) -> int:
    """Quads in ``graph`` (one query; pending writes committed first)."""
    result = store.query(f"SELECT (COUNT(*) AS ?n) WHERE {{ GRAPH {graph} {{ ?s ?p ?o }} }}")
    return int(next(iter(result))["n"].value)


def is_empty(store: Store, graph: NamedNode) -> bool:
    """Whether ``graph`` holds no quad (one ASK; pending writes committed first)."""
    return not bool(store.query(f"ASK {{ GRAPH {graph} {{ ?s ?p ?o }} }}"))


def dump(store: Store, graphs: list[NamedNode], restore_literals_from: NamedNode | None = None) -> list[Triple]:
    """Triples of ``graphs`` (deduplicated), blank nodes and literal forms restored."""
    out: dict[Triple, None] = {}
    for g in graphs:
        for t in store.triples(graph=g):
            if isinstance(t.object, Literal):
                form = store.original_literal(restore_literals_from or g, t.subject, t.predicate, t.object)
                t = Triple(t.subject, t.predicate, form)
            out[unskolemize(t)] = None
    return list(out)


__all__ = ["key_census"]
