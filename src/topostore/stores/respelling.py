"""A respelling in the unit of work (:mod:`.work`): one value's held spelling removed and another added in one
transaction, which only an undo writes.

Why: the open transaction's pending writes are keyed by value (:mod:`.presence`), so a removal and an
addition of one value cancel, and the graph keeps the spelling it held: what a manipulation wants (a value
removed and added again is no change).  An undo gives back what was held before the undone changes, which
may be another spelling than the one they left (``"1"^^xsd:int`` removed, then ``"1.0"^^xsd:decimal``
added).  Its addition is then pending under the value's key and the held spelling's removal under its own
quad (no value's key: those are tuples), so one commit writes both.  Only a pending addition of a value the
committed store holds is a respelling (:func:`unrespell` tells it so), so the reads and a manipulation's
toggles pay nothing for it.  Functions of the store, bound as its methods as those of :mod:`.work` are.
"""

from __future__ import annotations

from collections.abc import Hashable
from typing import TYPE_CHECKING

from pyoxigraph import Quad

if TYPE_CHECKING:
    from .base import Store
    from .facts import Fact


def restore_facts(store: Store, facts: list[Fact]) -> list[Fact]:
    """:meth:`toggle_facts` adding ``facts`` (an undo giving back what was held, deduplicated by the
    caller), each stored in its own spelling: where the open transaction removes a fact's value held in
    another spelling, the store writes a respelling (that removal and this addition), not nothing.

    Why: a removal and an addition of one value cancel in a transaction (its pending writes are keyed by
    value), which keeps the spelling held; an undo must give back the spelling that was held before
    instead (``"1"^^xsd:int`` removed, ``"1.0"^^xsd:decimal`` added: undone, the integer comes back).
    Only an undo pays for this: a manipulation's :meth:`toggle_facts` still cancels the two."""
    if not store._depth:
        with store.transaction():
            return store.restore_facts(facts)
    pending, plain, respelled = store._pending, [], []
    for f in facts:
        entry = pending.get(f.key) if f.value is not None else None
        if entry is not None and not entry[1] and entry[0].object != f.quad.object:
            respelled.append(f)
        else:
            plain.append(f)
    changed = store.toggle_facts(plain, True) if plain else []
    for f in respelled:
        held = pending.pop(f.key)[0]
        pending[held] = (held, False)  # keyed by its quad: no value's key (those are tuples)
        pending[f.key] = (f.quad, True)
        store._known[f.key] = True  # the committed store holds the value (see :func:`unrespell`)
        changed.append(f)
    return changed


def unrespell(store: Store, pending: dict, k: Hashable) -> None:
    """The addition a respelling of this transaction wrote for the value keyed ``k`` is taken back: what
    stays is its removal of the spelling held, pending under the value's key again."""
    held = next(key for key, (q, present) in list(pending.items())  # a rare path: a scan of the pending
                if not present and type(key) is Quad and store._key(q) == k)
    pending[k] = pending.pop(held)


__all__ = ["restore_facts", "unrespell"]
