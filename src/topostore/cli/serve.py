"""``topostore serve``: the HTTP service (:mod:`topostore.http.app`) from the command line.

Exit code 4 (:data:`EXIT_CANNOT_LISTEN`) and one line when it cannot listen
(the port is in use or the address is not this machine's), checked before the
server starts; uvicorn's own exit code 3 would read as "inconsistent" here.
"""

from __future__ import annotations

import errno
from pathlib import Path

import click

from .. import __version__
from .limits import apply_limits, limit_options
from .store_option import store_option

EXIT_CANNOT_LISTEN = 4


@click.command()
@click.option("--host", default="127.0.0.1", show_default=True, help="Address to listen on (loopback unless --token).")
@click.option("--port", default=8765, show_default=True, type=click.IntRange(0, 65535))
@click.option(
    "--data-dir",
    default="data",
    show_default=True,
    type=click.Path(file_okay=False),
    help="LOAD and SAVE paths are confined to this folder (created if missing).",
)
@click.option("--token", envvar="TOPOSTORE_TOKEN", help="Bearer token required on every request (env TOPOSTORE_TOKEN).")
@click.option(
    "--allow-update", is_flag=True, help="Accept SPARQL updates and Graph Store writes (PUT/POST/DELETE, uploads)."
)
@click.option(
    "--max-request-bytes",
    default=1024 * 1024,
    show_default=True,
    type=click.IntRange(1),
    help="Largest request body accepted (413 beyond).",
)
@click.option(
    "--sparql-timeout",
    default=10.0,
    show_default=True,
    type=click.FloatRange(min=0, min_open=True),
    help="Seconds a SPARQL query may run.",
)
@click.option(
    "--sparql-max-rows",
    default=500_000,
    show_default=True,
    type=click.IntRange(1),
    help="Most rows (or triples) a SPARQL result may have.",
)
@click.option("--short-names", is_flag=True, help="Answer aRMOR queries with short names instead of <IRI>s.")
@click.option("--strict", is_flag=True, help="LOAD refuses ontologies with axioms not reasoned completely "
              "(exit code 209, naming them) instead of loading them with the list.")
@click.option(
    "--cors-origin",
    "cors_origins",
    multiple=True,
    metavar="ORIGIN",
    help="Let web pages of ORIGIN (e.g. a YASGUI page) call the service (repeatable).",
)
@store_option
@click.option(
    "--sync",
    is_flag=True,
    help="With a directory --store: flush every acknowledged change to disk, so it "
    "also survives an OS crash or power loss (slower). With a server --store: send every "
    "change before the reply instead of with the next request (more round trips).",
)
@click.option("--store-query-url", metavar="URL", help="SPARQL query endpoint of a remote --store (default URL/query).")
@click.option(
    "--store-update-url", metavar="URL", help="SPARQL update endpoint of a remote --store (default URL/update)."
)
@limit_options
def serve(
    host: str,
    port: int,
    data_dir: str,
    token: str | None,
    allow_update: bool,
    max_request_bytes: int,
    sparql_timeout: float,
    sparql_max_rows: int,
    short_names: bool,
    strict: bool,
    cors_origins: tuple[str, ...],
    store: str | None,
    sync: bool,
    store_query_url: str | None,
    store_update_url: str | None,
    **limits: float,
) -> None:
    """Serve aRMOR commands (POST /armor) and SPARQL endpoints over HTTP.

    Exits with code 4 and one line when it cannot listen (port in use).

    \b
    Example:
      topostore serve --port 8765 --data-dir data
      topostore serve --store data/references        # references survive restarts
      topostore serve --store http://127.0.0.1:7878  # references on an Oxigraph server
      curl -s localhost:8765/armor -H 'Content-Type: application/json' -d '{"reference_name":"ref","command":"GET","primary_command_spec":"ALL","secondary_command_spec":"REFS"}'
    """  # noqa: E501 (an example run as written)
    from ..http.app import ServerConfig
    from ..http.app import serve as run_server

    config = ServerConfig(
        host=host,
        port=port,
        data_dir=Path(data_dir),
        token=token,
        allow_update=allow_update,
        max_request_bytes=max_request_bytes,
        sparql_timeout=sparql_timeout,
        sparql_max_rows=sparql_max_rows,
        short_names=short_names,
        strict=strict,
        cors_origins=cors_origins,
        store=store,
        sync=sync,
        store_query_url=store_query_url,
        store_update_url=store_update_url,
    )
    config.check()
    apply_limits(**limits)
    problem = _cannot_listen(host, port)
    if problem:
        click.echo(f"Error: {problem}", err=True)
        raise click.exceptions.Exit(EXIT_CANNOT_LISTEN)
    click.echo(
        f"topostore {__version__}: http://{host}:{port} (data directory {Path(data_dir).resolve()}; "
        f"SPARQL updates {'on' if allow_update else 'off'}; token {'required' if token else 'off'}; "
        f"store {store or 'memory'})",
        err=True,
    )
    try:
        run_server(config)
    except SystemExit as exc:  # uvicorn exits 3 when it cannot start; 3 means "inconsistent" here
        if exc.code in (0, None):
            raise
        click.echo(f"Error: the server could not start listening on {host}:{port} (see the log above)", err=True)
        raise click.exceptions.Exit(EXIT_CANNOT_LISTEN) from None


def _cannot_listen(host: str, port: int) -> str | None:
    """Why ``serve`` could not listen on host:port (None if it can), checked before the server starts."""
    import socket

    try:
        infos = socket.getaddrinfo(host, port, type=socket.SOCK_STREAM)
    except OSError as exc:
        return f"cannot resolve --host {host!r}: {exc.strerror or exc}"
    family, kind, proto, _, address = infos[0]
    with socket.socket(family, kind, proto) as sock:
        sock.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)  # as uvicorn does
        try:
            sock.bind(address)
        except OSError as exc:
            if exc.errno == errno.EADDRINUSE:
                return f"port {port} on {host} is already in use (another topostore serve?); choose one with --port"
            return f"cannot listen on {host}:{port}: {exc.strerror or exc}"
    return None


__all__ = ["serve", "EXIT_CANNOT_LISTEN"]
