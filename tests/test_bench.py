"""The benchmark harness runs and compares what it claims (tiny runs; no timing is asserted)."""

from __future__ import annotations

import csv
import json
import shutil
import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # the benchmarks package lives beside src/

from benchmarks import compare, maps, report, scale  # noqa: E402
from benchmarks.__main__ import _killed, run_size  # noqa: E402
from benchmarks.timing import counted, median, p95  # noqa: E402
from benchmarks.walk import Answers, Move, expected, plan  # noqa: E402
from benchmarks.warm_pellet import compile_peer  # noqa: E402

NOW = 1665579740


@pytest.mark.skipif(shutil.which("java") is None, reason="the warm Pellet peer needs a JDK (java and javac)")
def test_example_map_topostore_and_warm_pellet_agree(tmp_path: Path) -> None:
    classes = compile_peer(tmp_path / "classes")
    row = compare.run(maps.EXAMPLE, classes, compare.Limits(steps=2, pellet_warmup_s=1.0), tmp_path)
    assert row["mismatches"] == []
    assert row["compared_steps"] == 2
    assert row["pellet"]["status"] == "ok" and len(row["pellet"]["step_ms"]) == 2
    # the JVM walked a scratch copy first (at least one step, however long the first took)
    assert row["pellet"]["warm_steps"] >= 1 and row["pellet"]["warm_last_ms"] > 0
    assert len(row["topostore"]["step_ms"]) == 2 and row["topostore"]["median_ms"] > 0
    assert (row["locations"], row["doors"]) == (3, 2)
    text = report.table([row], report.machine())
    assert "| 3 | example file (3) |" in text and "equal (2 steps)" in text and "MISMATCH" not in text
    assert "Pellet warm-up on a scratch copy" in text and "Targets (issue 20):" in text
    report.write_csv([row], tmp_path / "bench.csv")
    with (tmp_path / "bench.csv").open() as f:
        written = list(csv.DictReader(f))
    assert written[0]["size"] == "example" and written[0]["pellet_steps"] == "2" and written[0]["mismatches"] == "0"
    assert report.write_plot([row], tmp_path / "bench.png").stat().st_size > 1000


def test_walk_on_the_example_map(tmp_path: Path) -> None:
    _, bench = maps.write(maps.EXAMPLE, tmp_path)
    moves = plan(bench, 3)
    # the neighbour visited longest ago: R1 (30 s ago), back to C1, then R2
    assert moves == [Move("R1", "C1", NOW + 5, NOW, NOW - 30), Move("C1", "R1", NOW + 10, NOW + 5, NOW),
                     Move("R2", "C1", NOW + 15, NOW + 10, NOW - 5)]
    assert expected(bench, moves) == [Answers(("R1", "R2"), ("R1",)), Answers(("C1",), ("R2",)),
                                      Answers(("R1", "R2"), ("R2",)), Answers(("C1",), ("R1",))]


def test_a_wrong_answer_is_reported() -> None:
    truth = [Answers(("R1",), ()), Answers(("C1",), ("R2",))]
    pellet = [Answers(("R1",), ()), Answers(("C1",), ("R2",))]
    wrong = [Answers(("R1",), ()), Answers(("C1",), ())]
    assert compare.mismatches(truth, pellet, pellet) == []
    assert compare.mismatches(truth, wrong, pellet) == [
        "after step 1: topostore vs expected: URGENT: only in the first [], only in the second ['R2']",
        "after step 1: topostore vs Pellet: URGENT: only in the first [], only in the second ['R2']"]


def test_chain_map_alone(tmp_path: Path) -> None:
    partial: list[str] = []
    row = scale.run("8", steps=4, budget_s=120.0, work=tmp_path, progress=lambda r: partial.append(json.dumps(r)))
    assert row["mismatches"] == []
    assert (row["locations"], row["doors"]) == (8, 7)
    assert len(row["step_ms"]) == 4 and row["full_s"] > 0 and row["peak_rss_mib"] > 0
    assert "chain 8" in report.table([row], report.machine())
    # load, then after each of the 4 steps, then before the full REASON
    assert [json.loads(p)["doing"] for p in partial] == ["load + first REASON"] + ["steps"] * 5 + ["full REASON"]
    # a size killed from outside keeps what it measured until then
    killed = _killed("scale", "8", 60.0, ("noise\n" + "\n".join(partial[:4])).encode())
    assert killed["killed"] == "killed after 60 s, during steps" and len(killed["step_ms"]) == 2
    assert "run killed after 60 s, during steps" in report.table([killed], report.machine())


def test_odd_chain_is_refused(tmp_path: Path) -> None:
    with pytest.raises(ValueError, match="even number"):
        maps.write("7", tmp_path)


def test_step_summaries() -> None:
    times = [100.0, 90.0, 80.0] + [float(v) for v in range(1, 21)]
    assert counted(times) == [float(v) for v in range(1, 21)]
    assert median(times) == 10.5
    assert p95(times) == 19.0
    assert median([3.0, 1.0]) == 2.0 and p95([3.0]) == 3.0 and median([]) is None


def test_a_size_that_dies_mid_run_is_a_failure_not_its_last_progress_row(tmp_path: Path,
                                                                         monkeypatch: pytest.MonkeyPatch) -> None:
    script = tmp_path / "dies.py"
    script.write_text('import json, os, signal\nprint(json.dumps({"kind": "scale", "size": "8", "label": "chain 8", '
                      '"doing": "load + first REASON", "mismatches": []}), flush=True)\n'
                      'os.kill(os.getpid(), signal.SIGKILL)\n')
    monkeypatch.setenv("PYTHONPATH", str(tmp_path))  # the size runs as `python -m dies`
    row = run_size(["dies"], 60, "8", "scale")
    assert row["error"].startswith("exit -9 (SIGKILL)") and "during load + first REASON" in row["error"]


def test_the_scale_bench_collects_the_maps_garbage_before_the_timed_load(tmp_path: Path,
                                                                         monkeypatch: pytest.MonkeyPatch) -> None:
    """The LOAD is timed as a fresh service's: what making the map left is collected before it, not in it."""
    import gc

    events: list[str] = []
    written = maps.write

    def write(*args, **kwargs):
        events.append("map written")
        return written(*args, **kwargs)

    class Robot(scale.ArmorRobot):
        def __init__(self, path: Path) -> None:
            events.append("LOAD")
            super().__init__(path)

    def collected(phase: str, info: dict) -> None:
        if phase == "stop" and info["generation"] == 2 and events[-1:] == ["map written"]:
            events.append("collected")

    monkeypatch.setattr(scale.maps, "write", write)
    monkeypatch.setattr(scale, "ArmorRobot", Robot)
    gc.callbacks.append(collected)
    try:
        scale.run("8", steps=1, budget_s=60.0, work=tmp_path, min_steps=1)
    finally:
        gc.callbacks.remove(collected)
    assert events[:3] == ["map written", "collected", "LOAD"]
