"""The node's events topic: every REASON on any reference, as the JSON event the HTTP stream sends.

``~events`` (``/armor_service/events`` for the default node name), type
``std_msgs/String``; each message's ``data`` is :func:`topostore.ontology.events.event_json`
of one REASON — the same text as the ``data:`` line of
``GET /references/{name}/events`` — with ``reference`` naming the reference, so
one topic serves every reference, including those LOADed after the node started.

Reasoning never waits for ROS: each reference has an
:class:`~topostore.ontology.events.EventHub` subscription (a bounded queue, ``queue_size``
events) drained by a thread of its own, which hands the message to rospy's
publisher queue (:data:`ROS_QUEUE` messages per subscriber; rospy sends from its own thread).
When the drain falls behind, the oldest events are dropped and the next message
says how many in ``missed``, exactly as the server-sent events do.  ``seq``
counts the REASONs of a reference published while the topic had subscribers, so
a ROS subscriber whose own ``queue_size`` overflowed (ROS drops those silently)
sees the gap too.

References are followed only while the topic has at least one subscriber (rospy
tells the publisher as subscribers come and go): following makes each REASON
snapshot the inferred triples twice, which costs as much as the REASON itself on
large maps (``python -m benchmarks.events``), and nobody should pay that for a
topic nobody reads.

Not latched: a message is a change (added and removed triples), meaningful only
to a listener that already knew the state before it.  Replaying the last change
of some reference to a late subscriber would present an old delta as news; a
newcomer asks the service for the current state (QUERY) and then follows the topic.
"""

from __future__ import annotations

import threading
from typing import TYPE_CHECKING, Any

from ..armor.codes import CommandError
from ..ontology.events import DEFAULT_QUEUE, Event, Subscription, event_json

if TYPE_CHECKING:  # pragma: no cover
    from ..armor import ArmorService
    from ..ontology.facade import Ontology

#: Relative to the node: ``/armor_service/events``, ``/robot1/armor_service/events`` under ``__ns:=/robot1``.
EVENTS_TOPIC = "~events"
#: rospy's outgoing queue per subscriber connection (rospy drops its oldest silently when full).
ROS_QUEUE = DEFAULT_QUEUE


class EventsTopic:
    """Publishes the REASON events of every reference of ``service`` on :data:`EVENTS_TOPIC`."""

    def __init__(self, service: ArmorService, queue_size: int = DEFAULT_QUEUE) -> None:
        if queue_size < 1:
            raise ValueError("the events queue holds at least one event")
        self.service = service
        self.queue_size = queue_size
        self._publisher: Any = None
        self._followed: dict[str, tuple[Ontology, Subscription]] = {}
        self._lock = threading.Lock()

    def start(self) -> None:
        """Advertise the topic (rospy's node must be initialised) and follow the loaded references."""
        import rospy
        from std_msgs.msg import String

        self._publisher = rospy.Publisher(EVENTS_TOPIC, String, queue_size=ROS_QUEUE, latch=False,
                                          subscriber_listener=_PeerWatch(self))
        self.follow()

    @property
    def resolved_name(self) -> str:
        return self._publisher.resolved_name

    def follow(self) -> None:
        """Subscribe to references loaded since the last call; let go of dropped or reloaded ones;
        let go of all of them while the topic has no subscriber.

        Cheap (a look at the registry's names): the node calls it around every request,
        so the first REASON after a LOAD is published, even in the same serialized call.
        """
        if self._publisher is None:
            return
        with self._lock:
            listened = self._publisher.get_num_connections() > 0
            names = self.service.reference_names() if listened else []
            current = {name: self._ontology(name) for name in names}
            for name, (onto, sub) in list(self._followed.items()):
                if current.get(name) is not onto:
                    sub.close()
                    del self._followed[name]
            for name, onto in current.items():
                if onto is not None and name not in self._followed:
                    sub = onto.events.subscribe(self._sender(name, onto), None, self.queue_size, every_reason=True)
                    self._followed[name] = (onto, sub)

    def close(self) -> None:
        """Stop following every reference (their drain threads end)."""
        with self._lock:
            for _onto, sub in self._followed.values():
                sub.close()
            self._followed.clear()

    def _ontology(self, name: str) -> Ontology | None:
        try:
            return self.service.reference(name).ontology
        except CommandError:  # dropped between the listing and the look-up
            return None

    def _sender(self, name: str, onto: Ontology):
        """The callback that runs on the subscription's own thread, never on REASON's."""
        from std_msgs.msg import String

        def send(event: Event) -> None:
            import rospy

            if rospy.is_shutdown():
                return
            self._publisher.publish(String(data=event_json(event, onto.prefix, name)))

        return send


class _PeerWatch:
    """rospy's subscriber listener interface (``rospy.SubscribeListener``): follow the references
    when a subscriber connects, let go of them when the last one leaves."""

    def __init__(self, topic: EventsTopic) -> None:
        self.topic = topic

    def peer_subscribe(self, topic_name: str, topic_publish: Any, peer_publish: Any) -> None:
        self.topic.follow()

    def peer_unsubscribe(self, topic_name: str, num_peers: int) -> None:
        if num_peers == 0:
            self.topic.follow()


__all__ = ["EVENTS_TOPIC", "ROS_QUEUE", "EventsTopic"]
