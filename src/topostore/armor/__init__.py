"""aRMOR-compatible command interface (spec: armor-protocol.md).

``ArmorService.call`` takes an ``ArmorRequest`` (or a dict with the same
fields) and returns an ``ArmorResponse``; ``call_many`` is the serialized
service.  Exit codes are documented in :mod:`topostore.armor.codes`.
"""

from .codes import CommandError
from .service import ArmorService
from .types import ArmorRequest, ArmorResponse, ArmorResponseList

__all__ = ["ArmorService", "ArmorRequest", "ArmorResponse", "ArmorResponseList", "CommandError"]
