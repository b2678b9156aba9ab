"""Every example in `topostore --help` and `topostore COMMAND --help` runs as written, and the CLI's messages.

Examples run through bash (globs and quotes as a user's shell reads them) in a
scratch folder where ``ontology/`` is the repository's, so the relative paths
of the examples resolve and nothing is written into the checkout.  The changes
made to an example: a server's port (8765) becomes a free one, because other
programs on the machine may hold 8765, and an example that names an Oxigraph
server (``http://127.0.0.1:7878``) gets a real ``oxigraph serve`` started for it
on a free port.
"""

from __future__ import annotations

import io
import json
import os
import re
import signal
import socket
import subprocess
import sys
import time
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

import pytest
from http_support import free_port
from rich.console import Console
from servers import oxigraph_server, stop

from topostore import Ontology
from topostore.cli.group import EXIT_CANNOT_LISTEN, cli, load_files, reason_with_progress
from topostore.demo import mapgen
from topostore.resources import default_ontology

ROOT = Path(__file__).resolve().parents[1]
BIN = Path(sys.executable).parent


def help_examples() -> list[tuple[str, str]]:
    """(command, example line) for every example line in the help texts."""
    out = []
    for name, command in [("", cli), *sorted(cli.commands.items())]:
        for line in (command.help or "").splitlines():
            m = re.match(r"^\s+((?:topostore|curl) .*)$", line)
            if m:
                out.append((name, m.group(1)))
    return out


@pytest.fixture
def workdir(tmp_path: Path) -> Path:
    (tmp_path / "ontology").symlink_to(ROOT / "ontology")
    return tmp_path


def shell_env() -> dict[str, str]:
    return {**os.environ, "PATH": f"{BIN}{os.pathsep}{os.environ.get('PATH', '')}"}


def sh(line: str, cwd: Path, timeout: float = 300) -> subprocess.CompletedProcess[str]:
    return subprocess.run(["bash", "-c", line], cwd=cwd, env=shell_env(), capture_output=True, text=True,
                          timeout=timeout, check=False)


def test_every_command_has_an_example() -> None:
    commands = {name for name, _ in help_examples()}
    assert commands == {"", *cli.commands}


SERVED = [line for _, line in help_examples() if line.startswith(("topostore serve", "curl"))]


EXAMPLE_SERVER = "http://127.0.0.1:7878"


@contextmanager
def with_its_server(line: str) -> Iterator[str]:
    """The example line, with a real Oxigraph server behind the URL it names (if it names one)."""
    if EXAMPLE_SERVER not in line:
        yield line
        return
    with oxigraph_server() as url:
        yield line.replace(EXAMPLE_SERVER, url)


@pytest.mark.parametrize("line", [line for _, line in help_examples() if line not in SERVED])
def test_help_example_runs(line: str, workdir: Path) -> None:
    with with_its_server(line) as line:
        done = sh(line, workdir)
    assert done.returncode == 0, f"{line}\n{done.stdout}\n{done.stderr}"
    assert "Traceback" not in done.stderr


def test_serve_help_example_with_its_curl(workdir: Path) -> None:
    """`topostore serve` as in its help, then the curl line of the same help (415 before it named its Content-Type)."""
    port = free_port()
    own = [line for name, line in help_examples() if name == "serve"]
    assert set(SERVED) == set(own)  # the top-level help repeats the serve line
    *serve_lines, curl_line = (line.replace("8765", str(port)) for line in own)
    for serve_line in serve_lines:  # each way of starting it, in turn, answers the help's curl
        with with_its_server(serve_line) as line:
            serve_and_curl(line.replace("topostore serve", f"topostore serve --port {port}")
                           if "--port" not in line else line, curl_line, port, workdir)


def serve_and_curl(serve_line: str, curl_line: str, port: int, workdir: Path) -> None:
    proc = subprocess.Popen(["bash", "-c", f"exec {serve_line}"], cwd=workdir, env=shell_env(),
                            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    try:
        deadline = time.monotonic() + 30
        while True:
            try:
                socket.create_connection(("127.0.0.1", port), timeout=1).close()
                break
            except OSError:
                assert proc.poll() is None and time.monotonic() < deadline, proc.stderr.read() if proc.stderr else ""
                time.sleep(0.1)
        done = sh(curl_line, workdir, timeout=30)
        assert done.returncode == 0, done.stderr
        answer = json.loads(done.stdout)
        assert answer["success"] is True and answer["exit_code"] == 0
    finally:
        stop(proc, signal.SIGINT)


def test_serve_on_a_busy_port_exits_4_with_one_line(workdir: Path) -> None:
    with socket.socket() as holder:
        holder.bind(("127.0.0.1", 0))
        holder.listen()
        port = holder.getsockname()[1]
        done = sh(f"topostore serve --port {port} --data-dir data", workdir, timeout=60)
    assert done.returncode == EXIT_CANNOT_LISTEN == 4
    assert done.stderr == (f"Error: port {port} on 127.0.0.1 is already in use (another topostore serve?); "
                           "choose one with --port\n")


def test_load_progress_counts_triples(tmp_path: Path) -> None:
    onto = Ontology.from_file(default_ontology())
    onto.add(*mapgen.generate(600, seed=1).triples())
    path = onto.save(tmp_path / "m600.ttl")
    buffer = io.StringIO()
    console = Console(file=buffer, force_terminal=True, width=120)
    loaded = load_files([str(path)], console=console)
    reason_with_progress(loaded, console=console)
    shown = re.sub(r"\x1b\[[0-9;?]*[A-Za-z]", "", buffer.getvalue())
    total = len(loaded.triples())
    assert "loading m600.ttl 5,000 triples parsed" in shown
    assert f"loaded m600.ttl {total:,} triples" in shown
    assert f"reasoning over {total:,} asserted triples" in shown
    assert "None" not in shown
