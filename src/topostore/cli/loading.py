"""Loading ontology files for the ``topostore`` commands, with a progress display by triples.

Every command that reads FILE(s) (reason, rules, query, map, explain) loads
them here, so all show the same progress on standard error (silent when it is
not a terminal) and refuse a missing file with the same one-line error.
"""

from __future__ import annotations

import logging
import warnings
from collections.abc import Iterator, Sequence
from contextlib import contextmanager
from pathlib import Path

import click
from rich.console import Console
from rich.progress import Progress, SpinnerColumn, TaskID, TextColumn, TimeElapsedColumn

from ..compile.notices import OntologyWarning
from ..compile.notices import logger as notices_logger
from ..ontology.facade import Ontology, ReasonReport
from ..rdf.vocab import ASSERTED

#: the log a REASON says its warnings on (topostore.ontology.pellet_values)
REASON_LOG = "topostore.reason"

err_console = Console(stderr=True, highlight=False)


@contextmanager
def _progress(enabled: bool = True, console: Console | None = None) -> Iterator[Progress]:
    """A progress display on standard error; silent when stderr is not a terminal."""
    console = console or err_console
    progress = Progress(
        SpinnerColumn(),
        TextColumn("{task.description}"),
        TextColumn("{task.fields[detail]}"),
        TimeElapsedColumn(),
        console=console,
        transient=True,
        disable=not enabled or not console.is_terminal,
    )
    with progress:
        yield progress


def load_files(
    files: Sequence[str], fmt: str | None = None, console: Console | None = None, store: str | None = None,
    strict: bool = False,
) -> Ontology:
    """Load ``files`` into one ontology (on ``store``), showing how many triples each has given so far;
    ``strict``: refuse files with axioms not reasoned completely (IncompleteOntologyError)."""
    onto = Ontology(store=store, strict=strict)
    context = click.get_current_context(silent=True)
    if store and context is not None:
        context.call_on_close(onto.store.close)  # a durable store is released when the command ends
    with _progress(console=console) as progress:
        for f in files:
            name = Path(f).name
            task = progress.add_task(f"loading {name}", detail="")

            def parsed(n: int, task: TaskID = task) -> None:
                progress.update(task, detail=f"{n:,} triples parsed", refresh=True)  # shown even when the load is fast

            with _notices_shown(console or err_console):
                added = onto.load(f, fmt=fmt, progress=parsed)
            progress.update(task, description=f"loaded {name}", detail=f"{added:,} triples")
            progress.stop_task(task)
    return onto


class _ConsoleHandler(logging.Handler):
    """Log records as ``warning: ...`` lines on a console."""

    def __init__(self, console: Console) -> None:
        super().__init__(logging.WARNING)
        self.console = console

    def emit(self, record: logging.LogRecord) -> None:
        self.console.print(f"warning: {record.getMessage()}", markup=False, soft_wrap=True)


@contextmanager
def _notices_shown(console: Console, log_name: str = notices_logger.name) -> Iterator[None]:
    """A load's notices (topostore.compile.notices; or what the log ``log_name`` says) as one ``warning:`` line
    each, not as Python warnings."""
    log = logging.getLogger(log_name)
    handler = _ConsoleHandler(console)
    log.addHandler(handler)
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", OntologyWarning)
            yield
    finally:
        log.removeHandler(handler)


def reason_with_progress(onto: Ontology, console: Console | None = None) -> ReasonReport:
    """REASON with a progress line; what it warns of (a :class:`~topostore.PelletDifferenceWarning`) shown as one
    ``warning:`` line each, as a load's notices are, whatever the warnings filter (``python -W error``)."""
    with _progress(console=console) as progress:
        progress.add_task(f"reasoning over {onto.store.count(ASSERTED):,} asserted triples", detail="")
        with _notices_shown(console or err_console, REASON_LOG):
            return onto.reason()


def _existing(files: Sequence[str]) -> None:
    for f in files:
        if not Path(f).is_file():
            raise click.ClickException(f"no such file: {f}")


__all__ = ["load_files", "reason_with_progress", "err_console"]
