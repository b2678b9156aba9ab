"""Drop-in replacement for the ``armor_api`` package of armor_py_api (spec §6).

``from topostore.armor_api.armor_client import ArmorClient`` works as
``from armor_api.armor_client import ArmorClient`` did; requests go to an
in-process :class:`topostore.armor.ArmorService` unless another transport is given.
"""

from . import armor_client, armor_exceptions, armor_manipulation_client, armor_query_client, armor_utils_client
from .armor_client import ArmorClient
from .armor_exceptions import ArmorPyException, ArmorServiceCallError, ArmorServiceInternalError
from .transport import Transport, default_service, set_default_service

__all__ = [
    "armor_client", "armor_exceptions", "armor_manipulation_client", "armor_query_client", "armor_utils_client",
    "ArmorClient", "ArmorPyException", "ArmorServiceCallError", "ArmorServiceInternalError",
    "Transport", "default_service", "set_default_service",
]
