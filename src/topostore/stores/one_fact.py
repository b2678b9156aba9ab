"""One committed fact replaced by another, written straight to the store: a robot's REPLACE.

Why: the unit of work (:mod:`.work`) serves every change: a transaction whose pending writes are keyed by
value, presence learnt and asked through them, a commit that sorts them by sign and records the literal
forms with an undo for a write that fails.  The change of one fact read from the committed store for one
of another value that read found absent needs none of it: its presence is known from the read, nothing
else is pending, and a failure of the one write of two quads is undone by putting the old quad back.
Written here it is the same write (the removal the quad read: the index's own term, which the spelling the
literal forms keep, :meth:`Store._removal_quad`'s, names for a store that canonicalises) and the same
literal forms, without a transaction around them.

Only where the store writes at once and keeps nothing beside its index (:func:`direct`); anywhere else the
caller takes the unit of work.

What such a change leaves is known without a read: the one fact of its subject and predicate, read back
once as the store holds it.  :class:`KeptFacts` keeps it while the store counts no other write of data
(:attr:`Store.data_writes`), so the next change of the same pair (a robot's clock, its place) reads
nothing before its write.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from pyoxigraph import Literal, NamedNode, Quad

from ..rdf.terms import Term, value_key
from .facts import Fact, fact_read
from .literal_forms import stored_seen

if TYPE_CHECKING:
    from .base import Store


def direct(store: Store) -> bool:
    """Whether a change may be written straight: no transaction open and no persisted state pending (the
    change would join them), a store that answers from its own index in the spelling it stores (no
    listings, canonical reads: a fact read is its own stored form) and persists no literal forms (a durable
    store writes them in the same commit)."""
    return not store._depth and store.listings is None and store.canonical_reads and not store.durable \
        and not store.persisted.pending


#: pairs :class:`KeptFacts` holds at most (a map's robot replaces a value of a few of them a step)
KEPT_MAX = 4096


class KeptFacts:
    """The committed facts of the (subject, predicate) pairs of one graph this path wrote last, each as
    the store holds it, while the store has counted no write since but this path's own
    (:attr:`Store.data_writes`: a reasoner's writes to its own graphs are not counted, every other write
    is, a SPARQL update whatever it names).  What :func:`read` would answer, without the index read."""

    __slots__ = ("facts", "writes")

    def __init__(self) -> None:
        self.facts: dict[tuple[Term, NamedNode], list[Fact]] = {}
        #: the store's count of data writes the facts hold at (-1: none yet)
        self.writes = -1

    def read(self, store: Store, s: Term, p: NamedNode, graph: NamedNode) -> list[Fact]:
        """:func:`read`, from the facts kept where they still hold."""
        if self.writes == store.data_writes:
            found = self.facts.get((s, p))
            if found is not None:
                return found
        elif self.facts:
            self.facts.clear()  # another write came: nothing kept is known to hold
        return read(store, s, p, graph)

    def wrote(self, store: Store, before: int, s: Term, p: NamedNode, now: Fact | None) -> None:
        """The write of :func:`replace` is done (``before``: the store's count of data writes when the
        facts it replaced were read): ``now`` is the one fact of (s, p) since (None: not known).  What is
        kept holds on only where that write was the one counted since."""
        facts = self.facts
        if self.writes != before or store.data_writes != before + 1:
            facts.clear()
        self.writes = store.data_writes
        if now is None:
            facts.pop((s, p), None)
            return
        if len(facts) >= KEPT_MAX:
            facts.clear()
        facts[(s, p)] = [now]


def read(store: Store, s: Term, p: NamedNode, graph: NamedNode) -> list[Fact]:
    """The committed facts (s, p, ?, graph), each quad keyed once: :meth:`Store.read_facts` with no
    transaction open (nothing pending to stand for a value, nothing to note as present)."""
    canonical = store.canonical_reads
    return [fact_read(q, canonical) for q in store._match(s, p, None, graph)]


def new_fact(s: Term, p: NamedNode, o: Term, graph: NamedNode) -> Fact:
    """The fact of (s, p, o) added after :func:`read` found no fact of its value: :meth:`Store.unread_fact`
    with no transaction to note it in, its key made of the terms given (each term read from a quad or a
    triple is a new object made by pyoxigraph).  Its quad is made here, not kept (a clock value is never
    named again as the same quad: the next step removes the quad it reads); nor is its triple: the next
    change of the pair finds it as written in the fact :class:`KeptFacts` holds."""
    q = Quad(s, p, o, graph)
    t = q.triple  # pyoxigraph makes it from the quad's terms: a Triple given a literal costs ≈ 3 µs to make
    if type(o) is not Literal:
        return Fact(t, q, q, None, t, t)
    value = value_key(o)
    return Fact(t, q, (s, p, value, graph), value, None, t)


def replace(store: Store, s: Term, p: NamedNode, o: Term, graph: NamedNode, old: Fact, new: Fact, alone: bool,
            kept: KeptFacts, before: int) -> None:
    """Remove ``old`` (a fact :func:`read` found) and add ``new`` (of (s, p, o) in ``graph``, a value that
    read did not find) in one write, then the literal forms: what a transaction's commit of the two toggles
    writes.  The forms follow the write, so a write that fails leaves them as they were.

    ``alone``: ``old`` was the one fact that read found, so the new one is the one fact of its subject and
    property now: a literal's stored form (what the change ledger keys it by) is read back from the index
    (one look-up of one fact) instead of asked of the probe store (a write and a removal of it there), and
    ``kept`` (``before``: the store's count of data writes at that read) holds the fact read back (an
    individual's fact is its own stored form) for the next change of the pair."""
    _write_or_restore(store, old.quad, new.quad)
    store.forms.replaced(graph, s, p, old.value, o, new.value)
    now = None
    if alone:
        now = new if new.stored is not None else _read_back(store, new, s, p, o, graph)  # type: ignore[arg-type]
    kept.wrote(store, before, s, p, now)


def _read_back(store: Store, new: Fact, s: Term, p: NamedNode, o: Literal, graph: NamedNode) -> Fact | None:
    """The fact of ``new``'s literal as the store holds it, its stored form noted in ``new`` too (None where
    the store holds no one term of it).  The read names the literal as written, which the engine takes in
    its own form: it finds the one quad, never the removed values of the pair, which an in-memory store
    keeps in its index until its next compaction (a clock's, one a step)."""
    quads = list(store._match(s, p, o, graph))
    if len(quads) != 1:
        return None
    q = quads[0]
    stored = new.stored = q.triple
    stored_seen(o, q.object)  # type: ignore[arg-type] - a fact with no stored form is a literal's
    # its written form is the one the literal forms now keep for it (the one given)
    return Fact(stored, q, new.key, new.value, stored, new.triple)


def _write_or_restore(store: Store, old: Quad, new: Quad) -> None:
    """One write removing ``old`` (read from the index: the quad as stored, canonical reads) and adding ``new``.
    The engine removes, then adds: where the addition fails the old quad is put back before the failure is
    raised, so that nothing changed, as the command's reply then says (a transaction's undo, for the one
    write this path makes)."""
    try:
        store._write([new], [old])
    except BaseException:
        store._commit([old], [new])
        raise


__all__ = ["KEPT_MAX", "KeptFacts", "direct", "new_fact", "read", "replace"]
