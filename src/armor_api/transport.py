"""armor_py_api's ``armor_api.transport``, served by :mod:`topostore.armor_api.transport`.

How the client reaches a service: any object with ``call`` and ``call_many``.
"""

from topostore.armor_api.transport import *  # noqa: F401,F403 - the same objects under armor_py_api's module name
from topostore.armor_api.transport import __all__  # noqa: F401
