"""The surveillance demo and the map picture, on the embedded map and on a generated one."""

from __future__ import annotations

import random
import time
from pathlib import Path

import pytest
from click.testing import CliRunner

from topostore import Ontology
from topostore.cli.group import cli
from topostore.demo import decide, mapgen, run_demo
from topostore.demo.mapview import MapView, draw_ontology
from topostore.demo.world import default_map_files
from topostore.resources import default_ontology

PNG_MAGIC = b"\x89PNG\r\n\x1a\n"


def check_policy(moves) -> None:
    """Every move follows the seed policy: urgent reachable first, else a reachable corridor."""
    for m in moves:
        assert m.consistent, m
        urgent_in_reach = [loc for loc in m.reachable if loc in m.urgent]
        if not m.reachable:
            assert m.destination is None
            continue
        assert m.destination in m.reachable, m
        if urgent_in_reach:
            assert m.went_urgent and m.destination in urgent_in_reach, m


def test_default_map_demo(tmp_path: Path) -> None:
    lines: list[str] = []
    picture = tmp_path / "out" / "map.png"
    result = run_demo(steps=4, seed=0, picture=picture, emit=lines.append)
    assert [f.name for f in default_map_files()] == ["topological_map.ttl", "topological_map_abox.ttl"]
    assert len(result.moves) == 4 and result.robots == ["Robot1"]
    first = result.moves[0]
    # the example environment: Robot1 in C1 reaches R1 and R2, R1 is URGENT (30 s > 7 s) -> goes to R1
    assert (first.origin, first.reachable, first.urgent, first.destination) == ("C1", ["R1", "R2"], ["R1"], "R1")
    assert result.moves[1].origin == "R1" and result.moves[1].reachable == ["C1"]
    check_policy(result.moves)
    times = [m.time for m in result.moves]
    assert times == sorted(times) and len(set(times)) == 4  # the robot's clock advances
    assert picture.read_bytes().startswith(PNG_MAGIC)
    trace = "\n".join(lines)
    assert "Step 4" in trace and "decision: R1 is URGENT" in trace and "REASON" in trace


@pytest.fixture(scope="module")
def generated_map(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A map saved from mapgen.generate(30) with the TBox, as a user would bring one."""
    onto = Ontology.from_file(default_ontology())
    onto.add(*mapgen.generate(30, seed=5).triples())
    path = tmp_path_factory.mktemp("maps") / "generated30.ttl"
    onto.save(path)
    return path


def test_generated_map_with_several_robots(generated_map: Path, tmp_path: Path) -> None:
    picture = tmp_path / "gen.svg"
    result = run_demo([generated_map], steps=3, seed=3, robots=3, picture=picture, emit=lambda _: None)
    assert result.robots == ["Robot1", "Robot2", "Robot3"]
    assert len(result.moves) == 9
    check_policy(result.moves)
    by_robot = {r: [m for m in result.moves if m.robot == r] for r in result.robots}
    for moves in by_robot.values():
        assert len(moves) == 3
        for before, after in zip(moves, moves[1:]):  # each robot continues from where it went
            assert after.origin == (before.destination or before.origin)
            assert after.time > before.time
    # the map generator starts robots in corridors C1, C2, C3
    assert [by_robot[r][0].origin for r in result.robots] == ["C1", "C2", "C3"]
    assert picture.read_text().lstrip().startswith(("<?xml", "<svg"))


def test_every_step_pictures(tmp_path: Path) -> None:
    result = run_demo(steps=2, picture=tmp_path / "m.png", every_step=True, emit=lambda _: None)
    assert [p.name for p in result.pictures] == ["m-001.png", "m-002.png"]
    assert all(p.read_bytes().startswith(PNG_MAGIC) for p in result.pictures)


@pytest.mark.parametrize("robots", [1, 2])
def test_time_scale_waits(robots: int, monkeypatch: pytest.MonkeyPatch) -> None:
    """Each move is followed by a sleep of time_scale real seconds per simulated second, one robot or a fleet."""
    slept: list[float] = []
    monkeypatch.setattr(time, "sleep", slept.append)  # recorded, not waited
    result = run_demo(steps=2, robots=robots, time_scale=0.05, picture=None, emit=lambda _: None)
    assert len(result.moves) == 2 * robots and all(m.elapsed > 0 for m in result.moves)
    assert sorted(slept) == sorted(0.05 * m.elapsed for m in result.moves)
    slept.clear()
    run_demo(steps=2, robots=robots, time_scale=0, picture=None, emit=lambda _: None)
    assert slept == []  # 0: as fast as possible


def test_demo_command(tmp_path: Path) -> None:
    picture = tmp_path / "demo.png"
    result = CliRunner().invoke(cli, ["demo", "--steps", "2", "--robots", "2", "--seed", "1", "--picture", str(picture)])
    assert result.exit_code == 0, result.output
    assert "Step 2" in result.output and "Robot2" in result.output and "decision:" in result.output
    assert picture.read_bytes().startswith(PNG_MAGIC)


def test_map_command_draws_the_reasoned_map(tmp_path: Path) -> None:
    files = [str(f) for f in default_map_files()]
    out = tmp_path / "map.svg"
    result = CliRunner().invoke(cli, ["map", *files, "-o", str(out)])
    assert result.exit_code == 0, result.output
    assert "<svg" in out.read_text()
    view = MapView.from_ontology(Ontology.from_file(*files))
    assert (view.corridors, view.rooms, view.doors) == (["C1"], ["R1", "R2"], ["D1", "D2"])
    assert view.urgent == {"R1"} and view.robots == {"Robot1": "C1"}
    assert view.connected == {frozenset({"C1", "R1"}), frozenset({"C1", "R2"})}


def test_picture_needs_a_known_format(tmp_path: Path) -> None:
    from topostore.errors import TopostoreError

    with pytest.raises(TopostoreError, match="png"):
        draw_ontology(Ontology.from_file(*default_map_files()), tmp_path / "map.bmp")


def test_policy() -> None:
    rng = random.Random(0)
    corridors = {"C1", "C2"}
    d = decide("C1", ["R1", "R2", "C2"], ["R1", "R2"], corridors, {"R1": 90, "R2": 80}, 100, rng)
    assert (d.destination, d.urgent) == ("R2", True)  # the most neglected urgent location
    d = decide("R1", ["C1", "R3"], [], corridors, {}, 100, rng)
    assert d.destination == "C1" and not d.urgent  # stay mostly in corridors
    d = decide("R1", ["R3"], [], corridors, {}, 100, rng)
    assert d.destination == "R3"
    assert decide("R1", [], ["R2"], corridors, {}, 100, rng).destination is None
