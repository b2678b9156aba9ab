"""``armor_msgs``: aRMOR's message and service definitions, compiled to Python by genpy.

The ``.msg``/``.srv`` files beside this module are byte for byte those of
EmaroLab/armor_msgs, so the MD5 sums ROS compares on every connection are the
same as aRMOR's (:data:`EXPECTED_MD5`) and existing nodes talk to topostore
without rebuilding.  The Python classes are not shipped: genpy (the code
generator ROS itself uses) writes them from these files, so they always match
the genpy/rospy installed next to them.
"""

from __future__ import annotations

import shutil
from pathlib import Path

from . import require_ros

PACKAGE = "armor_msgs"
DEFINITIONS = Path(__file__).with_name(PACKAGE)
MESSAGES = ("QueryItem", "ArmorDirectiveReq", "ArmorDirectiveRes")
SERVICES = ("ArmorDirective", "ArmorDirectiveList")

#: The MD5 sums of aRMOR's armor_msgs (as its generated clients declare them).
EXPECTED_MD5 = {
    "ArmorDirectiveReq": "385184fa98c36b7f00729ae2078dfc92",
    "ArmorDirectiveRes": "6846cf2c4447d7c66f608d63e1f65e77",
    "ArmorDirective": "39cbf11e18dc47e2c7b5fda84e5d8c39",
    "ArmorDirectiveList": "c8f7a3567fd279dae5ca45853049f5a7",
}


class GenerationError(RuntimeError):
    """genpy could not compile the definitions (it prints the details on stderr)."""


def definition_files() -> list[Path]:
    """Every definition file, in a fixed order (the cache key hashes them)."""
    return ([DEFINITIONS / "package.xml"] + [DEFINITIONS / "msg" / f"{m}.msg" for m in MESSAGES]
            + [DEFINITIONS / "srv" / f"{s}.srv" for s in SERVICES])


def copy_package(share_dir: Path) -> Path:
    """Copy the ROS package (package.xml, msg/, srv/) under ``share_dir``, where rosmsg/rossrv look."""
    target = share_dir / PACKAGE
    for source in definition_files():
        dest = target / source.relative_to(DEFINITIONS)
        dest.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(source, dest)
    return target


def generate_python(package_dir: Path, python_dir: Path) -> Path:
    """Run genpy on the package copied at ``package_dir``; write ``python_dir/armor_msgs``.

    Same layout as catkin's ``devel/lib/python3/dist-packages/armor_msgs``:
    ``msg/_ArmorDirectiveReq.py``…, ``srv/_ArmorDirective.py``… and
    ``__init__.py`` files that import them.
    """
    require_ros()
    from genpy.generate_initpy import write_modules
    from genpy.generator import MsgGenerator, SrvGenerator

    target = python_dir / PACKAGE
    search_path = {PACKAGE: [str(package_dir / "msg")]}
    jobs = ((MsgGenerator(), "msg", [package_dir / "msg" / f"{m}.msg" for m in MESSAGES]),
            (SrvGenerator(), "srv", [package_dir / "srv" / f"{s}.srv" for s in SERVICES]))
    for generator, kind, files in jobs:
        out = target / kind
        if generator.generate_messages(PACKAGE, [str(f) for f in files], str(out), search_path) != 0:
            raise GenerationError(f"genpy failed on {PACKAGE}/{kind} (details above)")
        write_modules(str(out))
    (target / "__init__.py").write_text("")
    return target
