"""Where a reference's graphs live: the one ``store`` setting and its three forms.

* absent (``None``, ``""``, ``":memory:"``): in memory, gone with the process;
* a directory: a durable pyoxigraph (RocksDB) store, one per reference
  (``DIR/<reference>/``, the name percent-encoded);
* ``http://…`` / ``https://…``: a remote SPARQL 1.1 Query + Update endpoint
  pair (``URL/query`` and ``URL/update`` as Oxigraph's server lays them out,
  ``URL`` itself when it ends in ``/sparql``; both overridable).

:func:`open_store` turns a setting into a :class:`~topostore.stores.base.Store`
(:func:`memory_store` is the fresh in-memory one);
:func:`list_references` tells which references a durable setting holds.
"""

from __future__ import annotations

import os
import urllib.parse
from pathlib import Path

from ..errors import RuleCompileError, StoreError
from ..rdf.vocab import POW_FUNCTION
from .base import Store
from .oxigraph import OxigraphStore

StoreSpec = str | os.PathLike[str] | None


def kind(spec: StoreSpec) -> str:
    """"memory", "directory" or "remote"."""
    if spec is None or str(spec) in ("", ":memory:"):
        return "memory"
    if str(spec).lower().startswith(("http://", "https://")):
        return "remote"
    return "directory"


def reference_dir(spec: StoreSpec, reference: str) -> Path:
    """The RocksDB directory of one reference (its name percent-encoded, so it stays one path component)."""
    name = urllib.parse.quote(reference, safe="")
    if name in ("", ".", ".."):
        raise StoreError(f"reference name {reference!r} cannot name a store directory")
    return Path(spec) / name


def memory_store() -> Store:
    """A fresh, empty in-memory store (scratch graphs, parsing a file, a reference without a ``store`` setting)."""
    return OxigraphStore()


def open_store(spec: StoreSpec = None, reference: str | None = None, *, sync: bool = False,
               query_url: str | None = None, update_url: str | None = None) -> Store:
    """The store a ``store`` setting names, for ``reference`` (None: the setting itself is the store).

    ``sync``: every acknowledged change is durable before the reply — flushed to disk (a directory), or
    sent at once instead of with the next request (a remote server, see :mod:`.remote`)."""
    which = kind(spec)
    if which == "memory":
        return memory_store()
    if which == "remote":
        from .remote import RemoteStore

        return RemoteStore(str(spec), reference=reference or "", query_url=query_url, update_url=update_url,
                           defer_writes=not sync)
    path = reference_dir(spec, reference) if reference else Path(spec)
    try:
        path.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise StoreError(f"cannot create the store directory {str(path)!r}: {exc.strerror or exc}") from None
    return OxigraphStore(path, sync=sync)


def list_references(spec: StoreSpec, *, query_url: str | None = None, update_url: str | None = None) -> list[str]:
    """References a durable setting holds (sorted); none in memory."""
    which = kind(spec)
    if which == "memory":
        return []
    if which == "remote":
        from .remote import list_references as remote_references

        return remote_references(str(spec), query_url=query_url, update_url=update_url)
    root = Path(spec)
    if not root.is_dir():
        return []
    return sorted(urllib.parse.unquote(p.name) for p in root.iterdir() if (p / "CURRENT").is_file())


def check_rules(store: Store, rules) -> None:
    """Refuse rules this store cannot evaluate the way the in-process store would (at load, never later)."""
    if store.custom_functions:
        return
    for rule in rules.rules:
        if str(POW_FUNCTION) in rule.sparql():
            raise RuleCompileError(
                f"rule {rule.name!r} needs swrlb:pow with a variable exponent, which topostore computes with its own "
                f"SPARQL function {POW_FUNCTION}; the remote SPARQL server cannot evaluate it, so this ontology "
                "only runs on a memory or directory store")


__all__ = ["open_store", "memory_store", "list_references", "check_rules", "kind", "reference_dir", "StoreSpec"]
