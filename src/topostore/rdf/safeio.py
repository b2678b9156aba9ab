"""File input and output that cannot hang, explode or escape.

Every file the service reads or writes on a client's behalf goes through here:

* :func:`read_regular_file` reads only regular files, never FIFOs or devices
  (``/dev/zero`` would be read forever, a FIFO blocks forever), and at most
  :data:`LIMITS.max_file_bytes` bytes.
* :func:`check_xml_entities` refuses RDF/XML whose DOCTYPE declares entities
  that would expand into more text than :data:`LIMITS.max_entity_expansion`
  ("billion laughs": nine levels of nested entities abort the process inside
  the RDF/XML parser), external entities, and entities referring to entities.
  Plain entity abbreviations as Protégé writes them (``&owl;``) stay accepted.
* :func:`atomic_write` writes through a temporary file in the target's own
  directory with an unpredictable name, created with ``O_EXCL|O_NOFOLLOW`` (so a
  planted symlink is never followed), renamed over the target on success and
  removed on failure.
* :func:`open_log` opens a log file for appending: regular files only, without
  following a symlink and without blocking on a FIFO.
"""

from __future__ import annotations

import os
import re
import stat
import tempfile
from dataclasses import dataclass
from pathlib import Path
from typing import TextIO

from ..errors import LoadError


@dataclass(frozen=True)
class FileLimits:
    """Bounds on files read for clients."""

    #: largest ontology file LOAD accepts (bytes)
    max_file_bytes: int = 256 * 1024 * 1024
    #: most characters the entities of one RDF/XML document may expand to
    max_entity_expansion: int = 1024 * 1024


LIMITS = FileLimits()


def set_limits(limits: FileLimits) -> None:
    """Replace the process-wide file limits (``topostore serve --max-file-size``)."""
    global LIMITS
    if limits.max_file_bytes < 1 or limits.max_entity_expansion < 0:
        raise ValueError("file limits must be positive")
    LIMITS = limits


def read_regular_file(path: str | os.PathLike[str], max_bytes: int | None = None) -> bytes:
    """The bytes of a regular file of at most ``max_bytes``; :class:`LoadError` otherwise."""
    limit = LIMITS.max_file_bytes if max_bytes is None else max_bytes
    try:
        fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK | getattr(os, "O_CLOEXEC", 0))
    except OSError as exc:
        raise LoadError(f"{path}: cannot read file: {exc.strerror or exc}") from exc
    info = os.fstat(fd)
    if not stat.S_ISREG(info.st_mode):
        os.close(fd)
        raise LoadError(f"{path}: not a regular file (a directory, FIFO or device cannot be loaded)")
    with os.fdopen(fd, "rb") as f:
        if info.st_size > limit:
            raise LoadError(f"{path}: the file has {info.st_size} bytes, more than the limit of {limit} "
                            "(server option --max-file-size)")
        data = f.read(limit + 1)
    if len(data) > limit:
        raise LoadError(f"{path}: the file is larger than the limit of {limit} bytes (server option --max-file-size)")
    return data


_DOCTYPE = re.compile(rb"<!DOCTYPE\b", re.I)
_ENTITY = re.compile(rb"<!ENTITY\s+(%\s+)?([^\s\"'>]+)\s+(SYSTEM|PUBLIC|\"([^\"]*)\"|'([^']*)')", re.I)
_REFERENCE = re.compile(rb"&([A-Za-z_][A-Za-z0-9_.\-]*);")


def check_xml_entities(data: bytes, source: str = "<input>", max_expansion: int | None = None) -> None:
    """Refuse entity declarations that could expand without bound (before any XML parser sees them)."""
    if not _DOCTYPE.search(data):
        return
    limit = LIMITS.max_entity_expansion if max_expansion is None else max_expansion
    sizes: dict[bytes, int] = {}
    for m in _ENTITY.finditer(data):
        name = m.group(2)
        if m.group(1) or m.group(3).upper() in (b"SYSTEM", b"PUBLIC"):
            raise LoadError(f"{source}: external or parameter entity {name.decode(errors='replace')!r} refused "
                            "(the service never fetches or expands external entities)")
        value = m.group(4) if m.group(4) is not None else m.group(5)
        if _REFERENCE.search(value):
            raise LoadError(f"{source}: entity {name.decode(errors='replace')!r} refers to another entity; nested "
                            "entities are refused (they can expand exponentially: 'billion laughs')")
        sizes[name] = len(value)
    if not sizes:
        return
    total = sum(sizes.get(m.group(1), 0) for m in _REFERENCE.finditer(data))
    if total > limit:
        raise LoadError(f"{source}: its entities would expand to {total} characters, more than the limit of {limit}")


def atomic_write(path: Path, data: bytes) -> Path:
    """Write ``data`` to ``path`` all or nothing; never through a symlink, never leaving a temporary file."""
    path = Path(path)
    if path.is_dir():
        raise IsADirectoryError(21, "is a directory, not a file name", str(path))
    # mkstemp opens with O_CREAT|O_EXCL|O_NOFOLLOW and a random name, in the target's directory
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=path.parent)
    try:
        with os.fdopen(fd, "wb") as f:
            f.write(data)
            f.flush()
            os.fsync(f.fileno())
        os.replace(tmp, path)
    except BaseException:
        try:
            os.unlink(tmp)
        except FileNotFoundError:
            pass
        raise
    return path


def open_log(path: Path) -> TextIO:
    """``path`` opened for appending text: a regular file only, no symlink followed, never blocking."""
    flags = os.O_WRONLY | os.O_APPEND | os.O_CREAT | os.O_NONBLOCK | getattr(os, "O_NOFOLLOW", 0) \
        | getattr(os, "O_CLOEXEC", 0)
    fd = os.open(path, flags, 0o644)
    try:
        if not stat.S_ISREG(os.fstat(fd).st_mode):
            raise OSError(22, "not a regular file (a FIFO or device cannot be a log file)", str(path))
        os.set_blocking(fd, True)
        return os.fdopen(fd, "a", encoding="utf-8")
    except BaseException:
        os.close(fd)
        raise


__all__ = ["FileLimits", "LIMITS", "set_limits", "read_regular_file", "check_xml_entities", "atomic_write",
           "open_log"]
