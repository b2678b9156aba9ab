"""The ``armor_api`` package of armor_py_api, for code written against it.

``from armor_api.armor_client import ArmorClient`` works unchanged: every
module re-exports the same objects as its home in :mod:`topostore.armor_api`
(module names as in EmaroLab/armor_py_api).  Requests go to an in-process
service unless ``url=`` or the ``TOPOSTORE_URL`` environment variable names a
``topostore serve`` instance.
"""

from topostore.armor_api import *  # noqa: F401,F403
from topostore.armor_api import __all__  # noqa: F401

from . import armor_client, armor_exceptions, armor_manipulation_client, armor_query_client, armor_utils_client  # noqa: E402,F401
