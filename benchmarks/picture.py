"""Drawing the reasoned map: ``python -m benchmarks.picture``.

The picture `topostore demo` and `topostore map` draw, timed apart from reasoning: a generated
corridor/room map is written down as what the reasoner concludes about it (the view
``tests/test_map_picture.py`` checks), then laid out and drawn to PNG and SVG.  Above the cluster
threshold (400 locations) corridors and their rooms are drawn as clusters, so the layout and the
number of drawn shapes change there.  Needs the ``viz`` extra (matplotlib).

    python -m benchmarks.picture                     # 200, 1,000 and 10,000 locations
    python -m benchmarks.picture --sizes 200 100000
"""

from __future__ import annotations

import argparse
import sys
import tempfile
import time
from pathlib import Path

SIZES = [200, 1000, 10_000]


def view_of(locations: int, seed: int = 4):
    """A generated map of ``locations`` locations and what the reasoner concludes about it."""
    from topostore.demo import mapgen
    from topostore.demo.layout import adjacency
    from topostore.demo.mapview import MapView

    m = mapgen.generate(locations, seed=seed, robots=2)
    _, neighbours = adjacency(m.has_door)
    return MapView(corridors=list(m.corridors), rooms=list(m.rooms), doors=list(m.doors), has_door=list(m.has_door),
                   connected={frozenset((a, b)) for a, near in neighbours.items() for b in near},
                   urgent={loc for loc, t in m.visited_at.items() if m.now - t > m.threshold}, robots=dict(m.robots))


def measure(locations: int) -> dict[str, float | int | bool]:
    """Seconds to lay out, and to lay out and draw to PNG and to SVG, one map; the picture's size."""
    from topostore.demo.layout import layout
    from topostore.demo.mapview import draw

    view = view_of(locations)
    start = time.perf_counter()
    placed = layout(view.corridors, view.rooms, view.has_door)
    row: dict[str, float | int | bool] = {"locations": locations, "layout_s": time.perf_counter() - start,
                                          "clustered": placed.clustered}
    with tempfile.TemporaryDirectory() as tmp:
        for fmt in ("png", "svg"):
            start = time.perf_counter()
            out = draw(view, Path(tmp) / f"map.{fmt}", f"{locations} locations")
            row[f"{fmt}_s"] = time.perf_counter() - start
            row[f"{fmt}_kib"] = out.stat().st_size // 1024
    return row


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(prog="python -m benchmarks.picture", description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--sizes", type=int, nargs="*", default=SIZES, help="numbers of locations (default 200 1000 10000)")
    args = p.parse_args(argv)
    measure(20)  # matplotlib's import and font cache belong to no row
    print("| locations | clustered | layout | layout + PNG | layout + SVG | PNG size | SVG size |")
    print("|---|---|---|---|---|---|---|")
    for n in args.sizes:
        r = measure(n)
        print(f"| {n:,} | {'yes' if r['clustered'] else 'no'} | {r['layout_s']:.2f} s | {r['png_s']:.2f} s "
              f"| {r['svg_s']:.2f} s | {r['png_kib']:,} KiB | {r['svg_kib']:,} KiB |", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
