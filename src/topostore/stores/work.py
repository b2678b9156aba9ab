"""The unit of work of a :class:`~topostore.stores.base.Store`: transactions, pending writes, presence.

A transaction gathers writes (``add``/``remove``/``meta_set``) into one atomic commit; reads inside it see
its pending writes.  Its state lives on the store (``_pending``: quad key -> (quad, present after commit);
``_known``: quad key -> present in the committed store, learnt during the transaction; ``_depth``; a
respelling, :mod:`.respelling`, adds one more removal keyed by its quad), which
the reads (:mod:`.reads`, :mod:`.batched`) consult too.

Presence is by value (:mod:`.presence`); within one call a value is changed once, in its first spelling,
a later spelling of it left out.

These are functions of the store, bound as its methods in :class:`~topostore.stores.base.Store` (``add =
work.add``): a robot step calls them hundreds of times, and a delegating method or a separate object
would add a call (or an attribute look-up) to each.  They call one another through the store, so an
implementation's override (``_write`` of a store that defers writes, ``_commit_stream``) is the one run.
"""

from __future__ import annotations

from collections.abc import Hashable, Iterable, Iterator
from typing import TYPE_CHECKING

from pyoxigraph import Literal, NamedNode, Quad, Triple

from ..rdf.terms import Term, keep_triple, quad, triple, value_key
from .facts import Fact, fact_of, fact_read, fact_written
from .presence import has_value, kept_quad
from .respelling import unrespell

if TYPE_CHECKING:
    from .base import Store

#: from this many quads on, :meth:`Store.add` asks whether the graph is empty (one look-up) and,
#: when it is, adds without looking each quad up
BULK_ADD = 1000


class _Transaction:
    """The context manager :meth:`Store.transaction` returns."""

    __slots__ = ("store",)

    def __init__(self, store: Store) -> None:
        self.store = store

    def __enter__(self) -> Store:
        self.store._begin()
        return self.store

    def __exit__(self, kind, value, traceback) -> None:
        self.store._end(kind is not None)


class _Joined:
    """The context manager of a transaction opened inside an open one: it joins it, so there is nothing to
    begin or end (the outer one commits, or forgets on an exception that reaches it)."""

    __slots__ = ()

    def __enter__(self) -> None:
        return None

    def __exit__(self, kind, value, traceback) -> None:
        return None


_JOINED = _Joined()


# ------------------------------------------------------------ transactions
def transaction(store: Store) -> _Transaction | _Joined:
    """Group writes into one atomic commit (nested calls join the outer one).

    On an exception nothing of the transaction is written.  A SPARQL query
    or update inside a transaction first commits what is pending, so that it
    sees it; manipulations only read through the quad methods, so they stay
    one commit.  (A plain context manager class: a robot step opens a dozen of them, most inside
    another, which are joined without a count: a REPLACE's change inside its unit of work.)
    """
    return _JOINED if store._depth else _Transaction(store)


def begin(store: Store) -> None:
    """Enter a transaction (the outermost one starts with nothing pending)."""
    if store._depth == 0:
        store._pending = {}
        store.persisted.pending = {}
        store._known = {}
    store._depth += 1


def end(store: Store, failed: bool) -> None:
    """Leave a transaction: the outermost one commits, or on failure forgets what is pending."""
    store._depth -= 1
    if store._depth:
        return
    pending = store._pending  # the commit takes it whole and leaves it as it was (see flush)
    if failed:
        _abandon(store, pending)
        return
    try:
        store._flush()  # one write, undone as a whole where it fails
    except BaseException:
        _abandon(store, pending)
        raise
    store._pending, store._known = None, {}


def _abandon(store: Store, pending: dict | None) -> None:
    """Forget what a transaction held pending and never wrote (a failure in the block, or in the commit's
    own write), and tell :attr:`Store.on_rolled_back` about it."""
    store._pending, store._known = None, {}
    store.persisted.pending = {}
    if pending and store.on_rolled_back:
        adds = [q for q, present in pending.values() if present]
        removes = [q for q, present in pending.values() if not present]
        for listener in list(store.on_rolled_back):
            listener(adds, removes)


def flush(store: Store) -> None:
    """Commit the pending writes of the open transaction (also the persisted state)."""
    pending, store._pending = store._pending or {}, ({} if store._depth else None)
    persisted = store.persisted
    meta = persisted.pending  # PersistedState.take_pending, without its call where none is pending (every
    if meta:  # manipulation of a memory store)
        meta = persisted.take_pending()
    if not pending and not meta:
        return
    keyed_adds: list[tuple[Quad, Hashable]] = []
    keyed_removes: list[tuple[Quad, Hashable]] = []
    adds: list[Quad] = []
    removes: list[Quad] = []
    for k, (q, present) in pending.items():  # one pass (a manipulation's commit holds one or two writes)
        if present:
            keyed_adds.append((q, k))
            adds.append(q)
        else:
            keyed_removes.append((q, k))
            removes.append(q)
    # undo: the literal forms as they were (the removed literals as their users wrote them)
    forms_add, forms_remove, undo = store.forms.record_keyed(keyed_adds, keyed_removes)
    meta_add, meta_remove = store.persisted.quads(meta) if meta else ([], [])
    try:
        store._write(adds + forms_add + meta_add, removes + forms_remove + meta_remove, undo)
    except BaseException:
        undo()
        raise
    if meta:
        persisted.committed(meta)


def flush_open(store: Store) -> None:
    """Commit what the open transaction holds pending, and forget what it learnt of the committed store:
    a SPARQL query or update (or a read outside the quad methods) is about to see the store itself."""
    if store._pending:
        store._flush()
    store._known = {}


# ------------------------------------------------------------ quads
def add(store: Store, triples: Iterable[Triple], graph: NamedNode, distinct: bool = False) -> int:
    """Add triples to ``graph``; returns how many facts were new: a value written in two spellings is one
    fact, stored in the first (``distinct``: the caller has removed repeated triples already, so a big load
    does not hash each one again)."""
    triples = triples if isinstance(triples, (list, tuple)) else list(triples)
    if store._depth == 0 and len(triples) >= BULK_ADD and store.is_empty(graph):
        return store._add_to_empty(triples, graph, distinct)
    return len(store.add_new(triples, graph))


def add_new(store: Store, triples: Iterable[Triple], graph: NamedNode) -> list[Triple]:
    """Add triples to ``graph``; returns those that were not there (deduplicated, a value's later spellings
    left out): what a caller recording the change needs, from the one presence look-up the addition makes
    anyway."""
    return store._toggle_each(triples, graph, True)


def remove_present(store: Store, triples: Iterable[Triple], graph: NamedNode) -> list[Triple]:
    """Remove triples from ``graph``; returns those that were there (deduplicated), as :meth:`add_new`."""
    return store._toggle_each(triples, graph, False)


def remove(store: Store, triples: Iterable[Triple], graph: NamedNode) -> int:
    """Remove triples from ``graph``; returns how many were there."""
    return len(store.remove_present(triples, graph))


def toggle_each(store: Store, triples: Iterable[Triple], graph: NamedNode, add: bool) -> list[Triple]:
    """Record the pending addition (or removal) of each triple that is absent (present) in ``graph``,
    in one transaction; returns those triples."""
    triples = triples if isinstance(triples, (list, tuple)) else list(triples)
    if len(triples) == 1:  # a manipulation's usual change: nothing to deduplicate
        t = triples[0]
        quads, triples = [quad(t.subject, t.predicate, t.object, graph)], [t]
    else:  # deduplicated by quad
        made = {quad(t.subject, t.predicate, t.object, graph): t for t in triples}
        quads, triples = list(made), list(made.values())
    keys = [store._key(q) for q in quads]  # a literal's value key is the costly part of a load: once each
    if not store._depth:
        with store.transaction():
            return store._toggle_absent(quads, triples, keys, add)
    return store._toggle_absent(quads, triples, keys, add)  # inside the caller's transaction (a manipulation's)


def toggle_absent(store: Store, quads: list[Quad], triples: list[Triple], keys: list[Hashable],
                  add: bool) -> list[Triple]:
    """:meth:`_toggle_each` inside an open transaction."""
    pending, changed, seen = store._pending, [], set()
    for q, t, k, present in zip(quads, triples, keys, store._present(quads, keys), strict=True):
        if present == add or k in seen:  # a later spelling of a value this call changed: one fact, changed once
            continue
        seen.add(k)
        entry = pending.get(k)  # pending True is absent from the committed store, False present; a change the other way cancels it
        if entry is None:
            pending[k] = (q if add else _held_quad(store, q, k), add)
        elif entry[1] != add:
            del pending[k]
        changed.append(t)
    return changed


def _held_quad(store: Store, q: Quad, k: Hashable) -> Quad:
    """The quad a removal of ``q`` writes: ``q``, or where the store holds its value as another term (a
    held ``"1"^^xsd:int`` removed as ``"1.0"^^xsd:decimal``) that term, as the literal forms keep it.  A
    graph may hold both terms (the reasoner's keep each spelling a rule derived): ``q`` itself goes then."""
    if type(q.object) is not Literal or store._has(q):
        return q
    held = kept_quad(store, q, k[2])  # type: ignore[index]
    return q if held is None else held


def add_to_empty(store: Store, triples: list[Triple] | tuple[Triple, ...], graph: NamedNode,
                 distinct: bool = False) -> int:
    """:meth:`add` into an empty graph with no transaction open: every triple is new, so none
    is looked up (a big load's look-ups cost as much as writing it), and quads are made only
    as the store takes them (one quad object is ≈ 440 bytes: a list of them for a map of
    100,000 locations was ≈ 800 MB).  As :meth:`add`, the first spelling of a value is
    written, and counts as new: one fact per value, whatever its spellings."""
    unique = triples if distinct else tuple(dict.fromkeys(triples))
    spelled: dict[tuple, Literal] = {}  # (subject, predicate, value key) -> the literal kept
    recorded: list[bool] = []
    respelled: list[bool] = []  # one per later spelling of a value (not written)

    def quads() -> Iterator[Quad]:
        """The quads to write, each triple's terms taken once; then the literal forms' quads."""
        for t in unique:
            s, p, o = t.subject, t.predicate, t.object
            if isinstance(o, Literal):
                key = (s, p, value_key(o))
                if key in spelled:
                    respelled.append(True)
                    continue
                spelled[key] = o
            yield Quad(s, p, o, graph)
        forms_add = store.forms.record_loaded(graph, list(spelled.items()))  # each value key computed once
        recorded.append(True)
        yield from forms_add

    store.data_writes += 1  # the in-memory store's stream is its own write, past Store._write
    try:
        store._commit_stream(quads(), [])
    except BaseException:
        if recorded:
            store.forms.record([], [Quad(s, p, o, graph) for (s, p, _), o in spelled.items()], undo=True)
        raise
    return len(unique) - len(respelled)


# ------------------------------------------------------------ facts: a change's triples with their keys made once
def fact(store: Store, t: Triple, graph: NamedNode, written: bool = True) -> Fact:
    """The :class:`~.facts.Fact` of a triple a caller adds (``written``: it is its own written form)
    or removes (its written form is asked of the literal forms when needed, see :meth:`written_fact`)."""
    return fact_of(t, graph, written)


def read_facts(store: Store, s: Term, p: NamedNode, graph: NamedNode) -> list[Fact]:
    """:meth:`triples` of (s, p, ?, graph) as facts, each quad keyed once (what a REPLACE reads, then
    removes some of): inside a transaction, their presence is remembered for the removal.  Their
    written forms are asked of the literal forms when they are removed (:meth:`written_fact`)."""
    pending = store._pending
    if pending is None or store.listings is not None:
        return [store.fact(t, graph, written=False) for t in store.triples(s, p, None, graph)]
    canonical, known, out = store.canonical_reads, store._known, []
    for q in list(store._match(s, p, None, graph)):
        f = fact_read(q, canonical)
        known[f.key] = True
        entry = pending.get(f.key)
        if entry is None:  # a pending write of its value stands for it (adding a held value: a respelling)
            out.append(f)
    for q, present in list(pending.values()):
        if present and q.subject == s and q.predicate == p and q.graph_name == graph:
            out.append(store.fact(q.triple, graph, written=False))
    return out


def unread_fact(store: Store, s: Term, p: NamedNode, o: Term, graph: NamedNode) -> Fact:
    """:meth:`fact` of the triple (s, p, o) the caller adds after its :meth:`read_facts` of the same subject,
    predicate and graph, in this transaction, found no fact of its value (its quad made first, the triple
    taken from it: :func:`~.facts.fact_written`).  That read saw every committed value of
    them, in every spelling, so the fact is noted absent from the committed store: its addition
    (:meth:`toggle_facts`) then asks no presence look-up (the quad as written, then the spelling kept),
    which a REPLACE would otherwise pay for a value it has just read."""
    f = fact_written(quad(s, p, o, graph))
    if type(o) is Literal:
        keep_triple(s, p, o, f.triple)
    if store._pending is not None and store.listings is None:  # read_facts noted what it read (see there)
        store._known.setdefault(f.key, False)  # a value the read found stays present
    return f


def written_fact(store: Store, f: Fact) -> Triple:
    """The triple of ``f`` as its user wrote it (kept in ``f.written``): what a removal reports and
    an undo restores."""
    written = f.written
    if written is None:
        t = f.triple
        o = t.object
        lit = store.forms.written(f.quad.graph_name, t.subject, t.predicate, o, f.value)
        written = f.written = t if lit == o else triple(t.subject, t.predicate, lit)
    return written


def toggle_facts(store: Store, facts: list[Fact], add: bool) -> list[Fact]:
    """:meth:`add_new` (or :meth:`remove_present`) of facts, deduplicated by the caller: those whose
    presence changed."""
    if not store._depth:
        with store.transaction():
            return store.toggle_facts(facts, add)
    pending, changed = store._pending, []
    if len(facts) == 1:  # a manipulation's usual change: its presence asked without a batch
        f = facts[0]
        k = f.key
        entry = pending.get(k)
        if entry is not None:
            present = entry[1]
        else:
            present = store._known.get(k)
            if present is None and store.listings is None:
                present = store._known[k] = has_value(store, f.quad, f.value)
            elif present is None:
                present = store._present([f.quad], [k])[0]
        if present != add:
            if entry is None:
                pending[k] = (f.quad if add else store._removal_quad(f), add)
            else:
                _cancel(store, pending, k, f)
            changed.append(f)
        return changed
    keys, seen = [f.key for f in facts], set()
    for f, k, present in zip(facts, keys, store._present([f.quad for f in facts], keys), strict=True):
        if present == add or k in seen:  # a later spelling of a value this call changed: one fact, changed once
            continue
        seen.add(k)
        entry = pending.get(k)
        if entry is None:
            pending[k] = (f.quad if add else store._removal_quad(f), add)
        elif entry[1] != add:
            _cancel(store, pending, k, f)
        changed.append(f)
    return changed


def _cancel(store: Store, pending: dict, k: Hashable, f: Fact) -> None:
    """``f`` undoes the write pending for its value (an earlier change of this transaction): the store is
    left as it was, in the spelling it held.  The fact is given that spelling's stored form, which the
    change ledger keys by, so that it cancels the earlier change there too (``"1.0"^^xsd:decimal`` added
    after ``"1"^^xsd:int`` was removed is no change, not a removed integer and an added decimal), and
    that spelling as its written form: what a removal reports and an undo restores, what a change says
    stays where ``f`` writes the value otherwise.  A respelling's addition (:func:`.respelling.restore_facts`) taken
    back leaves its removal of the spelling held."""
    held, added = pending.pop(k)
    if added and store._known.get(k):  # only a respelling adds a value the committed store holds
        unrespell(store, pending, k)
    held_triple = held.triple
    f.stored = store.stored_form(held_triple)
    if f.value is not None:
        f.written = held_triple


def pending_add(store: Store, k: Hashable) -> Triple | None:
    """The triple (as written) the open transaction's pending write of the fact keyed ``k`` (see
    :meth:`_key`) adds; None when none is pending or it removes: a change that removed and added one
    value left none where the store keeps the value as it was."""
    pending = store._pending
    entry = pending.get(k) if pending is not None else None
    return entry[0].triple if entry is not None and entry[1] else None


def pending_literal(store: Store, graph: NamedNode, s: Term, p: NamedNode, value: tuple | None) -> Literal | None:
    """The literal the open transaction's pending write adds as the fact (s, p, ``value``) of ``graph``, None
    when none is pending or it removes.  Why: the literal forms learn a spelling at the commit, so a read (or
    a change's warning) inside the transaction would otherwise name the spelling committed before it."""
    pending = store._pending
    if not pending or value is None:
        return None
    entry = pending.get((s, p, value, graph))
    return entry[0].object if entry is not None and entry[1] else None  # type: ignore[return-value]


def removal_quad(store: Store, f: Fact) -> Quad:
    """The quad a removal writes: the literal in the form kept for this fact, as it was asserted (a
    store that keeps literals as written, a remote one, matches it exactly); a fact with no form kept
    is removed as read, never in another subject's spelling of the value."""
    t = f.triple
    kept = store.forms.recorded(f.quad.graph_name, t.subject, t.predicate, f.value)
    if kept is None or kept == t.object:
        return f.quad
    return quad(t.subject, t.predicate, kept, f.quad.graph_name)
