"""aRMOR over ROS 1: a real roscore, `topostore ros`, the rosservice command line and rospy clients."""

from __future__ import annotations

import json
import os
import re
import signal
import socket
import struct
import subprocess
import sys
from collections.abc import Iterator
from pathlib import Path

import pytest
from ros_support import (
    ROOT,
    TOPOSTORE,
    RosWorld,
    free_port,
    kill_strays,
    node_world,
    prepare_data,
    reply,
    request,
    skip_without_ros,
    start_world,
    stop,
    stop_world,
    tutorial,
    tutorial_yaml,
)

CLIENT = str(Path(__file__).with_name("ros_client.py"))
SINGLE = "/armor_interface_srv"
SERIALIZED = "/armor_interface_serialized_srv"


@pytest.fixture(scope="module")
def world(tmp_path_factory: pytest.TempPathFactory) -> Iterator[RosWorld]:
    skip_without_ros()
    with node_world(tmp_path_factory.mktemp("ros")) as w:
        yield w


def yaml_reply(text: str) -> dict:
    yaml = pytest.importorskip("yaml")
    return yaml.safe_load(text)


def rosservice(world: RosWorld, yaml_text: str, service: str = SINGLE) -> subprocess.CompletedProcess:
    return world.run("rosservice", "call", service, yaml_text, timeout=60)


def rospy_client(world: RosWorld, mode: str, requests: list[dict]) -> subprocess.Popen:
    return subprocess.Popen([sys.executable, CLIENT, mode, json.dumps(requests)], env=world.env,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, start_new_session=True)


def client_result(proc: subprocess.Popen) -> dict:
    try:
        out, err = proc.communicate(timeout=120)
    except subprocess.TimeoutExpired:
        stop(proc)
        raise
    assert proc.returncode == 0, err
    return json.loads(out.strip().splitlines()[-1])


# ------------------------------------------------------------------ the tutorial, three ways

def test_tutorial_through_rosservice_command_line(world: RosWorld) -> None:
    for req, expected in tutorial():
        done = rosservice(world, tutorial_yaml(req))
        assert done.returncode == 0, (req, done.stderr)
        assert yaml_reply(done.stdout) == {"armor_response": expected}, req
    assert world.data_dir is not None and (world.data_dir / "ontoRef.owl").stat().st_size > 20_000


def test_tutorial_from_rospy_single_and_serialized(world: RosWorld) -> None:
    steps = tutorial(ref="pyRef")
    single = client_result(rospy_client(world, "single", [r for r, _ in steps]))
    assert single["result"] == [e for _, e in steps]
    steps = tutorial(ref="batchRef")
    batch = client_result(rospy_client(world, "serialized", [r for r, _ in steps]))
    assert batch["result"] == {"success": True, "is_consistent": True, "armor_responses": [e for _, e in steps]}


def test_two_client_nodes_at_once(world: RosWorld) -> None:
    a, b = tutorial(ref="robotA", client="a"), tutorial(ref="robotB", client="b")
    procs = [rospy_client(world, "single", [r for r, _ in a]), rospy_client(world, "serialized", [r for r, _ in b])]
    first, second = (client_result(p) for p in procs)
    assert first["node"] != second["node"]
    assert first["result"] == [e for _, e in a]
    assert second["result"]["armor_responses"] == [e for _, e in b]


def test_mount_exclusivity_across_nodes(world: RosWorld) -> None:
    load = request("LOAD", "FILE", "", "topological_map.owl", "http://bnc/exp-rob-lab/2022-23", "false", "PELLET",
                   "false", client="owner", ref="mounted")
    mount = request("MOUNT", client="owner", ref="mounted")
    owner = client_result(rospy_client(world, "single", [load, mount]))
    assert owner["result"] == [reply(), reply()]

    change = request("ADD", "IND", "CLASS", "R9", "LOCATION", client="intruder", ref="mounted")
    look = request("QUERY", "IND", "CLASS", "ROBOT", client="intruder", ref="mounted")
    intruder = client_result(rospy_client(world, "single", [change, look]))
    refused = reply(success=False, code=102, error="reference 'mounted' is mounted by client 'owner'; client "
                                                   "'intruder' may query it but not change it")
    assert intruder["result"] == [refused, reply("<http://bnc/exp-rob-lab/2022-23#Robot1>")]

    unmount = request("UNMOUNT", client="owner", ref="mounted")
    assert client_result(rospy_client(world, "single", [unmount]))["result"] == [reply()]
    assert client_result(rospy_client(world, "single", [change]))["result"] == [reply()]


# ------------------------------------------------------------------ bad requests

def test_missing_fields_get_a_failure_reply(world: RosWorld) -> None:
    done = rosservice(world, "armor_request: {command: 'GET', primary_command_spec: 'ALL'}")
    assert done.returncode == 0, done.stderr
    assert yaml_reply(done.stdout) == {"armor_response": reply(success=False, code=201, consistent=False,
                                                               error="reference_name is empty; every command needs one")}


def test_wrong_type_is_refused_and_node_keeps_serving(world: RosWorld) -> None:
    done = rosservice(world, "armor_request: {reference_name: 'x', command: 'GET', args: 5}")
    assert done.returncode != 0
    assert "args" in done.stderr or "Incompatible" in done.stderr, done.stderr
    assert_serving(world)


def test_garbage_on_the_wire_gets_no_reply(world: RosWorld) -> None:
    """An undecodable request (a string claiming 2 GiB) gets no reply; the node keeps serving.

    rospy refuses it before any handler runs: it logs the error and abandons the
    connection (closed, or left idle until garbage collection closes it), so a
    rospy caller gets a ServiceException or its own time-out.  Everyone else is
    served as before.
    """
    host, port = service_address(world, SINGLE)
    with socket.create_connection((host, port), timeout=10) as conn:
        send_header(conn, {"callerid": "/garbage", "service": SINGLE, "md5sum": "39cbf11e18dc47e2c7b5fda84e5d8c39"})
        header = read_header(conn)
        assert header["md5sum"] == "39cbf11e18dc47e2c7b5fda84e5d8c39"
        body = struct.pack("<I", 0x7FFFFFF0) + b"abcd"
        conn.sendall(struct.pack("<I", len(body)) + body)
        conn.settimeout(3)
        try:
            answer = conn.recv(1)
        except TimeoutError:
            answer = b""
        assert answer == b""
    assert_serving(world)


def test_wrong_md5_is_refused(world: RosWorld) -> None:
    host, port = service_address(world, SINGLE)
    with socket.create_connection((host, port), timeout=10) as conn:
        send_header(conn, {"callerid": "/old_client", "service": SINGLE, "md5sum": "0" * 32})
        assert "md5sums do not match" in read_header(conn)["error"]
    assert_serving(world)


def assert_serving(world: RosWorld) -> None:
    done = rosservice(world, tutorial_yaml(request("GET", "ALL", "REFS", ref="any")))
    assert done.returncode == 0, done.stderr
    assert yaml_reply(done.stdout)["armor_response"]["success"] is True


def service_address(world: RosWorld, service: str) -> tuple[str, int]:
    import xmlrpc.client

    code, _msg, uri = xmlrpc.client.ServerProxy(world.uri).lookupService("/test", service)
    assert code == 1
    host, port = uri.removeprefix("rosrpc://").rstrip("/").split(":")
    return host, int(port)


def send_header(conn: socket.socket, fields: dict[str, str]) -> None:
    data = b"".join(struct.pack("<I", len(f)) + f for f in (f"{k}={v}".encode() for k, v in fields.items()))
    conn.sendall(struct.pack("<I", len(data)) + data)


def read_header(conn: socket.socket) -> dict[str, str]:
    size = struct.unpack("<I", read_exactly(conn, 4))[0]
    data, fields = read_exactly(conn, size), {}
    while data:
        n = struct.unpack("<I", data[:4])[0]
        key, _, value = data[4:4 + n].decode().partition("=")
        fields[key], data = value, data[4 + n:]
    return fields


def read_exactly(conn: socket.socket, n: int) -> bytes:
    out = b""
    while len(out) < n:
        chunk = conn.recv(n - len(out))
        assert chunk, "connection closed"
        out += chunk
    return out


# ------------------------------------------------------------------ messages and environment

# The full definitions aRMOR's generated clients carry (genlisp's message-definition strings).
_DIRECTIVE_REQUEST_TEXT = (
    "ArmorDirectiveReq armor_request\n\n" + "=" * 80 + "\nMSG: armor_msgs/ArmorDirectiveReq\nstring client_name\n"
    "string reference_name\nstring command\nstring primary_command_spec\nstring secondary_command_spec\n"
    "string[] args\n")
_RES_TEXT = ("MSG: armor_msgs/ArmorDirectiveRes\nbool success\nbool timeout\nint32 exit_code\nstring error_description\n"
             "bool is_consistent\nstring[] queried_objects\nQueryItem[] sparql_queried_objects\n" + "=" * 80
             + "\nMSG: armor_msgs/QueryItem\nstring key\nstring value\n")
_DIRECTIVE_RESPONSE_TEXT = "ArmorDirectiveRes armor_response\n\n\n" + "=" * 80 + "\n" + _RES_TEXT
_LIST_RESPONSE_TEXT = "bool success\nbool is_consistent\nArmorDirectiveRes[] armor_responses\n\n" + "=" * 80 + "\n" + _RES_TEXT


def test_generated_messages_match_armor_msgs(tmp_path: Path) -> None:
    skip_without_ros()
    from topostore.ros import msgs, workspace

    work = workspace.ensure(tmp_path)
    assert workspace.ensure(tmp_path) == work  # generated once, then reused
    assert sorted(p.name for p in tmp_path.iterdir()) == [work.root.name]
    work.activate()
    from armor_msgs.msg import ArmorDirectiveReq, ArmorDirectiveRes, QueryItem
    from armor_msgs.srv import (
        ArmorDirective,
        ArmorDirectiveList,
        ArmorDirectiveListRequest,
        ArmorDirectiveListResponse,
        ArmorDirectiveRequest,
        ArmorDirectiveResponse,
    )

    assert Path(sys.modules["armor_msgs"].__file__).is_relative_to(work.python_dir)
    assert ArmorDirective._md5sum == "39cbf11e18dc47e2c7b5fda84e5d8c39"
    assert ArmorDirectiveList._md5sum == "c8f7a3567fd279dae5ca45853049f5a7"
    assert ArmorDirectiveReq._md5sum == "385184fa98c36b7f00729ae2078dfc92"
    assert ArmorDirectiveRes._md5sum == "6846cf2c4447d7c66f608d63e1f65e77"
    assert {k: v for k, v in msgs.EXPECTED_MD5.items()} == {
        "ArmorDirectiveReq": ArmorDirectiveReq._md5sum, "ArmorDirectiveRes": ArmorDirectiveRes._md5sum,
        "ArmorDirective": ArmorDirective._md5sum, "ArmorDirectiveList": ArmorDirectiveList._md5sum}
    assert ArmorDirectiveRequest._full_text == _DIRECTIVE_REQUEST_TEXT
    assert ArmorDirectiveResponse._full_text == _DIRECTIVE_RESPONSE_TEXT
    assert ArmorDirectiveListResponse._full_text == _LIST_RESPONSE_TEXT
    assert ArmorDirectiveListRequest._full_text == _DIRECTIVE_REQUEST_TEXT.replace(
        "ArmorDirectiveReq armor_request", "ArmorDirectiveReq[] armor_requests")
    assert QueryItem._full_text == "string key\nstring value\n"
    # The ROS service type names every tool shows.
    assert (ArmorDirective._type, ArmorDirectiveList._type) == ("armor_msgs/ArmorDirective", "armor_msgs/ArmorDirectiveList")


def test_env_lines_let_ros_tools_find_armor_msgs(world: RosWorld) -> None:
    shown = world.run("rosmsg", "show", "armor_msgs/ArmorDirectiveReq", check=True).stdout
    assert shown.split("\n") == ["string client_name", "string reference_name", "string command",
                                 "string primary_command_spec", "string secondary_command_spec", "string[] args",
                                 "", ""]
    assert world.run("rossrv", "md5", "armor_msgs/ArmorDirective", check=True).stdout.strip() == \
        "39cbf11e18dc47e2c7b5fda84e5d8c39"
    info = world.run("rosservice", "info", SINGLE, check=True).stdout
    assert "Node: /armor_service\n" in info and "Type: armor_msgs/ArmorDirective\n" in info
    assert world.run("rosservice", "type", SERIALIZED, check=True).stdout.strip() == "armor_msgs/ArmorDirectiveList"


# ------------------------------------------------------------------ start and stop

def test_no_master_is_a_one_line_error_with_exit_4(tmp_path: Path) -> None:
    skip_without_ros()
    env = dict(os.environ, ROS_MASTER_URI=f"http://127.0.0.1:{free_port()}", TOPOSTORE_ROS_DIR=str(tmp_path / "c"))
    done = subprocess.run([TOPOSTORE, "ros", "--data-dir", str(tmp_path / "d"), "--master-timeout", "1"], env=env,
                          capture_output=True, text=True, timeout=60)
    assert done.returncode == 4
    assert done.stdout == ""
    assert done.stderr.count("\n") == 1 and done.stderr.startswith("Error: no ROS master reachable at http://127.0.0.1:")


def test_without_ros_exit_5_says_what_to_install(tmp_path: Path) -> None:
    """A Python where rospy cannot be imported (here: shadowed by a module that refuses to load)."""
    (tmp_path / "rospy.py").write_text("raise ImportError('rospy hidden by the test')\n")
    env = dict(os.environ, PYTHONPATH=str(tmp_path), TOPOSTORE_ROS_DIR=str(tmp_path / "c"))
    done = subprocess.run([TOPOSTORE, "ros", "--env"], env=env, capture_output=True, text=True, timeout=60)
    assert done.returncode == 5
    assert done.stdout == ""
    assert done.stderr.count("\n") == 1
    assert "python3-rospy python3-rosservice python3-genpy python3-genmsg ros-core" in done.stderr


@pytest.mark.parametrize("environ,args,expected", [
    ({}, (), "127.0.0.1"),                                   # local master, nothing chosen: loopback
    ({"ROS_IP": "10.0.0.5"}, (), None),                       # the user's choice stands
    ({"ROS_HOSTNAME": "robot.local"}, (), "robot.local"),
    ({}, ("__ip:=10.0.0.5",), None),
])
def test_loopback_by_default(monkeypatch: pytest.MonkeyPatch, environ: dict, args: tuple, expected: str | None) -> None:
    from topostore.cli.ros import _loopback_by_default

    for name in ("ROS_IP", "ROS_HOSTNAME"):
        monkeypatch.delenv(name, raising=False)
    for name, value in environ.items():
        monkeypatch.setenv(name, value)
    _loopback_by_default("http://localhost:11311", args)
    assert os.environ.get("ROS_HOSTNAME") == expected
    monkeypatch.delenv("ROS_HOSTNAME", raising=False)
    _loopback_by_default("http://master.lan:11311", ())  # a remote master: rospy's own choice
    assert "ROS_HOSTNAME" not in os.environ


def test_stray_argument_is_a_usage_error() -> None:
    done = subprocess.run([TOPOSTORE, "ros", "surprise"], capture_output=True, text=True, timeout=60)
    assert done.returncode == 2
    assert "unexpected argument 'surprise' (ROS remappings look like NAME:=VALUE)" in done.stderr


@pytest.mark.parametrize("sig", [signal.SIGTERM, signal.SIGINT])
def test_signal_stops_the_node_cleanly(world: RosWorld, tmp_path: Path, sig: signal.Signals) -> None:
    """A second node in its own namespace (relative service names, like aRMOR's) stops on SIGTERM/Ctrl-C."""
    ns = f"/stop_{sig.name.lower()}"
    node = world.start_node(prepare_data(tmp_path / "data"), "--name", "armor_other", f"__ns:={ns}")
    assert world.service_provider(f"{ns}/armor_interface_srv") == f"{ns}/armor_other"
    assert world.service_provider(SINGLE) == "/armor_service"  # the first node is untouched
    os.kill(node.pid, sig)
    assert node.wait(20) == 0
    assert world.service_provider(f"{ns}/armor_interface_srv") is None
    assert world.service_provider(f"{ns}/armor_interface_serialized_srv") is None


# ------------------------------------------------------------------ roslaunch

TUTORIAL_LAUNCH = """<launch>
  <node pkg="armor" type="execute" name="armor_service" args="it.emarolab.armor.ARMORMainService"/>
</launch>
"""


@pytest.mark.parametrize("launch", ["tutorial line", "shipped file"])
def test_roslaunch_starts_topostore(tmp_path: Path, launch: str) -> None:
    """aRMOR's launch line (pkg armor, type execute) and `roslaunch armor armor_service.launch` start the node."""
    skip_without_ros()
    world = start_world(tmp_path)
    try:
        data = prepare_data(tmp_path / "data")
        if launch == "tutorial line":
            (tmp_path / "armor.launch").write_text(TUTORIAL_LAUNCH)
            cmd = ["roslaunch", str(tmp_path / "armor.launch")]
        else:
            cmd = ["roslaunch", "armor", "armor_service.launch"]
        env = dict(world.env, TOPOSTORE_DATA_DIR=str(data))
        with (tmp_path / "launch.log").open("w") as log:
            proc = subprocess.Popen(cmd, env=env, stdout=log, stderr=subprocess.STDOUT, start_new_session=True)
        world.nodes.append(proc)
        wait_until(lambda: world.service_provider(SINGLE) == "/armor_service" or proc.poll() is not None)
        assert world.service_provider(SINGLE) == "/armor_service", (tmp_path / "launch.log").read_text()
        load, expected = tutorial()[0]
        done = rosservice(world, tutorial_yaml(load))
        assert yaml_reply(done.stdout) == {"armor_response": expected}, done.stderr
        assert stop(proc, 30) == 0
        assert world.service_provider(SINGLE) is None
    finally:
        stop_world(world)


def wait_until(condition, seconds: float = 30.0) -> None:
    import time

    deadline = time.monotonic() + seconds
    while not condition() and time.monotonic() < deadline:
        time.sleep(0.2)


# ------------------------------------------------------------------ the ROS page's shell session

def readme_ros_block() -> str:
    """The one shell block of docs/ros.md."""
    (block,) = re.findall(r"```sh\n(.*?)```", (ROOT / "docs" / "ros.md").read_text(), re.S)
    return block


def test_readme_ros_section_runs_as_written(tmp_path: Path) -> None:
    """docs/ros.md's shell block, in a scratch copy of the repository layout, on a free port instead of 11311."""
    skip_without_ros()
    port = free_port()
    (tmp_path / ".venv").symlink_to(Path(sys.executable).parents[1])  # the project's venv, pyvenv.cfg and all
    (tmp_path / "ontology").symlink_to(ROOT / "ontology")
    env = dict(os.environ, ROS_MASTER_URI=f"http://127.0.0.1:{port}", ROS_HOSTNAME="127.0.0.1",
               ROS_HOME=str(tmp_path / "ros_home"), TOPOSTORE_ROS_DIR=str(tmp_path / "cache"))
    script = "set -e\n" + readme_ros_block().replace("11311", str(port))
    with (tmp_path / "out.txt").open("w") as out_file, (tmp_path / "err.txt").open("w") as err_file:
        proc = subprocess.Popen(["bash", "-c", script], cwd=tmp_path, env=env, stdout=out_file, stderr=err_file,
                                start_new_session=True)
    try:
        proc.wait(180)
    finally:
        for sig in (signal.SIGINT, signal.SIGKILL):  # whatever the block left running when it failed
            try:
                os.killpg(proc.pid, sig)
            except ProcessLookupError:
                break
            wait_until(lambda: proc.poll() is not None, 10)
        proc.wait(10)
        kill_strays(tmp_path / "ros_home")
    out, err = (tmp_path / "out.txt").read_text(), (tmp_path / "err.txt").read_text()
    assert proc.returncode == 0, err
    assert "39cbf11e18dc47e2c7b5fda84e5d8c39" in out
    r1, r2, c1 = (f"<http://bnc/exp-rob-lab/2022-23#{n}>" for n in ("R1", "R2", "C1"))
    assert f"  queried_objects: \n    - {r1}\n    - {r2}\n" in out  # rosservice prints lists as YAML blocks
    assert f"    queried_objects: \n      - {c1}\n" in out
    assert "queried_objects: \n  - CORRIDOR\n" in out
    assert (tmp_path / "data" / "map.ttl").exists()


def test_armor_api_client_over_ros(world: RosWorld) -> None:
    """topostore's armor_py_api client with RosTransport: the tutorial as robot code writes it."""
    result = client_result(rospy_client_raw(world, "armor_api", "apiRef"))["result"]
    assert result == {"reach_from_E": ["R3", "R4"], "now": ['"1665579740"^^xsd:long'], "batch": [True, True, [0, 0]],
                      "reach_from_R3": ["E"], "urgent": ["R3", "R4"], "refused": 208,
                      "unreachable": "/no_such_srv"}


def rospy_client_raw(world: RosWorld, mode: str, argument: str) -> subprocess.Popen:
    return subprocess.Popen([sys.executable, CLIENT, mode, argument], env=world.env, stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True, start_new_session=True)


# ------------------------------------------------------------------ a durable store behind the node

def test_references_survive_a_node_restart_with_store(tmp_path: Path) -> None:
    """`topostore ros --store DIR`: a reference loaded and changed through ROS is there after a restart."""
    skip_without_ros()
    world = start_world(tmp_path)
    try:
        data, store = prepare_data(tmp_path / "data"), tmp_path / "store"
        node = world.start_node(data, "--store", str(store))
        load = request("LOAD", "FILE", "", "topological_map.owl", "http://bnc/exp-rob-lab/2022-23", "false",
                       "PELLET", "false", ref="kept")
        add = request("ADD", "IND", "CLASS", "R9", "LOCATION", ref="kept")
        reason = request("REASON", ref="kept")
        assert client_result(rospy_client(world, "single", [load, add, reason]))["result"] == [reply()] * 3
        assert stop(node, 30) == 0
        world.start_node(data, "--store", str(store))
        look = request("QUERY", "IND", "CLASS", "LOCATION", ref="kept")
        answer = client_result(rospy_client(world, "single", [look]))["result"]
        assert answer == [reply("<http://bnc/exp-rob-lab/2022-23#R9>")]
    finally:
        stop_world(world)
