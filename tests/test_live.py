"""The live routes of the real service: explanations, server-sent events and the map page in a real browser.

The server is `topostore serve` in a subprocess on a free loopback port; the
browser is Debian's chromium driven by Playwright (install: `apt-get install
chromium`, `pip install -e .[test]`; `make test` does both).
"""

from __future__ import annotations

import http.client
import json
import threading
import urllib.parse
from pathlib import Path

import pytest
from http_support import CHROMIUM, CHROMIUM_FLAGS
from http_support import Live as Server


def get_json(server: Server, path: str) -> tuple[int, dict]:
    status, _, body = server.request(path)
    return status, json.loads(body)


def test_explain_route(live_map: Server) -> None:
    query = urllib.parse.urlencode({"s": "R1", "p": "rdf:type", "o": "URGENT"})
    status, tree = get_json(live_map, f"/references/ontoRef/explain?{query}")
    assert status == 200
    assert (tree["triple"], tree["rule"], tree["status"]) == ("R1 rdf:type URGENT", "swrl:Urgency", "inferred")
    assert [p["triple"] for p in tree["premises"]] == [
        "Robot1 rdf:type ROBOT", "Robot1 now 1665579740", "R1 rdf:type LOCATION", "R1 visitedAt 1665579710",
        "Robot1 urgencyThreshold 7"]
    query = urllib.parse.urlencode({"s": "R2", "p": "rdf:type", "o": "URGENT"})
    assert get_json(live_map, f"/references/ontoRef/explain?{query}") == (
        200, {"triple": "R2 rdf:type URGENT", "status": "not entailed"})
    assert get_json(live_map, "/references/ontoRef/explain?s=R1&p=rdf:type")[0] == 400
    assert get_json(live_map, "/references/nope/explain?s=R1&p=a&o=URGENT")[0] == 404
    status, body = get_json(live_map, "/references/ontoRef/explain?s=R1&p=a&o=" + urllib.parse.quote("bad name"))
    assert status == 400 and "bad name" in body["error"]


class SseReader:
    """Reads a server-sent event stream on a thread of its own, keeping events and comments."""

    def __init__(self, server: Server, path: str) -> None:
        host, port = server.url.removeprefix("http://").split(":")
        self.conn = http.client.HTTPConnection(host, int(port), timeout=30)
        self.conn.request("GET", path)
        self.response = self.conn.getresponse()
        self.events: list[dict] = []
        self.comments: list[str] = []
        self.cond = threading.Condition()
        threading.Thread(target=self._read, daemon=True).start()

    def _read(self) -> None:
        data: list[str] = []
        try:
            for raw in self.response:
                line = raw.decode().rstrip("\n")
                with self.cond:
                    if line.startswith(":"):
                        self.comments.append(line)
                    elif line.startswith("data: "):
                        data.append(line[6:])
                    elif not line and data:
                        self.events.append(json.loads("".join(data)))
                        data = []
                    self.cond.notify_all()
        except (OSError, ValueError, AttributeError):  # the connection was closed by the test
            pass

    def wait(self, predicate, timeout: float = 20) -> bool:
        with self.cond:
            return self.cond.wait_for(lambda: predicate(self), timeout)

    def close(self) -> None:
        self.conn.close()


def test_r2_becoming_urgent_arrives_over_sse_within_one_reason(live_map: Server) -> None:
    reader = SseReader(live_map, "/references/ontoRef/events?pattern=" + urllib.parse.quote("rdf:type URGENT")
                       + "&keepalive=0.2")
    try:
        assert reader.response.status == 200
        assert reader.response.getheader("Content-Type").startswith("text/event-stream")
        assert reader.wait(lambda r: ": connected" in r.comments)
        assert reader.wait(lambda r: ": keep-alive" in r.comments)          # keep-alive comments flow
        # one manipulation with the live reasoner = one REASON
        live_map.ok("REPLACE", "DATAPROP", "IND", ["now", "Robot1", "LONG", "1665579750", "1665579740"])
        assert reader.wait(lambda r: len(r.events) >= 1)
        event = reader.events[0]
        assert event["added"] == [{"s": "C1", "p": "rdf:type", "o": "URGENT"},
                                  {"s": "R2", "p": "rdf:type", "o": "URGENT"}]
        assert (event["removed"], event["consistent"], event["missed"]) == ([], True, 0)
        assert event["reference"] == "ontoRef"                            # as on the ROS events topic
        live_map.ok("REASON")                                                  # nothing changes: still one event
        assert reader.wait(lambda r: len(r.events) >= 2)
        assert (reader.events[1]["added"], reader.events[1]["removed"]) == ([], [])
        assert reader.events[1]["seq"] == event["seq"] + 1
    finally:
        reader.close()


def test_events_route_errors(live_map: Server) -> None:
    assert get_json(live_map, "/references/nope/events")[0] == 404
    assert get_json(live_map, "/references/ontoRef/events?keepalive=0")[0] == 400
    assert get_json(live_map, "/references/ontoRef/events?pattern=a+b+c+d")[0] == 400


def test_map_data(live_map: Server) -> None:
    status, data = get_json(live_map, "/references/ontoRef/map.json")
    assert status == 200
    assert [(l["id"], l["kind"], l["urgent"]) for l in data["locations"]] == [
        ("C1", "CORRIDOR", False), ("R1", "ROOM", True), ("R2", "ROOM", False)]
    assert data["doors"] == [{"id": "D1"}, {"id": "D2"}]
    assert data["robots"] == [{"id": "Robot1", "isIn": "C1", "now": "1665579740"}]
    assert (data["urgent"], data["consistent"]) == (["R1"], True)
    status, _, page = live_map.request("/references/ontoRef/map")
    assert status == 200 and b"/static/cytoscape.min.js" in page
    status, headers, script = live_map.request("/static/cytoscape.min.js")
    assert status == 200 and len(script) == (Path(__file__).parents[1] / "src/topostore/http/static/cytoscape.min.js").stat().st_size


def test_the_live_page_in_a_real_browser(live_map: Server, tmp_path: Path) -> None:
    if CHROMIUM is None:
        pytest.skip("needs chromium (apt-get install chromium; `make test` installs it as root)")
    sync_api = pytest.importorskip("playwright.sync_api", reason="needs playwright (pip install -e .[test])")
    with sync_api.sync_playwright() as p:
        browser = p.chromium.launch(executable_path=CHROMIUM, args=CHROMIUM_FLAGS, timeout=60_000)
        try:
            page = browser.new_page(viewport={"width": 1200, "height": 700})
            page.set_default_timeout(20_000)
            page.goto(live_map.url + "/references/ontoRef/map")
            page.wait_for_function("() => window.topostoreMap && window.topostoreMap.cy.nodes().length === 6")
            assert page.locator("#urgent li").all_inner_texts() == ["R1"]
            page.wait_for_function("() => document.getElementById('status').textContent.startsWith('consistent')")
            # a REASON that makes R2 (and C1) URGENT, by the robot's clock advancing
            live_map.ok("REPLACE", "DATAPROP", "IND", ["now", "Robot1", "LONG", "1665579750", "1665579740"])
            page.wait_for_function("() => document.body.dataset.events === '1'")
            page.wait_for_function("() => document.querySelectorAll('#urgent li').length === 3")
            assert page.locator("#urgent li").all_inner_texts() == ["C1", "R1", "R2"]
            assert page.evaluate("() => window.topostoreMap.cy.getElementById('R2').hasClass('urgent')") is True
            assert page.locator("#log li").first.inner_text() == \
                "#1 + C1 rdf:type URGENT + R2 rdf:type URGENT"
            # click-to-explain: tap R2 as a user would (at its rendered position)
            box = page.evaluate("() => { const n = window.topostoreMap.cy.getElementById('R2');"
                                " const p = n.renderedPosition(); return [p.x, p.y]; }")
            page.mouse.click(box[0], box[1])
            page.wait_for_function("() => document.getElementById('explanation').textContent.includes('swrl:Urgency')")
            first = page.locator("#explanation li").first.inner_text().splitlines()[0]
            assert first == "R2 rdf:type URGENT ← swrl:Urgency: SWRL rule Urgency"
            shot = tmp_path / "live-map.png"
            page.screenshot(path=str(shot))
            assert shot.stat().st_size > 10_000
            print(f"screenshot: {shot}")
        finally:
            browser.close()
