"""The layer table of docs/architecture.md is the module map, and the imports obey it.

The table (docs/architecture.md, "Layers") names every module of ``src/topostore`` once
and says what each may import; rows are in dependency order, so everything a
row may import sits in a row above it.  The imports are read with :mod:`ast`,
lazy ones inside functions included; imports under ``if TYPE_CHECKING:`` are
for type checkers only and do not count.
"""

from __future__ import annotations

import ast
import re
from dataclasses import dataclass
from pathlib import Path

import topostore

PACKAGE = Path(topostore.__file__).parent
ARCHITECTURE = PACKAGE.parent.parent / "docs" / "architecture.md"

#: The two imports that go upward, each inside one function, as docs/architecture.md says.
UPWARD = {
    ("store.py", "stores/oxigraph.py"),  # Store() gives a fresh in-memory OxigraphStore
    ("ros/launcher.py", "cli.py"),  # the `armor` launcher runs the command line
}


@dataclass
class Row:
    index: int
    entries: list[str]
    may_import: list[str]


def architecture_rows(text: str) -> list[Row]:
    """The rows of the ``| module | owns | may import |`` table of the Layers section."""
    section = text.split("\n## Layers\n", 1)[1].split("\n## ", 1)[0]
    lines = section.split("| module | owns | may import |\n|---|---|---|\n", 1)[1].split("\n\n", 1)[0]
    rows = []
    for i, line in enumerate(lines.strip().splitlines()):
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        rows.append(Row(i, re.findall(r"`([^`]+)`", cells[0]), re.findall(r"`([^`]+)`", cells[-1])))
    return rows


def covers(entry: str, path: str) -> bool:
    """``compile/`` covers every module of the package; ``compile/rule.py`` only itself."""
    return path.startswith(entry) if entry.endswith("/") else path == entry


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


def imported_modules(path: str) -> set[str]:
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
            # `from . import builtins` names a module; `from .store import Store` a name in one
            names = [f"{module}.{a.name}" if module_file(f"{module}.{a.name}") else module for a in node.names]
        else:
            continue
        for name in names:
            target = module_file(name)
            assert target is not None, f"{path} imports {name}, which is no module of topostore"
            if target != path:
                found.add(target)
    return found


ROWS = architecture_rows(ARCHITECTURE.read_text(encoding="utf-8"))


def row_of(path: str) -> Row:
    return next(r for r in ROWS if path in r.entries)


def test_the_table_names_every_module_once_and_nothing_else() -> None:
    named = [e for r in ROWS for e in r.entries]
    assert sorted(e for e in named if e.endswith(".py")) == modules()
    assert [e for e in named if not e.endswith(".py")] == ["data/", "static/"]
    assert all((PACKAGE / e).exists() for e in named)


def test_a_row_may_import_only_rows_above_it() -> None:
    for row in ROWS:
        for allowed in row.may_import:
            above = [m for m in modules() if covers(allowed, m) and m not in row.entries]
            assert above, f"row {row.entries}: {allowed!r} names no module"
            assert all(row_of(m).index < row.index for m in above), f"row {row.entries} may import {allowed!r} below it"


def test_every_import_is_one_its_row_allows() -> None:
    wrong = []
    for path in modules():
        row = row_of(path)
        for target in sorted(imported_modules(path)):
            allowed = target in row.entries or any(covers(a, target) for a in row.may_import)
            if not allowed and (path, target) not in UPWARD:
                wrong.append(f"{path} imports {target}")
    assert wrong == []


def test_the_check_sees_lazy_imports_and_skips_type_checking_ones() -> None:
    assert "stores/oxigraph.py" in imported_modules("store.py")          # inside Store.__new__
    assert "ontology.py" not in imported_modules("sparql/target.py")     # under TYPE_CHECKING
    assert "compile/builtins.py" in imported_modules("compile/swrl.py")  # `from . import builtins`
