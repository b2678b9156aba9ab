"""The benchmark harness measures what it claims (a tiny run; no timing is asserted)."""

from __future__ import annotations

import csv
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # the benchmarks package lives beside src/

from benchmarks.report import machine, table, write_csv
from benchmarks.workload import percentile, run


def test_seed_map_run_is_verified_and_reported(tmp_path) -> None:
    row = run("seed", steps=3, full_steps=1, verify=True).__dict__
    assert row["verified"] == "identical"
    assert row["consistent"] and row["inferred"] > 0 and row["inc_steps"] == 3 and row["full_steps"] == 1
    assert row["inc_fallbacks"] == 0  # robot steps are maintained incrementally
    assert row["rss_peak_mib"] >= row["rss_after_reason_mib"] > 0
    row["owlrl"] = {"status": "timeout", "why": "no result within 1 s"}
    text = table([row], machine())
    assert "seed map (3)" in text and "timeout" in text and "identical" in text
    write_csv([row], tmp_path / "bench.csv")
    with (tmp_path / "bench.csv").open() as f:
        rows = list(csv.DictReader(f))
    assert rows[0]["size"] == "seed" and rows[0]["owlrl_status"] == "timeout"


def test_percentile() -> None:
    values = [float(v) for v in range(1, 101)]
    assert percentile(values, 0.5) in (50.0, 51.0)
    assert percentile(values, 0.95) == 95.0
    assert percentile([3.0], 0.95) == 3.0
