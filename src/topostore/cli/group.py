"""``topostore``: reason, inspect rules, query, serve, run the demo, draw maps.

Errors are printed as one line (``Error: ...``) unless ``--debug`` is given;
exit codes: 0 success, 1 error, 2 usage error, 3 inconsistent ontology,
4 ``serve`` cannot listen (the port is in use or the address is not this machine's);
``topostore ros``: 4 no ROS master reachable, 5 ROS not installed.

This module is the ``topostore`` group (one-line errors, ``--debug``) and the
list of its commands; each family lives in its own module: ``reason``,
``rules`` and ``query`` in :mod:`.ontology`, ``check`` and ``repair`` in
:mod:`.check`, ``serve`` in
:mod:`.serve`, ``demo`` and ``map`` in :mod:`.pictures`, ``bench`` in
:mod:`.bench`, ``explain`` in :mod:`.explain`, ``ros`` in
:mod:`.ros`; loading files with progress in :mod:`.loading`.
"""

from __future__ import annotations

import sys
from collections.abc import Sequence

import click

from .. import __version__
from ..errors import TopostoreError
from .bench import bench
from .check import check, repair
from .explain import explain
from .loading import _existing, err_console, load_files, reason_with_progress
from .ontology import EXIT_INCONSISTENT, query, reason, rules
from .pictures import demo, map_command
from .ros import ros  # imports no ROS module until it runs
from .serve import EXIT_CANNOT_LISTEN, serve


class TopostoreGroup(click.Group):
    """A group that turns any error into one clear line (a traceback only with ``--debug``)."""

    def invoke(self, ctx: click.Context) -> object:
        try:
            return super().invoke(ctx)
        except (click.ClickException, click.exceptions.Exit, click.Abort, BrokenPipeError):
            raise  # click reports these itself (a broken pipe, e.g. into `head`, ends quietly)
        except KeyboardInterrupt:
            raise click.Abort() from None
        # The command line's one boundary, like ArmorService.call's: a user gets one line, not a
        # traceback, whatever failed; --debug re-raises so that a bug shows where it is.
        except Exception as exc:
            if ctx.meta.get("topostore.debug"):
                raise
            raise click.ClickException(one_line(exc)) from None


def one_line(exc: BaseException) -> str:
    """The message of an error on one line; the class name for errors that are not ours."""
    text = " ".join(str(exc).split())
    if isinstance(exc, (TopostoreError, OSError)):
        return text or type(exc).__name__
    return f"{type(exc).__name__}: {text}" if text else type(exc).__name__


@click.group(cls=TopostoreGroup, context_settings={"help_option_names": ["-h", "--help"], "max_content_width": 100})
@click.option("--debug", is_flag=True, help="Show full tracebacks on errors.")
@click.version_option(__version__, prog_name="topostore")
@click.pass_context
def cli(ctx: click.Context, debug: bool) -> None:
    """An OWL + SWRL ontology service for robots (the aRMOR replacement).

    \b
    Examples:
      topostore reason ontology/topological_map.ttl ontology/topological_map_abox.ttl
      topostore query --list
      topostore serve --port 8765 --data-dir data
      topostore serve --store data/references        # references survive restarts
      topostore serve --store http://127.0.0.1:7878  # references on an Oxigraph server
      topostore demo --steps 20 --robots 2
    """
    ctx.meta["topostore.debug"] = debug


for _command in (reason, rules, query, check, repair, serve, demo, map_command, bench, ros, explain):
    cli.add_command(_command)


def main(argv: Sequence[str] | None = None) -> int:
    """Console-script entry point."""
    try:
        code = cli.main(args=list(argv) if argv is not None else None, prog_name="topostore", standalone_mode=False)
        return code if isinstance(code, int) else 0  # click returns the code of ctx.exit()/Exit here
    except click.exceptions.Exit as exc:
        return exc.exit_code
    except click.ClickException as exc:
        exc.show()
        return exc.exit_code
    except click.Abort:
        click.echo("Aborted.", err=True)
        return 130


__all__ = ["cli", "main", "one_line", "load_files", "reason_with_progress", "err_console", "_existing",
           "EXIT_INCONSISTENT", "EXIT_CANNOT_LISTEN"]


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
