"""References that outlive the process: the aRMOR side of a durable ``store`` setting.

Each reference keeps, beside its graphs and in the same store, one JSON record
(``Store.meta["reference"]``): the LOAD settings (IRI, source file, buffered
flags, reasoner name), the mounted client and the pending buffered
manipulations as the requests that made them.  The record is written in the
same transaction as the change it describes, so after ``kill -9`` the store
holds either the state before a manipulation or the state after it.  A buffered
reasoner's class hierarchy of its last REASON (what QUERY CLASS CLASS answers
until the next one, spec §2.5) is written beside it (``Store.meta["classification"]``)
with the first change after that REASON, and given back to a reference reopened
with changes since: classified then from the rules the REASON had, never a
REASON-sized write.  On start
the service reopens every reference the store holds and replays the buffered
requests into the buffer (their handlers validate again and queue the same
changes).  On a remote store each reference is claimed with a
:class:`~topostore.stores.lock.WriterLease`; a reference another process holds
is not opened, and LOADing it is refused with the holder's name.
"""

from __future__ import annotations

import logging
import shutil
import threading
import uuid
from pathlib import Path
from typing import TYPE_CHECKING

from pyoxigraph import NamedNode

from ..errors import StoreError, StoreLockedError, TopostoreError
from ..ontology.facade import Ontology
from ..rdf.vocab import ASSERTED
from ..reason.classify import Classification
from ..stores import kind, list_references, open_store, reference_dir
from ..stores.base import Store
from . import codes
from .codes import CommandError
from .context import NOT_KEPT
from .reference import Reference

if TYPE_CHECKING:  # pragma: no cover
    from .service import ArmorService

logger = logging.getLogger("topostore.armor")


#: the persisted key of a buffered reasoner's class hierarchy as of its last REASON
KEPT = "classification"


def record(ref: Reference) -> dict:
    """The persisted settings and pending state of a reference."""
    return {
        "name": ref.name, "iri": ref.iri, "source": None if ref.source is None else str(ref.source),
        "buffered_manipulation": ref.buffered_manipulation, "reasoner": ref.reasoner,
        "buffered_reasoner": ref.buffered_reasoner, "owner": ref.owner,
        "buffer": [c.origin for c in ref.buffer if c.origin is not None],
    }


def classification_record(supers: dict[NamedNode, set[NamedNode]]) -> dict:
    """A classification as the JSON value the store keeps: each class's superclasses, as IRIs."""
    return {"superclasses": {c.value: sorted(d.value for d in ds) for c, ds in supers.items()}}


def superclasses_of(value: object) -> dict[NamedNode, set[NamedNode]] | None:
    """The classification a :func:`classification_record` value holds (None: none, or not one)."""
    table = value.get("superclasses") if isinstance(value, dict) else None
    if not isinstance(table, dict):
        return None
    return {NamedNode(c): {NamedNode(d) for d in ds} for c, ds in table.items()}


class DurableReferences:
    """Opens, persists, restores and discards the references of one durable store setting."""

    def __init__(self, spec, sync: bool = False, query_url: str | None = None, update_url: str | None = None) -> None:
        self.spec = spec
        self.sync = sync
        self.urls = {"query_url": query_url, "update_url": update_url}
        self.remote = kind(spec) == "remote"
        self._leases: dict[str, object] = {}
        self._stop = threading.Event()
        self._renewer: threading.Thread | None = None
        #: the kept classification of each reference (by name) last written to its store or read from it, with
        #: the token its value there carries (:meth:`_keep`)
        self._kept: dict[str, tuple[Classification, str]] = {}

    # ------------------------------------------------------------ stores
    def new_store(self, name: str) -> Store:
        """A store for a reference being LOADed (emptied when it held a half-created reference)."""
        store = self._open(name)
        if store.meta.get("reference") is None and not store.is_empty(ASSERTED):
            self._wipe(store)
        return store

    def _open(self, name: str) -> Store:
        try:
            store = open_store(self.spec, name, sync=self.sync, **self.urls)
        except StoreError as exc:
            raise CommandError(codes.FILE_ERROR, f"cannot open the store of reference {name!r}: {exc}") from None
        if self.remote:
            from ..stores.lock import WriterLease

            # the lease has a connection of its own: its renewals run on another thread than the
            # manipulations, whose open transaction a shared store object would otherwise commit
            lease = WriterLease(open_store(self.spec, name, **self.urls))
            try:
                lease.claim(f"reference {name!r} on {self.spec}")
            except StoreLockedError as exc:
                store.close()
                lease.store.close()
                raise CommandError(codes.MOUNTED_BY_OTHER, str(exc)) from None
            self._leases[name] = lease
            self._start_renewer(lease.lease / 3)
        return store

    def persist(self, ref: Reference) -> None:
        """Write the reference's record (and its kept classification where it changed), in the transaction of
        the change it describes."""
        ref.ontology.store.meta_set("reference", record(ref))
        self._keep(ref)

    def _keep(self, ref: Reference) -> None:
        """A buffered reasoner's classification of its last REASON, written where the store holds another: at the
        first change after that REASON (a manipulation persists its reference in its own transaction), so that a
        restart before the next REASON answers the same hierarchy.  Where it cannot be made, the store holds none
        and the reopened reference says so (``context.NOT_KEPT``).

        Whether the store holds it is read from the store itself: its value carries a token naming this
        classification, and the store's values are the committed ones with the open transaction's on top.  A
        commit that fails drops the pending value, so the next change writes it again instead of leaving an
        older REASON's hierarchy to be answered after a restart."""
        onto = ref.ontology
        kept = onto.reasoning.kept
        if not (ref.buffered_reasoner and onto.dirty and onto.store.durable) or kept is None:
            return
        known = self._kept.get(ref.name)
        token = known[1] if known is not None and known[0] is kept else uuid.uuid4().hex
        held = onto.store.meta.get(KEPT)
        if isinstance(held, dict) and held.get("token") == token:
            return
        try:
            value: dict = classification_record(onto.reasoning.kept_classification() or {})
        except TopostoreError as exc:
            logger.warning("reference %r: the class hierarchy of its last REASON could not be made to keep (%s)",
                           ref.name, exc)
            value = {}
        value["token"] = token
        onto.store.meta_set(KEPT, value)
        self._kept[ref.name] = (kept, token)

    def discard(self, name: str, store: Store | None) -> None:
        """Remove a reference's durable data (DROP, or a LOAD that failed)."""
        self._kept.pop(name, None)
        lease = self._leases.pop(name, None)
        if store is not None:
            self._wipe(store)
        if lease is not None:
            lease.release()
        if store is not None:
            store.close()
        if kind(self.spec) == "directory":
            shutil.rmtree(reference_dir(self.spec, name), ignore_errors=True)

    def _wipe(self, store: Store) -> None:
        from ..rdf.vocab import ASSERTED, AUX, ENTAILED, INFERRED
        from ..stores.base import FORMS, META

        for graph in (ASSERTED, INFERRED, AUX, ENTAILED, FORMS, META):
            store.clear(graph)
        store.persisted.forget()

    # ------------------------------------------------------------ restore
    def restore(self, service: ArmorService) -> dict[str, Reference]:
        """Every reference the store holds, as it was acknowledged (references held by another writer are left out)."""
        refs: dict[str, Reference] = {}
        for name in list_references(self.spec, **self.urls):
            try:
                refs[name] = self._restore_one(service, name)
            except CommandError as exc:
                logger.warning("reference %r not opened: %s", name, exc.message)
        return refs

    def reopen(self, service: ArmorService, name: str) -> Reference | None:
        """The reference ``name`` if the store holds it (created by another process since this one started)."""
        if name not in list_references(self.spec, **self.urls):
            return None
        return self._restore_one(service, name)

    def _restore_one(self, service: ArmorService, name: str) -> Reference:
        store = self._open(name)
        data = store.meta.get("reference")
        if not isinstance(data, dict):
            self.discard(name, store)
            raise CommandError(codes.FILE_ERROR, "its LOAD never finished; the half-created data was removed")
        onto = Ontology(prefix=data["iri"] + "#", store=store)
        ref = Reference(name, onto, data["iri"], Path(data["source"]) if data.get("source") else None,
                        bool(data["buffered_manipulation"]), data["reasoner"], bool(data["buffered_reasoner"]),
                        owner=data.get("owner"))
        if not ref.buffered_reasoner and onto.dirty:
            # a live reasoner has seen every applied change: a change committed by a process killed
            # before its REASON finished is reasoned now (the change itself was never acknowledged)
            try:
                onto.reason()
            except TopostoreError as exc:  # the reference still opens, its asserted facts only
                logger.warning("reference %r: its unreasoned change could not be reasoned (%s); opened with "
                               "its asserted facts only", name, exc)
        if ref.buffered_reasoner:
            self._restore_kept(ref)
        self._replay(service, ref, data.get("buffer") or [])
        ref.persist = self.persist
        logger.info("reference %r reopened from %s (%s, %d buffered)", name, self.spec, onto.opened, len(ref.buffer))
        return ref

    def _restore_kept(self, ref: Reference) -> None:
        """What a reopened buffered reasoner answers as its last REASON's class hierarchy: the store's where changes
        were made since (None where it holds none: a store written before it was kept, or whose hierarchy could
        not be made), else the one of the store as reopened (its last REASON's state)."""
        onto = ref.ontology
        if not onto.dirty:
            try:
                onto.reasoning.keep()
            except TopostoreError as exc:  # the rules cannot be compiled: the next change or REASON says so
                logger.warning("reference %r: its class hierarchy could not be kept (%s)", ref.name, exc)
            return
        held = onto.store.meta.get(KEPT) if onto.opened == "reopened" else None
        supers = superclasses_of(held)
        if supers is None:
            logger.warning("reference %r: %s", ref.name, NOT_KEPT)
            return
        onto.reasoning.kept = kept = Classification(None, supers=supers)
        token = held.get("token") if isinstance(held, dict) else None
        if isinstance(token, str):  # the store holds it: the next change need not write it again
            self._kept[ref.name] = (kept, token)

    def _replay(self, service: ArmorService, ref: Reference, requests: list[dict]) -> None:
        """Queue the buffered requests again through their handlers (which validate and plan them)."""
        from .commands import COMMANDS, Context
        from .types import ArmorRequest

        for data in requests:
            req = ArmorRequest.from_dict(data)
            command = COMMANDS[(req.command.upper(), req.primary_command_spec.upper(), req.secondary_command_spec.upper())]
            ctx = Context(service, req, ref)
            command.handler(ctx)

    # ------------------------------------------------------------ leases
    def _start_renewer(self, every: float) -> None:
        if self._renewer is None:
            self._renewer = threading.Thread(target=self._renew_loop, args=(every,), name="topostore-lease",
                                             daemon=True)
            self._renewer.start()

    def _renew_loop(self, every: float) -> None:
        while not self._stop.wait(every):
            for name, lease in list(self._leases.items()):
                try:
                    if not lease.renew():
                        logger.error("lost the writer lock of reference %r to another process", name)
                except (TopostoreError, OSError) as exc:  # a server down for a while: renewed later perhaps
                    logger.warning("could not renew the writer lock of %r: %s", name, exc)

    def held(self, name: str) -> bool:
        lease = self._leases.get(name)
        return lease is None or lease.held

    def close(self, refs: dict[str, Reference]) -> None:
        """Release every lease and close every store (a clean shutdown)."""
        self._stop.set()
        for name, ref in refs.items():
            lease = self._leases.pop(name, None)
            if lease is not None:
                lease.release()
            ref.ontology.store.close()


__all__ = ["DurableReferences", "record", "classification_record", "superclasses_of", "KEPT"]
