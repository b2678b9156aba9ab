"""Refuse SPARQL that would make the service reach the network or the file system.

Oxigraph evaluates ``SERVICE <url>`` in queries and ``LOAD <url>`` in updates by
fetching the URL itself.  Exposed over HTTP, that would let any client make
the robot's ontology service issue requests to arbitrary hosts (server-side
request forgery).  aRMOR has no such feature, so both keywords are refused.

The check is lexical: the text is scanned with SPARQL's own escaping rules
(``\\uXXXX`` escapes are decoded first, as the SPARQL grammar requires) and
the keywords are looked for outside IRIs, strings and comments, and not as part
of prefixed names or variables.  A false alarm only refuses a query; the
scanner never lets a keyword through.
"""

from __future__ import annotations

import re

from ..errors import QueryError
from ..queries import skip_non_code

_ESCAPE = re.compile(r"\\u([0-9A-Fa-f]{4})|\\U([0-9A-Fa-f]{8})")
_WORD = re.compile(r"[A-Za-z_][A-Za-z0-9_\-]*")
_NAME_CHARS = set("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-.:")
#: characters that, just before a word, make it part of a name rather than a keyword
_JOINERS = _NAME_CHARS - {"."}

FORBIDDEN = ("SERVICE", "LOAD")


class UnsafeOperationError(QueryError):
    """The request uses an operation this service refuses (SERVICE, LOAD)."""


def decode_escapes(text: str) -> str:
    """Apply SPARQL's ``\\u``/``\\U`` code point escapes (done before parsing, §19.2)."""

    def repl(m: re.Match[str]) -> str:
        code = int(m.group(1) or m.group(2), 16)
        return chr(code) if code <= 0x10FFFF else m.group(0)

    return _ESCAPE.sub(repl, text)


def keywords(text: str) -> list[str]:
    """The bare words of a query outside IRIs, strings and comments, upper-cased."""
    text = decode_escapes(text)
    found: list[str] = []
    i, n = 0, len(text)
    while i < n:
        nxt = skip_non_code(text, i)
        if nxt is not None:
            i = nxt
            continue
        c = text[i]
        if c in "?$":  # a variable: skip its name
            m = _WORD.match(text, i + 1)
            i = m.end() if m else i + 1
            continue
        m = _WORD.match(text, i)
        if m:
            prev = text[i - 1] if i > 0 else " "
            after = text[m.end()] if m.end() < n else " "
            if prev not in _JOINERS and after != ":":
                found.append(m.group(0).upper())
            i = m.end()
            # the rest of a prefixed name (ex:LOAD) is not a keyword
            while i < n and text[i] in _NAME_CHARS:
                i += 1
            continue
        i += 1
    return found


def check_safe(text: str) -> None:
    """Raise :class:`UnsafeOperationError` if ``text`` uses SERVICE or LOAD."""
    used = sorted(set(keywords(text)) & set(FORBIDDEN))
    if used:
        raise UnsafeOperationError(
            f"{' and '.join(used)} is not allowed on this endpoint: it would make the service fetch remote data")


__all__ = ["UnsafeOperationError", "check_safe", "keywords", "decode_escapes", "FORBIDDEN"]
