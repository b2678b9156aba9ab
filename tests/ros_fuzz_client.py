"""A long-lived rospy client for the ROS fuzz suite: one JSON request per stdin line, one JSON reply per stdout line.

Starting a ROS node costs about a second, so the fuzz suite keeps this one
running and sends it every case.  Input lines are ``{"service": "single" |
"serialized", "requests": [ArmorDirectiveReq fields...]}``; output lines are
``{"replies": [...], "success": bool}`` or ``{"error": "..."}`` when the service
call itself failed (the node raised, closed the connection or vanished).

ROS strings are bytes on the wire: a string holding lone surrogates is sent as
those bytes (``surrogateescape`` for U+DC80..U+DCFF, i.e. raw invalid UTF-8,
else ``surrogatepass``), so the node also receives text that is not UTF-8.
"""

from __future__ import annotations

import json
import sys

import rospy
from armor_msgs.msg import ArmorDirectiveReq
from armor_msgs.srv import ArmorDirective, ArmorDirectiveList

SINGLE, SERIALIZED = "/armor_interface_srv", "/armor_interface_serialized_srv"


class Wire(str):
    """A str that genpy serialises byte for byte, surrogates included (genpy calls ``.encode('utf-8')``)."""

    def encode(self, encoding: str = "utf-8", errors: str = "strict") -> bytes:  # type: ignore[override]
        try:
            return str.encode(self, "utf-8", "surrogateescape")
        except UnicodeEncodeError:
            return str.encode(self, "utf-8", "surrogatepass")


def message(fields: dict) -> ArmorDirectiveReq:
    """An ArmorDirectiveReq whose every string goes on the wire unchanged."""
    return ArmorDirectiveReq(client_name=Wire(fields["client_name"]), reference_name=Wire(fields["reference_name"]),
                             command=Wire(fields["command"]), primary_command_spec=Wire(fields["primary_command_spec"]),
                             secondary_command_spec=Wire(fields["secondary_command_spec"]),
                             args=[Wire(a) for a in fields["args"]])


def as_dict(res) -> dict:
    return {"success": res.success, "timeout": res.timeout, "exit_code": res.exit_code,
            "error_description": res.error_description, "is_consistent": res.is_consistent,
            "queried_objects": list(res.queried_objects),
            "sparql_queried_objects": [[i.key, i.value] for i in res.sparql_queried_objects]}


class Proxies:
    """Persistent connections to both services, reopened after a failed call."""

    def __init__(self) -> None:
        rospy.wait_for_service(SINGLE, timeout=30)
        rospy.wait_for_service(SERIALIZED, timeout=30)
        self.open()

    def open(self) -> None:
        self.single = rospy.ServiceProxy(SINGLE, ArmorDirective, persistent=True)
        self.serialized = rospy.ServiceProxy(SERIALIZED, ArmorDirectiveList, persistent=True)

    def call(self, service: str, requests: list[dict]) -> dict:
        try:
            if service == "single":
                res = self.single(message(requests[0])).armor_response
                return {"replies": [as_dict(res)], "success": res.success}
            out = self.serialized([message(r) for r in requests])
            return {"replies": [as_dict(r) for r in out.armor_responses], "success": out.success}
        except (rospy.ServiceException, rospy.ROSException, OSError) as exc:
            self.single.close()
            self.serialized.close()
            self.open()
            return {"error": f"{type(exc).__name__}: {exc}"}


def main() -> None:
    rospy.init_node("armor_fuzz_client", anonymous=True, disable_signals=True)
    proxies = Proxies()
    print(json.dumps({"ready": rospy.get_name()}), flush=True)
    for line in sys.stdin:
        case = json.loads(line)
        print(json.dumps(proxies.call(case["service"], case["requests"])), flush=True)
    rospy.signal_shutdown("done")


if __name__ == "__main__":
    main()
