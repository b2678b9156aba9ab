"""The floor of a full REASON (benchmarks.full_floor) derives exactly what topostore infers, and says so when not."""

from __future__ import annotations

from pathlib import Path

import pytest
from pyoxigraph import RdfFormat, Store

from benchmarks import full_floor, full_floor_closure, maps


def _floors_against_topostore(path: Path, work: Path) -> dict[str, tuple[list[str], list[str]]]:
    dumps = {part: work / f"{part}.nt" for part in full_floor.PARTS}
    for part, run in full_floor.PARTS.items():
        run(path, 1, dumps[part])
    return {part: full_floor.differences(dumps[part], dumps["topostore"]) for part in ("sparql", "python")}


@pytest.mark.parametrize("size", ["example", "200"])
def test_both_floors_derive_topostores_inferred_graph(size: str, tmp_path: Path) -> None:
    path, _ = maps.write(size, tmp_path, RdfFormat.N_TRIPLES)
    for part, (only_floor, only_topostore) in _floors_against_topostore(path, tmp_path).items():
        assert (only_floor, only_topostore) == ([], []), part


def test_a_floor_missing_a_rule_is_reported(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    path, _ = maps.write("40", tmp_path, RdfFormat.N_TRIPLES)
    rules = [r for r in full_floor_closure.RULES if r[0] != "Reachability"]
    monkeypatch.setattr(full_floor_closure, "RULES", rules)
    only_floor, only_topostore = _floors_against_topostore(path, tmp_path)["sparql"]
    assert only_floor == []
    assert only_topostore and all("canReach" in line for line in only_topostore)


def test_what_the_floor_does_not_model_is_refused(tmp_path: Path) -> None:
    path, _ = maps.write("20", tmp_path, RdfFormat.N_TRIPLES)
    store = Store()
    store.bulk_load(path=str(path), format=RdfFormat.N_TRIPLES)
    store.update(f"INSERT DATA {{ <{maps.MAP_NS}Robot1> <{maps.MAP_NS}isIn> <{maps.MAP_NS}R1> }}")
    with pytest.raises(full_floor_closure.OutsideModel, match="robot in two places"):
        full_floor_closure.refuse_outside(store)


def test_the_floor_runs_another_round_when_the_closing_update_adds(tmp_path: Path) -> None:
    """An asserted connectedTo to a place nothing else types: its LOCATION comes from the closing update,
    so the rules run again, and the closure is still topostore's."""
    path, bench = maps.write("20", tmp_path, RdfFormat.N_TRIPLES)
    with path.open("a") as out:
        out.write(f"<{maps.MAP_NS}{bench.start}> <{maps.MAP_NS}connectedTo> <{maps.MAP_NS}Elsewhere> .\n")
    assert full_floor.part_sparql(path, 1, None)["rounds"] == 2
    for part, (only_floor, only_topostore) in _floors_against_topostore(path, tmp_path).items():
        assert (only_floor, only_topostore) == ([], []), part
