"""Change notifications: what each REASON changed, delivered to subscribers without ever blocking it.

The delta of one REASON is computed by ONE function, :func:`delta`, from two
:class:`Snapshot` values (the user-visible inferred triples and the consistency
before and after).  Snapshots are taken only while someone is subscribed, so a
robot without subscribers pays nothing.  (The reasoning engine knows the
delta already; it can later build the two snapshots' difference itself and
call :meth:`EventHub.publish` with a :class:`Delta` directly.)

Delivery never blocks reasoning: every subscription has a bounded queue; when
it is full the oldest event is dropped and the next event the subscriber gets
says how many it missed (``missed``).  Callback subscribers are called from a
thread of their own; the HTTP service drains a subscription from its event
loop (server-sent events).
"""

from __future__ import annotations

import json
import logging
import threading
import time
from collections import deque
from collections.abc import Callable
from dataclasses import dataclass, field

from pyoxigraph import Literal, NamedNode, Triple

from ..errors import InvalidNameError
from ..rdf.terms import Term, entity
from ..rdf.vocab import ENTAILED, INFERRED, OWL, RDF, RDFS, XSD

logger = logging.getLogger("topostore.events")

#: Graphs whose triples are "what was inferred" for subscribers (the helper graph is internal).
VISIBLE_INFERRED = (INFERRED, ENTAILED)
DEFAULT_QUEUE = 100
_PREFIXES = {"rdf": RDF, "rdfs": RDFS, "owl": OWL, "xsd": XSD}


@dataclass(frozen=True)
class Snapshot:
    """The user-visible inferred triples and the consistency at one moment."""

    triples: frozenset
    consistent: bool | None


@dataclass(frozen=True)
class Delta:
    """What one REASON changed: inferred triples added and removed, and consistency."""

    added: frozenset
    removed: frozenset
    consistency_changed: bool
    consistent: bool | None


def snapshot(store, consistent: bool | None) -> Snapshot:
    """The visible inferred triples of ``store`` (one indexed scan per graph)."""
    triples: set[Triple] = set()
    for g in VISIBLE_INFERRED:
        triples.update(store.triples(graph=g))
    return Snapshot(frozenset(triples), consistent)


def delta(before: Snapshot, after: Snapshot) -> Delta:
    """The change from ``before`` to ``after`` — the one place a REASON's delta is computed."""
    return Delta(after.triples - before.triples, before.triples - after.triples,
                 before.consistent != after.consistent, after.consistent)


@dataclass(frozen=True)
class Pattern:
    """A triple pattern; None matches anything."""

    s: Term | None = None
    p: Term | None = None
    o: Term | None = None

    def matches(self, t: Triple) -> bool:
        return all(want is None or want == got for want, got in
                   ((self.s, t.subject), (self.p, t.predicate), (self.o, t.object)))


def parse_pattern(text: str | None, prefix: str) -> Pattern | None:
    """``"rdf:type URGENT"`` (predicate object), ``"R1 rdf:type *"`` (subject predicate object)
    or ``"canReach"`` (predicate); ``*`` or ``?x`` match anything.  Names are resolved
    against ``prefix``; ``rdf:``/``rdfs:``/``owl:``/``xsd:`` names and ``<IRI>``s are accepted."""
    if text is None or not text.strip():
        return None
    parts = text.split()
    if len(parts) > 3:
        raise InvalidNameError(f"a pattern has at most 3 parts (subject predicate object), got {len(parts)} in {text!r}")
    terms = [None if x == "*" or x.startswith("?") else _resolve(x, prefix) for x in parts]
    if len(terms) == 1:
        return Pattern(p=terms[0])
    if len(terms) == 2:
        return Pattern(p=terms[0], o=terms[1])
    return Pattern(*terms)


def _resolve(name: str, prefix: str) -> NamedNode:
    if name == "a":
        return NamedNode(RDF + "type")
    head, sep, local = name.partition(":")
    if sep and head in _PREFIXES and not name.startswith("<"):
        return NamedNode(_PREFIXES[head] + local)
    return entity(name, prefix)


def term_text(term: Term, prefix: str) -> str:
    """A term as users name it: local names of the ontology, ``rdf:type``, literal values."""
    if isinstance(term, Literal):
        return term.value
    if isinstance(term, NamedNode):
        v = term.value
        if v.startswith(prefix):
            return v[len(prefix):]
        for short, ns in _PREFIXES.items():
            if v.startswith(ns):
                return f"{short}:{v[len(ns):]}"
        return v
    return str(term)


@dataclass
class Event:
    """One REASON as a subscriber sees it (triples filtered by its pattern)."""

    seq: int
    added: list[Triple]
    removed: list[Triple]
    consistent: bool | None
    consistency_changed: bool
    seconds: float = 0.0
    #: events this subscriber missed (dropped from its full queue) just before this one
    missed: int = 0
    time: float = field(default_factory=time.time)

    def to_dict(self, prefix: str) -> dict:
        def triples(ts: list[Triple]) -> list[dict]:
            rows = [{"s": term_text(t.subject, prefix), "p": term_text(t.predicate, prefix),
                     "o": term_text(t.object, prefix)} for t in ts]
            return sorted(rows, key=lambda r: (r["s"], r["p"], r["o"]))

        return {"seq": self.seq, "added": triples(self.added), "removed": triples(self.removed),
                "consistent": self.consistent, "consistency_changed": self.consistency_changed,
                "missed": self.missed, "reason_seconds": round(self.seconds, 6), "time": self.time}


def event_json(event: Event, prefix: str, reference: str) -> str:
    """One event as the JSON text every interface sends: the data of a server-sent event
    and the ``std_msgs/String`` of the ROS events topic (one serialisation for both)."""
    return json.dumps({"reference": reference, **event.to_dict(prefix)})


class Subscription:
    """A bounded queue of events for one subscriber.  :meth:`offer` never blocks."""

    def __init__(self, hub: EventHub, pattern: Pattern | None, maxsize: int, every_reason: bool,
                 notify: Callable[[], None] | None = None) -> None:
        if maxsize < 1:
            raise ValueError("a subscription queue holds at least one event")
        self.hub, self.pattern, self.maxsize, self.every_reason = hub, pattern, maxsize, every_reason
        self.notify = notify
        self._queue: deque[Event] = deque()
        self._missed = 0
        self._cond = threading.Condition()
        self.closed = False

    def _filtered(self, seq: int, d: Delta, seconds: float) -> Event | None:
        added = [t for t in d.added if self.pattern is None or self.pattern.matches(t)]
        removed = [t for t in d.removed if self.pattern is None or self.pattern.matches(t)]
        if not (added or removed or d.consistency_changed or self.every_reason):
            return None
        return Event(seq, added, removed, d.consistent, d.consistency_changed, seconds)

    def offer(self, seq: int, d: Delta, seconds: float) -> None:
        """Queue the event for this subscriber; a full queue drops its oldest event (counted as missed)."""
        event = self._filtered(seq, d, seconds)
        if event is None or self.closed:
            return
        with self._cond:
            if len(self._queue) >= self.maxsize:
                self._queue.popleft()
                self._missed += 1
            self._queue.append(event)
            self._cond.notify_all()
        if self.notify is not None:
            try:
                self.notify()
            except Exception:  # a subscriber's wake-up must never break reasoning
                logger.exception("event notification failed")

    def get(self, timeout: float | None = None) -> Event | None:
        """The next event (None after ``timeout`` seconds or once closed); ``missed`` says what was dropped."""
        with self._cond:
            if not self._queue and not self.closed:
                self._cond.wait(timeout)
            if not self._queue:
                return None
            event = self._queue.popleft()
            event.missed, self._missed = self._missed, 0
            return event

    def close(self) -> None:
        with self._cond:
            self.closed = True
            self._cond.notify_all()
        self.hub._remove(self)


class EventHub:
    """The subscribers of one ontology and the per-REASON publication."""

    def __init__(self, prefix: Callable[[], str]) -> None:
        self.prefix = prefix
        self._subs: list[Subscription] = []
        self._lock = threading.Lock()
        self.seq = 0

    @property
    def active(self) -> bool:
        return bool(self._subs)

    def open(self, pattern: str | Pattern | None = None, maxsize: int = DEFAULT_QUEUE, every_reason: bool = True,
             notify: Callable[[], None] | None = None) -> Subscription:
        """A subscription to drain with :meth:`Subscription.get` (by default, one event per REASON)."""
        pat = parse_pattern(pattern, self.prefix()) if isinstance(pattern, str) or pattern is None else pattern
        sub = Subscription(self, pat, maxsize, every_reason, notify)
        with self._lock:
            self._subs.append(sub)
        return sub

    def subscribe(self, callback: Callable[[Event], None], pattern: str | Pattern | None = None,
                  maxsize: int = DEFAULT_QUEUE, every_reason: bool = False) -> Subscription:
        """Call ``callback(event)`` from a thread of its own after each REASON that changed
        something matching ``pattern`` (or changed consistency; after every REASON with
        ``every_reason``).  A slow callback only delays itself: its queue drops the oldest
        events and the next event says how many."""
        sub = self.open(pattern, maxsize, every_reason=every_reason)

        def deliver() -> None:
            while not sub.closed:
                event = sub.get(timeout=0.5)
                if event is None:
                    continue
                try:
                    callback(event)
                except Exception:
                    logger.exception("event subscriber failed")

        threading.Thread(target=deliver, name="topostore-events", daemon=True).start()
        return sub

    def _remove(self, sub: Subscription) -> None:
        with self._lock:
            if sub in self._subs:
                self._subs.remove(sub)

    # ------------------------------------------------------------ around REASON
    def before_reason(self, store, consistent: bool | None) -> Snapshot | None:
        """The snapshot before a REASON, only when someone listens."""
        return snapshot(store, consistent) if self.active else None

    def after_reason(self, store, consistent: bool | None, before: Snapshot | None, seconds: float) -> None:
        if before is None or not self.active:
            return
        self.publish(delta(before, snapshot(store, consistent)), seconds)

    def publish(self, d: Delta, seconds: float = 0.0) -> None:
        """Offer one REASON's delta to every subscriber (never blocks)."""
        with self._lock:
            self.seq += 1
            seq, subs = self.seq, list(self._subs)
        for sub in subs:
            sub.offer(seq, d, seconds)


__all__ = ["Delta", "Snapshot", "Event", "EventHub", "Pattern", "Subscription", "delta", "event_json", "snapshot",
           "parse_pattern", "term_text"]
