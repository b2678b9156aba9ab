"""Exit codes of the aRMOR protocol, old and new.

Codes 0-206 keep the meaning they have in aRMOR (spec §1.5) so existing
clients that branch on them keep working.  aRMOR reported every internal
failure as 205 ("malformed command") or did not reply at all; topostore gives
each kind of failure its own code (spec §7 item 3) so a caller can tell a typo
in the command from a missing reference or a bad argument:

===== ==========================================================================
code  meaning
===== ==========================================================================
0     success (also QUERY IND on an individual that does not occur: success=false)
101   unsupported value type name (STRING, INTEGER, LONG, FLOAT, DOUBLE, BOOLEAN...)
102   the reference is mounted by another client; the manipulation was refused
201   empty ``reference_name``
202   empty ``command``
203   MOUNT refused: another client holds the reference
205   unknown COMMAND/SPEC1/SPEC2 combination, or the registered INVALID COMMAND
206   (client side) a single-value replace found several values
207   the reference named by ``reference_name`` (or by an argument) is not loaded
208   wrong number of arguments, a value that does not parse as its type, an
      illegal entity name, or an option value that is not recognised
209   the reasoner or a SPARQL query failed (malformed query, non-SELECT, ...)
210   a file could not be read, parsed or written, or the path is not allowed
===== ==========================================================================
"""

from __future__ import annotations

SUCCESS = 0
UNKNOWN_TYPE = 101
MOUNTED_BY_OTHER = 102
EMPTY_REFERENCE = 201
EMPTY_COMMAND = 202
CANNOT_MOUNT = 203
UNKNOWN_COMMAND = 205
SEVERAL_VALUES = 206
UNKNOWN_REFERENCE = 207
INVALID_ARGUMENT = 208
REASONER_OR_QUERY_FAILURE = 209
FILE_ERROR = 210

DESCRIPTIONS: dict[int, str] = {
    SUCCESS: "success",
    UNKNOWN_TYPE: "unsupported value type",
    MOUNTED_BY_OTHER: "reference mounted by another client",
    EMPTY_REFERENCE: "empty reference_name",
    EMPTY_COMMAND: "empty command",
    CANNOT_MOUNT: "client cannot be mounted",
    UNKNOWN_COMMAND: "unknown command/spec combination",
    SEVERAL_VALUES: "several values where one was expected",
    UNKNOWN_REFERENCE: "unknown reference",
    INVALID_ARGUMENT: "wrong number of arguments, invalid value or invalid name",
    REASONER_OR_QUERY_FAILURE: "reasoner or query failure",
    FILE_ERROR: "file input/output error",
}


class CommandError(Exception):
    """A command that cannot be executed; becomes a ``success=false`` reply with ``code``."""

    def __init__(self, code: int, message: str) -> None:
        super().__init__(message)
        self.code = code
        self.message = message


__all__ = [name for name in dir() if name.isupper()] + ["DESCRIPTIONS", "CommandError"]
