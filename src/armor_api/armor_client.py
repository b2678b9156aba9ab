"""armor_py_api's ``armor_api.armor_client``, served by :mod:`topostore.armor_api.armor_client`.

``ArmorClient``: drop-in replacement for armor_py_api's client (spec §6.2).
"""

from topostore.armor_api.armor_client import *  # noqa: F401,F403 - the same objects under armor_py_api's module name
from topostore.armor_api.armor_client import __all__  # noqa: F401
