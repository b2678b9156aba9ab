"""The inspector in a real browser: from the live map to R1's page (URGENT inferred, with its proof), a link to C1,
a named query in the SPARQL console, the map made inconsistent and the report; nothing fetched from elsewhere.

Debian's chromium driven by Playwright, as tests/test_live.py does.  Screenshots go to the test's temporary
directory; with ``TOPOSTORE_DOCS_SCREENSHOTS=1`` they replace the ones in docs/ that docs/inspector.md shows.
"""

from __future__ import annotations

import os
import urllib.parse
from pathlib import Path

import pytest
from http_support import CHROMIUM, CHROMIUM_FLAGS
from http_support import Live as Server

DOCS = Path(__file__).parents[1] / "docs"


def screenshots(tmp_path: Path) -> Path:
    return DOCS if os.environ.get("TOPOSTORE_DOCS_SCREENSHOTS") == "1" else tmp_path


def test_the_inspector_in_a_real_browser(live_map: Server, tmp_path: Path) -> None:
    if CHROMIUM is None:
        pytest.skip("needs chromium (apt-get install chromium; `make test` installs it as root)")
    sync_api = pytest.importorskip("playwright.sync_api", reason="needs playwright (pip install -e .[test])")
    shots = screenshots(tmp_path)
    elsewhere: list[str] = []

    def only_the_service(route) -> None:
        if route.request.url.startswith(live_map.url + "/"):
            route.continue_()
        else:  # the page works offline: anything else is a failure (and is not fetched)
            elsewhere.append(route.request.url)
            route.abort()

    with sync_api.sync_playwright() as p:
        browser = p.chromium.launch(executable_path=CHROMIUM, args=CHROMIUM_FLAGS, timeout=60_000)
        try:
            page = browser.new_page(viewport={"width": 1280, "height": 860})
            page.set_default_timeout(20_000)
            page.route("**/*", only_the_service)
            errors: list[str] = []
            page.on("pageerror", lambda exc: errors.append(str(exc)))
            page.on("console", lambda msg: errors.append(msg.text) if msg.type == "error" else None)

            # the live map links to the inspector
            page.goto(live_map.url + "/references/ontoRef/map")
            page.click("#inspector")
            page.wait_for_url("**/references/ontoRef/inspector")
            page.wait_for_selector("#overview .grid a.entity")
            assert page.inner_text("#status") == "consistent"
            page.screenshot(path=str(shots / "inspector-overview.png"))

            # the search box finds R1; its page marks URGENT inferred, with its proof
            page.fill("#search", "R1")
            page.click("#hits a[href='#entity/R1']")
            page.wait_for_function("() => document.querySelector('#entity h1')?.textContent.startsWith('R1')")
            row = page.locator("#entity tr:has(td:first-child a.entity:text-is('URGENT'))")
            assert row.get_attribute("class") == "inferred"
            assert row.locator("td.status .chip").inner_text() == "inferred"
            row.locator("summary").click()
            proof = row.locator("ul.proof").first
            assert proof.locator("li").first.inner_text().splitlines()[0] == \
                "R1 rdf:type URGENT ← swrl:Urgency: SWRL rule Urgency"
            assert "R1 visitedAt 1665579710 asserted" in proof.inner_text()
            hasdoor = page.locator("#entity tr:has(td:first-child a.entity:text-is('hasDoor'))")
            assert hasdoor.get_attribute("class") == "asserted"
            page.screenshot(path=str(shots / "inspector-entity.png"), full_page=True)

            # a link in a fact leads to C1's page
            page.locator("#entity table.facts > tbody > tr > td > a.entity:text-is('C1')").first.click()
            page.wait_for_function("() => document.querySelector('#entity h1')?.textContent.startsWith('C1')")
            assert "CORRIDOR" in page.inner_text("#entity")
            assert page.evaluate("() => location.hash") == "#entity/C1"
            # a class page: its superclasses (one inferred, with the classification proof), members, axioms
            page.locator("#entity table.facts > tbody > tr > td > a.entity:text-is('CORRIDOR')").click()
            page.wait_for_function("() => document.querySelector('#entity h1')?.textContent.startsWith('CORRIDOR')")
            room = page.locator("#entity tr:has(td:first-child a.entity:text-is('ROOM'))")
            assert room.get_attribute("class") == "inferred"
            room.locator("summary").click()
            assert "CORRIDOR rdfs:subClassOf ROOM ← classification" in room.inner_text()
            assert "CORRIDOR EquivalentTo (LOCATION and (hasDoor min 2 DOOR))" in page.inner_text("#entity")
            page.screenshot(path=str(shots / "inspector-class.png"), full_page=True)

            # a named query in the SPARQL console (YASGUI) shows its rows, inferred ones included
            page.click("header nav a[data-view='sparql']")
            page.click("#queries button[data-query='urgent-locations']")
            page.wait_for_function("() => document.querySelector('#yasgui .yasr table tbody')"
                                   "?.textContent.includes('R1')")
            table = page.inner_text("#yasgui .yasr table tbody")
            assert "1665579710" in table and "R2" not in table
            page.screenshot(path=str(shots / "inspector-sparql.png"))
            # class and property names complete from this reference (never from LOV on the Internet)
            completions = page.evaluate("""async () => {
                const yasqe = window.topostoreInspector.state.yasgui.getTab().getYasqe();
                const get = name => Yasgui.Yasqe.Autocompleters[name].get;
                const ns = "http://bnc/exp-rob-lab/2022-23#";
                return [await get("topostore-class")(yasqe, { string: "map:UR", autocompletionString: ns + "UR" }),
                        await get("topostore-property")(yasqe, { string: "<" + ns + "is", autocompletionString: ns + "is" }),
                        yasqe.config.autocompleters];
            }""")
            assert completions == [["http://bnc/exp-rob-lab/2022-23#URGENT"], ["http://bnc/exp-rob-lab/2022-23#isIn"],
                                   ["variables", "topostore-class", "topostore-property"]]
            yasqe = "window.topostoreInspector.state.yasgui.getTab().getYasqe()"
            page.evaluate(f"() => {yasqe}.setValue('PREFIX map: <http://bnc/exp-rob-lab/2022-23#>\\n"
                          "SELECT * WHERE {{ ?x a ')")
            page.click("#yasgui .CodeMirror-line >> nth=1")
            page.keyboard.press("End")
            page.keyboard.type("map:UR")
            page.keyboard.press("Control+Space")
            page.wait_for_selector(".CodeMirror-hint")
            assert page.locator(".CodeMirror-hint").all_inner_texts() == ["map:URGENT"]
            page.keyboard.press("Escape")
            page.click("#yasgui .yasr table tbody a.iri")  # a result IRI opens its entity page
            page.wait_for_function("() => document.querySelector('#entity h1')?.textContent.startsWith('R1')")

            # the robot's clock advances (R2 and C1 become URGENT), then the map is made inconsistent
            live_map.ok("REPLACE", "DATAPROP", "IND", ["now", "Robot1", "LONG", "1665579750", "1665579740"])
            live_map.ok("ADD", "IND", "CLASS", ["R1", "DOOR"])
            page.wait_for_function("() => document.body.dataset.consistent === 'false'")
            assert page.inner_text("#status") == "INCONSISTENT"
            # an entity page still fetching when the user goes elsewhere is never drawn over the view asked for:
            # its answer is held back until the consistency view is shown, then let through
            held: list = []
            page.route("**/entities/C1", lambda route: held.append(route))
            with page.expect_request("**/entities/C1"):
                page.evaluate("() => { location.hash = '#entity/C1'; }")
            page.evaluate("() => { location.hash = '#consistency'; }")
            page.wait_for_selector("#consistency .violation")
            assert held, "the entity page was not held back"
            with page.expect_response("**/entities/C1"):
                held[0].continue_()
            page.unroute("**/entities/C1")
            page.wait_for_timeout(300)  # the late answer handled
            assert page.locator("#entity").is_hidden() and page.locator("#consistency").is_visible()
            page.evaluate("() => { location.hash = '#entity/R1'; }")
            page.wait_for_function("() => !document.getElementById('entity').hidden")
            page.click("#status")
            page.wait_for_selector("#consistency .violation")
            report = page.inner_text("#consistency")
            assert "DOOR DisjointWith LOCATION" in report and "?x = R1" in report
            assert "R1 rdf:type DOOR asserted" in report  # the proof of the clash, open
            assert "R1 rdf:type LOCATION ← prp-dom: " in report
            assert page.locator("#consistency .violation > div > a.entity", has_text="R1").count() == 1
            page.screenshot(path=str(shots / "inspector-consistency.png"))

            # the history: what became URGENT when, and when the map became inconsistent
            page.click("header nav a[data-view='history']")
            page.wait_for_selector("#history .timeline li.became-inconsistent")
            timeline = page.inner_text("#history .timeline")
            assert "+ R2 rdf:type URGENT" in timeline and "became INCONSISTENT" in timeline
            page.fill("#history-filter", "R2 urgent")  # what became URGENT when: only R2's entry is left
            assert page.locator("#history .timeline > li:visible").count() == 1
            assert page.locator("#history .timeline > li:visible .fact:visible").all_inner_texts() == [
                "+ R2 rdf:type URGENT"]
            page.fill("#history-filter", "")
            page.screenshot(path=str(shots / "inspector-history.png"))

            # the report's individual links to its page
            page.click("#status")
            page.locator("#consistency .violation > div > a.entity", has_text="R1").click()
            page.wait_for_function("() => document.querySelector('#entity h1')?.textContent.startsWith('R1')")
            assert "inconsistent" in page.inner_text("#entity .warning")
            assert errors == []
        finally:
            browser.close()
    assert elsewhere == []
    assert all((shots / f"inspector-{n}.png").stat().st_size > 10_000 for n in ("entity", "sparql", "consistency"))


def test_a_hostile_name_cannot_run_script_in_the_page(live_map: Server) -> None:
    """An IRI may hold quotes; YASGUI's result table writes IRIs into links as they are, so a name like
    ``x'onmouseover='…`` would be an event handler: the page's Content-Security-Policy refuses to run it."""
    if CHROMIUM is None:
        pytest.skip("needs chromium (apt-get install chromium; `make test` installs it as root)")
    sync_api = pytest.importorskip("playwright.sync_api", reason="needs playwright (pip install -e .[test])")
    hostile = "x'onmouseover='window.pwned=1'"
    live_map.ok("ADD", "IND", "CLASS", [hostile, "DOOR"])
    with sync_api.sync_playwright() as p:
        browser = p.chromium.launch(executable_path=CHROMIUM, args=CHROMIUM_FLAGS, timeout=60_000)
        try:
            page = browser.new_page()
            page.set_default_timeout(20_000)
            page.goto(live_map.url + "/references/ontoRef/inspector#sparql")
            page.wait_for_selector("#yasgui .CodeMirror")
            page.evaluate("""() => { const tab = window.topostoreInspector.state.yasgui.getTab();
                tab.setQuery('SELECT ?door WHERE { ?door a <http://bnc/exp-rob-lab/2022-23#DOOR> }'); tab.query(); }""")
            page.wait_for_function("() => document.querySelector('#yasgui .yasr table tbody')?.textContent.includes('onmouseover')")
            link = page.locator("#yasgui .yasr table tbody a.iri", has_text="onmouseover")
            assert link.get_attribute("onmouseover") is not None  # the attribute is there (YASGUI's markup) ...
            link.hover()
            page.wait_for_timeout(300)
            assert page.evaluate("() => window.pwned") is None  # ... and does not run
            page.goto(live_map.url + "/references/ontoRef/inspector#entity/" + urllib.parse.quote(hostile, safe=""))
            page.wait_for_selector("#entity h1")
            assert page.inner_text("#entity h1").startswith(hostile)  # shown as text on the entity page
        finally:
            browser.close()
