"""The ROS node's events topic: every REASON on any reference, as the JSON of the HTTP event stream."""

from __future__ import annotations

import json
import subprocess
import sys
from collections.abc import Iterator
from pathlib import Path

import pytest
from ros_support import RosWorld, node_world, request, skip_without_ros, stop
from support import ABOX_OWL, IRI

LISTENER = str(Path(__file__).with_name("ros_events_client.py"))
CLIENT = str(Path(__file__).with_name("ros_client.py"))
TOPIC = "/armor_service/events"


@pytest.fixture(scope="module")
def world(tmp_path_factory: pytest.TempPathFactory) -> Iterator[RosWorld]:
    skip_without_ros()
    with node_world(tmp_path_factory.mktemp("ros_events"), ABOX_OWL) as w:
        yield w


def listen(world: RosWorld, topic: str, count: int, until_seq: int | None = None) -> subprocess.Popen:
    """A rospy subscriber in its own process; returns once it is connected to the publisher."""
    extra = [] if until_seq is None else [str(until_seq)]
    proc = subprocess.Popen([sys.executable, LISTENER, topic, str(count), "60", *extra], env=world.env,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, start_new_session=True)
    world.nodes.append(proc)
    assert proc.stdout is not None
    line = proc.stdout.readline()
    if line != "ready\n":
        stop(proc)
        raise AssertionError(f"listener not connected: {line!r} {proc.stderr.read() if proc.stderr else ''}")
    return proc


def messages(proc: subprocess.Popen) -> list[dict]:
    try:
        out, err = proc.communicate(timeout=90)
    except subprocess.TimeoutExpired:
        stop(proc)
        raise
    assert proc.returncode == 0, err
    return [json.loads(line) for line in out.splitlines()]


def call(world: RosWorld, mode: str, requests: list[dict], *remap: str) -> dict:
    proc = subprocess.run([sys.executable, CLIENT, mode, json.dumps(requests), *remap], env=world.env,
                          capture_output=True, text=True, timeout=120)
    assert proc.returncode == 0, proc.stderr
    return json.loads(proc.stdout.strip().splitlines()[-1])["result"]


def load(ref: str) -> dict:
    return request("LOAD", "FILE", "", "topological_map_abox.owl", IRI, "true", "PELLET", "false", ref=ref)


def urgent(*names: str) -> list[dict]:
    return [{"s": n, "p": "rdf:type", "o": "URGENT"} for n in names]


def event(reference: str, seq: int, added: list[dict], removed: list[dict]) -> dict:
    return {"reference": reference, "seq": seq, "added": added, "removed": removed, "consistent": True,
            "consistency_changed": False, "missed": 0}


def without_timing(msg: dict) -> dict:
    assert isinstance(msg.pop("time"), float) and isinstance(msg.pop("reason_seconds"), float)
    return msg


def test_topic_is_advertised_by_the_node(world: RosWorld) -> None:
    assert world.run("rostopic", "type", TOPIC, check=True).stdout.strip() == "std_msgs/String"
    info = world.run("rostopic", "info", TOPIC, check=True).stdout
    assert "Publishers: \n * /armor_service (http://127.0.0.1:" in info


def test_each_reason_on_references_loaded_later_is_published(world: RosWorld) -> None:
    """The tutorial-like sequence through the aRMOR service: R2 (and C1) become URGENT, then R1 stops being."""
    listener = listen(world, TOPIC, 3)
    steps = [load("eventsRef"),
             request("REPLACE", "DATAPROP", "IND", "now", "Robot1", "LONG", "1665579750", "1665579740",
                     ref="eventsRef"),
             request("REASON", ref="eventsRef"),
             request("REPLACE", "DATAPROP", "IND", "visitedAt", "R1", "LONG", "1665579750", "1665579710",
                     ref="eventsRef"),
             request("REASON", ref="eventsRef")]
    assert [r["success"] for r in call(world, "single", steps)] == [True] * 5
    # LOAD and REASON of a new reference in one serialized call: that REASON is published too
    batch = call(world, "serialized", [load("batchRef"), request("REASON", ref="batchRef")])
    assert (batch["success"], batch["is_consistent"]) == (True, True)
    got = [without_timing(m) for m in messages(listener)]
    assert got == [event("eventsRef", 1, urgent("C1", "R2"), []),
                   event("eventsRef", 2, [], urgent("R1")),
                   event("batchRef", 1, [], [])]


def test_a_lagging_topic_says_what_it_missed(world: RosWorld, tmp_path: Path) -> None:
    """A node whose event queue holds one event, 100 REASONs in one call: every REASON is either
    delivered or counted in the next message's ``missed`` (the gap in ``seq``), and the last one arrives."""
    ns = "/lagging"
    node = world.start_node(world.data_dir, "--events-queue", "1", f"__ns:={ns}", log=tmp_path / "node.log")
    try:
        reasons = 100
        listener = listen(world, f"{ns}/armor_service/events", reasons, until_seq=reasons)
        remap = f"/armor_interface_serialized_srv:={ns}/armor_interface_serialized_srv"
        batch = call(world, "serialized", [load("burst")] + [request("REASON", ref="burst")] * reasons, remap)
        assert batch["success"] is True
        got = messages(listener)
    finally:
        stop(node)
    seqs = [m["seq"] for m in got]
    assert seqs[-1] == reasons and seqs == sorted(set(seqs))
    assert [m["missed"] for m in got] == [seq - before - 1 for before, seq in zip([0] + seqs, seqs)]
    assert len(got) + sum(m["missed"] for m in got) == reasons
    print(f"{len(got)} of {reasons} events delivered, {reasons - len(got)} reported missed")


def test_references_are_followed_only_while_someone_listens(world: RosWorld) -> None:
    """Without subscribers REASON pays nothing for the topic: ``seq`` stops counting.

    rospy learns that a subscriber left when writing to its closed connection fails,
    so at most the first two REASONs after the last one left are still followed."""
    first = listen(world, TOPIC, 1)
    call(world, "serialized", [load("quietRef"), request("REASON", ref="quietRef")])
    assert [m["seq"] for m in messages(first)] == [1]
    call(world, "serialized", [request("REASON", ref="quietRef")] * 6)   # nobody listens
    second = listen(world, TOPIC, 1)
    call(world, "serialized", [request("REASON", ref="quietRef")])
    (msg,) = messages(second)
    assert msg["reference"] == "quietRef"
    assert 2 <= msg["seq"] <= 4, msg
    print(f"first seq after six REASONs nobody heard: {msg['seq']}")
