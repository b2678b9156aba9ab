"""``--store``, the one store setting, as a click option shared by every command that keeps references."""

from __future__ import annotations

import click


def store_option(f):
    """``--store``: where the ontology lives (memory by default, a directory, or a SPARQL server URL)."""
    return click.option("--store", "store", metavar="DIR|URL", envvar="TOPOSTORE_STORE",
                        help="Keep the ontology in a durable store: a directory (RocksDB) or an http(s) SPARQL 1.1 "
                             "server (URL/query + URL/update); default: in memory. Credentials for a server come "
                             "from TOPOSTORE_STORE_TOKEN or TOPOSTORE_STORE_USER/TOPOSTORE_STORE_PASSWORD.")(f)


__all__ = ["store_option"]
