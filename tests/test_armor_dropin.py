"""Code written for armor_py_api runs unchanged against the top-level ``armor_api`` package.

The tutorial below is the seed course's client code as students write it:
``from armor_api.armor_client import ArmorClient``, raw ``client.call`` with
rosservice-style arguments (``[""]`` for REASON), and the timestamps sliced out
of aRMOR's literal rendering with ``[1:-11]``.  It runs in-process, and over
HTTP with only environment variables set (TOPOSTORE_URL, TOPOSTORE_TOKEN).
"""

from __future__ import annotations

import http.client
import os
import subprocess
import sys
import textwrap
import threading
import time
from pathlib import Path
from typing import Any

import pytest
from http_support import TBOX, free_port, start_server, stop_server, threaded, with_map
from support import IRI

from topostore.armor import ArmorRequest, ArmorResponse, ArmorService
from topostore.armor_api import transport
from topostore.http.app import ServerConfig

#: The seed tutorial's client code, verbatim in style (only the ontology path is a parameter).
TUTORIAL = textwrap.dedent('''
    from armor_api.armor_client import ArmorClient

    client = ArmorClient("example", "ontoRef")
    client.call("LOAD", "FILE", "", [PATH, "http://bnc/exp-rob-lab/2022-23", "true", "PELLET", "false"])
    client.call("ADD", "OBJECTPROP", "IND", ["hasDoor", "E", "D5"])
    client.call("ADD", "OBJECTPROP", "IND", ["hasDoor", "E", "D6"])
    client.call("ADD", "OBJECTPROP", "IND", ["hasDoor", "R3", "D6"])
    client.call("ADD", "DATAPROP", "IND", ["visitedAt", "E", "Long", "1665579700"])
    client.call("ADD", "DATAPROP", "IND", ["visitedAt", "R3", "Long", "1665579735"])
    client.call("DISJOINT", "IND", "", ["E", "R3", "D5", "D6"])
    client.call("ADD", "OBJECTPROP", "IND", ["isIn", "Robot1", "E"])
    client.call("REASON", "", "", [""])

    res = client.call("QUERY", "DATAPROP", "IND", ["now", "Robot1"])
    now = res.queried_objects[0][1:-11]
    print("now", now)
    res = client.call("QUERY", "OBJECTPROP", "IND", ["canReach", "Robot1"])
    reachable = [x[32:-1] for x in res.queried_objects]
    print("reachable", sorted(reachable))
    urgent = client.query.ind_b2_class("URGENT")
    print("urgent", sorted(urgent))
    visited = client.query.dataprop_b2_ind("visitedAt", "R3")[0][1:-11]
    print("visited R3", visited)

    new_now = str(int(now) + 5)
    client.call("REPLACE", "DATAPROP", "IND", ["now", "Robot1", "Long", new_now, now])
    client.call("REPLACE", "OBJECTPROP", "IND", ["isIn", "Robot1", "R3", "E"])
    client.call("REPLACE", "DATAPROP", "IND", ["visitedAt", "R3", "Long", new_now, visited])
    client.utils.sync_buffered_reasoner()
    print("now", client.query.dataprop_b2_ind("now", "Robot1")[0][1:-11])
    print("reachable", client.query.objectprop_b2_ind("canReach", "Robot1"))
    print("classes", client.call("QUERY", "CLASS", "IND", ["R3", "true"]).queried_objects)
''')

EXPECTED = textwrap.dedent("""\
    now 1665579740
    reachable ['R3']
    urgent ['E']
    visited R3 1665579735
    now 1665579745
    reachable ['E']
    classes ['ROOM']
""")


def test_tutorial_runs_unchanged_in_process(capsys: pytest.CaptureFixture[str]) -> None:
    transport.set_default_service(None)
    try:
        exec(compile(TUTORIAL, "tutorial.py", "exec"), {"PATH": str(TBOX)})  # noqa: S102 - our test script
    finally:
        transport.set_default_service(None)
    assert capsys.readouterr().out == EXPECTED


def test_module_names_are_armor_py_api_s() -> None:
    import armor_api
    import armor_api.armor_client
    import armor_api.armor_exceptions
    import armor_api.armor_manipulation_client
    import armor_api.armor_query_client
    import armor_api.armor_utils_client
    import topostore.armor_api as home

    assert armor_api.armor_client.ArmorClient is home.ArmorClient
    assert armor_api.armor_query_client.ArmorQueryClient is home.armor_query_client.ArmorQueryClient
    assert armor_api.armor_manipulation_client.ArmorManipulationClient is \
        home.armor_manipulation_client.ArmorManipulationClient
    assert armor_api.armor_utils_client.ArmorUtilsClient is home.armor_utils_client.ArmorUtilsClient
    assert armor_api.armor_exceptions.ArmorServiceInternalError is home.ArmorServiceInternalError
    exec("from armor_api import *", {})  # noqa: S102 - __all__ lists real names


def test_tutorial_runs_unchanged_over_http_with_environment_only(tmp_path: Path) -> None:
    """The same script, another process, pointed at a token-protected server by environment variables."""
    server = start_server(tmp_path / "data", token="tutorial-token")
    try:
        script = tmp_path / "tutorial.py"
        script.write_text("PATH = 'topological_map.owl'\n" + TUTORIAL)
        env = {**os.environ, "TOPOSTORE_URL": server.url, "TOPOSTORE_TOKEN": "tutorial-token"}
        done = subprocess.run([sys.executable, str(script)], env=env, capture_output=True, text=True, timeout=120,
                              cwd=tmp_path)
        assert done.returncode == 0, done.stderr
        assert done.stdout == EXPECTED
        status, _, _ = server.request("/references", headers={"Authorization": "Bearer wrong"})
        assert status == 401
    finally:
        stop_server(server)


class SlowLoad(ArmorService):
    """An ArmorService whose LOAD answers only after ``delay`` seconds: longer than the client's timeout."""

    def __init__(self, delay: float, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.delay = delay
        self.held: list[str] = []

    def call(self, request: Any) -> ArmorResponse:
        if ArmorRequest.from_dict(request).command == "LOAD":
            time.sleep(self.delay)  # the answer cannot come before the client's timeout has passed
            self.held.append("LOAD")
        return super().call(request)


def test_timeout_waits_for_the_service_and_does_not_cap_a_long_load(tmp_path: Path) -> None:
    """armor_py_api's timeout is rospy.wait_for_service's: a LOAD answered after it has passed still succeeds."""
    from armor_api.armor_client import ArmorClient

    data = with_map(tmp_path / "data")
    service = SlowLoad(delay=1.0, data_dir=data)
    with threaded(ServerConfig(data_dir=data), service=service) as server:
        client = ArmorClient("robot", "slow", url=server.url, timeout=0.5)
        client.utils.load_ref_from_file("topological_map.owl", IRI, reasoner="PELLET", buffered_reasoner=False)
        assert service.held == ["LOAD"]  # answered 1 s after the request, twice the client's timeout
        assert client.query.ind_b2_class("ROBOT") == ["Robot1"]


def test_timeout_waits_for_a_service_that_starts_late(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    from armor_api.armor_client import ArmorClient
    from armor_api.armor_exceptions import ArmorServiceCallError

    attempts: list[int] = []
    connect = http.client.HTTPConnection.connect

    def counted(self: http.client.HTTPConnection) -> None:
        attempts.append(self.port)
        connect(self)

    port = free_port()
    with monkeypatch.context() as patch:
        patch.setattr(http.client.HTTPConnection, "connect", counted)
        with pytest.raises(ArmorServiceCallError, match="within 0.5 s"):
            ArmorClient("robot", "ref", url=f"http://127.0.0.1:{port}", timeout=0.5).utils.mount_on_ref()
    assert len(attempts) >= 2 and set(attempts) == {port}  # it kept trying until the timeout, then gave up

    data = tmp_path / "data"
    holder: dict = {}

    def start_later() -> None:
        time.sleep(0.5)
        holder["server"] = start_server(data, port=port)

    thread = threading.Thread(target=start_later)
    thread.start()
    try:
        client = ArmorClient("robot", "ontoRef", url=f"http://127.0.0.1:{port}", timeout=60)
        client.utils.load_ref_from_file("topological_map.owl", IRI)  # waits until the server listens
        assert client.query.ind_b2_class("ROBOT") == ["Robot1"]
    finally:
        thread.join(60)
        if "server" in holder:
            stop_server(holder["server"])
