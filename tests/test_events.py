"""Change notifications: the per-REASON delta, pattern filters, bounded queues that never block REASON."""

from __future__ import annotations

import threading

from pyoxigraph import NamedNode, Triple
from support import NS

from topostore import Ontology
from topostore.ontology.events import Delta, EventHub, Snapshot, delta, parse_pattern
from topostore.resources import default_ontology_files

TYPE = NamedNode("http://www.w3.org/1999/02/22-rdf-syntax-ns#type")


def urgent(name: str) -> Triple:
    return Triple(NamedNode(NS + name), TYPE, NamedNode(NS + "URGENT"))


def example() -> Ontology:
    onto = Ontology.from_file(*default_ontology_files())
    onto.reason()
    return onto


def test_delta_is_the_difference_of_two_snapshots() -> None:
    a, b, c = urgent("R1"), urgent("R2"), urgent("C1")
    d = delta(Snapshot(frozenset({a, b}), True), Snapshot(frozenset({b, c}), False))
    assert d == Delta(frozenset({c}), frozenset({a}), True, False)
    assert delta(Snapshot(frozenset(), None), Snapshot(frozenset(), None)).consistency_changed is False


def test_patterns() -> None:
    p = parse_pattern("rdf:type URGENT", NS)
    assert (p.s, p.p, p.o) == (None, TYPE, NamedNode(NS + "URGENT"))
    assert p.matches(urgent("R2")) and not p.matches(Triple(NamedNode(NS + "R2"), TYPE, NamedNode(NS + "ROOM")))
    assert parse_pattern("R1 * *", NS).s == NamedNode(NS + "R1")
    assert parse_pattern("canReach", NS).p == NamedNode(NS + "canReach")
    assert parse_pattern("  ", NS) is None


def test_callback_gets_what_matches_its_pattern() -> None:
    onto = example()
    got: list[dict] = []
    done = threading.Event()

    def on_event(event) -> None:
        got.append(event.to_dict(onto.prefix))
        done.set()

    onto.subscribe(on_event, "rdf:type URGENT")
    onto.replace("Robot1", "now", onto.value(1665579750, "long"))
    onto.reason()
    assert done.wait(10)
    assert [(e["seq"], e["added"], e["removed"], e["missed"], e["consistent"]) for e in got] == [
        (1, [{"s": "C1", "p": "rdf:type", "o": "URGENT"}, {"s": "R2", "p": "rdf:type", "o": "URGENT"}], [], 0, True)]
    onto.replace("R1", "visitedAt", onto.value(1665579750, "long"))
    done.clear()
    onto.reason()
    assert done.wait(10)
    assert (got[1]["added"], got[1]["removed"]) == ([], [{"s": "R1", "p": "rdf:type", "o": "URGENT"}])


def test_consistency_change_is_an_event() -> None:
    onto = example()
    sub = onto.events.open("rdf:type URGENT", every_reason=False)
    onto.add_fact("R1", "hasDoor", "R2")      # a location as a door: inconsistent
    onto.reason()
    event = sub.get(timeout=5)
    assert (event.consistent, event.consistency_changed) == (False, True)


def test_no_subscriber_no_snapshot() -> None:
    onto = example()
    calls = []
    original = EventHub.before_reason

    def spy(self, store, consistent):
        result = original(self, store, consistent)
        calls.append(result)
        return result

    EventHub.before_reason = spy
    try:
        onto.replace("Robot1", "now", onto.value(1665579750, "long"))
        onto.reason()
        sub = onto.events.open()
        onto.reason()
        sub.close()
        onto.reason()
    finally:
        EventHub.before_reason = original
    assert [c is None for c in calls] == [True, False, True]


def test_a_blocked_subscriber_never_blocks_reason_and_is_told_what_it_missed() -> None:
    onto = example()
    release = threading.Event()
    received = []

    def stuck(event) -> None:
        received.append((event.seq, event.missed))
        release.wait(30)

    onto.subscribe(stuck, maxsize=2)
    listener = onto.events.open(every_reason=True)

    def step(k: int) -> None:
        onto.replace("Robot1", "now", onto.value(1665579750 - 10 * (k % 2), "long"))  # C1, R2 URGENT or not
        onto.reason()

    def five_reasons() -> None:
        step(0)
        for _ in range(200):  # the subscriber holds event 1 (a REASON may be quicker than its thread)
            if received:
                break
            threading.Event().wait(0.05)
        for k in range(1, 5):
            step(k)

    worker = threading.Thread(target=five_reasons)
    worker.start()
    worker.join(60)
    assert not worker.is_alive()                       # REASON did not wait for the stuck callback
    assert [listener.get(timeout=1).seq for _ in range(5)] == [1, 2, 3, 4, 5]
    release.set()
    for _ in range(100):
        if len(received) == 3:
            break
        threading.Event().wait(0.05)
    # event 1 was being handled; 2..5 went to a queue of 2: 2 and 3 were dropped
    assert received == [(1, 0), (4, 2), (5, 0)]


def test_event_json_is_the_event_with_its_reference() -> None:
    """The one serialisation of the SSE stream and the ROS topic."""
    import json

    from topostore.ontology.events import Event, event_json

    e = Event(3, [urgent("R2")], [urgent("R1")], True, False, 0.25, missed=2, time=1.5)
    assert json.loads(event_json(e, NS, "ontoRef")) == {
        "reference": "ontoRef", "seq": 3, "added": [{"s": "R2", "p": "rdf:type", "o": "URGENT"}],
        "removed": [{"s": "R1", "p": "rdf:type", "o": "URGENT"}], "consistent": True, "consistency_changed": False,
        "missed": 2, "reason_seconds": 0.25, "time": 1.5}
