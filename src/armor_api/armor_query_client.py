"""armor_py_api's ``armor_api.armor_query_client``, served by :mod:`topostore.armor_api.armor_query_client`.

``client.query``: armor_py_api's query methods (spec §6.4), bugs of §7 item 25 fixed.
"""

from topostore.armor_api.armor_query_client import *  # noqa: F401,F403 - the same objects under armor_py_api's module name
from topostore.armor_api.armor_query_client import __all__  # noqa: F401
