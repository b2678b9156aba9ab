"""A clock flip's scanned candidates outside the window's span left out (topostore.reason.look_flip):
the answers stay those from scratch at the span's ends, for other spellings and past the integer bound."""

from __future__ import annotations

from unittest import mock

from test_incremental import N, assert_same_as_scratch, new_map, set_clock
from test_window import rule_with

from topostore.compile import condition
from topostore.demo.mapgen import generate
from topostore.reason import look_flip, window


def test_overflow_free_takes_bounded_linear_tests_only() -> None:
    names = frozenset({"t", "v", "h"})
    chain = rule_with(condition.bind("(?t - ?v)", "?d"), condition.test("?d > ?h"))
    assert window.overflow_free(chain, "t", names)
    assert not window.overflow_free(chain, "t", frozenset({"t", "v"}))  # reads a value not checked
    assert not window.overflow_free(rule_with(condition.test(f"?t - ?v > {2 ** 61}")), "t", names)
    assert not window.overflow_free(rule_with(condition.test("?t * ?v > ?h")), "t", names)
    doubled = "(" + " + ".join(["?t"] * 9) + ")"
    nested = [condition.bind(doubled, "?a")] + [condition.bind(f"(?{chr(97 + k)} + ?{chr(97 + k)} + ?{chr(97 + k)})",
                                                               f"?{chr(98 + k)}") for k in range(12)]
    assert not window.overflow_free(rule_with(*nested, condition.test("?m > ?h")), "t", names)  # 9·3**12 > 2**20
    assert window.overflow_free(rule_with(condition.test("?v > ?h")), "t", names)  # does not read t


def _outside_spy():
    calls: list[bool] = []
    outside = look_flip.Flipped._outside

    def spy(self, solution, olds, spans):
        found = outside(self, solution, olds, spans)
        calls.append(found)
        return found
    return calls, spy


def test_a_clock_crossing_a_visit_times_threshold_is_decided_at_the_spans_ends() -> None:
    """The clock moved forward and back so that one location's ``now - visitedAt`` crosses the threshold by
    one: that location is at an end of the span (decided, not skipped), the others mostly outside."""
    onto = new_map(8, 2, True)
    onto.max_change_share = 1.0
    onto.reason()
    m = generate(8, seed=2)
    edge = m.visited_at["R1"] + m.threshold
    calls, spy = _outside_spy()
    with mock.patch.object(look_flip.Flipped, "_outside", spy):
        for now in (edge, edge + 1, edge, edge + 1, edge + 40, edge - 1, edge + 1, edge - 60):
            set_clock(onto, "Robot1", now)
            assert onto.reason().stats.program == "compiled"
            assert_same_as_scratch(onto)
    assert any(calls) and not all(calls)


def test_other_spellings_and_values_past_the_bound_are_decided() -> None:
    """A decimal clock, a decimal visit time and values past the integer bound are never skipped (their
    span is not computed in ints); the threshold changed between REASONs changes the span."""
    onto = new_map(8, 2, True)
    onto.max_change_share = 1.0
    onto.reason()
    m = generate(8, seed=2)
    edge = m.visited_at["R2"] + m.threshold
    onto.replace(N("R3"), N("visitedAt"), onto.value(f"{edge - m.threshold}.5", "decimal"))
    onto.reason()
    calls, spy = _outside_spy()
    with mock.patch.object(look_flip.Flipped, "_outside", spy):
        for value in (onto.value(f"{edge + 1}.0", "decimal"), onto.value(edge, "long"), onto.value(edge + 1, "integer")):
            onto.replace(N("Robot1"), N("now"), value)
            assert onto.reason().stats.program == "compiled"
            assert_same_as_scratch(onto)
        for k, visited in enumerate((2 ** 41, 2 ** 41 + 5, 2 ** 41 - 3)):
            onto.replace(N(f"C{k + 1}"), N("visitedAt"), onto.value(visited, "integer"))
        onto.reason()
        for now in (2 ** 41 + 5 + m.threshold, 2 ** 41 + 6 + m.threshold, edge):
            set_clock(onto, "Robot1", now)
            onto.reason()
            assert_same_as_scratch(onto)
    assert calls


def test_a_visit_time_whose_difference_overflows_in_one_state_is_decided() -> None:
    """``now - visitedAt`` past 64 bits before the move (an error: not urgent) and within them after it
    (urgent): far outside the span, yet it flips; its value past the bound keeps it from being skipped."""
    onto = new_map(8, 2, True)
    onto.max_change_share = 1.0
    onto.reason()
    onto.replace(N("C1"), N("visitedAt"), onto.value(-(2 ** 62), "integer"))
    set_clock(onto, "Robot1", 2 ** 62 + 10)
    onto.reason()
    assert_same_as_scratch(onto)
    set_clock(onto, "Robot1", 2 ** 62 - 10)
    assert onto.reason().stats.program == "compiled"
    assert_same_as_scratch(onto)
