"""A writer lock that lives in a shared SPARQL store, one per reference.

Several ``topostore serve`` processes may point at one SPARQL server; each
reference has at most one writer.  A process claims a reference with one
conditional update (it writes its name and a lease expiry only where no other
live lease is found, inside the server's transaction), then reads the lock back
after a settle time to make sure no other claim raced it.  The lease is renewed
in the background; a process that died (``kill -9``) loses it when the lease
expires, or at once when its successor runs on the same host and the holder's
process id is gone.  A second writer is refused with
:class:`~topostore.errors.StoreLockedError` naming the holder.
"""

from __future__ import annotations

import os
import socket
import time
import uuid

from pyoxigraph import Literal, NamedNode

from ..errors import StoreLockedError
from ..rdf.vocab import INTERNAL, XSD
from .remote import RemoteStore

LOCK_GRAPH = NamedNode(INTERNAL + "graph:lock")
_LOCK = NamedNode(INTERNAL + "lock")
_HOLDER = NamedNode(INTERNAL + "lock:holder")
_EXPIRES = NamedNode(INTERNAL + "lock:expires")
#: Seconds a lease lasts without renewal.
LEASE_SECONDS = 30.0
#: Seconds between the claim and the check that no other claim raced it.
SETTLE_SECONDS = 0.3


def _me() -> str:
    return f"{socket.gethostname()}:{os.getpid()}:{uuid.uuid4().hex[:8]}"


def _dead_local(holder: str) -> bool:
    """True when ``holder`` is a process of this host that no longer runs."""
    host, _, rest = holder.partition(":")
    pid = rest.partition(":")[0]
    if host != socket.gethostname() or not pid.isdigit():
        return False
    try:
        os.kill(int(pid), 0)
    except ProcessLookupError:
        return True
    except PermissionError:
        return False
    return False


class WriterLease:
    """This process's claim on one reference of a remote store."""

    def __init__(self, store: RemoteStore, lease: float = LEASE_SECONDS) -> None:
        self.store = store
        self.lease = lease
        self.holder = _me()
        self.held = False

    def holders(self) -> list[tuple[str, float]]:
        text = (f"SELECT ?h ?e WHERE {{ GRAPH {LOCK_GRAPH} {{ {_LOCK} {_HOLDER} ?h . {_LOCK} {_EXPIRES} ?e }} }}")
        return [(r["h"].value, float(r["e"].value)) for r in self.store.query(text)]

    def _write(self, steal: str | None) -> None:
        """Write this lease where no other live lease exists (or over ``steal``, a dead local holder's)."""
        me = Literal(self.holder)
        expires = Literal(f"{time.time() + self.lease:.3f}", datatype=NamedNode(XSD + "decimal"))
        other = f" && ?h != {Literal(steal)}" if steal else ""
        free = (f"FILTER NOT EXISTS {{ GRAPH {LOCK_GRAPH} {{ {_LOCK} {_HOLDER} ?h . {_LOCK} {_EXPIRES} ?e }} "
                f"FILTER(?h != {me} && ?e > {time.time():.3f}{other}) }}")
        # two operations of one request (one transaction): the old lease goes, this one comes, both only
        # where no other live lease exists (one DELETE/INSERT with an OPTIONAL does the same, but Virtuoso
        # 7.2 then inserts nothing)
        self.store.update(
            f"DELETE {{ GRAPH {LOCK_GRAPH} {{ {_LOCK} ?p ?o }} }} WHERE {{ GRAPH {LOCK_GRAPH} {{ {_LOCK} ?p ?o }} {free} }} ;\n"
            f"INSERT {{ GRAPH {LOCK_GRAPH} {{ {_LOCK} {_HOLDER} {me} . {_LOCK} {_EXPIRES} {expires} }} }} WHERE {{ {free} }}")

    def claim(self, what: str) -> None:
        """Take the lock or raise :class:`StoreLockedError` saying who holds it."""
        now = time.time()
        live = [(h, e) for h, e in self.holders() if h != self.holder and e > now]
        steal = live[0][0] if len(live) == 1 and _dead_local(live[0][0]) else None
        if live and steal is None:
            self._refuse(what, live)
        self._write(steal)
        time.sleep(SETTLE_SECONDS)
        found = self.holders()
        if [h for h, _ in found] != [self.holder]:
            self._refuse(what, [(h, e) for h, e in found if h != self.holder] or live)
        self.held = True

    def renew(self) -> bool:
        """Extend the lease; False when another process took it (this one must stop writing)."""
        if not self.held:
            return False
        self._write(None)
        self.held = [h for h, _ in self.holders()] == [self.holder]
        return self.held

    def release(self) -> None:
        """Give the lock up (a clean shutdown) and close the lease's connection."""
        if self.held:
            self.store.update(f"DELETE WHERE {{ GRAPH {LOCK_GRAPH} {{ {_LOCK} {_HOLDER} {Literal(self.holder)} . "
                              f"{_LOCK} {_EXPIRES} ?e }} }}")
            self.held = False
        self.store.close()

    def _refuse(self, what: str, holders: list[tuple[str, float]]) -> None:
        who = ", ".join(f"{h} (lease until {time.strftime('%H:%M:%S', time.localtime(e))})" for h, e in holders)
        raise StoreLockedError(
            f"{what} is written by another topostore process: {who or 'a concurrent claim'}; a reference has one "
            f"writer at a time: stop that process, use another reference name, or wait {self.lease:.0f} s after it died")


__all__ = ["WriterLease", "LEASE_SECONDS", "LOCK_GRAPH"]
