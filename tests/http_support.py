"""Clients of the HTTP service for the tests: in-process (Starlette's TestClient), on a real socket served by uvicorn
in a thread of the test process (for clients that need a URL: rdflib, SPARQLWrapper, the armor client), or a
``topostore serve`` subprocess (the real command, kept for one smoke test per suite).

The first two run the service's code in the test process, so coverage sees it.  All three answer the same
``request``/``armor``/``ok``/``sparql_get`` calls, so a test reads the same whichever it uses.
"""

from __future__ import annotations

import contextlib
import json
import shutil
import socket
import subprocess
import sys
import threading
import time
import urllib.error
import urllib.parse
import urllib.request
from collections.abc import Iterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from servers import free_port
from support import IRI, NS
from support import TBOX_OWL as TBOX

from topostore import Ontology
from topostore.armor import ArmorService
from topostore.http.app import ServerConfig, create_app
from topostore.resources import default_ontology_files

__all__ = ["IRI", "NS", "TBOX", "TOKEN", "Client", "InProcess", "Live", "config", "example_map_server", "free_port",
           "in_process", "start_server", "stop_server", "threaded", "with_map"]

#: the bearer token of the tests that need one
TOKEN = "s3cret-token"
#: Debian's chromium, driven by Playwright for the live map and the inspector (None: those tests skip)
CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")
CHROMIUM_FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
                  "--disable-background-networking", "--disable-component-update", "--disable-sync"]


def config(data_dir: Path, **settings: Any) -> ServerConfig:
    """What ``topostore serve --data-dir DATA_DIR`` with these settings configures (the tutorial's TBox in it)."""
    return ServerConfig(data_dir=with_map(data_dir), **settings)


class Client:
    """aRMOR and SPARQL requests over :meth:`request`, which subclasses implement."""

    data_dir: Path
    token: str | None = None

    def request(self, path: str, body: bytes | None = None, headers: dict[str, str] | None = None,
                method: str | None = None) -> tuple[int, dict[str, str], bytes]:
        raise NotImplementedError

    def _headers(self, body: bytes | None, headers: dict[str, str] | None) -> dict[str, str]:
        h = dict(headers or {})
        if body is not None and "Content-Type" not in h:
            h["Content-Type"] = "application/json"
        if self.token and "Authorization" not in h:
            h["Authorization"] = f"Bearer {self.token}"
        return h

    def armor(self, command: str, spec1: str = "", spec2: str = "", args: list[str] | None = None,
              ref: str = "ontoRef", client: str = "example") -> dict:
        payload = {"client_name": client, "reference_name": ref, "command": command,
                   "primary_command_spec": spec1, "secondary_command_spec": spec2, "args": args or []}
        status, _, body = self.request("/armor", json.dumps(payload).encode(), {"Content-Type": "application/json"})
        assert status == 200, body
        return json.loads(body)

    def ok(self, *a: Any, **k: Any) -> dict:
        res = self.armor(*a, **k)
        assert res["success"] and res["exit_code"] == 0, (a, res)
        return res

    def sparql_get(self, query: str, accept: str | None = None,
                   ref: str = "ontoRef") -> tuple[int, dict[str, str], bytes]:
        headers = {"Accept": accept} if accept else {}
        return self.request(f"/references/{ref}/sparql?" + urllib.parse.urlencode({"query": query}), headers=headers)


@dataclass
class InProcess(Client):
    """The application called in-process through Starlette's TestClient (no socket)."""

    client: Any
    data_dir: Path
    token: str | None = None

    def request(self, path: str, body: bytes | None = None, headers: dict[str, str] | None = None,
                method: str | None = None) -> tuple[int, dict[str, str], bytes]:
        method = method or ("POST" if body is not None else "GET")
        res = self.client.request(method, path, content=body, headers=self._headers(body, headers))
        return res.status_code, dict(res.headers), res.content


@dataclass
class Live(Client):
    """A service on a real loopback socket, reached with the standard library's HTTP client."""

    url: str
    data_dir: Path
    token: str | None = None
    proc: subprocess.Popen | None = field(default=None, repr=False)

    def request(self, path: str, body: bytes | None = None, headers: dict[str, str] | None = None,
                method: str | None = None) -> tuple[int, dict[str, str], bytes]:
        """(status, headers, body) of one HTTP request; errors are returned, not raised."""
        req = urllib.request.Request(self.url + path, data=body, headers=self._headers(body, headers), method=method)
        try:
            with urllib.request.urlopen(req, timeout=30) as res:
                return res.status, {k.lower(): v for k, v in res.headers.items()}, res.read()
        except urllib.error.HTTPError as exc:
            return exc.code, {k.lower(): v for k, v in exc.headers.items()}, exc.read()


def with_map(data_dir: Path) -> Path:
    """``data_dir`` created, holding the tutorial's TBox as topological_map.owl."""
    data_dir.mkdir(parents=True, exist_ok=True)
    shutil.copy(TBOX, data_dir / "topological_map.owl")
    return data_dir


@contextlib.contextmanager
def in_process(config: ServerConfig) -> Iterator[InProcess]:
    """The application of ``config`` behind a TestClient, its lifespan run (closed on exit)."""
    from starlette.testclient import TestClient

    with TestClient(create_app(config), base_url="http://127.0.0.1") as client:
        yield InProcess(client, Path(config.data_dir), config.token)


@contextlib.contextmanager
def threaded(config: ServerConfig, timeout: float = 20, service: ArmorService | None = None) -> Iterator[Live]:
    """The application of ``config`` (serving ``service`` when given) on a free loopback port, in a thread of this
    process."""
    import uvicorn

    sock = socket.socket()
    sock.bind(("127.0.0.1", 0))  # bound here, so no other process can take the port before uvicorn listens
    port = sock.getsockname()[1]
    app = create_app(config, service)
    server = uvicorn.Server(uvicorn.Config(app, log_level="warning", timeout_graceful_shutdown=5))
    thread = threading.Thread(target=server.run, kwargs={"sockets": [sock]}, name="uvicorn-test", daemon=True)
    thread.start()
    try:
        deadline = time.monotonic() + timeout
        while not server.started:
            if not thread.is_alive() or time.monotonic() > deadline:
                raise RuntimeError(f"uvicorn did not start in {timeout} s")
            time.sleep(0.02)
        yield Live(f"http://127.0.0.1:{port}", Path(config.data_dir), config.token)
    finally:
        server.should_exit = True
        thread.join(15)
        sock.close()


@contextlib.contextmanager
def example_map_server(data_dir: Path) -> Iterator[Live]:
    """A service on a real socket with the example map loaded as reference ontoRef (live reasoner: every change
    reasons), for the browser and the server-sent events."""
    with threaded(config(data_dir)) as server:
        Ontology.from_file(*default_ontology_files()).save(server.data_dir / "example.ttl")
        server.ok("LOAD", "FILE", "", ["example.ttl", IRI, "false", "PELLET", "false"])
        yield server


def start_server(data_dir: Path, *extra: str, token: str | None = None, port: int | None = None) -> Live:
    """``topostore serve`` in a subprocess on a free loopback port (stop it with :func:`stop_server`)."""
    with_map(data_dir)
    port = port or free_port()
    log = open(data_dir / "server.log", "wb")
    cmd = [sys.executable, "-m", "topostore.cli", "serve", "--host", "127.0.0.1", "--port", str(port),
           "--data-dir", str(data_dir), *extra]
    if token:
        cmd += ["--token", token]
    proc = subprocess.Popen(cmd, stdout=log, stderr=subprocess.STDOUT)
    server = Live(f"http://127.0.0.1:{port}", data_dir, token, proc)
    deadline = time.monotonic() + 20
    while time.monotonic() < deadline:
        if proc.poll() is not None:
            raise RuntimeError(f"server exited: {(data_dir / 'server.log').read_text()}")
        try:
            if server.request("/health")[0] == 200:
                return server
        except OSError:
            pass
        time.sleep(0.1)
    proc.kill()
    raise RuntimeError("server did not start in 20 s")


def stop_server(server: Live) -> None:
    assert server.proc is not None
    server.proc.terminate()
    try:
        server.proc.wait(10)
    except subprocess.TimeoutExpired:
        server.proc.kill()
        server.proc.wait(5)
