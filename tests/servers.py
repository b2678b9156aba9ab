"""Real SPARQL servers for the tests: ``oxigraph serve`` and Virtuoso, on free loopback ports.

Each is started in its own temporary directory, waited for (bounded), and
stopped by its process id.  ``oxigraph`` comes from the ``oxigraph`` PyPI
package (the test extra); Virtuoso from Debian's ``virtuoso-opensource``
(``make test`` installs it when run as root on Debian).
"""

from __future__ import annotations

import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

import httpx

VIRTUOSO = shutil.which("virtuoso-t")
ISQL = shutil.which("isql-vt") or shutil.which("isql")
OXIGRAPH = shutil.which("oxigraph") or str(Path(sys.executable).with_name("oxigraph"))


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def _wait_http(url: str, proc: subprocess.Popen, seconds: float, log: Path) -> None:
    deadline = time.monotonic() + seconds
    while time.monotonic() < deadline:
        if proc.poll() is not None:
            raise RuntimeError(f"{url}: the server exited with {proc.returncode}: {log.read_text()[-2000:]}")
        try:
            httpx.get(url, params={"query": "ASK {}"}, timeout=2)
            return
        except httpx.HTTPError:
            time.sleep(0.2)
    raise RuntimeError(f"{url}: the server did not answer within {seconds} s: {log.read_text()[-2000:]}")


def stop(proc: subprocess.Popen, sig: int = signal.SIGTERM) -> None:
    """Stop a process the tests started: ``sig``, then SIGKILL after 10 s."""
    if proc.poll() is None:
        proc.send_signal(sig)
        try:
            proc.wait(10)
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.wait(10)


@contextmanager
def oxigraph_server() -> Iterator[str]:
    """``oxigraph serve`` on a RocksDB directory; yields its base URL (``URL/query``, ``URL/update``)."""
    if not Path(OXIGRAPH).exists():
        raise RuntimeError("the oxigraph server is missing: pip install 'oxigraph>=0.4' (the test extra)")
    with tempfile.TemporaryDirectory(prefix="oxigraph-") as tmp:
        port = free_port()
        log = Path(tmp) / "server.log"
        with log.open("w") as out:
            proc = subprocess.Popen([OXIGRAPH, "serve", "-l", str(Path(tmp) / "db"), "-b", f"127.0.0.1:{port}"],
                                    stdout=out, stderr=subprocess.STDOUT)
        try:
            url = f"http://127.0.0.1:{port}"
            _wait_http(url + "/query", proc, 30, log)
            yield url
        finally:
            stop(proc)


_VIRTUOSO_INI = """[Database]
DatabaseFile = {d}/virtuoso.db
ErrorLogFile = {d}/virtuoso.log
LockFile = {d}/virtuoso.lck
TransactionFile = {d}/virtuoso.trx
xa_persistent_file = {d}/virtuoso.pxa
[TempDatabase]
DatabaseFile = {d}/virtuoso-temp.db
TransactionFile = {d}/virtuoso-temp.trx
[Parameters]
ServerPort = 127.0.0.1:{sql}
DisableUnixSocket = 1
CaseMode = 2
DirsAllowed = ., {d}
NumberOfBuffers = 20000
MaxDirtyBuffers = 15000
MaxQueryMem = 1G
ThreadsPerQuery = 1
[HTTPServer]
ServerPort = 127.0.0.1:{http}
ServerRoot = {d}
ServerThreads = 10
MaxClientConnections = 10
[SPARQL]
ResultSetMaxRows = 1000000
MaxQueryExecutionTime = 300
"""


def virtuoso_available() -> bool:
    return bool(VIRTUOSO and ISQL)


@contextmanager
def virtuoso_server() -> Iterator[str]:
    """Virtuoso Open Source 7 in a temporary database; yields its ``/sparql`` endpoint URL (updates allowed)."""
    if not virtuoso_available():
        raise RuntimeError("Virtuoso is missing: apt-get install virtuoso-opensource (Debian)")
    with tempfile.TemporaryDirectory(prefix="virtuoso-") as tmp:
        http, sql = free_port(), free_port()
        ini = Path(tmp) / "virtuoso.ini"
        ini.write_text(_VIRTUOSO_INI.format(d=tmp, http=http, sql=sql))
        log = Path(tmp) / "stdout.log"
        with log.open("w") as out:
            proc = subprocess.Popen([VIRTUOSO, "+foreground", "+configfile", str(ini)], cwd=tmp,
                                    stdout=out, stderr=subprocess.STDOUT)
        try:
            url = f"http://127.0.0.1:{http}/sparql"
            _wait_http(url, proc, 90, log)
            grant = 'GRANT SPARQL_UPDATE TO "SPARQL"; DB.DBA.RDF_DEFAULT_USER_PERMS_SET (\'nobody\', 7);'
            subprocess.run([ISQL, f"127.0.0.1:{sql}", "dba", "dba", f"exec={grant}"], check=True,
                           capture_output=True, timeout=60)
            yield url
        finally:
            stop(proc)


@contextmanager
def remote_server(name: str) -> Iterator[str]:
    with (oxigraph_server() if name == "oxigraph" else virtuoso_server()) as url:
        yield url


__all__ = ["oxigraph_server", "virtuoso_server", "remote_server", "virtuoso_available", "free_port"]
