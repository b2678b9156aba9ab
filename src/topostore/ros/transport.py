"""``RosTransport``: topostore's armor_py_api client (:mod:`topostore.armor_api`) over ROS services.

``ArmorClient("robot", "ontoRef", transport=RosTransport())`` sends every
command to ``/armor_interface_srv`` (and batches to
``/armor_interface_serialized_srv``) like EmaroLab's armor_py_api does, so the
same robot code reaches ``topostore ros`` or a Java aRMOR node.  The calling
process needs the generated ``armor_msgs`` (:func:`topostore.ros.workspace.ensure`
is called here) and, as for any rospy client, preferably ``rospy.init_node``.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

from ..armor import ArmorRequest, ArmorResponse
from ..armor.types import ArmorResponseList, QueryItem
from ..armor_api.armor_exceptions import ArmorServiceCallError
from . import SERIALIZED_SERVICE, SINGLE_SERVICE, require_ros


class RosTransport:
    """Calls aRMOR's ROS services; unreachable services raise :class:`ArmorServiceCallError`.

    ``timeout`` bounds the wait for the service to be advertised (as in
    armor_py_api); a call itself is not bounded by rospy.
    """

    def __init__(self, service_name: str = "/" + SINGLE_SERVICE,
                 serial_service_name: str = "/" + SERIALIZED_SERVICE, timeout: float = 5) -> None:
        require_ros()
        from . import workspace

        workspace.ensure().activate()
        import rospy
        from armor_msgs.srv import ArmorDirective, ArmorDirectiveList

        self.service_name, self.serial_service_name, self.timeout = service_name, serial_service_name, timeout
        self._single = rospy.ServiceProxy(service_name, ArmorDirective)
        self._serial = rospy.ServiceProxy(serial_service_name, ArmorDirectiveList)

    def call(self, request: ArmorRequest) -> ArmorResponse:
        reply = self._invoke(self._single, self.service_name, _message(request))
        return _response(reply.armor_response)

    def call_many(self, requests: Sequence[ArmorRequest]) -> ArmorResponseList:
        reply = self._invoke(self._serial, self.serial_service_name, [_message(r) for r in requests])
        return ArmorResponseList(success=reply.success, is_consistent=reply.is_consistent,
                                 armor_responses=[_response(r) for r in reply.armor_responses])

    def _invoke(self, proxy: Any, name: str, argument: Any) -> Any:
        import rospy

        try:
            proxy.wait_for_service(self.timeout)
            return proxy(argument)
        except (rospy.ServiceException, rospy.ROSException) as exc:
            raise ArmorServiceCallError(f"{name}: {exc}") from None


def _message(request: ArmorRequest | Any) -> Any:
    from armor_msgs.msg import ArmorDirectiveReq

    return ArmorDirectiveReq(**ArmorRequest.from_dict(request).to_dict())


def _response(message: Any) -> ArmorResponse:
    return ArmorResponse(success=message.success, exit_code=message.exit_code,
                         error_description=message.error_description, is_consistent=message.is_consistent,
                         timeout=message.timeout, queried_objects=list(message.queried_objects),
                         sparql_queried_objects=[QueryItem(i.key, i.value) for i in message.sparql_queried_objects])


__all__ = ["RosTransport"]
