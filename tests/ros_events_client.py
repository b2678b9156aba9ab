"""A rospy node for the ROS events tests: listens to the events topic and prints each message's data.

usage: python ros_events_client.py TOPIC COUNT SECONDS [UNTIL_SEQ]
Prints ``ready`` once connected to the topic's publisher, then the ``data`` of
each message received, one per line, and exits after COUNT messages or after a
message whose ``seq`` is UNTIL_SEQ (exit 0), or after SECONDS seconds (exit 3).  Its own queue is large, so it drops nothing itself.
"""

from __future__ import annotations

import json
import queue
import sys
import time

import rospy
from std_msgs.msg import String


def main(topic: str, count: int, seconds: float, until_seq: int | None = None) -> int:
    rospy.init_node("armor_events_listener", anonymous=True, disable_signals=True)
    received: queue.Queue[str] = queue.Queue()
    sub = rospy.Subscriber(topic, String, lambda msg: received.put(msg.data), queue_size=10_000)
    deadline = time.monotonic() + seconds
    while sub.get_num_connections() == 0:
        if time.monotonic() > deadline:
            return 3
        time.sleep(0.05)
    print("ready", flush=True)
    for _ in range(count):
        try:
            data = received.get(timeout=max(deadline - time.monotonic(), 0.01))
        except queue.Empty:
            return 3
        print(data, flush=True)
        if until_seq is not None and json.loads(data)["seq"] == until_seq:
            break
    rospy.signal_shutdown("done")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1], int(sys.argv[2]), float(sys.argv[3]), *(int(a) for a in sys.argv[4:5])))
