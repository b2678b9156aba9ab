"""A rospy client node for the ROS tests: aRMOR requests through ServiceProxy, replies printed as JSON.

usage: python ros_client.py single|serialized REQUESTS_JSON
Each run is a separate ROS node (anonymous name ``armor_test_client_…``).
"""

from __future__ import annotations

import json
import sys

import rospy
from armor_msgs.msg import ArmorDirectiveReq
from armor_msgs.srv import ArmorDirective, ArmorDirectiveList


def as_dict(res) -> dict:
    """An ArmorDirectiveRes as a plain dict."""
    return {"success": res.success, "timeout": res.timeout, "exit_code": res.exit_code,
            "error_description": res.error_description, "is_consistent": res.is_consistent,
            "queried_objects": list(res.queried_objects),
            "sparql_queried_objects": [{"key": i.key, "value": i.value} for i in res.sparql_queried_objects]}


def main(mode: str, requests_json: str) -> None:
    rospy.init_node("armor_test_client", anonymous=True, disable_signals=True)
    requests = [ArmorDirectiveReq(**r) for r in json.loads(requests_json)]
    if mode == "single":
        rospy.wait_for_service("/armor_interface_srv", timeout=20)
        proxy = rospy.ServiceProxy("/armor_interface_srv", ArmorDirective, persistent=True)
        out: object = [as_dict(proxy(r).armor_response) for r in requests]
        proxy.close()
    else:
        rospy.wait_for_service("/armor_interface_serialized_srv", timeout=20)
        reply = rospy.ServiceProxy("/armor_interface_serialized_srv", ArmorDirectiveList)(requests)
        out = {"success": reply.success, "is_consistent": reply.is_consistent,
               "armor_responses": [as_dict(r) for r in reply.armor_responses]}
    print(json.dumps({"node": rospy.get_name(), "result": out}))
    rospy.signal_shutdown("done")


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
