"""``topostore serve`` in a process forked from one that has imported topostore already.

Why: the kill -9 loop (tests/test_durable.py) starts the server again after every kill, 21 times; each start
in a fresh interpreter paid Python's start and the imports of topostore, the HTTP app and uvicorn, most of
the test's time.  A fork server (:mod:`multiprocessing`, ``forkserver``) imports them once; each server is
then a fork of it: a process of its own, listening, writing its store and killed with SIGKILL as before,
with the same code already imported.  Its stderr goes to a file, read when it exits early.
"""

from __future__ import annotations

import multiprocessing
import os
import signal
import subprocess
from collections.abc import Sequence
from pathlib import Path

#: what every server imports before it listens: imported once, in the fork server
PRELOAD = ["topostore.cli.group", "topostore.http.app", "uvicorn"]
_CONTEXT = multiprocessing.get_context("forkserver")
_CONTEXT.set_forkserver_preload(PRELOAD)


def _serve(args: list[str], log: str) -> None:
    """The forked process: ``topostore serve ARGS``, stdout discarded, stderr to ``log``."""
    os.dup2(os.open(os.devnull, os.O_WRONLY), 1)
    os.dup2(os.open(log, os.O_WRONLY | os.O_CREAT | os.O_APPEND, 0o600), 2)
    from topostore.cli.group import main

    raise SystemExit(main(["serve", *args]))


class ForkedServe:
    """One forked ``topostore serve``, with the :class:`subprocess.Popen` methods the tests use on a server."""

    def __init__(self, args: Sequence[str], log: Path) -> None:
        self.args = list(args)
        self.log = log
        self._process = _CONTEXT.Process(target=_serve, args=(self.args, str(log)), name="topostore-serve")
        self._process.start()
        self.pid = self._process.pid

    @property
    def returncode(self) -> int | None:
        return self._process.exitcode

    def poll(self) -> int | None:
        return self._process.exitcode

    def send_signal(self, sig: int) -> None:
        if self._process.exitcode is None:
            os.kill(self.pid, sig)

    def kill(self) -> None:
        self.send_signal(signal.SIGKILL)

    def wait(self, timeout: float | None = None) -> int:
        self._process.join(timeout)
        if self._process.exitcode is None:
            raise subprocess.TimeoutExpired(["topostore", "serve", *self.args], timeout or 0)
        return self._process.exitcode

    def stderr_text(self) -> str:
        return self.log.read_text(errors="replace") if self.log.exists() else ""


__all__ = ["ForkedServe", "PRELOAD"]
