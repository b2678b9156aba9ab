"""The ROS 1 node: aRMOR's two services on one :class:`~topostore.armor.ArmorService`.

``/armor_interface_srv`` (``armor_msgs/ArmorDirective``) runs one request,
``/armor_interface_serialized_srv`` (``armor_msgs/ArmorDirectiveList``) runs a
list in order with the README's intended semantics.  rospy serves every client
connection on its own thread; ArmorService serialises manipulations of one
reference, so concurrent clients are safe.

Both services go through :meth:`ArmorNode.execute`, which keeps the events
topic (:mod:`.events`, ``~events``) following every reference, including those
a request has just LOADed.
"""

from __future__ import annotations

import sys
import time
import xmlrpc.client
from collections.abc import Iterator, Sequence
from typing import Any

from ..armor import ArmorService
from ..armor.types import ArmorResponse, ArmorResponseList
from ..ontology.events import DEFAULT_QUEUE
from . import DEFAULT_NODE_NAME, SERIALIZED_SERVICE, SINGLE_SERVICE, require_ros
from .events import EventsTopic
from .workspace import Workspace


class NoMaster(RuntimeError):
    """No ROS master answers at the configured URI."""


def master_uri(ros_args: Sequence[str] = ()) -> str:
    """The master URI as rospy will use it (``__master:=`` remapping, else ROS_MASTER_URI)."""
    require_ros()
    import rosgraph

    return rosgraph.get_master_uri(argv=[sys.argv[0], *ros_args])


def check_master(uri: str, timeout: float = 3.0) -> None:
    """Raise :class:`NoMaster` unless the master at ``uri`` answers within ``timeout`` seconds.

    rospy itself would wait for a master forever, retrying in the background;
    a service that is started without one should say so and stop instead.  The
    master is asked again until the time is up, so a node started together
    with ``roscore`` (a script, a boot sequence) waits for it.
    """
    deadline = time.monotonic() + timeout
    while True:
        left = deadline - time.monotonic()
        proxy = xmlrpc.client.ServerProxy(uri, transport=_TimeoutTransport(max(left, 0.1)))
        try:
            code, message, _pid = proxy.getPid("/topostore_probe")
            break
        except (TimeoutError, OSError, xmlrpc.client.Error) as exc:
            if time.monotonic() + 0.25 >= deadline:
                raise NoMaster(f"no ROS master reachable at {uri} within {timeout:g} s ({_reason(exc)}); "
                               f"start `roscore` or set ROS_MASTER_URI") from None
            time.sleep(0.25)
    if code != 1:
        raise NoMaster(f"the ROS master at {uri} refused a request: {message}")


class _TimeoutTransport(xmlrpc.client.Transport):
    def __init__(self, timeout: float) -> None:
        super().__init__()
        self._timeout = timeout

    def make_connection(self, host: Any) -> Any:
        connection = super().make_connection(host)
        connection.timeout = self._timeout
        return connection


def _reason(exc: BaseException) -> str:
    return " ".join(str(exc).split()) or type(exc).__name__


class ArmorNode:
    """A ROS node named ``name`` answering aRMOR requests with ``service``."""

    def __init__(self, service: ArmorService, workspace: Workspace, name: str = DEFAULT_NODE_NAME,
                 ros_args: Sequence[str] = (), events_queue: int = DEFAULT_QUEUE) -> None:
        self.service = service
        self.workspace = workspace
        self.name = name
        self.ros_args = list(ros_args)
        self._servers: list[Any] = []
        self.events = EventsTopic(service, events_queue)

    def start(self) -> None:
        """Register with the master, advertise the events topic and both services."""
        require_ros()
        self.workspace.activate()
        import rospy
        from armor_msgs.srv import ArmorDirective, ArmorDirectiveList

        rospy.init_node(self.name, argv=[sys.argv[0], *self.ros_args])
        self.events.start()
        self._servers = [rospy.Service(SINGLE_SERVICE, ArmorDirective, self._single),
                         rospy.Service(SERIALIZED_SERVICE, ArmorDirectiveList, self._serialized)]

    @property
    def service_names(self) -> tuple[str, str]:
        """The resolved names of the single and the serialized service."""
        return tuple(server.resolved_name for server in self._servers)  # type: ignore[return-value]

    @property
    def resolved_name(self) -> str:
        import rospy

        return rospy.get_name()

    def spin(self) -> None:
        """Serve until shutdown (SIGINT/SIGTERM: rospy unregisters the services from the master)."""
        import rospy

        try:
            rospy.spin()
        except KeyboardInterrupt:  # a second Ctrl-C while shutting down
            rospy.signal_shutdown("interrupted")
        finally:
            self.events.close()

    def shutdown(self, reason: str = "stopped") -> None:
        import rospy

        rospy.signal_shutdown(reason)

    # ---------------------------------------------------------------- handlers
    def execute(self, requests: Sequence[Any]) -> ArmorResponseList:
        """Run requests (ROS ``ArmorDirectiveReq`` messages) in order; never raises."""
        return self.service.call_many(self._following(requests))

    def _following(self, requests: Sequence[Any]) -> Iterator[Any]:
        """The requests, the events topic catching up with the references before each one runs
        and after the last (a LOAD then a REASON in one serialized call publishes that REASON)."""
        for request in requests:
            self.events.follow()
            yield request
        self.events.follow()

    def _single(self, request: Any) -> Any:
        from armor_msgs.srv import ArmorDirectiveResponse

        (response,) = self.execute([request.armor_request]).armor_responses
        return ArmorDirectiveResponse(armor_response=to_message(response))

    def _serialized(self, request: Any) -> Any:
        from armor_msgs.srv import ArmorDirectiveListResponse

        result = self.execute(list(request.armor_requests))
        return ArmorDirectiveListResponse(success=result.success, is_consistent=result.is_consistent,
                                          armor_responses=[to_message(r) for r in result.armor_responses])


def to_message(response: ArmorResponse) -> Any:
    """An :class:`ArmorResponse` as an ``armor_msgs/ArmorDirectiveRes``."""
    from armor_msgs.msg import ArmorDirectiveRes, QueryItem

    return ArmorDirectiveRes(
        success=bool(response.success), timeout=bool(response.timeout), exit_code=int(response.exit_code),
        error_description=response.error_description, is_consistent=bool(response.is_consistent),
        queried_objects=[str(o) for o in response.queried_objects],
        sparql_queried_objects=[QueryItem(key=i.key, value=i.value) for i in response.sparql_queried_objects])
