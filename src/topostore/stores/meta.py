"""The small persisted state of a reference: JSON values beside the data in a durable store.

Settings and flags (the reasoning state of :mod:`topostore.ontology.state`) are
kept as one quad per key in the ``META`` graph and written with the
transaction that changes them, so they never disagree with the data.
"""

from __future__ import annotations

import json
from typing import TYPE_CHECKING

from pyoxigraph import Literal, NamedNode, Quad

from ..rdf.vocab import INTERNAL

if TYPE_CHECKING:
    from .base import Store

#: Graph of the persisted state of a reference, its subject, and the prefix of its keys.
META = NamedNode(INTERNAL + "graph:meta")
META_SUBJECT = NamedNode(INTERNAL + "meta")
META_KEY = INTERNAL + "meta:"
_MISSING = object()


class PersistedState:
    """The ``META`` graph of one :class:`~topostore.stores.base.Store` (``store.persisted``).

    Values set inside a transaction wait in :attr:`pending` until the store commits them with
    its data (:meth:`take_pending`, :meth:`quads`, :meth:`committed`), so state and data never
    disagree.  A memory store keeps nothing (``durable`` is read from the store at each call).
    """

    def __init__(self, store: Store) -> None:
        self._store = store
        self._values: dict[str, object] | None = None  # read from the graph on first use
        self.pending: dict[str, object] = {}

    @property
    def values(self) -> dict[str, object]:
        """The persisted values with the open transaction's pending ones on top."""
        if self._values is None:
            self._values = {}
            for q in self._store._match(META_SUBJECT, None, None, META):
                try:
                    self._values[q.predicate.value[len(META_KEY):]] = json.loads(q.object.value)
                except ValueError:
                    continue
        return {**self._values, **self.pending}

    def set(self, key: str, value: object) -> None:
        """Persist ``key`` (JSON value) with the store's current transaction; no-op on a memory store."""
        if not self._store.durable or self.values.get(key, _MISSING) == value:
            return
        with self._store.transaction():
            self.pending[key] = value

    def take_pending(self) -> dict[str, object]:
        """The values set in the transaction being committed (and none pending any more)."""
        pending, self.pending = self.pending, {}
        return pending

    def quads(self, values: dict[str, object]) -> tuple[list[Quad], list[Quad]]:
        """The quads to add and remove so that the graph holds ``values``."""
        adds, removes = [], []
        self.values  # noqa: B018 - loads the persisted values once; they name the quads to replace
        known = self._values or {}
        for key, value in values.items():
            pred = NamedNode(META_KEY + key)
            if key in known:
                removes.append(Quad(META_SUBJECT, pred, Literal(json.dumps(known[key], sort_keys=True)), META))
            adds.append(Quad(META_SUBJECT, pred, Literal(json.dumps(value, sort_keys=True)), META))
        return adds, removes

    def committed(self, values: dict[str, object]) -> None:
        """``values`` are in the graph now."""
        if values:
            self._values = {**(self._values or {}), **values}

    def forget(self) -> None:
        """Read the values from the graph again at next use (the graph was cleared underneath)."""
        self._values = None


__all__ = ["META", "META_KEY", "META_SUBJECT", "PersistedState"]
