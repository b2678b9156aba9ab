"""aRMOR over ROS 1: the ``topostore ros`` node and the ``armor_msgs`` it speaks.

Modules: :mod:`.msgs` generates the ``armor_msgs`` Python classes with genpy,
:mod:`.workspace` keeps them (and the ``armor`` launcher package) in a cache
folder and prints the environment that makes ROS tools find them,
:mod:`.node` is the ROS node, :mod:`topostore.cli.ros` the ``topostore ros`` command.

Nothing here imports ``rospy`` at module level: the rest of topostore works
without ROS.  :func:`require_ros` is the one place that makes ROS importable.
"""

from __future__ import annotations

import importlib
import sys
from pathlib import Path

from ..errors import TopostoreError

#: Debian's ROS 1 packages (Debian 12 ships ROS Noetic's Python parts as these).
DEBIAN_PACKAGES = ("python3-rospy", "python3-rosservice", "python3-genpy", "python3-genmsg", "ros-core")
#: Where Debian installs them; the Python of a virtual environment does not search it.
DEBIAN_DIST_PACKAGES = Path("/usr/lib/python3/dist-packages")

#: Relative names, as aRMOR advertises them: ``/armor_interface_srv`` in the root
#: namespace, ``/robot1/armor_interface_srv`` for a node started with ``__ns:=/robot1``.
SINGLE_SERVICE = "armor_interface_srv"
SERIALIZED_SERVICE = "armor_interface_serialized_srv"
DEFAULT_NODE_NAME = "armor_service"

#: ``topostore ros`` exit codes beyond the CLI's 0-3.
EXIT_NO_MASTER = 4
EXIT_NO_ROS = 5


class RosUnavailable(TopostoreError):
    """The ROS 1 Python packages cannot be imported."""


def install_hint() -> str:
    """What to install, said the same way by the CLI and by skipped tests."""
    return (f"install Debian's ROS 1 packages (`apt-get install {' '.join(DEBIAN_PACKAGES)}`) and make "
            f"{DEBIAN_DIST_PACKAGES} visible to this Python (`make ros-deps`, part of `make test`, does both "
            f"when run as root on Debian)")


def require_ros() -> None:
    """Import rospy and genpy, or raise :class:`RosUnavailable` saying what to install.

    A virtual environment built on another Python of the same version (the
    project's pyenv 3.11 and Debian's 3.11) can use Debian's packages: when
    they are not already on ``sys.path`` (``make test`` adds them with a
    ``.pth`` file) the Debian folder is appended, after the environment's own
    packages, so it never shadows them.
    """
    try:
        _import_all()
        return
    except ImportError:
        pass
    if _debian_python_matches() and str(DEBIAN_DIST_PACKAGES) not in sys.path:
        sys.path.append(str(DEBIAN_DIST_PACKAGES))
        importlib.invalidate_caches()
        try:
            _import_all()
            return
        except ImportError as exc:
            raise RosUnavailable(f"ROS 1 Python packages are incomplete ({exc}): {install_hint()}") from None
    raise RosUnavailable(f"ROS 1 Python packages not found: {install_hint()}")


def ros_available() -> bool:
    """True when :func:`require_ros` succeeds."""
    try:
        require_ros()
    except RosUnavailable:
        return False
    return True


def _import_all() -> None:
    for name in ("rospy", "rosgraph", "genpy", "genmsg"):
        importlib.import_module(name)


def _debian_python_matches() -> bool:
    """Debian's compiled modules (netifaces, _yaml) only load in the same minor Python version."""
    expected = f"python{sys.version_info.major}.{sys.version_info.minor}"
    return (DEBIAN_DIST_PACKAGES / "rospy").is_dir() and Path("/usr/lib", expected).is_dir()


__all__ = ["DEBIAN_PACKAGES", "DEFAULT_NODE_NAME", "EXIT_NO_MASTER", "EXIT_NO_ROS", "SERIALIZED_SERVICE",
           "SINGLE_SERVICE", "RosUnavailable", "install_hint", "require_ros", "ros_available"]
