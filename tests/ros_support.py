"""A real ROS 1 world for the ROS tests: roscore on a free loopback port and `topostore ros`.

Every process is started in its own session and stopped by its process id
(SIGINT, then SIGKILL after a bounded wait), so no test leaves a master behind.
"""

from __future__ import annotations

import os
import shutil
import signal
import socket
import subprocess
import sys
import time
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field
from pathlib import Path

import pytest
from support import IRI, TBOX_OWL

from topostore.ros import install_hint, ros_available

ROOT = Path(__file__).resolve().parents[1]
TOPOSTORE = str(Path(sys.executable).with_name("topostore"))
STARTUP_SECONDS = 30.0


def skip_without_ros() -> None:
    """Skip (saying what to install) unless rospy, genpy and the ROS command-line tools are present."""
    missing = [tool for tool in ("roscore", "rosservice", "rosmsg") if shutil.which(tool) is None]
    if not ros_available() or missing:
        pytest.skip(f"ROS 1 not available: {install_hint()}")


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def stop(proc: subprocess.Popen, timeout: float = 10.0) -> int:
    """Interrupt a process group we started (Ctrl-C), kill it if it does not end in time."""
    if proc.poll() is None:
        try:
            os.killpg(proc.pid, signal.SIGINT)
            return proc.wait(timeout)
        except subprocess.TimeoutExpired:
            os.killpg(proc.pid, signal.SIGKILL)
        except ProcessLookupError:
            pass
    return proc.wait(timeout)


@dataclass
class RosWorld:
    """A running master; ``env`` is what every ROS process of the test gets."""

    port: int
    env: dict[str, str]
    home: Path
    master: subprocess.Popen
    nodes: list[subprocess.Popen] = field(default_factory=list)
    data_dir: Path | None = None

    @property
    def uri(self) -> str:
        return f"http://127.0.0.1:{self.port}"

    def run(self, *cmd: str, timeout: float = 60.0, check: bool = False) -> subprocess.CompletedProcess:
        return subprocess.run(list(cmd), env=self.env, capture_output=True, text=True, timeout=timeout,
                              check=check)

    def start_node(self, data_dir: Path, *args: str, log: Path | None = None) -> subprocess.Popen:
        """`topostore ros` in the background; returns once its services are registered."""
        log = log or self.home / f"node-{len(self.nodes)}.log"
        with log.open("w") as out:
            proc = subprocess.Popen([TOPOSTORE, "ros", "--data-dir", str(data_dir), "--master-timeout", "10", *args],
                                    env=self.env, stdout=out, stderr=subprocess.STDOUT, start_new_session=True)
        self.nodes.append(proc)
        self.wait_for(log, proc)
        return proc

    def wait_for(self, log: Path, proc: subprocess.Popen) -> None:
        deadline = time.monotonic() + STARTUP_SECONDS
        while "/armor_interface_srv and " not in log.read_text():
            if proc.poll() is not None or time.monotonic() > deadline:
                stop(proc)
                raise AssertionError(f"topostore ros did not start (exit {proc.poll()}):\n{log.read_text()}")
            time.sleep(0.1)

    def service_provider(self, service: str) -> str | None:
        """The node the master lists for ``service`` (None when it is not registered)."""
        import xmlrpc.client

        code, _msg, state = xmlrpc.client.ServerProxy(self.uri).getSystemState("/test")
        assert code == 1
        return next((nodes[0] for name, nodes in state[2] if name == service), None)


def start_world(tmp: Path, attempts: int = 3) -> RosWorld:
    """roscore on a free port with ROS_HOME, logs and the armor_msgs cache inside ``tmp``.

    A port that ``free_port`` found free can be taken (by a node of an earlier test) before roscore
    binds it; then roscore exits or a stranger answers the probe, and another port is tried.
    """
    home = tmp / "ros_home"
    home.mkdir()
    for _ in range(attempts):
        world = _launch_master(tmp, home, free_port())
        if _wait_for_master(world):
            return world
        stop(world.master)
    raise AssertionError(f"roscore did not start on any of {attempts} free ports")


def _launch_master(tmp: Path, home: Path, port: int) -> RosWorld:
    env = dict(os.environ)
    env.update(ROS_MASTER_URI=f"http://127.0.0.1:{port}", ROS_HOSTNAME="127.0.0.1", ROS_HOME=str(home),
               ROS_LOG_DIR=str(home / "log"), TOPOSTORE_ROS_DIR=str(tmp / "ros_cache"), PYTHONUNBUFFERED="1")
    env.pop("ROS_IP", None)
    exports = subprocess.run([TOPOSTORE, "ros", "--env"], env=env, capture_output=True, text=True, timeout=60,
                             check=True).stdout
    env.update(_evaluate_exports(exports, env))
    master = subprocess.Popen(["roscore", "-p", str(port)], env=env, stdout=subprocess.DEVNULL,
                              stderr=subprocess.DEVNULL, start_new_session=True)
    return RosWorld(port, env, home, master)


def kill_strays(marker: Path) -> list[int]:
    """SIGKILL processes whose command line names ``marker`` (a test's scratch folder).

    roscore's rosmaster and rosout outlive a shell that started roscore in the
    background and exited; their ``__log:=`` argument names the test's ROS_HOME.
    """
    killed = []
    for entry in Path("/proc").iterdir():
        if not entry.name.isdigit() or int(entry.name) == os.getpid():
            continue
        try:
            cmdline = (entry / "cmdline").read_bytes().replace(b"\0", b" ").decode(errors="replace")
        except OSError:
            continue
        if str(marker) in cmdline:
            try:
                os.kill(int(entry.name), signal.SIGKILL)
                killed.append(int(entry.name))
            except ProcessLookupError:
                pass
    return killed


def stop_world(world: RosWorld) -> None:
    for node in world.nodes:
        stop(node)
    stop(world.master, timeout=20.0)


def _evaluate_exports(lines: str, env: dict[str, str]) -> dict[str, str]:
    """Run the `--env` lines in a real shell, as a user's `eval "$(topostore ros --env)"` does."""
    script = f'{lines}\nprintf "%s\\0%s" "$PYTHONPATH" "$ROS_PACKAGE_PATH"'
    out = subprocess.run(["bash", "-c", script], env=env, capture_output=True, text=True, timeout=10,
                         check=True).stdout
    python_path, package_path = out.split("\0")
    return {"PYTHONPATH": python_path, "ROS_PACKAGE_PATH": package_path}


def _wait_for_master(world: RosWorld) -> bool:
    """True once our roscore answers; False when it died or another server holds its port."""
    import xmlrpc.client

    deadline = time.monotonic() + STARTUP_SECONDS
    while True:
        try:
            xmlrpc.client.ServerProxy(world.uri).getPid("/test")
            return world.master.poll() is None
        except xmlrpc.client.Fault:
            return False
        except OSError:
            if world.master.poll() is not None:
                return False
            if time.monotonic() > deadline:
                stop(world.master)
                raise AssertionError(f"roscore did not start on port {world.port}") from None
            time.sleep(0.2)


# --------------------------------------------------------------------------- the tutorial



def iri(name: str) -> str:
    return f"<{IRI}#{name}>"


def request(command: str, spec1: str = "", spec2: str = "", *args: str, client: str = "example",
            ref: str = "ontoRef") -> dict:
    """An ArmorDirectiveReq as a dict (the fields of the tutorial's YAML)."""
    return {"client_name": client, "reference_name": ref, "command": command, "primary_command_spec": spec1,
            "secondary_command_spec": spec2, "args": list(args)}


def reply(*objects: str, success: bool = True, code: int = 0, consistent: bool = True, error: str = "") -> dict:
    """An ArmorDirectiveRes as a dict, every field given."""
    return {"success": success, "timeout": False, "exit_code": code, "error_description": error,
            "is_consistent": consistent, "queried_objects": list(objects), "sparql_queried_objects": []}


def tutorial(ref: str = "ontoRef", client: str = "example") -> list[tuple[dict, dict]]:
    """The topological_map tutorial's calls on topological_map.owl and the exact answers.

    Corridor E has doors D6 and D7 to rooms R3 and R4; Robot1 starts in E at
    1665579740, then moves to R3 ten seconds later and visits it.
    """
    def r(*a: str) -> dict:
        return request(*a, client=client, ref=ref)

    return [
        (r("LOAD", "FILE", "", "topological_map.owl", IRI, "true", "PELLET", "false"), reply()),
        (r("ADD", "OBJECTPROP", "IND", "hasDoor", "E", "D6"), reply()),
        (r("ADD", "OBJECTPROP", "IND", "hasDoor", "E", "D7"), reply()),
        (r("ADD", "OBJECTPROP", "IND", "hasDoor", "R3", "D6"), reply()),
        (r("ADD", "OBJECTPROP", "IND", "hasDoor", "R4", "D7"), reply()),
        (r("ADD", "DATAPROP", "IND", "visitedAt", "R3", "LONG", "1665579700"), reply()),
        (r("ADD", "DATAPROP", "IND", "visitedAt", "R4", "LONG", "1665579735"), reply()),
        (r("DISJOINT", "IND", "", "E", "R3", "R4", "D6", "D7"), reply()),
        (r("ADD", "OBJECTPROP", "IND", "isIn", "Robot1", "E"), reply()),
        (r("REASON"), reply()),
        (r("QUERY", "DATAPROP", "IND", "now", "Robot1"), reply('"1665579740"^^xsd:long')),
        (r("QUERY", "OBJECTPROP", "IND", "canReach", "Robot1"), reply(iri("R3"), iri("R4"))),
        (r("QUERY", "IND", "CLASS", "URGENT"), reply(iri("R3"))),
        (r("REPLACE", "DATAPROP", "IND", "now", "Robot1", "LONG", "1665579750", "1665579740"), reply()),
        (r("REPLACE", "DATAPROP", "IND", "visitedAt", "R3", "LONG", "1665579750", "1665579700"), reply()),
        (r("REPLACE", "OBJECTPROP", "IND", "isIn", "Robot1", "R3", "E"), reply()),
        (r("REASON"), reply()),
        (r("QUERY", "OBJECTPROP", "IND", "canReach", "Robot1"), reply(iri("E"))),
        (r("QUERY", "IND", "CLASS", "URGENT"), reply(iri("R4"))),
        (r("QUERY", "CLASS", "IND", "E", "true"), reply("CORRIDOR")),
        (r("QUERY", "CLASS", "IND", "R3", "true"), reply("ROOM")),
        (r("SAVE", "", "", f"{ref}.owl"), reply()),
    ]


def tutorial_yaml(req: dict) -> str:
    """The request as the tutorial types it after `rosservice call /armor_interface_srv`."""
    def quoted(text: str) -> str:
        return "'" + text.replace("'", "''") + "'"

    args = ", ".join(quoted(a) for a in req["args"])
    return ("armor_request:\n"
            f"  client_name: {quoted(req['client_name'])}\n"
            f"  reference_name: {quoted(req['reference_name'])}\n"
            f"  command: {quoted(req['command'])}\n"
            f"  primary_command_spec: {quoted(req['primary_command_spec'])}\n"
            f"  secondary_command_spec: {quoted(req['secondary_command_spec'])}\n"
            f"  args: [{args}]")


def prepare_data(data_dir: Path) -> Path:
    """A data directory holding the tutorial's ontology file."""
    data_dir.mkdir(parents=True, exist_ok=True)
    shutil.copyfile(TBOX_OWL, data_dir / "topological_map.owl")
    return data_dir


@contextmanager
def node_world(tmp: Path, *files: Path) -> Iterator[RosWorld]:
    """roscore and one `topostore ros` on the tutorial's data directory (plus ``files``), stopped afterwards."""
    world = start_world(tmp)
    try:
        world.data_dir = prepare_data(tmp / "data")
        for f in files:
            shutil.copyfile(f, world.data_dir / f.name)
        world.start_node(world.data_dir)
        yield world
    finally:
        stop_world(world)
