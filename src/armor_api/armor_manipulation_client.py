"""armor_py_api's ``armor_api.armor_manipulation_client``, served by :mod:`topostore.armor_api.armor_manipulation_client`.

``client.manipulation``: armor_py_api's manipulation methods (spec §6.3), bugs of §7 item 25 fixed.
"""

from topostore.armor_api.armor_manipulation_client import *  # noqa: F401,F403 - the same objects under armor_py_api's module name
from topostore.armor_api.armor_manipulation_client import __all__  # noqa: F401
