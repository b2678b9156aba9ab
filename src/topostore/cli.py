"""``topostore``: reason, inspect rules, query, serve, run the demo, draw maps.

Errors are printed as one line (``Error: ...``) unless ``--debug`` is given;
exit codes: 0 success, 1 error, 2 usage error, 3 inconsistent ontology,
4 ``serve`` cannot listen (the port is in use or the address is not this machine's);
``topostore ros``: 4 no ROS master reachable, 5 ROS not installed.
"""

from __future__ import annotations

import errno
import json
import os
import subprocess
import sys
import time
from collections.abc import Iterator, Sequence
from contextlib import contextmanager
from pathlib import Path

import click

from .store_cli import store_option
from rich.console import Console
from rich.progress import Progress, SpinnerColumn, TaskID, TextColumn, TimeElapsedColumn
from rich.table import Table

from . import __version__
from .errors import TopostoreError
from .ontology import Ontology, ReasonReport
from .queries import QueryItem, named_queries
from .store import guess_format, serialize
from .vocab import ASSERTED, INFERRED, OWL, RDF, RDFS, XSD

EXIT_INCONSISTENT = 3
EXIT_CANNOT_LISTEN = 4

err_console = Console(stderr=True, highlight=False)


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


# --------------------------------------------------------------------------- loading with progress

@contextmanager
def _progress(enabled: bool = True, console: Console | None = None) -> Iterator[Progress]:
    """A progress display on standard error; silent when stderr is not a terminal."""
    console = console or err_console
    progress = Progress(SpinnerColumn(), TextColumn("{task.description}"), TextColumn("{task.fields[detail]}"),
                        TimeElapsedColumn(), console=console, transient=True,
                        disable=not enabled or not console.is_terminal)
    with progress:
        yield progress


def load_files(files: Sequence[str], fmt: str | None = None, console: Console | None = None,
               store: str | None = None) -> Ontology:
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


# --------------------------------------------------------------------------- reason

@cli.command()
@click.argument("files", nargs=-1, metavar="FILE...")
@store_option
@click.option("-o", "--output", type=click.Path(dir_okay=False, writable=True), help="Write asserted + inferred triples here.")
@click.option("--inferred-only", is_flag=True, help="With -o: write only the inferred triples.")
@click.option("--format", "fmt", metavar="F", help="Output format: turtle, ntriples or rdfxml (default: from -o's extension).")
@click.option("--input-format", metavar="F", help="Format of the input files when their extension does not tell.")
def reason(files: tuple[str, ...], store: str | None, output: str | None, inferred_only: bool, fmt: str | None,
           input_format: str | None) -> None:
    """Load FILE(s) (into --store, if given), reason, and print a summary; exit 3 if inconsistent.

    \b
    Examples:
      topostore reason ontology/topological_map.ttl ontology/topological_map_abox.ttl -o out/closure.ttl
      topostore reason --store out/mapdb ontology/topological_map.ttl ontology/topological_map_abox.ttl
      topostore reason --store out/mapdb        # the stored ontology again, no files
    """
    if not files and not store:
        raise click.UsageError("give the ontology file(s), or --store holding an ontology")
    _existing(files)
    if inferred_only and not output:
        raise click.UsageError("--inferred-only needs -o FILE")
    start = time.perf_counter()
    onto = load_files(files, input_format, store=store)
    loaded = time.perf_counter() - start
    report = reason_with_progress(onto)
    asserted = onto.store.count(ASSERTED)
    inferred = onto.store.count(INFERRED)
    click.echo(f"Loaded {len(files)} file(s): {asserted} asserted triples in {loaded:.3f} s")
    click.echo(f"Reasoned in {report.stats.seconds:.3f} s ({report.stats.rounds} rounds, "
               f"{len(onto.rules.rules)} rules): {inferred} inferred triples")
    if output:
        out = Path(output)
        rdf_format = guess_format(out, fmt)
        if inferred_only:
            triples = onto.store.dump([INFERRED], restore_literals_from=ASSERTED)
        else:
            triples = onto.triples(inferred=True)
        prefixes = {"owl": OWL, "rdf": RDF, "rdfs": RDFS, "xsd": XSD, "": onto.prefix}
        out.parent.mkdir(parents=True, exist_ok=True)
        out.write_bytes(serialize(triples, rdf_format, prefixes))
        click.echo(f"Wrote {len(triples)} triples to {out}")
    if report.consistent:
        click.echo("Consistent.")
        return
    click.echo(f"INCONSISTENT: {len(report.violations)} violation(s)", err=True)
    for v in report.violations:
        who = ", ".join(f"{k}={_short(val)}" for k, val in v.individuals.items())
        click.echo(f"  - {v.message}\n    axiom: {v.axiom} (rule {v.rule})" + (f"\n    individuals: {who}" if who else ""),
                   err=True)
    raise click.exceptions.Exit(EXIT_INCONSISTENT)


def _short(term: object) -> str:
    value = getattr(term, "value", str(term))
    return value.rsplit("#", 1)[-1] if "#" in value else value


# --------------------------------------------------------------------------- rules

RULE_GROUPS = ("SWRL rules", "OWL axioms", "Consistency checks", "Generic OWL 2 RL rules")


@cli.command()
@click.argument("files", nargs=-1, required=True, metavar="FILE...")
@click.option("--all", "show_all", is_flag=True, help="Also print the generic OWL 2 RL rules every ontology gets.")
def rules(files: tuple[str, ...], show_all: bool) -> None:
    """Print the rules compiled from FILE(s): SPARQL per rule, grouped, with its origin.

    \b
    Example:
      topostore rules ontology/topological_map.ttl
    """
    from .compile.generic import generic_rules

    _existing(files)
    onto = load_files(files)
    generic = {(r.name, r.where(), r.head) for r in generic_rules()}
    groups: dict[str, list] = {g: [] for g in RULE_GROUPS}
    for rule in onto.rules.rules:
        if (rule.name, rule.where(), rule.head) in generic:
            groups["Generic OWL 2 RL rules"].append(rule)
        elif rule.name.startswith("swrl:"):
            groups["SWRL rules"].append(rule)
        elif rule.is_check:
            groups["Consistency checks"].append(rule)
        else:
            groups["OWL axioms"].append(rule)
    shown = 0
    for title in RULE_GROUPS:
        if title == "Generic OWL 2 RL rules" and not show_all:
            continue
        members = groups[title]
        click.echo(f"### {title} ({len(members)})\n")
        for rule in members:
            click.echo(rule.sparql() + "\n")
        shown += len(members)
    hidden = "" if show_all else f", {len(groups['Generic OWL 2 RL rules'])} generic rules not shown (--all)"
    click.echo(f"# {shown} rules{hidden}")


# --------------------------------------------------------------------------- query

def _parse_params(pairs: Sequence[str]) -> dict[str, object]:
    params: dict[str, object] = {}
    for pair in pairs:
        name, sep, value = pair.partition("=")
        if not sep or not name:
            raise click.UsageError(f"--param takes NAME=VALUE, not {pair!r}")
        params[name] = int(value) if value.lstrip("-").isdigit() else value
    return params


def _rows(items: list[QueryItem]) -> tuple[list[str], list[list[str]]]:
    """Regroup aRMOR-style flat items into rows: every row lists every variable, in order."""
    variables: list[str] = []
    for item in items:
        if item.key in variables:
            break
        variables.append(item.key)
    width = len(variables) or 1
    return variables, [[i.value for i in items[k:k + width]] for k in range(0, len(items), width)]


@cli.command()
@click.argument("args", nargs=-1, metavar="FILE... NAME_OR_RQ_FILE")
@click.option("--param", "-p", "params", multiple=True, metavar="NAME=VALUE", help="A query parameter (repeatable).")
@click.option("--format", "fmt", type=click.Choice(["table", "json", "tsv"]), default="table", show_default=True)
@click.option("--list", "list_only", is_flag=True, help="List the named queries and their parameters.")
@click.option("--full-iris", is_flag=True, help="Show full IRIs in tables instead of names in the ontology's namespace.")
@store_option
def query(args: tuple[str, ...], params: tuple[str, ...], fmt: str, list_only: bool, full_iris: bool,
          store: str | None) -> None:
    """Reason on FILE(s), then run a named query (see --list) or a SPARQL .rq file.

    \b
    Examples:
      topostore query --list
      topostore query ontology/topological_map.ttl ontology/topological_map_abox.ttl urgent-locations
      topostore query ontology/*.ttl reachable-locations --param robot=Robot1 --format json
      topostore query --store out/mapdb urgent-locations      # the ontology kept in a store
    """
    if list_only:
        for q in named_queries().values():
            sig = " ".join(f"{name}={kind}" for name, kind in q.params.items())
            click.echo(f"{q.name}{' ' + sig if sig else ''}\n    {q.description}")
        return
    if len(args) < (1 if store else 2):
        raise click.UsageError("give the ontology file(s) and then a query name or .rq file (topostore query --list)")
    files, name = args[:-1], args[-1]
    _existing(files)
    onto = load_files(files, store=store)
    report = reason_with_progress(onto)
    if not report.consistent:
        click.echo(f"warning: the ontology is inconsistent ({report.explain()}); answering from asserted facts only",
                   err=True)
    items = onto.query(name, _parse_params(params))
    variables, rows = _rows(items)
    if fmt == "json":
        click.echo(json.dumps([dict(zip(variables, row)) for row in rows], indent=2, ensure_ascii=False))
    elif fmt == "tsv":
        if variables:
            click.echo("\t".join(variables))
        for row in rows:
            click.echo("\t".join(v.replace("\t", " ").replace("\n", " ") for v in row))
    else:
        table = Table(*variables) if variables else Table("(no variables)")
        for row in rows:
            table.add_row(*[v if full_iris else _readable(v, onto.prefix) for v in row])
        Console(highlight=False, soft_wrap=True).print(table)
        click.echo(f"{len(rows)} row(s)")


def _readable(value: str, prefix: str) -> str:
    """A table cell: names in the ontology's namespace without it, XML Schema values without their datatype."""
    if value.startswith(prefix):
        return value[len(prefix):]
    lexical, sep, datatype = value.rpartition("^^")
    if sep and datatype.startswith(XSD):
        return lexical
    return value


# --------------------------------------------------------------------------- serve

from .limits_cli import apply_limits, limit_options  # noqa: E402 - beside the command that uses them


@cli.command()
@click.option("--host", default="127.0.0.1", show_default=True, help="Address to listen on (loopback unless --token).")
@click.option("--port", default=8765, show_default=True, type=click.IntRange(0, 65535))
@click.option("--data-dir", default="data", show_default=True, type=click.Path(file_okay=False),
              help="LOAD and SAVE paths are confined to this folder (created if missing).")
@click.option("--token", envvar="TOPOSTORE_TOKEN", help="Bearer token required on every request (env TOPOSTORE_TOKEN).")
@click.option("--allow-update", is_flag=True, help="Accept SPARQL updates and Graph Store writes (PUT/POST/DELETE, uploads).")
@click.option("--max-request-bytes", default=1024 * 1024, show_default=True, type=click.IntRange(1),
              help="Largest request body accepted (413 beyond).")
@click.option("--sparql-timeout", default=10.0, show_default=True, type=click.FloatRange(min=0, min_open=True),
              help="Seconds a SPARQL query may run.")
@click.option("--sparql-max-rows", default=500_000, show_default=True, type=click.IntRange(1),
              help="Most rows (or triples) a SPARQL result may have.")
@click.option("--short-names", is_flag=True, help="Answer aRMOR queries with short names instead of <IRI>s.")
@click.option("--cors-origin", "cors_origins", multiple=True, metavar="ORIGIN",
              help="Let web pages of ORIGIN (e.g. a YASGUI page) call the service (repeatable).")
@store_option
@click.option("--sync", is_flag=True, help="With a directory --store: flush every acknowledged change to disk, so it "
              "also survives an OS crash or power loss (slower).")
@click.option("--store-query-url", metavar="URL", help="SPARQL query endpoint of a remote --store (default URL/query).")
@click.option("--store-update-url", metavar="URL", help="SPARQL update endpoint of a remote --store (default URL/update).")
@limit_options
def serve(host: str, port: int, data_dir: str, token: str | None, allow_update: bool, max_request_bytes: int,
          sparql_timeout: float, sparql_max_rows: int, short_names: bool, cors_origins: tuple[str, ...],
          store: str | None, sync: bool, store_query_url: str | None, store_update_url: str | None,
          **limits: float) -> None:
    """Serve aRMOR commands (POST /armor) and SPARQL endpoints over HTTP.

    Exits with code 4 and one line when it cannot listen (port in use).

    \b
    Example:
      topostore serve --port 8765 --data-dir data
      topostore serve --store data/references        # references survive restarts
      topostore serve --store http://127.0.0.1:7878  # references on an Oxigraph server
      curl -s localhost:8765/armor -H 'Content-Type: application/json' -d '{"reference_name":"ref","command":"GET","primary_command_spec":"ALL","secondary_command_spec":"REFS"}'
    """
    from .server import ServerConfig, serve as run_server

    config = ServerConfig(host=host, port=port, data_dir=Path(data_dir), token=token, allow_update=allow_update,
                          max_request_bytes=max_request_bytes, sparql_timeout=sparql_timeout,
                          sparql_max_rows=sparql_max_rows, short_names=short_names,
                          cors_origins=cors_origins, store=store, sync=sync, store_query_url=store_query_url,
                          store_update_url=store_update_url)
    config.check()
    apply_limits(**limits)
    problem = _cannot_listen(host, port)
    if problem:
        click.echo(f"Error: {problem}", err=True)
        raise click.exceptions.Exit(EXIT_CANNOT_LISTEN)
    click.echo(f"topostore {__version__}: http://{host}:{port} (data directory {Path(data_dir).resolve()}; "
               f"SPARQL updates {'on' if allow_update else 'off'}; token {'required' if token else 'off'}; "
               f"store {store or 'memory'})", err=True)
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


# --------------------------------------------------------------------------- demo

@cli.command()
@click.option("--map", "map_files", multiple=True, type=click.Path(exists=True, dir_okay=False),
              help="Map file (repeatable; default: the embedded topological map and its example environment).")
@click.option("--steps", default=10, show_default=True, type=click.IntRange(0))
@click.option("--seed", default=0, show_default=True, type=int, help="Seed of the robots' random choices.")
@click.option("--robots", default=1, show_default=True, type=click.IntRange(1), help="Number of robots.")
@click.option("--time-scale", default=0.0, show_default=True, type=click.FloatRange(0),
              help="Real seconds per simulated second (0: run as fast as possible).")
@click.option("--picture", default="out/map.png", show_default=True, type=click.Path(dir_okay=False),
              help="Where to draw the reasoned map (.png, .svg or .pdf).")
@click.option("--no-picture", is_flag=True, help="Do not draw the map.")
@click.option("--every-step", is_flag=True, help="Draw the map after every step (map-001.png, ...).")
@store_option
def demo(map_files: tuple[str, ...], steps: int, seed: int, robots: int, time_scale: float, picture: str,
         no_picture: bool, every_step: bool, store: str | None) -> None:
    """The surveillance demo: robots patrol the map, visiting URGENT locations.

    \b
    Examples:
      topostore demo
      topostore demo --steps 30 --robots 2 --seed 7 --picture out/map.svg
      topostore demo --map ontology/topological_map.ttl --map ontology/topological_map_abox.ttl --every-step
      topostore demo --robots 3 --store http://127.0.0.1:7878   # a fleet: one client per robot, one shared map
    """
    from .demo import run_demo
    from .demo.mapview import VizMissing, require_matplotlib

    if not no_picture:
        try:
            require_matplotlib()
        except VizMissing as exc:
            click.echo(f"note: no picture: {exc}", err=True)
            no_picture = True
    run_demo(list(map_files) or None, steps=steps, seed=seed, robots=robots, time_scale=time_scale,
             picture=None if no_picture else picture, every_step=every_step, emit=click.echo, store=store)


# --------------------------------------------------------------------------- map

@cli.command("map")
@click.argument("files", nargs=-1, required=True, metavar="FILE...")
@click.option("-o", "--output", required=True, type=click.Path(dir_okay=False), help="Picture file: .png, .svg or .pdf.")
@click.option("--title", default="", help="Title above the map.")
@click.option("--robots/--no-robots", default=True, show_default=True, help="Mark where each robot isIn.")
@click.option("--urgent/--no-urgent", default=True, show_default=True, help="Ring URGENT locations in red.")
@click.option("--cluster-above", default=400, show_default=True, type=click.IntRange(1), metavar="N",
              help="Draw corridors with their rooms as clusters when the map has more than N locations.")
def map_command(files: tuple[str, ...], output: str, title: str, robots: bool, urgent: bool, cluster_above: int) -> None:
    """Draw the reasoned map of FILE(s): rooms, corridors, doors, connections, robots, URGENT.

    Corridors form the spine, rooms sit around their corridor; big maps are
    drawn as clusters of corridors with their rooms.  Needs the [viz] extra.

    \b
    Examples:
      topostore map ontology/topological_map.ttl ontology/topological_map_abox.ttl -o out/map.svg
      topostore map ontology/topological_map.ttl ontology/topological_map_abox.ttl -o out/plain.png --no-robots --no-urgent
    """
    from .demo.mapview import Style, draw_ontology, require_matplotlib

    require_matplotlib()
    _existing(files)
    onto = load_files(files)
    report = reason_with_progress(onto)
    if not report.consistent:
        raise click.ClickException(f"the ontology is inconsistent, nothing reliable to draw: {report.explain()}")
    path = draw_ontology(onto, output, title, Style(robots=robots, urgent=urgent, cluster_above=cluster_above))
    click.echo(f"Wrote {path}")


# --------------------------------------------------------------------------- bench

@cli.command(context_settings={"ignore_unknown_options": True, "allow_extra_args": True})
@click.argument("args", nargs=-1, type=click.UNPROCESSED)
def bench(args: tuple[str, ...]) -> None:
    """Run the benchmarks (python -m benchmarks); arguments are passed on.

    \b
    Example (`make bench-quick` is the quick suite, `make bench` the whole one):
      topostore bench --sizes example 8 --scale-sizes --steps 5 --no-pellet --out out/bench-example
    """
    from .resources import source_root

    root = source_root()
    if root is None or not (root / "benchmarks" / "__main__.py").is_file():
        raise click.ClickException("the benchmarks package is not available: it ships with the source tree "
                                   "(git clone, then pip install -e '.[bench]')")
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join(filter(None, [str(root), env.get("PYTHONPATH", "")]))
    code = subprocess.call([sys.executable, "-m", "benchmarks", *args], cwd=root, env=env)
    raise click.exceptions.Exit(code)


from . import cli_explain  # noqa: E402,F401  (registers `topostore explain`)
# --------------------------------------------------------------------------- ros

from .ros.command import ros as _ros_command  # noqa: E402  (imports no ROS module until it runs)

cli.add_command(_ros_command)


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


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
