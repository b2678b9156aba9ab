"""A robot's repeated step: what maintenance decides from the kind of a change is decided once.

The reasoner keeps, per kind of change (its added and lost read keys, its cleanly replaced
predicates) and sizes of the keys with facts, the program's signature, whether an added fact may
have been inferred and whether the completion must ask again (``KeptKinds._decide``).  These
tests check that a repeated step takes the kept answer, and that random sequences of robot steps
mixed with changes that give new keys facts (doors, second places, declarations of difference)
still equal a REASON from scratch after every step.
"""

from __future__ import annotations

from unittest import mock

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from profiles import property_examples
from test_incremental import (
    DOORS,
    NAMES,
    TIMES,
    add_door,
    assert_same_as_scratch,
    different_from,
    new_map,
    remove_door,
    robot_step,
    second_place,
)

from topostore.reason.kinds import KeptKinds


def test_a_repeated_kind_of_change_is_decided_once() -> None:
    onto = new_map(8, 0, True)
    onto.reason()
    robot_step(onto, "C1", 1665579750)
    onto.reason()  # the first step may give keys facts: the sizes the kept answer is found by settle
    with mock.patch.object(KeptKinds, "_decide", side_effect=KeptKinds._decide) as kind:
        for k, where in enumerate(["R1", "C2", "R2", "C1", "R3"]):
            robot_step(onto, where, 1665579760 + 10 * k)
            assert onto.reason().stats.program == "compiled"
    assert kind.call_count <= 1


extra = st.one_of(
    st.none(),
    st.tuples(st.just(add_door), st.sampled_from(NAMES), st.sampled_from(DOORS)),
    st.tuples(st.just(remove_door), st.integers(0, 1000)),
    st.tuples(st.just(second_place), st.sampled_from(NAMES)),
    st.tuples(st.just(different_from), st.sampled_from(NAMES), st.sampled_from(NAMES), st.booleans()),
)
step = st.tuples(st.sampled_from(NAMES), TIMES, extra)


@settings(max_examples=property_examples(40), deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(n=st.integers(2, 8), seed=st.integers(0, 3), declared=st.booleans(),
       steps=st.lists(step, min_size=2, max_size=10))
def test_repeated_steps_with_new_keys_between_equal_from_scratch(n: int, seed: int, declared: bool,
                                                                  steps: list) -> None:
    """Robot steps (one kind of change, decided once while no new key gets facts), now and then a change
    that gives a key its first facts or withdraws some: every REASON equals one from scratch."""
    onto = new_map(n, seed, declared)
    onto.max_change_share = 1.0
    assert_same_as_scratch(onto)
    for where, t, change in steps:
        robot_step(onto, where, t)
        if change is not None:
            op, *args = change
            op(onto, *args)
        assert_same_as_scratch(onto)
