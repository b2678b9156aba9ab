"""The reasoning state a durable store keeps, so that a reopened ontology is never stale nor a mix.

Three persisted keys (``Store.meta``): ``dirty`` (asserted facts changed since
the last REASON), ``inferred`` ("valid" once a REASON finished, "building"
while one runs) and ``consistent`` (its outcome).  ``inferred`` is set to
"building" before REASON writes anything, so a process killed half-way leaves
a mark, and the reopened ontology rebuilds the inferred graphs from the
asserted ones instead of serving a mix of old and new conclusions.
"""

from __future__ import annotations

import logging
from typing import TYPE_CHECKING

from ..errors import TopostoreError
from ..rdf.vocab import ASSERTED, AUX, DIFFERENT_KEY_OF, LEGACY_DIFFERENT_KEY

if TYPE_CHECKING:  # pragma: no cover
    from ..stores.base import Store
    from .facade import Ontology

logger = logging.getLogger("topostore.store")

#: the persisted key saying how the helper graph's AllDifferent keys name their group, and its value
#: now: the member list (``urn:topostore:key:<md5(list)>:<md5(member)>``), or the member itself where the
#: asserted graph holds one member list, for that list's members only (``topostore.compile.key_form``);
#: an earlier version keyed by member every list the rule reached in a one-list store (one inferred too,
#: which joined two groups), before that a one-list store's keys named the list too ("by-list": an
#: incremental REASON after reopening would add the new members' keys in the other form), and before
#: that named the AllDifferent node, which made members of a node's two lists different
KEY_FORMAT, BY_LIST = "different-keys", "by-list, the counted list by member"


def note_changed(store: Store) -> None:
    """Asserted facts are about to change (joins the manipulation's transaction)."""
    if store.durable and not store.meta.get("dirty"):
        store.meta_set("dirty", True)


def begin_reason(store: Store) -> None:
    """REASON is about to rewrite the inferred graphs."""
    if store.durable:
        store.meta_set("inferred", "building")


def end_reason(store: Store, consistent: bool) -> None:
    """REASON finished: the inferred graphs are the closure of the asserted ones."""
    if store.durable:
        with store.transaction():
            store.meta_set("inferred", "valid")
            store.meta_set("dirty", False)
            store.meta_set("consistent", consistent)
            store.meta_set(KEY_FORMAT, BY_LIST)


def reopen(onto: Ontology) -> str:
    """Bring an ontology opened on a durable store to a sound state; says how ("new", "reopened", "rebuilt",
    or "asserted only" where the rebuilding REASON failed: the inferred graphs are then left empty).

    Finished inferred graphs are kept as they are (with the consistency they
    had); unfinished ones, or an inconsistent state whose explanations are
    needed, or a helper graph holding keys of an earlier format (:func:`_legacy_keys`), are rebuilt by a
    full REASON over the asserted graph.  That REASON
    runs while the :class:`Ontology` is being built (its constructor calls this),
    so it is said on the ``topostore.store`` log and in the result ("rebuilt").  A reopened state is
    the one a later failed REASON returns to: changes made before it was closed without a REASON since
    (``dirty``) are kept, as they were when it was opened.
    """
    store = onto.store
    if not store.durable or store.is_empty(ASSERTED):
        return "new"
    meta = store.meta
    legacy = _legacy_keys(store)
    if not legacy and meta.get("inferred") == "valid" and (meta.get("consistent") is True or meta.get("dirty")):
        onto.restore_report(bool(meta.get("consistent")), dirty=bool(meta.get("dirty")))
        # the state as reopened is the one a failed REASON returns to (its changes since are recorded)
        onto.ledger.succeeded(incremental_ready=False)
        return "reopened"
    if legacy:
        why = "written with AllDifferent keys of an earlier format"
    else:
        why = "unfinished" if meta.get("inferred") != "valid" else "inconsistent (its violations are not kept)"
    logger.warning("the store's inferred graphs are %s: rebuilding them with a full REASON while opening it", why)
    try:
        onto.reason(mode="full")
    except TopostoreError as exc:  # one store that cannot be reasoned must not stop the process opening it
        logger.warning("the store's inferred graphs could not be rebuilt (%s): opened with its asserted facts "
                       "only; REASON again once the cause is removed", exc)
        return "asserted only"
    return "rebuilt"


def _legacy_keys(store: Store) -> bool:
    """Whether the helper graph holds AllDifferent keys of an earlier format: written member first
    (``m ts:differentKey k``; the rules now read them key first), or grouped by the AllDifferent node
    (a store whose last REASON did not record :data:`BY_LIST`). An incremental REASON over such a store
    would miss the differences of the old members or find wrong ones; a full REASON clears the helper
    graph and writes them anew."""
    if next(iter(store.triples(None, LEGACY_DIFFERENT_KEY, None, AUX)), None) is not None:
        return True
    return (store.meta.get(KEY_FORMAT) != BY_LIST
            and next(iter(store.triples(None, DIFFERENT_KEY_OF, None, AUX)), None) is not None)


__all__ = ["note_changed", "begin_reason", "end_reason", "reopen"]
