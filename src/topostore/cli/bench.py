"""``topostore bench``: the benchmarks of the source tree (``python -m benchmarks``), arguments passed on."""

from __future__ import annotations

import os
import subprocess
import sys

import click


@click.command(context_settings={"ignore_unknown_options": True, "allow_extra_args": True})
@click.argument("args", nargs=-1, type=click.UNPROCESSED)
def bench(args: tuple[str, ...]) -> None:
    """Run the benchmarks (python -m benchmarks); arguments are passed on.

    \b
    Example (`make bench-quick` is the quick suite, `make bench` the whole one):
      topostore bench --parts steps --sizes example 8 --scale-sizes --steps 5 --no-pellet --out out/bench-example
    """
    from ..resources import source_root

    root = source_root()
    if root is None or not (root / "benchmarks" / "__main__.py").is_file():
        raise click.ClickException(
            "the benchmarks package is not available: it ships with the source tree "
            "(git clone, then pip install -e '.[bench]')"
        )
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join(filter(None, [str(root), env.get("PYTHONPATH", "")]))
    code = subprocess.call([sys.executable, "-m", "benchmarks", *args], cwd=root, env=env)
    raise click.exceptions.Exit(code)


__all__ = ["bench"]
