"""The small persisted state of a reference: JSON values beside the data in a durable store.

Settings and flags (the reasoning state of :mod:`topostore.stores.state`) are
kept as one quad per key in the ``META`` graph and written with the
transaction that changes them, so they never disagree with the data.
"""

from __future__ import annotations

import json

from pyoxigraph import Literal, NamedNode, Quad

from .vocab import INTERNAL

#: Graph of the persisted state of a reference, its subject, and the prefix of its keys.
META = NamedNode(INTERNAL + "graph:meta")
META_SUBJECT = NamedNode(INTERNAL + "meta")
META_KEY = INTERNAL + "meta:"
_MISSING = object()


class PersistedState:
    """``meta``/``meta_set`` (a mixin of :class:`~topostore.store.Store`).

    Uses the store's ``durable`` flag, its ``transaction`` and its ``_match`` primitive.
    """

    durable = False

    def _init_meta(self) -> None:
        self._meta: dict[str, object] | None = None
        self._meta_pending: dict[str, object] = {}

    @property
    def meta(self) -> dict[str, object]:
        """The small JSON state a durable store keeps beside the data (settings, flags)."""
        if self._meta is None:
            self._meta = {}
            for q in self._match(META_SUBJECT, None, None, META):
                try:
                    self._meta[q.predicate.value[len(META_KEY):]] = json.loads(q.object.value)
                except ValueError:
                    continue
        return {**self._meta, **self._meta_pending}

    def meta_set(self, key: str, value: object) -> None:
        """Persist ``key`` (JSON value) with the current transaction; no-op on a memory store."""
        if not self.durable or self.meta.get(key, _MISSING) == value:
            return
        with self.transaction():
            self._meta_pending[key] = value

    def _meta_quads(self, meta: dict[str, object]) -> tuple[list[Quad], list[Quad]]:
        adds, removes = [], []
        self.meta  # noqa: B018 - loads the persisted values once; they name the quads to replace
        for key, value in meta.items():
            pred = NamedNode(META_KEY + key)
            if key in self._meta:
                removes.append(Quad(META_SUBJECT, pred, Literal(json.dumps(self._meta[key], sort_keys=True)), META))
            adds.append(Quad(META_SUBJECT, pred, Literal(json.dumps(value, sort_keys=True)), META))
        return adds, removes


__all__ = ["META", "META_KEY", "META_SUBJECT", "PersistedState"]
