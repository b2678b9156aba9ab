"""The inspector's history: the change events of each reference (what each REASON added and removed), kept.

Recording a reference's events costs every REASON a snapshot of its inferred
graph (:mod:`topostore.ontology.events` takes snapshots only while someone listens), so
a robot that nobody inspects pays nothing: recording starts when the inspector
page is first opened for the reference (or its history first asked for) and
goes on until the reference is dropped or recording is stopped (``DELETE``).
The answer says since when (``since``) and the page says so.

No thread is used: each reference has one bounded event subscription, drained
when the history is asked for; what the queue dropped meanwhile is counted
(``missed``), and at most ``keep`` events are kept, newest first.
"""

from __future__ import annotations

import threading
import time
import weakref
from collections import deque
from typing import TYPE_CHECKING, Any

from pyoxigraph import Triple

from ..ontology.events import Event
from .entities import View

if TYPE_CHECKING:  # pragma: no cover
    from ..armor.reference import Reference
    from ..ontology.facade import Ontology

DEFAULT_KEEP = 500
#: facts of one event kept for the page (one REASON of a large map can change thousands)
FACTS_PER_EVENT = 200


class History:
    """The recorded events of one ontology."""

    def __init__(self, onto: Ontology, keep: int = DEFAULT_KEEP) -> None:
        # weak references: a dropped reference's ontology (and its subscription, which only the
        # ontology's event hub holds) is freed even if the inspector never asks about it again
        self._onto = weakref.ref(onto)
        self.since = time.time()
        self.events: deque[dict[str, Any]] = deque(maxlen=keep)
        self.dropped = 0
        self._subscription = weakref.ref(onto.events.open(None, keep, every_reason=True))

    @property
    def onto(self) -> Ontology | None:
        return self._onto()

    def drain(self) -> None:
        """Move the queued events into the kept list (call under the reference's lock)."""
        onto, subscription = self._onto(), self._subscription()
        if onto is None or subscription is None:
            return
        view = View(onto)
        while (event := subscription.get(timeout=0)) is not None:
            if len(self.events) == self.events.maxlen:
                self.dropped += 1
            self.events.append(self._entry(view, event))

    def _entry(self, view: View, event: Event) -> dict[str, Any]:
        def facts(triples: list[Triple]) -> list[dict[str, Any]]:
            ordered = sorted(triples, key=lambda t: (str(t.subject), str(t.predicate), str(t.object)))
            return [{"s": view.term(t.subject), "p": view.term(t.predicate), "o": view.term(t.object)}
                    for t in ordered[:FACTS_PER_EVENT]]

        return {"seq": event.seq, "time": event.time, "reason_seconds": round(event.seconds, 6),
                "added": facts(event.added), "removed": facts(event.removed),
                "added_count": len(event.added), "removed_count": len(event.removed),
                "consistent": event.consistent, "consistency_changed": event.consistency_changed,
                "missed": event.missed}

    def to_dict(self) -> dict[str, Any]:
        return {"recording": True, "since": self.since, "events": list(reversed(self.events)), "kept": self.events.maxlen,
                "dropped": self.dropped, "facts_per_event": FACTS_PER_EVENT}

    def close(self) -> None:
        subscription = self._subscription()
        if subscription is not None:
            subscription.close()


class Histories:
    """One :class:`History` per reference, started on first use; a reference loaded anew
    under the same name (a new ontology) starts a new history."""

    def __init__(self, keep: int = DEFAULT_KEEP) -> None:
        self.keep = keep
        self._by_name: dict[str, History] = {}
        self._lock = threading.Lock()

    def of(self, ref: Reference) -> History:
        with self._lock:
            found = self._by_name.get(ref.name)
            if found is not None and found.onto is ref.ontology:
                return found
            if found is not None:
                found.close()
            made = History(ref.ontology, self.keep)
            self._by_name[ref.name] = made
            return made

    def stop(self, ref: Reference) -> bool:
        """Stop recording ``ref``'s events and forget them; whether it was recorded."""
        with self._lock:
            found = self._by_name.pop(ref.name, None)
        if found is not None:
            found.close()
        return found is not None

    def close(self) -> None:
        with self._lock:
            for h in self._by_name.values():
                h.close()
            self._by_name.clear()


__all__ = ["History", "Histories", "DEFAULT_KEEP", "FACTS_PER_EVENT"]
