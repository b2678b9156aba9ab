"""The changes a remote store accepted and has not sent yet, and how they go.

A round trip per write would make every manipulation and every round of a REASON wait on the
network, so :class:`~topostore.stores.remote.RemoteStore` queues them here: the data change of a
manipulation, the updates the reasoner sends while it runs, and its drop of its scratch graphs.
They go with the next request, joined with ``;`` to the next update (one request, one transaction
on the server), or before a read that may see one.  A queued change the server then refuses is
undone in this process (through each change's ``undo`` and the store's ``writes_lost``) and
reported as :class:`~topostore.errors.WritesLostError`; an update refused on its own does not take
the queued changes with it (they are sent again alone).

Nothing here knows HTTP: the store hands in how one update request is posted.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Collection, Iterator
from dataclasses import dataclass
from functools import cached_property

from pyoxigraph import NamedNode, Quad

from ..errors import QueryError, StoreError, WritesLostError
from .literal_forms import FORMS
from .meta import META

#: an update that only drops graphs named by full IRIs (what a reasoner does with its scratch graphs)
_DROPS = re.compile(r"(?:\s*DROP\s+SILENT\s+GRAPH\s+<[^<>\s]+>\s*;?)+\s*", re.IGNORECASE)
_DROPPED = re.compile(r"GRAPH\s+<([^<>\s]+)>", re.IGNORECASE)
#: an update that declares its own prefixes or base (comments may come first)
PROLOGUE = re.compile(r"(?:\s|#[^\n]*\n)*(?:PREFIX|BASE)\b", re.IGNORECASE)

#: a lost change, as :meth:`~topostore.stores.base.Store._writes_lost` takes it: (adds, removes)
Lost = list[tuple[list[Quad], list[Quad]]]


@dataclass
class Queued:
    """A data change accepted by the store and not yet sent: its update text (graph names on the wire),
    its quads, and how to undo what was recorded in memory for it."""

    text: str
    adds: list[Quad]
    removes: list[Quad]
    undo: Callable[[], None] | None
    #: graphs the change drops whole (a reasoner's scratch graphs)
    dropped: frozenset[NamedNode] = frozenset()
    #: a reasoner's update, whatever it reads and writes: every read sends it first
    opaque: bool = False
    #: the prefixes its text uses (declared once at the head of the request that carries it)
    prefixes: dict[str, str] | None = None

    @cached_property
    def _written(self) -> tuple[frozenset, frozenset]:
        """The graphs and the (subject, predicate, graph) and (None, predicate, graph) patterns it writes."""
        quads = (*self.adds, *self.removes)
        return (frozenset(q.graph_name for q in quads) | self.dropped,
                frozenset(k for q in quads for k in ((q.subject, q.predicate, q.graph_name),
                                                       (None, q.predicate, q.graph_name))))

    def touches(self, graphs: Collection[NamedNode] | None, patterns: Collection[tuple] | None) -> bool:
        """Whether a read of ``graphs`` (None: any) or of (subject, predicate, graph) ``patterns`` (subject
        None: any predicate's subject) sees it."""
        if self.opaque or (graphs is None and patterns is None):
            return True
        written, keys = self._written
        if patterns is None:
            return not written.isdisjoint(graphs)
        return not keys.isdisjoint(patterns) or any(p[2] in self.dropped for p in patterns)


class WriteQueue:
    """The queued changes of one store, in order, and the one way they are sent (:meth:`send`)."""

    def __init__(self, post_update: Callable[[str], object], writes_lost: Callable[[Lost, bool], None]) -> None:
        #: posts one update request; raises StoreError (no answer) or QueryError (refused)
        self._post = post_update
        #: tells the store which changes did not reach the server (``certain``: surely not applied)
        self._writes_lost = writes_lost
        self.items: list[Queued] = []

    def __bool__(self) -> bool:
        return bool(self.items)

    def __iter__(self) -> Iterator[Queued]:
        return iter(self.items)

    def append(self, queued: Queued) -> None:
        self.items.append(queued)

    def touched(self, graphs: Collection[NamedNode] | None, patterns: Collection[tuple] | None) -> bool:
        """Whether a read of ``graphs`` or ``patterns`` (see :meth:`Queued.touches`) sees a queued change."""
        return any(q.touches(graphs, patterns) for q in self.items)

    def holds_reasoning(self) -> bool:
        """Whether a reasoner's update waits (a REASON is done only once its writes are on the server)."""
        return any(q.opaque for q in self.items)

    def clashes(self, prefixes: dict[str, str] | None) -> bool:
        """Whether ``prefixes`` declare a name the queued updates use for another IRI (one request then
        cannot declare both)."""
        return bool(prefixes) and any(q.prefixes and any(q.prefixes.get(k, v) != v for k, v in prefixes.items())
                                      for q in self.items)

    def defer_reasoning(self, text: str, prefixes: dict[str, str] | None) -> None:
        """Queue a reasoner's update (already on the wire's graph names): it goes with the reasoner's next
        update, or before its next read (any read: what it changes is not known here)."""
        if self.clashes(prefixes):
            self.send()
        self.items.append(Queued(text, [], [], None, opaque=True, prefixes=prefixes))

    def defer_drops(self, text: str, out: Callable[[str], str], kept: frozenset[NamedNode]) -> bool:
        """Queue an update that only drops graphs the caller declared its own (``kept``: a reasoner
        clearing its scratch graphs); False, and nothing queued, for any other update."""
        if not _DROPS.fullmatch(text):
            return False
        dropped = frozenset(NamedNode(iri) for iri in _DROPPED.findall(text))
        if dropped & (kept | {META, FORMS}):
            return False
        self.items.append(Queued(out(text.strip().rstrip(";")), [], [], None, dropped))
        return True

    def send(self, text: str = "", prefixes: dict[str, str] | None = None) -> None:
        """One update request: the queued changes, then ``text`` (either may be empty); the prefixes of
        all of them are declared once, first (the caller saw that they do not clash)."""
        queued, self.items = self.items, []
        body = " ;\n".join([q.text for q in queued] + ([text] if text else []))
        if not body:
            return
        declared: dict[str, str] = {}
        for q in queued:
            declared.update(q.prefixes or {})
        body = with_prefixes(body, {**declared, **(prefixes or {})})
        try:
            self._post(body)
        except StoreError as exc:  # no answer: the queued changes may or may not be there
            if queued:
                self._lose(queued, f"the server did not answer, so whether it applied them is unknown: {exc}",
                           certain=False)
            raise
        except QueryError as exc:  # refused: nothing of the request was applied
            if not queued:
                raise
            self._refused(queued, bool(text), exc)

    def _refused(self, queued: list[Queued], with_update: bool, exc: QueryError) -> None:
        """A request carrying queued changes was refused.  The manipulations' data changes are not to be
        lost for an update that went with them (the caller's, or the reasoner's queued ones): they are
        sent again alone; what still fails is undone here and said (WritesLostError).  Re-raises
        ``exc`` when the caller's update alone was at fault."""
        data = [q for q in queued if not (q.opaque or q.dropped)]
        reasoner = [q for q in queued if q.opaque or q.dropped]
        if not data or not (with_update or reasoner):
            self._lose(queued, f"the server refused them: {exc}")
        try:
            self._post(" ;\n".join(q.text for q in data))
        except (QueryError, StoreError) as again:
            self._lose(queued, f"the server refused them: {exc}; sent alone: {again}",
                       certain=isinstance(again, QueryError))
        if reasoner:
            self._lose(reasoner, f"the server refused them: {exc}")
        raise exc

    def _lose(self, queued: list[Queued], why: str, certain: bool = True) -> None:
        """Undo queued changes that did not reach the server, in this process; raises WritesLostError."""
        for q in reversed(queued):
            if q.undo is not None:
                q.undo()
        # a lost drop or reasoner update leaves graphs' content unknown here: as an unanswered request does
        reasoner = sum(1 for q in queued if q.dropped or q.opaque)
        self._writes_lost([(q.adds, q.removes) for q in queued], certain and not reasoner)
        data = sum(1 for q in queued if any(x.graph_name != META for x in (*q.adds, *q.removes)))
        what = f"{data} change(s) of the data" + (f", {reasoner} update(s) of the reasoner" if reasoner else "")
        note = " (the next REASON is a full one)" if reasoner else ""
        raise WritesLostError(f"{what} ({len(queued) - data - reasoner} of the persisted state) accepted earlier and "
                              f"waiting to be written to the SPARQL server were not written, and were undone "
                              f"here{note}: {why}")


def with_prefixes(text: str, prefixes: dict[str, str] | None) -> str:
    """PREFIX declarations for pyoxigraph's ``prefixes=`` argument, which servers do not have."""
    if not prefixes:
        return text
    return "".join(f"PREFIX {p}: <{iri}>\n" for p, iri in prefixes.items()) + text
