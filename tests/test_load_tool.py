"""The load tool (benchmarks/load.py, benchmarks/load_durable.py) counts what it claims to count.

`make load` runs it for minutes; here a short durable phase with one kill -9 runs end to end, and the
lost-write count is shown to see a write that is not there.
"""

from __future__ import annotations

import shutil
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from benchmarks.load import SHARED, Client, Stats, load_references, missing_writes, start_server  # noqa: E402
from benchmarks.load_durable import run_durable  # noqa: E402


def test_missing_writes_sees_an_acknowledged_write_that_is_not_there(tmp_path: Path) -> None:
    shutil.copy(SHARED / "topological_map_abox.owl", tmp_path / "map.owl")
    proc, url = start_server(tmp_path)
    try:
        stats = Stats()
        load_references(url, 1, stats)
        assert Client(url, "c", stats).armor("shared", "ADD", "IND", "", ["written"])["success"] is True
        assert missing_writes(url, {"shared": ["written"]}) == 0
        assert missing_writes(url, {"shared": ["written", "never_written"], "own0": ["also_never"]}) == 2
    finally:
        proc.kill()
        proc.wait(30)


def test_durable_phase_with_one_kill_finds_every_acknowledged_write() -> None:
    report = run_durable(clients=2, seconds=3, kills=1)
    (kill,) = report["kills"]
    assert kill["acknowledged_before_kill"] >= 1
    assert kill["found_after_restart"] == kill["acknowledged_before_kill"]
    figures = (report["lost_writes"], report["errors"], report["mount_violations"], report["server_alive"])
    assert figures == (0, 0, 0, True)
    assert report["acknowledged_writes"] >= kill["acknowledged_before_kill"]
