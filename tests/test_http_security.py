"""The HTTP service's protections (topostore.http.security), in-process with Starlette's TestClient.

Each step is checked on its own: foreign origins refused (also a cross-site form POST that would change
the map), CORS for allowed origins, the Host check without a token, the token, the size limits.
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from starlette.testclient import TestClient
from support import IRI, SHARED

from topostore.armor import ArmorService
from topostore.http.app import ServerConfig, create_app
from topostore.http.security import LOOPBACK_HOSTS, allowed_hosts
from topostore.rdf.vocab import ASSERTED

ORIGIN = "https://yasgui.example.org"
UPDATE = "INSERT DATA { <http://example.org/a> <http://example.org/p> <http://example.org/b> }"


def _service(data: Path) -> ArmorService:
    data.mkdir()
    (data / "map.owl").write_bytes((SHARED / "topological_map_abox.owl").read_bytes())
    service = ArmorService(data_dir=data)
    r = service.call({"reference_name": "ref", "command": "LOAD", "primary_command_spec": "FILE",
                      "args": ["map.owl", IRI, "false", "PELLET", "false"]})
    assert r.exit_code == 0, r
    return service


@pytest.fixture
def app_for(tmp_path: Path):
    """TestClient factory: a service with the example map as reference ``ref``, behind the given settings."""
    clients = []

    def make(**settings) -> tuple[TestClient, ArmorService]:
        service = _service(tmp_path / f"data{len(clients)}")
        config = ServerConfig(data_dir=service.data_dir, allow_update=True, **settings)
        client = TestClient(create_app(config, service), base_url="http://127.0.0.1")
        clients.append(client.__enter__())
        return client, service

    yield make
    for c in clients:
        c.__exit__(None, None, None)


def asserted_count(service: ArmorService) -> int:
    return service.reference("ref").ontology.store.count(ASSERTED)


def test_a_cross_site_form_post_is_refused_and_changes_nothing(app_for) -> None:
    client, service = app_for(cors_origins=(ORIGIN,))
    before = asserted_count(service)
    res = client.post("/references/ref/sparql", data={"update": UPDATE}, headers={"Origin": "http://evil.example"})
    assert res.status_code == 403 and "--cors-origin" in res.json()["error"]
    assert "access-control-allow-origin" not in res.headers
    assert asserted_count(service) == before
    res = client.post("/references/ref/sparql", data={"update": UPDATE})  # the same update, not from a web page
    assert res.status_code == 200, res.text
    assert asserted_count(service) == before + 1


def test_allowed_origin_gets_cors_headers_and_preflights(app_for) -> None:
    client, _ = app_for(cors_origins=(ORIGIN + "/",))  # a trailing slash in the setting is ignored
    res = client.get("/health", headers={"Origin": ORIGIN})
    assert res.status_code == 200
    assert (res.headers["access-control-allow-origin"], res.headers["access-control-expose-headers"]) == (
        ORIGIN, "Content-Type")
    res = client.options("/references/ref/sparql", headers={
        "Origin": ORIGIN, "Access-Control-Request-Method": "POST", "Access-Control-Request-Headers": "Content-Type"})
    assert res.status_code == 200 and res.headers["access-control-allow-origin"] == ORIGIN
    assert res.headers["access-control-max-age"] == "600"
    res = client.options("/references/ref/sparql", headers={"Origin": ORIGIN, "Access-Control-Request-Method": "PUT"})
    assert (res.status_code, res.text) == (400, "Disallowed CORS method")


def test_host_check_only_without_a_token(app_for) -> None:
    client, _ = app_for()
    assert client.get("/health", headers={"host": "rebind.evil.example"}).status_code == 400
    client, _ = app_for(token="s3cret")
    headers = {"host": "robot.example.org", "Authorization": "Bearer s3cret"}  # e.g. served on the network
    assert client.get("/health", headers=headers).status_code == 200


def test_token_is_required_on_every_route(app_for) -> None:
    client, _ = app_for(token="s3cret")
    for path in ("/health", "/references", "/references/ref/sparql?query=ASK{}"):
        res = client.get(path)
        assert res.status_code == 401 and res.headers["www-authenticate"] == 'Bearer realm="topostore"'
        assert client.get(path, headers={"Authorization": "Bearer wrong"}).status_code == 401
        assert client.get(path, headers={"Authorization": "bearer s3cret"}).status_code == 200


def test_size_limits(app_for) -> None:
    client, service = app_for(max_request_bytes=1000)
    before = asserted_count(service)
    res = client.get("/references/ref/sparql", params={"query": "ASK {}" + " " * 1000})
    assert res.status_code == 414 and "send the query with POST" in res.json()["error"]
    res = client.post("/references/ref/sparql", data={"update": UPDATE + " " * 1000})
    assert res.status_code == 413 and "--max-request-bytes" in res.json()["error"]

    def chunks():  # no Content-Length: the limit is enforced while reading
        for _ in range(20):
            yield b"x" * 100

    res = client.post("/armor", content=chunks(), headers={"Content-Type": "application/json"})
    assert res.status_code == 413
    assert asserted_count(service) == before
    request = {"reference_name": "ref", "command": "GET", "primary_command_spec": "ALL",
               "secondary_command_spec": "REFS"}
    res = client.post("/armor", content=json.dumps(request), headers={"Content-Type": "application/json"})
    assert res.status_code == 200 and res.json()["queried_objects"] == ["ref"], res.json()


def test_allowed_hosts_add_the_loopback_address_bound() -> None:
    assert allowed_hosts("127.0.0.1") == list(LOOPBACK_HOSTS)
    assert allowed_hosts("127.0.0.5") == [*LOOPBACK_HOSTS, "127.0.0.5"]
    assert allowed_hosts("::1") == list(LOOPBACK_HOSTS)
    assert allowed_hosts("0.0.0.0") == list(LOOPBACK_HOSTS)  # with a token only, and then the check is off
    assert allowed_hosts("localhost") == list(LOOPBACK_HOSTS)
