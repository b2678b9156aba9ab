"""``topostore ros``: the command that starts the node (or prints the ROS environment).

Imports nothing from ROS until it runs, so ``topostore --help`` works without ROS.
"""

from __future__ import annotations

import os
import urllib.parse
from collections.abc import Sequence
from pathlib import Path
from typing import NoReturn

import click

from .. import __version__
from ..ontology.events import DEFAULT_QUEUE
from ..ros import DEFAULT_NODE_NAME, EXIT_NO_MASTER, EXIT_NO_ROS, RosUnavailable, require_ros
from .limits import apply_limits, limit_options
from .store_option import store_option


@click.command("ros", context_settings={"ignore_unknown_options": True})
@click.option("--name", default=DEFAULT_NODE_NAME, show_default=True, help="ROS node name.")
@click.option("--data-dir", default="data", show_default=True, envvar="TOPOSTORE_DATA_DIR",
              type=click.Path(file_okay=False),
              help="LOAD and SAVE paths are confined to this folder (created if missing; env TOPOSTORE_DATA_DIR).")
@click.option("--short-names", is_flag=True, help="Answer aRMOR queries with short names instead of <IRI>s.")
@click.option("--env", "print_env", is_flag=True,
              help="Print the export lines that let rosservice, rosmsg and rospy scripts find armor_msgs; start nothing.")
@click.option("--master-timeout", default=3.0, show_default=True, type=click.FloatRange(min=0, min_open=True),
              help="Seconds to wait for the ROS master at start-up (exit 4 after).")
@click.option("--events-queue", default=DEFAULT_QUEUE, show_default=True, type=click.IntRange(min=1),
              help="REASON events held per reference for the ~events topic; when full the oldest are dropped "
                   "and the next message says how many (missed).")
@store_option
@click.option("--sync", is_flag=True, help="With a directory --store: flush every acknowledged change to disk.")
@limit_options
@click.argument("ros_args", nargs=-1, type=click.UNPROCESSED, metavar="[NAME:=VALUE]...")
def ros(name: str, data_dir: str, short_names: bool, print_env: bool, master_timeout: float, events_queue: int,
        store: str | None, sync: bool, ros_args: tuple[str, ...], **limits: float) -> None:
    """Serve aRMOR's ROS services /armor_interface_srv and /armor_interface_serialized_srv.

    Every REASON is also published on ~events (/armor_service/events, std_msgs/String
    holding the JSON event of the HTTP service's /references/{name}/events) while
    the topic has subscribers.

    Needs a running ROS master (ROS_MASTER_URI). Exit codes: 0 after Ctrl-C or
    SIGTERM, 4 when no master is reachable, 5 when ROS is not installed.
    Extra NAME:=VALUE arguments are ROS remappings (e.g. __ns:=/robot1).

    \b
    Example:
      roscore &
      topostore ros --data-dir data &
      eval "$(topostore ros --env)"
      rosservice call /armor_interface_srv "armor_request: {reference_name: ref, command: GET,
        primary_command_spec: ALL, secondary_command_spec: REFS}"
    """
    bad = [a for a in ros_args if ":=" not in a]
    if bad:
        raise click.UsageError(f"unexpected argument {bad[0]!r} (ROS remappings look like NAME:=VALUE)")
    try:
        require_ros()
    except RosUnavailable as exc:
        _fail(str(exc), EXIT_NO_ROS)
    from ..ros import workspace as ws
    from ..ros.node import ArmorNode, NoMaster, check_master, master_uri

    work = ws.ensure()
    if print_env:
        for line in work.export_lines():
            click.echo(line)
        return
    uri = master_uri(ros_args)
    _loopback_by_default(uri, ros_args)
    try:
        check_master(uri, master_timeout)
    except NoMaster as exc:
        _fail(str(exc), EXIT_NO_MASTER)
    from ..armor import ArmorService

    apply_limits(**limits)  # the same limits as `topostore serve`, before the service exists
    data = Path(data_dir)
    data.mkdir(parents=True, exist_ok=True)
    service = ArmorService(data_dir=data, short_names=short_names, store=store, sync=sync)
    node = ArmorNode(service, work, name, ros_args, events_queue)
    node.start()
    single, serialized = node.service_names
    click.echo(f"topostore {__version__}: ROS node {node.resolved_name} (master {uri}) serving {single} "
               f"and {serialized}, events on {node.events.resolved_name} (data directory {data.resolve()})", err=True)
    node.spin()


def _fail(message: str, code: int) -> NoReturn:
    click.echo(f"Error: {' '.join(message.split())}", err=True)
    raise click.exceptions.Exit(code)


def _loopback_by_default(uri: str, ros_args: Sequence[str]) -> None:
    """Bind the node to loopback when the master is local and no address was chosen.

    rospy listens on every interface unless ROS_IP/ROS_HOSTNAME name a loopback
    address, and ROS has no authentication: with a local master and nothing
    configured, listening on 127.0.0.1 loses nothing and exposes nothing.
    """
    chosen = os.environ.get("ROS_IP") or os.environ.get("ROS_HOSTNAME") or any(
        a.startswith(("__ip:=", "__hostname:=")) for a in ros_args)
    host = urllib.parse.urlparse(uri).hostname or ""
    if not chosen and (host == "localhost" or host.startswith("127.")):
        os.environ["ROS_HOSTNAME"] = "127.0.0.1"
