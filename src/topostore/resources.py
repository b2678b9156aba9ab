"""Where the data files shipped with topostore live (rules/, queries/, ontology/).

They are package data of ``topostore.data``, read with :mod:`importlib.resources`,
so every kind of install finds them: a wheel, ``pip install --user`` or
``--target``, and an editable checkout.  In the repository they stay at the
top of the tree; ``src/topostore/data/`` holds symbolic links to them, which
the wheel build follows (the files are copied into the wheel).
``TOPOSTORE_HOME`` (a folder holding ``rules/`` and ``queries/``) overrides
the packaged files, e.g. to try changed rules without reinstalling.
"""

from __future__ import annotations

import os
from functools import cache
from importlib import resources
from pathlib import Path


class MissingDataError(FileNotFoundError):
    """The packaged data files cannot be found (a broken install)."""


@cache
def home() -> Path:
    """The folder holding ``rules/``, ``queries/`` and ``ontology/``."""
    env = os.environ.get("TOPOSTORE_HOME")
    if env:
        candidate = Path(env)
        if (candidate / "rules").is_dir() and (candidate / "queries").is_dir():
            return candidate
        raise MissingDataError(f"TOPOSTORE_HOME={env!r} holds no rules/ and queries/ folders")
    packaged = resources.files("topostore") / "data"
    # importlib.resources gives a real directory for every file-system install; a zipped install
    # would need extraction, which topostore does not support (pyoxigraph reads files by path).
    if isinstance(packaged, Path) and (packaged / "rules").is_dir() and (packaged / "queries").is_dir():
        return packaged
    raise MissingDataError("topostore's data files (topostore/data/rules, queries, ontology) are missing from "
                           f"the installation at {packaged}; reinstall topostore or set TOPOSTORE_HOME")


def source_root() -> Path | None:
    """The repository checkout this package runs from (editable installs), else ``None``.

    Only the ``bench`` command needs it: the benchmarks ship with the source tree, not the wheel.
    """
    root = Path(__file__).resolve().parents[2]
    return root if (root / "pyproject.toml").is_file() and (root / "src" / "topostore").is_dir() else None


def rules_dir() -> Path:
    return home() / "rules"


def queries_dir() -> Path:
    return home() / "queries"


def ontology_dir() -> Path:
    return home() / "ontology"


def default_ontology() -> Path:
    """The embedded topological map TBox with its SWRL rules (the example environment is beside it)."""
    return ontology_dir() / "topological_map.ttl"


def default_ontology_files() -> list[Path]:
    """The embedded topological map as [TBox with the SWRL rules, example environment (ABox)]."""
    return [default_ontology(), ontology_dir() / "topological_map_abox.ttl"]
