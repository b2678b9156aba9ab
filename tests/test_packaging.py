"""The built wheel is a real package: installed in a fresh venv outside the checkout, it finds its data.

The wheel is built from the checkout, installed with its core dependencies only
(no ``[viz]``) into a new virtual environment in a temporary folder, and its
``topostore`` command is run from that folder with a clean environment, so
nothing of the source tree can be found by accident.  Dependencies come from
the package index (pip's cache usually serves them); the whole test takes
about a minute on a warm cache.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import venv
from pathlib import Path

import pytest
from support import SHARED

ROOT = Path(__file__).resolve().parents[1]
LIMIT = 600  # seconds for any one step (a cold pip cache downloads pyoxigraph and friends)


def run(cmd: list[str], cwd: Path, env: dict[str, str] | None = None) -> subprocess.CompletedProcess[str]:
    return subprocess.run(cmd, cwd=cwd, env=env, capture_output=True, text=True, timeout=LIMIT, check=False)


@pytest.fixture(scope="module")
def installed(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, Path]:
    """(the fresh venv's bin folder, a work folder outside the checkout)."""
    base = tmp_path_factory.mktemp("wheel")
    assert not base.resolve().is_relative_to(ROOT)
    built = run([sys.executable, "-m", "pip", "wheel", "--no-deps", "--quiet", "-w", str(base / "dist"), str(ROOT)], base)
    assert built.returncode == 0, built.stderr
    wheels = list((base / "dist").glob("topostore-*.whl"))
    assert len(wheels) == 1
    # no pip of its own (ensurepip was most of this fixture's time): this pip installs into it (``--python``)
    venv.EnvBuilder(with_pip=False, clear=True).create(base / "venv")
    bin_dir = base / "venv" / "bin"
    done = run([*pip_for(bin_dir), "install", "--quiet", str(wheels[0])], base)
    assert done.returncode == 0, done.stderr
    work = base / "work"
    work.mkdir()
    shutil.copy(wheels[0], work.parent / wheels[0].name)
    return bin_dir, work


def pip_for(bin_dir: Path) -> list[str]:
    """This environment's pip, installing into the fresh venv's interpreter (pip's ``--python``)."""
    return [sys.executable, "-m", "pip", "--python", str(bin_dir / "python")]


def clean_env(bin_dir: Path) -> dict[str, str]:
    """No PYTHONPATH, no TOPOSTORE_HOME: only the installed package can be found."""
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "TOPOSTORE_HOME", "VIRTUAL_ENV")}
    env["PATH"] = f"{bin_dir}{os.pathsep}{env.get('PATH', '')}"
    return env


def test_wheel_holds_data_and_runs_outside_the_checkout(installed: tuple[Path, Path]) -> None:
    bin_dir, work = installed
    env = clean_env(bin_dir)
    where = run([str(bin_dir / "python"), "-c",
                 "import topostore.resources as r; print(r.home()); print(len(list(r.rules_dir().glob('*.rq'))))"], work, env)
    assert where.returncode == 0, where.stderr
    home, n_rules = where.stdout.split()
    assert Path(home).is_relative_to(bin_dir.parent) and not Path(home).resolve().is_relative_to(ROOT)
    assert int(n_rules) == len(list((ROOT / "rules").glob("*.rq")))

    demo = run([str(bin_dir / "topostore"), "demo", "--steps", "2"], work, env)
    assert demo.returncode == 0, demo.stderr
    assert "Map: 3 locations (1 corridors); robots: Robot1" in demo.stdout
    assert "Step 2" in demo.stdout
    # pictures are the [viz] extra: the core install says how to get them instead of failing
    assert "pip install 'topostore[viz]'" in demo.stderr

    for name in ("topological_map.owl", "topological_map_abox.owl"):
        shutil.copy(SHARED / name, work / name)
    reason = run([str(bin_dir / "topostore"), "reason", "topological_map.owl", "topological_map_abox.owl"], work, env)
    assert reason.returncode == 0, reason.stderr
    assert ": 29 inferred triples\nConsistent.\n" in reason.stdout  # 12 of them range axioms the xsd:long ranges imply

    drawn = run([str(bin_dir / "topostore"), "map", "topological_map_abox.owl", "-o", "m.png"], work, env)
    assert drawn.returncode == 1
    assert drawn.stderr.strip().splitlines()[-1].startswith("Error: drawing maps needs matplotlib")
    assert not (work / "m.png").exists()


@pytest.mark.parametrize("how", ["--target", "--user"])
def test_target_and_user_installs_find_their_data(installed: tuple[Path, Path], how: str) -> None:
    """``pip install --target DIR`` and ``pip install --user`` put the package data beside the code too.

    The fresh venv supplies the dependencies; the copy installed the other way comes first on the path
    (``PYTHONPATH``), and its rules, queries and ontology must be the ones it finds.
    """
    bin_dir, work = installed
    wheel = next(work.parent.glob("topostore-*.whl"))
    env = clean_env(bin_dir)
    root = work.parent / how.strip("-")
    if how == "--target":
        done = run([*pip_for(bin_dir), "install", "--quiet", "--no-deps", "--target", str(root), str(wheel)], work, env)
        site = root
    else:  # a user base of its own (pip refuses --user inside a venv, so the base python installs it)
        env_user = {**env, "PYTHONUSERBASE": str(root)}
        base_python = Path(sys.base_prefix) / "bin" / "python3"
        done = run([str(base_python), "-m", "pip", "install", "--quiet", "--no-deps", "--user",
                    "--no-warn-script-location", str(wheel)], work, env_user)
        site = next(root.glob("lib/python*/site-packages"))
    assert done.returncode == 0, done.stderr
    env["PYTHONPATH"] = str(site)
    where = run([str(bin_dir / "python"), "-c", "import topostore.resources as r; print(r.home()); "
                 "print(len(list(r.rules_dir().glob('*.rq'))), len(list(r.queries_dir().glob('*.rq'))))"], work, env)
    assert where.returncode == 0, where.stderr
    home, n_rules, n_queries = where.stdout.split()
    assert Path(home).resolve().is_relative_to(site.resolve())
    assert (int(n_rules), int(n_queries)) == (len(list((ROOT / "rules").glob("*.rq"))),
                                             len(list((ROOT / "queries").glob("*.rq"))))
