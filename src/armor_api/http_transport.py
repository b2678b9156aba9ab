"""armor_py_api's ``armor_api.http_transport``, served by :mod:`topostore.armor_api.http_transport`.

``HttpTransport``: the armor_py_api client talking to ``topostore serve`` over HTTP.
"""

from topostore.armor_api.http_transport import *  # noqa: F401,F403 - the same objects under armor_py_api's module name
from topostore.armor_api.http_transport import __all__  # noqa: F401
