"""The floor of a robot step's REASON (benchmarks.step_floor) gives topostore's answers, and says so when not."""

from __future__ import annotations

import pytest

from benchmarks import step_floor

#: every test twice: the compiled step's staged runs generated and interpreted (reason/staged_code.py)
pytestmark = pytest.mark.usefixtures("staged_form")


@pytest.mark.parametrize("size", ["example", "8"])
def test_the_floor_answers_as_topostore(size: str) -> None:
    times = step_floor.measure(size, 40, warm=12)
    assert len(times) == 40 and all(t > 0 for t in times)


def test_a_floor_writing_other_facts_is_reported(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(step_floor, "URGENT", step_floor._node("NOT_URGENT"))
    with pytest.raises(AssertionError, match="differ"):
        step_floor.measure("8", 40, warm=12)
