"""A rospy client node for the ROS tests: aRMOR requests through ServiceProxy, replies printed as JSON.

usage: python ros_client.py single|serialized REQUESTS_JSON
       python ros_client.py armor_api REFERENCE   (topostore's armor_py_api client over RosTransport)
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


def armor_api_scenario(ref: str) -> dict:
    """The tutorial through ArmorClient, as a robot script written for armor_py_api would run it."""
    from topostore.armor_api.armor_client import ArmorClient
    from topostore.armor_api.armor_exceptions import ArmorServiceCallError, ArmorServiceInternalError
    from topostore.ros.transport import RosTransport

    client = ArmorClient("example", ref, transport=RosTransport())
    out: dict = {}
    client.utils.load_ref_from_file("topological_map.owl", "http://bnc/exp-rob-lab/2022-23", True, "PELLET", False)
    for location, door in (("E", "D6"), ("E", "D7"), ("R3", "D6"), ("R4", "D7")):
        client.manipulation.add_objectprop_to_ind("hasDoor", location, door)
    client.manipulation.add_dataprop_to_ind("visitedAt", "R3", "LONG", "1665579700")
    client.manipulation.add_dataprop_to_ind("visitedAt", "R4", "LONG", "1665579735")
    client.call("DISJOINT", "IND", "", ["E", "R3", "R4", "D6", "D7"])
    client.manipulation.add_objectprop_to_ind("isIn", "Robot1", "E")
    client.utils.sync_buffered_reasoner()
    out["reach_from_E"] = client.query.objectprop_b2_ind("canReach", "Robot1")
    out["now"] = client.query.dataprop_b2_ind("now", "Robot1")
    client.manipulation.replace_one_dataprop_b2_ind("now", "Robot1", "LONG", "1665579750")
    batch = client.call_serialized([("REPLACE", "OBJECTPROP", "IND", ["isIn", "Robot1", "R3", "E"]),
                                    ("REASON", "", "", [])])
    out["batch"] = [batch.success, batch.is_consistent, [r.exit_code for r in batch.armor_responses]]
    out["reach_from_R3"] = client.query.objectprop_b2_ind("canReach", "Robot1")
    out["urgent"] = client.query.ind_b2_class("URGENT")
    try:
        client.manipulation.add_objectprop_to_ind("isIn", "Robot1", "no such thing")
    except ArmorServiceInternalError as exc:
        out["refused"] = exc.code
    nowhere = ArmorClient("x", ref, transport=RosTransport("/no_such_srv", "/no_such_serialized_srv", timeout=0.5))
    try:
        nowhere.query.ind_b2_class("URGENT")
    except ArmorServiceCallError as exc:
        out["unreachable"] = str(exc).split(":")[0]
    return out


def main(mode: str, requests_json: str) -> None:
    rospy.init_node("armor_test_client", anonymous=True, disable_signals=True)
    if mode == "armor_api":
        print(json.dumps({"node": rospy.get_name(), "result": armor_api_scenario(requests_json)}))
        return
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
