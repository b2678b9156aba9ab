"""``topostore demo`` and ``topostore map``: the patrol demo and pictures of a reasoned map.

Pictures need the ``[viz]`` extra (matplotlib); ``demo`` runs without it and says so.
"""

from __future__ import annotations

import click

from .loading import _existing, load_files, reason_with_progress
from .store_option import store_option


@click.command()
@click.option(
    "--map",
    "map_files",
    multiple=True,
    type=click.Path(exists=True, dir_okay=False),
    help="Map file (repeatable; default: the embedded topological map and its example environment).",
)
@click.option("--steps", default=10, show_default=True, type=click.IntRange(0))
@click.option("--seed", default=0, show_default=True, type=int, help="Seed of the robots' random choices.")
@click.option("--robots", default=1, show_default=True, type=click.IntRange(1), help="Number of robots.")
@click.option(
    "--time-scale",
    default=0.0,
    show_default=True,
    type=click.FloatRange(0),
    help="Real seconds per simulated second (0: run as fast as possible).",
)
@click.option(
    "--picture",
    default="out/map.png",
    show_default=True,
    type=click.Path(dir_okay=False),
    help="Where to draw the reasoned map (.png, .svg or .pdf).",
)
@click.option("--no-picture", is_flag=True, help="Do not draw the map.")
@click.option("--every-step", is_flag=True, help="Draw the map after every step (map-001.png, ...).")
@store_option
def demo(
    map_files: tuple[str, ...],
    steps: int,
    seed: int,
    robots: int,
    time_scale: float,
    picture: str,
    no_picture: bool,
    every_step: bool,
    store: str | None,
) -> None:
    """The surveillance demo: robots patrol the map, visiting URGENT locations.

    \b
    Examples:
      topostore demo
      topostore demo --steps 30 --robots 2 --seed 7 --picture out/map.svg
      topostore demo --map ontology/topological_map.ttl --map ontology/topological_map_abox.ttl --every-step
      topostore demo --robots 3 --store http://127.0.0.1:7878   # a fleet: one client per robot, one shared map
    """
    from ..demo import run_demo
    from ..demo.mapview import VizMissing, require_matplotlib

    if not no_picture:
        try:
            require_matplotlib()
        except VizMissing as exc:
            click.echo(f"note: no picture: {exc}", err=True)
            no_picture = True
    run_demo(
        list(map_files) or None,
        steps=steps,
        seed=seed,
        robots=robots,
        time_scale=time_scale,
        picture=None if no_picture else picture,
        every_step=every_step,
        emit=click.echo,
        store=store,
    )


# --------------------------------------------------------------------------- map


@click.command("map")
@click.argument("files", nargs=-1, required=True, metavar="FILE...")
@click.option(
    "-o", "--output", required=True, type=click.Path(dir_okay=False), help="Picture file: .png, .svg or .pdf."
)
@click.option("--title", default="", help="Title above the map.")
@click.option("--robots/--no-robots", default=True, show_default=True, help="Mark where each robot isIn.")
@click.option("--urgent/--no-urgent", default=True, show_default=True, help="Ring URGENT locations in red.")
@click.option(
    "--cluster-above",
    default=400,
    show_default=True,
    type=click.IntRange(1),
    metavar="N",
    help="Draw corridors with their rooms as clusters when the map has more than N locations.",
)
def map_command(
    files: tuple[str, ...], output: str, title: str, robots: bool, urgent: bool, cluster_above: int
) -> None:
    """Draw the reasoned map of FILE(s): rooms, corridors, doors, connections, robots, URGENT.

    Corridors form the spine, rooms sit around their corridor; big maps are
    drawn as clusters of corridors with their rooms.  Needs the [viz] extra.

    \b
    Examples:
      topostore map ontology/topological_map.ttl ontology/topological_map_abox.ttl -o out/map.svg
      topostore map ontology/topological_map.ttl ontology/topological_map_abox.ttl -o out/plain.png --no-robots --no-urgent
    """  # noqa: E501 (an example run as written)
    from ..demo.mapview import Style, draw_ontology, require_matplotlib

    require_matplotlib()
    _existing(files)
    onto = load_files(files)
    report = reason_with_progress(onto)
    if not report.consistent:
        raise click.ClickException(f"the ontology is inconsistent, nothing reliable to draw: {report.explain()}")
    path = draw_ontology(onto, output, title, Style(robots=robots, urgent=urgent, cluster_above=cluster_above))
    click.echo(f"Wrote {path}")


__all__ = ["demo", "map_command"]
