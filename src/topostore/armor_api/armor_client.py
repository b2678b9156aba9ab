"""``ArmorClient``: drop-in replacement for armor_py_api's client (spec §6.2).

>>> from topostore.armor_api.armor_client import ArmorClient
>>> client = ArmorClient("example", "ref")

The ROS service names are kept as attributes for compatibility; the requests
go through a pluggable :class:`~topostore.armor_api.transport.Transport`:
``url=`` (or the ``TOPOSTORE_URL`` environment variable) selects the HTTP
transport, ``token=`` (or ``TOPOSTORE_TOKEN``) the bearer token it sends;
otherwise the shared in-process service.  ``timeout`` keeps armor_py_api's
meaning: seconds to wait for the service, not a limit on a command.
"""

from __future__ import annotations

import importlib
import os
from collections.abc import Sequence

from ..armor import ArmorRequest, ArmorResponse
from ..armor.types import ArmorResponseList
from .armor_exceptions import ArmorServiceCallError, ArmorServiceInternalError
from .armor_manipulation_client import ArmorManipulationClient
from .armor_query_client import ArmorQueryClient
from .armor_utils_client import ArmorUtilsClient
from .transport import Transport, default_service


def _http_transport(url: str, timeout: float, token: str | None) -> Transport:
    """An HTTP transport from ``topostore.armor_api.http_transport`` when that module is installed."""
    try:
        module = importlib.import_module("topostore.armor_api.http_transport")
    except ImportError as exc:
        raise ArmorServiceCallError(f"no HTTP transport is available for {url!r}: {exc}") from None
    return module.HttpTransport(url, timeout=timeout, token=token)


class ArmorClient:
    """A client of one reference, identified by ``client_id`` for the mount system."""

    def __init__(self, client_id: str, reference_name: str, service_name: str = "/armor_interface_srv",
                 serial_service_name: str = "/armor_interface_serialized_srv", timeout: float = 5,
                 transport: Transport | None = None, url: str | None = None, token: str | None = None) -> None:
        self.client_id = client_id
        self.reference_name = reference_name
        self.service_name = service_name
        self.serial_service_name = serial_service_name
        self.timeout = timeout
        if transport is None:
            url = url if url is not None else os.environ.get("TOPOSTORE_URL") or None
            transport = _http_transport(url, timeout, token) if url is not None else default_service()
        self.transport: Transport = transport
        self.manipulation = ArmorManipulationClient(self)
        self.query = ArmorQueryClient(self)
        self.utils = ArmorUtilsClient(self)

    def _prepare_request(self, command: str, first_spec: str, second_spec: str, args_list: Sequence[str]) -> ArmorRequest:
        """The request the original client builds: this client's identity and reference."""
        return ArmorRequest(self.client_id, self.reference_name, command, first_spec, second_spec, [str(a) for a in args_list])

    def call(self, command: str, first_spec: str, second_spec: str, args_list: Sequence[str]) -> ArmorResponse:
        """Send one command and return the raw response (``success`` is not checked).

        Transport failures propagate; the manipulation/query/utils methods turn
        them into :class:`ArmorServiceCallError`.
        """
        return self.transport.call(self._prepare_request(command, first_spec, second_spec, args_list))

    def call_serialized(self, commands: Sequence[tuple[str, str, str, Sequence[str]]]) -> ArmorResponseList:
        """Send several commands through the serialized service (executed in order)."""
        requests = [self._prepare_request(*c) for c in commands]
        try:
            return self.transport.call_many(requests)
        except OSError as exc:  # the service cannot be reached (the Transport contract); other errors are bugs
            raise ArmorServiceCallError(f"serialized service call failed: {exc}") from exc

    def _checked(self, command: str, first_spec: str, second_spec: str, args_list: Sequence[str]) -> ArmorResponse:
        """``call``, with transport errors as ArmorServiceCallError and failures as ArmorServiceInternalError."""
        res = self._unchecked(command, first_spec, second_spec, args_list)
        if not res.success:
            raise ArmorServiceInternalError(res.error_description, res.exit_code)
        return res

    def _unchecked(self, command: str, first_spec: str, second_spec: str, args_list: Sequence[str]) -> ArmorResponse:
        """``call`` with transport errors converted, ``success`` not checked."""
        try:
            return self.call(command, first_spec, second_spec, args_list)
        except OSError as exc:  # the service cannot be reached (the Transport contract); other errors are bugs
            raise ArmorServiceCallError(f"service call {command} {first_spec} {second_spec} failed: {exc}") from exc


__all__ = ["ArmorClient"]
