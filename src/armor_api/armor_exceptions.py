"""armor_py_api's ``armor_api.armor_exceptions``, served by :mod:`topostore.armor_api.armor_exceptions`.

Exceptions of the armor_py_api client, with the original names and attributes.
"""

from topostore.armor_api.armor_exceptions import *  # noqa: F401,F403 - the same objects under armor_py_api's module name
from topostore.armor_api.armor_exceptions import __all__  # noqa: F401
