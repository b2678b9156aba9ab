"""Where the data files shipped with topostore live (rules/, queries/, ontology/).

They sit at the top of the source tree (an editable install) or under
``<prefix>/share/topostore`` (a wheel install); ``TOPOSTORE_HOME`` overrides both.
"""

from __future__ import annotations

import os
import sys
from functools import cache
from pathlib import Path


@cache
def home() -> Path:
    env = os.environ.get("TOPOSTORE_HOME")
    candidates = [Path(env)] if env else []
    candidates += [Path(__file__).resolve().parents[2], Path(sys.prefix) / "share" / "topostore"]
    for c in candidates:
        if (c / "rules").is_dir() and (c / "queries").is_dir():
            return c
    raise FileNotFoundError("cannot find topostore's rules/ and queries/ folders; set TOPOSTORE_HOME")


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
