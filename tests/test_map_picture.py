"""`topostore map` and the structural layout at 3, 200 and 10,000 locations, with no SciPy or networkx."""

from __future__ import annotations

import math
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest
from click.testing import CliRunner

from topostore import Ontology
from topostore.cli.group import cli
from topostore.demo import mapgen
from topostore.demo.layout import adjacency, layout
from topostore.demo.mapview import MapView, Style, draw
from topostore.resources import default_ontology, default_ontology_files

PNG_MAGIC = b"\x89PNG\r\n\x1a\n"


def saved_map(path: Path, n: int, robots: int = 1) -> Path:
    onto = Ontology.from_file(default_ontology())
    onto.add(*mapgen.generate(n, seed=4, robots=robots).triples())
    onto.save(path)
    return path


def view_of(m: mapgen.TopoMap) -> MapView:
    """What the reasoner concludes about a generated map, written down from its construction."""
    _, neighbours = adjacency(m.has_door)
    return MapView(corridors=list(m.corridors), rooms=list(m.rooms), doors=list(m.doors), has_door=list(m.has_door),
                   connected={frozenset((a, b)) for a, near in neighbours.items() for b in near},
                   urgent={loc for loc, t in m.visited_at.items() if m.now - t > m.threshold}, robots=dict(m.robots))


def test_map_command_example(tmp_path: Path) -> None:
    files = [str(f) for f in default_ontology_files()]
    out = tmp_path / "m.png"
    result = CliRunner().invoke(cli, ["map", *files, "-o", str(out), "--title", "example"])
    assert result.exit_code == 0, result.output
    assert result.output == f"Wrote {out}\n"
    assert out.read_bytes().startswith(PNG_MAGIC)
    plain = tmp_path / "plain.svg"
    result = CliRunner().invoke(cli, ["map", *files, "-o", str(plain), "--no-robots", "--no-urgent"])
    assert result.exit_code == 0, result.output
    svg = plain.read_text()
    assert "Robot1" not in svg and "URGENT" not in svg and "CORRIDOR" in svg


def test_map_command_200_locations_unclustered(tmp_path: Path) -> None:
    path = saved_map(tmp_path / "m200.ttl", 200, robots=2)
    out = tmp_path / "m200.svg"
    result = CliRunner().invoke(cli, ["map", str(path), "-o", str(out)])
    assert result.exit_code == 0, result.output
    svg = out.read_text()
    for name in ("C1", "C40", "R1", "R160", "Robot1", "Robot2"):
        assert f"<!-- {name} -->" in svg  # matplotlib writes each text's string as a comment


def test_layout_200_corridors_are_a_spine_and_rooms_surround_them() -> None:
    m = mapgen.generate(200, seed=4)
    placed = layout(m.corridors, m.rooms, m.has_door)
    assert not placed.clustered
    assert len(placed.positions) == 200 and len(set(placed.positions.values())) == 200
    order = [g.corridor for g in placed.groups]
    assert order == m.corridors  # a chain C1-C2-...-C40 is walked in order
    steps = {round(math.dist(placed.positions[a], placed.positions[b]), 6) for a, b in zip(order, order[1:])}
    assert len(steps) == 1  # consecutive corridors are neighbours in the picture, on the snake
    for g in placed.groups:
        for room in g.rooms:
            assert room in m.neighbours(g.corridor)
            assert math.dist(placed.positions[room], placed.positions[g.corridor]) == pytest.approx(1.0)
    assert set(placed.doors) == set(m.doors)


def test_rooms_behind_rooms_and_unreachable_locations_are_placed() -> None:
    has_door = [("C1", "D1"), ("C1", "D2"), ("R1", "D1"), ("R1", "D3"), ("R2", "D3"), ("X", "D9")]
    placed = layout(["C1"], ["R1", "R2", "X"], has_door)
    assert [(g.corridor, g.rooms) for g in placed.groups] == [("C1", ["R1", "R2"]), (None, ["X"])]
    assert set(placed.positions) == {"C1", "R1", "R2", "X"}
    assert placed.doors["D3"] == pytest.approx(tuple((a + b) / 2 for a, b in zip(placed.positions["R1"],
                                                                                    placed.positions["R2"])))


def test_10000_locations_clustered(tmp_path: Path) -> None:
    m = mapgen.generate(10_000, seed=4, robots=2)
    view = view_of(m)
    out = draw(view, tmp_path / "m10000.png", "10,000 locations")  # its time: python -m benchmarks.picture
    assert out.read_bytes().startswith(PNG_MAGIC)
    placed = layout(view.corridors, view.rooms, view.has_door)
    assert placed.clustered and placed.clusters is not None
    assert 100 <= len(placed.clusters) <= 150
    assert sorted(m for c in placed.clusters for m in c.members) == sorted(view.locations)
    assert placed.clusters[0].label == "C1–C14"


def test_cluster_threshold_is_a_choice(tmp_path: Path) -> None:
    m = mapgen.generate(60, seed=1)
    out = draw(view_of(m), tmp_path / "c.svg", style=Style(cluster_above=10))
    assert "clusters" in out.read_text()


def test_no_scipy_or_networkx_needed(tmp_path: Path) -> None:
    """The picture that used to need SciPy from ~250 nodes is drawn with both made unimportable."""
    script = textwrap.dedent(f"""
        import sys
        sys.modules["scipy"] = None
        sys.modules["networkx"] = None
        from topostore.demo import mapgen
        from topostore.demo.mapview import MapView, draw
        m = mapgen.generate(300, seed=1)
        view = MapView(corridors=m.corridors, rooms=m.rooms, doors=m.doors, has_door=m.has_door)
        print(draw(view, {str(tmp_path / 'm300.png')!r}))
    """)
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    assert (tmp_path / "m300.png").read_bytes().startswith(PNG_MAGIC)


def test_demo_on_a_big_map_draws(tmp_path: Path) -> None:
    path = saved_map(tmp_path / "m260.ttl", 260)  # networkx needed SciPy from about 250
    out = tmp_path / "demo.png"
    result = CliRunner().invoke(cli, ["demo", "--map", str(path), "--steps", "1", "--picture", str(out)])
    assert result.exit_code == 0, result.output
    assert out.read_bytes().startswith(PNG_MAGIC)
