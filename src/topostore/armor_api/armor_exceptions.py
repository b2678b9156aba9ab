"""Exceptions of the armor_py_api client, with the original names and attributes."""

from __future__ import annotations


class ArmorPyException(Exception):
    """Base class of every client error; ``msg`` holds the message."""

    def __init__(self, message: str) -> None:
        super().__init__(message)
        self.msg = message


class ArmorServiceCallError(ArmorPyException):
    """The service could not be reached or did not answer (transport failure)."""


class ArmorServiceInternalError(ArmorPyException):
    """The service answered ``success=false``; ``code`` is the exit code as an ``int``."""

    def __init__(self, message: str, exit_code: int) -> None:
        super().__init__(message)
        self.code = int(exit_code)

    def __str__(self) -> str:
        return f"ARMOR internal error {self.code}: {self.msg}"


__all__ = ["ArmorPyException", "ArmorServiceCallError", "ArmorServiceInternalError"]
