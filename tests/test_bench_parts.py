"""The drift, remote-store, full-REASON and picture benchmark tools measure what they claim (tiny runs; no timing
is asserted): windows and pauses, HTTP requests counted at the transport, the TBox generator, every
engine's answers, and the tables' met/missed verdicts."""

from __future__ import annotations

import importlib.util
import shutil
import sys
import threading
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer
from pathlib import Path

import httpx
import pytest
from pyoxigraph import RdfFormat, parse

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # the benchmarks package lives beside src/

from benchmarks import drift, full, paired, picture, remote, report, schema_change, tables, tbox  # noqa: E402
from benchmarks.http_count import counting  # noqa: E402

OWL = "http://www.w3.org/2002/07/owl#"


def test_drift_windows_and_the_longest_pause() -> None:
    times = [50.0] * 9 + [1.0] * 91 + [2.0] * 300 + [3.0] * 100
    times[200] = 900.0
    assert drift.windows(times) == (1.0, 3.0)
    assert drift.longest(times) == (900.0, 201)
    assert drift.windows([]) == (None, None) and drift.longest([]) == (None, None)


def test_a_short_drift_walk_on_the_example_map(tmp_path: Path) -> None:
    row = drift.run("example", 12, tmp_path)
    assert row["mismatches"] == [] and len(row["step_ms"]) == 12
    assert row["early_ms"] > 0 and row["late_ms"] > 0 and 1 <= row["longest_step"] <= 12


def test_the_schema_change_rounds_time_each_command() -> None:
    """Each round times the three commands after its REASON; every command succeeded (run raises otherwise)."""
    times = schema_change.run("example", 2)
    assert set(times) == set(schema_change.COMMANDS) and all(len(t) == 2 and min(t) > 0 for t in times.values())


def test_a_tree_compared_with_itself_in_turns() -> None:
    """Two worker processes of the same tree take turns on the example map; the line names both medians
    and the per-round difference (no figure is asserted: it is a measurement)."""
    tree = Path(__file__).resolve().parents[1]
    line = paired.compare(tree, tree, "example", 2, 2)
    assert line.startswith("example: A ") and "A - B per round: median" in line and "(2 rounds of 2 steps)" in line


def test_the_picture_benchmark_draws_both_kinds_of_map(capsys: pytest.CaptureFixture[str]) -> None:
    pytest.importorskip("matplotlib")
    assert picture.main(["--sizes", "30", "450"]) == 0
    rows = [line.split("|")[1:-1] for line in capsys.readouterr().out.splitlines()[2:]]
    assert [(r[0].strip(), r[1].strip()) for r in rows] == [("30", "no"), ("450", "yes")]  # clusters above 400
    assert all(int(r[5].split()[0].replace(",", "")) > 0 for r in rows)  # a PNG was written


class _Ok(BaseHTTPRequestHandler):
    def do_GET(self) -> None:  # noqa: N802 - the handler's own name
        self.send_response(200)
        self.send_header("Content-Length", "0")
        self.end_headers()

    def log_message(self, *args: object) -> None:
        pass


def test_requests_are_counted_at_the_transport_and_the_transport_restored() -> None:
    server = ThreadingHTTPServer(("127.0.0.1", 0), _Ok)
    threading.Thread(target=server.serve_forever, daemon=True).start()
    url = f"http://127.0.0.1:{server.server_address[1]}"
    original = httpx.HTTPTransport.handle_request
    try:
        with counting() as http, httpx.Client() as client:
            for _ in range(3):
                client.get(url + "/query")
            client.get(url + "/other")
        assert http.total == 4 and http.by_endpoint == {"GET /query": 3, "GET /other": 1}
        assert httpx.HTTPTransport.handle_request is original
        with httpx.Client() as client:  # outside the block nothing is counted
            client.get(url + "/query")
        assert http.total == 4
    finally:
        server.shutdown()


@pytest.mark.skipif(not Path(shutil.which("oxigraph") or Path(sys.executable).with_name("oxigraph")).exists(),
                    reason="oxigraph serve is missing (pip install 'oxigraph>=0.4')")
def test_remote_steps_on_oxigraph_serve_count_their_requests(tmp_path: Path) -> None:
    row = remote.run("example", 3, tmp_path)
    assert row["mismatches"] == [] and len(row["requests_per_step"]) == 3
    assert all(n >= 1 for n in row["requests_per_step"]) and row["load_requests"] >= 1
    assert sum(row["last_step_requests"].values()) == row["requests_per_step"][-1]
    by_command = row["requests_by_command"]
    assert {"REASON", "QUERY OBJECTPROP IND canReach", "QUERY IND CLASS URGENT"} <= set(by_command)
    assert by_command["REPLACE OBJECTPROP IND isIn"] == 0  # its write goes with the REASON's update
    assert by_command["QUERY OBJECTPROP IND canReach"] + by_command["QUERY IND CLASS URGENT"] <= 1
    assert "HTTP requests per step ≤ 3 on the example map" in tables.extra_tables([row])


def test_the_tutorial_style_tbox_has_what_the_tutorial_teaches(tmp_path: Path) -> None:
    path = tbox.write(100, tmp_path)
    triples = list(parse(path=str(path), format=RdfFormat.N_TRIPLES))
    count = lambda p: sum(1 for t in triples if t.predicate.value == p)  # noqa: E731
    classes = {t.subject.value for t in triples if t.object.value == OWL + "Class" and t.subject.value.startswith(tbox.NS)}
    assert len(classes) == 100
    for p in ("someValuesFrom", "allValuesFrom", "unionOf", "complementOf", "oneOf", "hasValue", "intersectionOf"):
        assert count(OWL + p) >= 1, p
    assert count(OWL + "disjointWith") > 300 and count(OWL + "someValuesFrom") > 100
    assert 10 <= len(full.individuals(path, tbox.NS)) <= 20
    assert len(list(parse(path=str(tbox.write(150, tmp_path)), format=RdfFormat.N_TRIPLES))) > len(triples)
    with pytest.raises(ValueError, match="at least"):
        tbox.write(20, tmp_path)


def test_the_tbox_timing_table_has_a_row_per_size_and_the_growth(tmp_path: Path) -> None:
    lines = tbox.timing_table([50, 60], tmp_path)
    assert lines[0].startswith("| classes |") and len(lines) == 5
    assert lines[2].startswith("| 50 |") and lines[3].startswith("| 60 |")
    assert lines[4].startswith("growth from 50 to 60 classes")
    row = tbox.timing(50, tmp_path)
    assert row["triples"] > 0 and row["rules"] > 0 and row["load_s"] > 0 and row["second_full_s"] > 0


def test_full_reason_rows_of_topostore_and_owlrl_agree_on_a_small_tbox(tmp_path: Path) -> None:
    mine = full.run("topostore", "tbox:50", tmp_path / "a")
    other = full.run("owlrl", "tbox:50", tmp_path / "b")
    assert mine["consistent"] and mine["reason_s"] > 0 and mine["peak_rss_mib"] > 0
    # the defined classes that OWL 2 RL derives from the individuals' own facts
    assert "CheeseyPizza" in mine["types"]["pizzaA"] and "ItalianPizza" in mine["types"]["pizzaB"]
    assert "CheeseyPizza" in other["types"]["pizzaA"] and "ItalianPizza" in other["types"]["pizzaB"]


def test_full_reason_on_a_map_checks_the_robot(tmp_path: Path) -> None:
    row = full.run("topostore", "8", tmp_path)
    assert row["mismatches"] == [] and row["can_reach"] == row["expected_can_reach"]


@pytest.mark.skipif(importlib.util.find_spec("reasonable") is None, reason="reasonable is in the bench extra")
def test_reasonable_runs_on_the_same_file(tmp_path: Path) -> None:
    row = full.run("reasonable", "8", tmp_path)
    assert "error" not in row and row["triples_out"] > 0 and "can_reach" not in row  # no SWRL: no canReach


@pytest.mark.skipif(shutil.which("java") is None, reason="Pellet needs Java")
def test_pellet_through_owlready2_is_the_reference_of_the_tbox_row(tmp_path: Path) -> None:
    pellet = full.run("pellet", "tbox:50", tmp_path / "p")
    assert "error" not in pellet, pellet.get("error")
    assert "NonVegetarianPizza" in pellet["types"]["pizzaA"]  # a complement: beyond OWL 2 RL
    text = tables.extra_tables([pellet, full.run("owlrl", "tbox:50", tmp_path / "o")])
    assert "| pellet | " in text and "the reference" in text and "differ from Pellet" in text


def test_a_failing_engine_is_a_row_saying_so(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    def broken(*args: object) -> None:
        raise RuntimeError("no JVM")

    monkeypatch.setitem(full.RUNNERS, "pellet", broken)
    row = full.run("pellet", "tbox:50", tmp_path)
    assert row["error"] == "RuntimeError: no JVM"
    assert "failed: RuntimeError: no JVM" in tables.extra_tables([row])


def test_verdicts_say_met_and_missed() -> None:
    assert tables.type_differences({"a": ["X", "Y"]}, {"a": ["Y", "Z"], "b": ["W"]}) == ["a: +X -Z", "b: -W"]
    rows = [{"kind": "drift", "label": "m", "size": "m", "steps": 4000, "early_ms": 1.0, "late_ms": 2.0, "drift": 2.0,
             "longest_ms": 40.0, "longest_step": 7, "mismatches": []},
            {"kind": "full", "engine": "topostore", "size": "10000", "input_kind": "map", "label": "chain 10,000",
             "load_s": 1.0, "reason_s": 0.5, "peak_rss_mib": 100.0, "can_reach": [], "mismatches": []},
            {"kind": "full", "engine": "topostore", "size": "100000", "input_kind": "map", "label": "chain 100,000",
             "load_s": 5.0, "reason_s": 8.0, "peak_rss_mib": 2000.0, "can_reach": [], "mismatches": []}]
    text = tables.extra_tables(rows)
    assert "drift ≤ 1.5 on m: 2.00 — missed" in text
    assert "full REASON ≤ 1 s at 10,000: 0.50 s — met" in text
    assert "load + full REASON ≤ 10 s at 100,000: 13.0 s — missed" in text
    assert "peak RSS ≤ 1.5 GiB at 100,000: 1.95 GiB — missed" in text
    assert "full(100,000) / full(10,000) ≤ 12: 16.0 — missed" in text
    sums = [{"kind": "compare", "size": "example", "label": "example", "speedup": 5.0, "topostore_median_ms": 0.8},
            {"kind": "compare", "size": "8", "label": "chain 8", "speedup": 3.0, "topostore_median_ms": 2.0},
            {"kind": "scale", "size": "1000", "label": "1k", "speedup": None, "topostore_median_ms": 2.0},
            {"kind": "scale", "size": "100000", "label": "100k", "speedup": None, "topostore_median_ms": 12.0}]
    got = report.targets(sums)
    assert "lowest 3.00× (chain 8) — missed" in got[0] and got[1].endswith("0.80 ms — met")
    assert got[-2].endswith("12.0 ms — met") and got[-1] == "- step(100,000) / step(1,000) ≤ 5: 6.0 — missed"
    assert report.speedup_cell(sums[0]) == "5.00× met" and report.speedup_cell(sums[2]) == "–"


def test_the_reasoning_time_limit_is_lifted_for_measurements() -> None:
    from benchmarks.limits import BENCH_MAX_SECONDS, lift_time_limit
    from topostore import Ontology
    from topostore.reason import limits as reason_limits

    before = reason_limits.DEFAULTS
    try:
        reason_limits.set_defaults(reason_limits.ReasonLimits(max_rounds=77, max_seconds=1.0))
        lifted = lift_time_limit()
        assert lifted.max_seconds == BENCH_MAX_SECONDS and lifted.max_rounds == 77  # only the time changes
        assert Ontology().limits.max_seconds == BENCH_MAX_SECONDS
    finally:
        reason_limits.set_defaults(before)
