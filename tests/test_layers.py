"""docs/architecture.md's layer table is the package map, and the imports obey it.

The table (``| package | owns |``) names every package of ``src/topostore`` once, bottom-up.
A module may import modules of its own package (sideways) and of rows above its own row (down
the data path), never a row below; and the module import graph has no cycle.  Imports are read
with :mod:`ast`, lazy ones inside functions included; imports under ``if TYPE_CHECKING:`` are
for type checkers only and do not count.
"""

from __future__ import annotations

import ast
import re
from collections.abc import Collection, Mapping
from dataclasses import dataclass
from functools import cache
from pathlib import Path

import topostore

PACKAGE = Path(topostore.__file__).parent
ARCHITECTURE = PACKAGE.parent.parent / "docs" / "architecture.md"
#: The modules allowed at the top of src/topostore (docs/architecture.md says why).
TOP_LEVEL = ["__init__.py", "errors.py", "resources.py"]


@dataclass
class Row:
    index: int
    entries: list[str]


def layer_rows(text: str) -> list[Row]:
    """The rows of the ``| package | owns |`` table, in their order (bottom-up)."""
    body = text.split("| package | owns |\n|---|---|\n", 1)[1].split("\n\n", 1)[0]
    rows = []
    for i, line in enumerate(body.strip().splitlines()):
        first = line.strip().strip("|").split("|")[0]
        rows.append(Row(i, re.findall(r"`([^`]+)`", first)))
    return rows


def modules() -> list[str]:
    return sorted(str(p.relative_to(PACKAGE)) for p in PACKAGE.rglob("*.py"))


def module_file(name: str) -> str | None:
    """``topostore.compile.rule`` → ``compile/rule.py``; a package → its ``__init__.py``."""
    parts = name.split(".")[1:]
    base = PACKAGE.joinpath(*parts)
    if base.with_suffix(".py").is_file():
        return str(base.with_suffix(".py").relative_to(PACKAGE))
    if (base / "__init__.py").is_file():
        return str((base / "__init__.py").relative_to(PACKAGE))
    return None


@cache  # both import checks read every module: parsed once per worker
def imported_modules(path: str) -> frozenset[str]:
    """Modules of topostore that ``path`` imports (outside ``if TYPE_CHECKING:``), as paths."""
    tree = ast.parse((PACKAGE / path).read_text(encoding="utf-8"))
    package = ["topostore", *Path(path).parent.parts]
    typing_only = {id(n) for block in ast.walk(tree) if isinstance(block, ast.If)
                   and "TYPE_CHECKING" in ast.unparse(block.test) for n in ast.walk(block)}
    found = set()
    for node in ast.walk(tree):
        if id(node) in typing_only:
            continue
        if isinstance(node, ast.Import):
            names = [a.name for a in node.names if a.name.split(".")[0] == "topostore"]
        elif isinstance(node, ast.ImportFrom):
            base = package[: len(package) - node.level + 1] if node.level else []
            module = ".".join(base + ([node.module] if node.module else []))
            if module.split(".")[0] != "topostore":
                continue
            # `from . import builtins` names a module; `from .base import Store` a name in one
            names = [f"{module}.{a.name}" if module_file(f"{module}.{a.name}") else module for a in node.names]
        else:
            continue
        for name in names:
            target = module_file(name)
            assert target is not None, f"{path} imports {name}, which is no module of topostore"
            if target != path:
                found.add(target)
    return frozenset(found)


def unit_of(path: str) -> str:
    """The table entry a module belongs to: its top folder (``compile/``) or itself at the top."""
    return path.split("/", 1)[0] + "/" if "/" in path else path


ROWS = layer_rows(ARCHITECTURE.read_text(encoding="utf-8"))


def row_index(path: str) -> int:
    return next(r.index for r in ROWS if unit_of(path) in r.entries)


def find_cycle(graph: Mapping[str, Collection[str]]) -> list[str]:
    """One cycle of ``graph`` (a path that ends where it started), or [] when there is none."""
    state: dict[str, int] = {}  # 1 on the current path, 2 done
    path: list[str] = []

    def visit(node: str) -> list[str]:
        state[node] = 1
        path.append(node)
        for nxt in sorted(graph.get(node, ())):
            if state.get(nxt) == 1:
                return path[path.index(nxt):] + [nxt]
            if nxt not in state and (found := visit(nxt)):
                return found
        path.pop()
        state[node] = 2
        return []

    for start in sorted(graph):
        if start not in state and (found := visit(start)):
            return found
    return []


def test_the_table_names_every_package_once_and_nothing_else() -> None:
    named = [e for r in ROWS for e in r.entries]
    assert len(named) == len(set(named))
    units = sorted({unit_of(m) for m in modules()})
    assert sorted(e for e in named if e != "data/") == units
    assert all((PACKAGE / e).exists() for e in named)


def test_no_flat_modules_but_the_named_ones() -> None:
    assert sorted(m for m in modules() if "/" not in m) == TOP_LEVEL


def test_every_import_goes_sideways_within_its_package_or_down_the_table() -> None:
    wrong = [f"{path} imports {target}" for path in modules() for target in sorted(imported_modules(path))
             if unit_of(target) != unit_of(path) and row_index(target) > row_index(path)]
    assert wrong == []


def test_no_import_loops_between_modules() -> None:
    assert find_cycle({m: imported_modules(m) for m in modules()}) == []


def test_the_cycle_finder_finds_a_loop_through_three_modules() -> None:
    assert find_cycle({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}) == ["a", "b", "c", "a"]
    assert find_cycle({"a": {"b"}, "b": {"c"}, "d": {"a", "c"}}) == []


def test_the_check_sees_lazy_imports_and_skips_type_checking_ones() -> None:
    assert "demo/mapview.py" in imported_modules("demo/patrol.py")              # inside _draw
    assert "ontology/facade.py" not in imported_modules("sparql/target.py")    # under TYPE_CHECKING
    assert "compile/builtins.py" in imported_modules("compile/swrl.py")        # `from . import builtins`
