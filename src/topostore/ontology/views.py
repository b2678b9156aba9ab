"""Class answers kept up to date from each REASON's changes: reading one costs its rows.

Why
---
A robot asks for the same class every step (``QUERY IND CLASS URGENT``).  On a
large map most locations are members, so reading the class from the store
costs a scan of every member per step, far more than the step's reasoning.
An incremental REASON knows exactly which type facts it touched (the triples
in its new-facts and over-deleted graphs, see
:mod:`topostore.reason.incremental`), so a class asked once is kept as a
view: after each incremental REASON only the touched members are re-decided
by index look-ups.

When a view is used
-------------------
A view belongs to one REASON outcome (the report object it was brought up to
date with).  It answers only while no asserted change has been made since
(``dirty`` is false) and the report is still that one; it moves on to the next
report only through an incremental REASON that reports its touched type facts.
A full REASON, a rollback (which puts an older report back), a change of the
visible graphs or an inconsistent outcome (the asserted graph alone answers, and an
asserted type fact the closure infers too is touched by no REASON) drops every view;
the next read builds it again from the store.

When the touched members are decided
------------------------------------
Not at the REASON: the touched pairs wait (:meth:`ClassViews.pending`) until a view
is read, and are then decided in one batch.  On a store reached over HTTP that batch
is a round trip; a read that goes to the server anyway (the robot's other question,
``QUERY OBJECTPROP IND``) carries it (:meth:`ClassViews.settle`), so the step's two
questions cost one request.
"""

from __future__ import annotations

import bisect
from collections.abc import Callable, Hashable, Iterable

from pyoxigraph import NamedNode

from ..rdf.terms import Term

#: at most this many classes are kept (the ones asked for most recently)
MAX_VIEWS = 32


#: renders a member as an answer string, None for a member the answer leaves out
Render = Callable[[Term], "str | None"]


class Rendered:
    """A class's members rendered and sorted (what an aRMOR answer is), kept with the members.

    Two members may render alike (short names): the list holds each string once,
    ``counts`` how many members give it.
    """

    def __init__(self, render: Render, members: Iterable[Term]) -> None:
        self.render = render
        self.counts: dict[str, int] = {}
        for m in members:
            self.add(m, insort=False)
        self.sorted = sorted(self.counts)

    def add(self, member: Term, insort: bool = True) -> None:
        text = self.render(member)
        if text is None:
            return
        n = self.counts.get(text, 0)
        self.counts[text] = n + 1
        if n == 0 and insort:
            bisect.insort(self.sorted, text)

    def remove(self, member: Term) -> None:
        text = self.render(member)
        if text is None or text not in self.counts:
            return
        self.counts[text] -= 1
        if not self.counts[text]:
            del self.counts[text]
            del self.sorted[bisect.bisect_left(self.sorted, text)]


class _View:
    def __init__(self, members: Iterable[Term]) -> None:
        self.members: dict[Term, None] = dict.fromkeys(members)
        self.rendered: dict[Hashable, Rendered] = {}


class ClassViews:
    """Members of the classes asked for, per REASON outcome (see the module docstring)."""

    def __init__(self) -> None:
        self._views: dict[NamedNode, _View] = {}
        self._owner: object | None = None  # the report the views are up to date with
        # (individual, class) pairs a REASON touched, to re-decide before a view answers
        self._stale: dict[tuple[Term, NamedNode], None] = {}
        self._decide: Callable[[list[tuple[Term, NamedNode]]], list[bool]] | None = None

    def get(self, cls: NamedNode, owner: object, compute: Callable[[], Iterable[Term]]) -> list[Term]:
        """The members of ``cls`` under ``owner`` (the current report); built with ``compute`` once."""
        return list(self._view(cls, owner, compute).members)

    def rendered(self, cls: NamedNode, owner: object, compute: Callable[[], Iterable[Term]], key: Hashable,
                 render: Render) -> list[str]:
        """The members rendered by ``render`` (one renderer per ``key``), sorted and without duplicates."""
        view = self._view(cls, owner, compute)
        done = view.rendered.get(key)
        if done is None:
            done = view.rendered[key] = Rendered(render, view.members)
        return list(done.sorted)

    def _view(self, cls: NamedNode, owner: object, compute: Callable[[], Iterable[Term]]) -> _View:
        if owner is not self._owner:
            self.clear()
            self._owner = owner
        if self._stale and self._decide is not None:
            pairs = list(self._stale)
            self.settle(pairs, self._decide(pairs))
        view = self._views.pop(cls, None)
        if view is None:
            view = _View(compute())
            while len(self._views) >= MAX_VIEWS:
                del self._views[next(iter(self._views))]
        self._views[cls] = view  # most recently asked last
        return view

    def pending(self, owner: object) -> list[tuple[Term, NamedNode]]:
        """The touched (individual, class) pairs the views of ``owner`` still have to decide."""
        return list(self._stale) if owner is self._owner else []

    def settle(self, pairs: list[tuple[Term, NamedNode]], members: list[bool]) -> None:
        """Whether each pending pair is a member now (decided by the caller, e.g. with another read)."""
        for (s, cls), now in zip(pairs, members, strict=True):
            self._stale.pop((s, cls), None)
            view = self._views.get(cls)
            if view is None:
                continue
            was = s in view.members
            if now and not was:
                view.members[s] = None
                for r in view.rendered.values():
                    r.add(s)
            elif was and not now:
                del view.members[s]
                for r in view.rendered.values():
                    r.remove(s)

    def advance(self, before: object, after: object, touched: Iterable[tuple[Term, NamedNode]] | None,
                are_members: Callable[[list[tuple[Term, NamedNode]]], list[bool]]) -> None:
        """Bring the views of ``before`` to ``after``: each touched (individual, class) pair is to be
        re-decided, in one batch with ``are_members`` when a view is next read (see the module docstring).

        ``touched`` None (a full REASON, or a run that cannot say) drops the views.  Pairs still pending
        from an earlier REASON stay pending: they are decided against the state of the latest one.
        """
        if touched is None or before is not self._owner or before is None:
            self.clear()
            return
        self._stale.update(((s, cls), None) for s, cls in touched if cls in self._views)
        self._decide = are_members
        self._owner = after

    def clear(self) -> None:
        self._views.clear()
        self._stale.clear()
        self._owner = None


__all__ = ["ClassViews", "MAX_VIEWS", "Render", "Rendered"]
