"""The generated ROS folder: ``armor_msgs`` (definitions + genpy classes) and the ``armor`` launcher.

Layout of one generation (a folder named by a hash of its inputs, so a new
topostore, genpy or Python makes a new one and two versions never mix)::

    <cache>/<key>/python/armor_msgs/{msg,srv}/...   -> PYTHONPATH
    <cache>/<key>/share/armor_msgs/{package.xml,msg,srv}  -> ROS_PACKAGE_PATH (rosmsg, rossrv)
    <cache>/<key>/share/armor/{package.xml,execute}        -> roslaunch's <node pkg="armor" type="execute"/>

``<cache>`` is ``$TOPOSTORE_ROS_DIR``, else ``$XDG_CACHE_HOME/topostore/ros``,
else ``~/.cache/topostore/ros``.  A generation is built in a temporary folder
and renamed into place, so concurrent first runs never see half a package.
"""

from __future__ import annotations

import hashlib
import os
import shlex
import shutil
import sys
import tempfile
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path

from .. import __version__
from . import launcher, msgs, require_ros

_COMPLETE = ".complete"


@dataclass(frozen=True)
class Workspace:
    """One complete generation folder."""

    root: Path

    @property
    def python_dir(self) -> Path:
        return self.root / "python"

    @property
    def share_dir(self) -> Path:
        return self.root / "share"

    def export_lines(self) -> list[str]:
        """``export`` lines (POSIX shell) putting this folder first on PYTHONPATH and ROS_PACKAGE_PATH.

        Existing values are kept after ours, expanded when the lines are
        evaluated (``eval "$(topostore ros --env)"``), not when printed.
        """
        return [_prepend("PYTHONPATH", self.python_dir), _prepend("ROS_PACKAGE_PATH", self.share_dir)]

    def activate(self) -> None:
        """Make the generated ``armor_msgs`` importable in this process."""
        path = str(self.python_dir)
        if path not in sys.path:
            sys.path.insert(0, path)
        for name in [m for m in sys.modules if m == msgs.PACKAGE or m.startswith(msgs.PACKAGE + ".")]:
            del sys.modules[name]  # an armor_msgs imported from elsewhere must not shadow ours


def _prepend(variable: str, path: Path) -> str:
    return f'export {variable}={shlex.quote(str(path))}"${{{variable}:+:${variable}}}"'


def cache_root(environ: Mapping[str, str] | None = None) -> Path:
    """Where generations live (see the module docstring)."""
    env = os.environ if environ is None else environ
    if env.get("TOPOSTORE_ROS_DIR"):
        return Path(env["TOPOSTORE_ROS_DIR"]).expanduser()
    base = Path(env["XDG_CACHE_HOME"]).expanduser() if env.get("XDG_CACHE_HOME") else Path.home() / ".cache"
    return base / "topostore" / "ros"


def generation_key() -> str:
    """Hash of everything the generated files depend on."""
    import genpy

    digest = hashlib.sha256()
    for part in (__version__, sys.executable, getattr(genpy, "__version__", ""), launcher.SCRIPT_VERSION):
        digest.update(str(part).encode() + b"\0")
    for path in [*msgs.definition_files(), launcher.LAUNCH_FILE]:
        digest.update(path.name.encode() + b"\0" + path.read_bytes() + b"\0")
    return digest.hexdigest()[:16]


def ensure(root: Path | None = None) -> Workspace:
    """The current generation, generated first if missing (the first run, or after an upgrade)."""
    require_ros()
    base = root if root is not None else cache_root()
    target = base / generation_key()
    if (target / _COMPLETE).exists():
        return Workspace(target)
    base.mkdir(parents=True, exist_ok=True)
    scratch = Path(tempfile.mkdtemp(prefix=".partial-", dir=base))
    try:
        _generate(scratch)
        try:
            scratch.rename(target)
        except OSError:
            if not (target / _COMPLETE).exists():  # not a concurrent run's complete copy: a real failure
                raise
    finally:
        shutil.rmtree(scratch, ignore_errors=True)
    return Workspace(target)


def _generate(folder: Path) -> None:
    work = Workspace(folder)
    package = msgs.copy_package(work.share_dir)
    msgs.generate_python(package, work.python_dir)
    launcher.write_package(work.share_dir)
    (folder / _COMPLETE).write_text(__version__ + "\n")
