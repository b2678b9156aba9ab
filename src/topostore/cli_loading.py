"""Loading ontology files for the ``topostore`` commands, with a progress display by triples.

Every command that reads FILE(s) (reason, rules, query, map, explain) loads
them here, so all show the same progress on standard error (silent when it is
not a terminal) and refuse a missing file with the same one-line error.
"""

from __future__ import annotations

from collections.abc import Iterator, Sequence
from contextlib import contextmanager
from pathlib import Path

import click
from rich.console import Console
from rich.progress import Progress, SpinnerColumn, TaskID, TextColumn, TimeElapsedColumn

from .ontology import Ontology, ReasonReport
from .vocab import ASSERTED

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
    files: Sequence[str], fmt: str | None = None, console: Console | None = None, store: str | None = None
) -> Ontology:
    """Load ``files`` into one ontology (on ``store``), showing how many triples each has given so far."""
    onto = Ontology(store=store)
    context = click.get_current_context(silent=True)
    if store and context is not None:
        context.call_on_close(onto.store.close)  # a durable store is released when the command ends
    with _progress(console=console) as progress:
        for f in files:
            name = Path(f).name
            task = progress.add_task(f"loading {name}", detail="")

            def parsed(n: int, task: TaskID = task) -> None:
                progress.update(task, detail=f"{n:,} triples parsed")

            added = onto.load(f, fmt=fmt, progress=parsed)
            progress.update(task, description=f"loaded {name}", detail=f"{added:,} triples")
            progress.stop_task(task)
    return onto


def reason_with_progress(onto: Ontology, console: Console | None = None) -> ReasonReport:
    with _progress(console=console) as progress:
        progress.add_task(f"reasoning over {onto.store.count(ASSERTED):,} asserted triples", detail="")
        return onto.reason()


def _existing(files: Sequence[str]) -> None:
    for f in files:
        if not Path(f).is_file():
            raise click.ClickException(f"no such file: {f}")


__all__ = ["load_files", "reason_with_progress", "err_console"]
