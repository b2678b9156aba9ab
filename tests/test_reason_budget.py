"""One REASON, one budget (topostore.reason.limits): nested blocks share the outer budget, and leaving the
outer block, by an error too, leaves no budget running."""

from __future__ import annotations

import pytest

from topostore.reason import limits
from topostore.reason.limits import ReasonLimitExceeded, ReasonLimits


def test_a_nested_block_keeps_the_outer_budget_and_the_outer_one_ends_it() -> None:
    with limits.budget(ReasonLimits(max_rounds=2)) as outer:
        with limits.budget(ReasonLimits(max_rounds=100)) as inner:
            assert inner is outer
            limits.tick()
        limits.tick()  # the inner block's end did not end the budget: its rounds count on
        assert outer.rounds == 2
        with pytest.raises(ReasonLimitExceeded):
            limits.tick()
    limits.tick()  # outside any block: nothing counts, nothing stops
    with limits.budget(ReasonLimits()) as fresh:
        assert fresh is not outer and fresh.rounds == 0


def test_a_block_left_by_an_error_leaves_no_budget_running() -> None:
    with pytest.raises(RuntimeError), limits.budget(ReasonLimits(max_rounds=1)):
        limits.tick()
        raise RuntimeError("stop")
    limits.tick()
    limits.tick()  # over the old budget's rounds: it is gone
    with limits.budget(ReasonLimits()) as fresh:
        assert fresh.rounds == 0
