"""The keys a staged compiled step tells it changed, and what the reads after it decide from them (see
topostore.reason.change_checks.ChangeChecks.after_step): supersets of the changed graphs' keys, so that a
check or a negated premise they rule out is one the changed graphs rule out too."""

from __future__ import annotations

from unittest import mock

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from profiles import property_examples
from test_incremental import assert_same_as_scratch, batches, new_map, robot_step

from topostore.reason import change_checks, staged_code
from topostore.reason.scratch import NEW_FACTS, OVERDELETED


def _keys(census: tuple[dict, dict]) -> tuple[set, set]:
    return set(census[0]), set(census[1])


class _Spy:
    """Checks, after every staged run, that its keys cover NEW_FACTS and OVERDELETED, and, at the reads
    after it, that what the keys decide the changed graphs decide too."""

    def __init__(self) -> None:
        self.runs = self.decided = 0
        self._run = staged_code.run
        self._negated = change_checks.ChangeChecks.negated_match
        self._possible = change_checks.ChangeChecks.violation_possible

    def run(self, run):  # noqa: ANN001, ANN201 - staged_code.run's own
        out = self._run(run)
        gained, lost = run.gained(), run.lost()
        if gained is not None and lost is not None:
            self.runs += 1
            new, gone = change_checks.step_keys(gained), change_checks.step_keys(lost)
            if new is None or gone is None:
                return out
            made, removed = (_keys(run.store.census(g)) for g in (NEW_FACTS, OVERDELETED))
            assert made[0] <= new[0] and made[1] <= new[1], (made, gained)
            assert removed[0] <= gone[0] and removed[1] <= gone[1], (removed, lost)
        return out

    def negated_match(self, checks: change_checks.ChangeChecks) -> bool:
        step = checks._step
        if step is not None and checks.negated and not step[0]:
            self.decided += 1
            assert checks._after()[0] == ""  # the changed graphs start no negated-premise group either
        return self._negated(checks)

    def violation_possible(self, checks: change_checks.ChangeChecks) -> bool:
        step = checks._step
        if step is not None and not step[1]:
            _, fixed, ranged = checks._after()
            assert not fixed and set(ranged) <= set(step[2])
        return self._possible(checks)

    def __enter__(self) -> _Spy:
        spy = self
        self._patches = [
            mock.patch.object(staged_code, "run", self.run),
            mock.patch.object(change_checks.ChangeChecks, "negated_match", lambda c: spy.negated_match(c)),
            mock.patch.object(change_checks.ChangeChecks, "violation_possible", lambda c: spy.violation_possible(c)),
        ]
        for p in self._patches:
            p.start()
        return self

    def __exit__(self, *exc: object) -> None:
        for p in reversed(self._patches):
            p.stop()


def test_an_ordinary_robot_step_decides_its_reads_from_the_step_keys() -> None:
    """A robot step's keys start no negated-premise group and range checks only: the changed graphs are
    not counted for them (no shape of the change is made) unless the run sent SPARQL text, whose keys are
    not told; the answers stay exact."""
    onto = new_map(6, 2, True)
    onto.reason()
    told = []
    counted = []
    run, shape = staged_code.run, change_checks.shape

    def spy_run(r):  # noqa: ANN001, ANN202
        out = run(r)
        told.append(r.gained() is not None and r.lost() is not None)
        return out

    def spy_shape(*args):  # noqa: ANN002, ANN202
        counted.append(len(told))
        return shape(*args)

    with mock.patch.object(staged_code, "run", spy_run), mock.patch.object(change_checks, "shape", spy_shape):
        for k, where in enumerate(["R1", "C1", "R2", "C2", "R1", "C1", "R2", "C2"]):
            robot_step(onto, where, 1665579750 + 300 * k)
            assert_same_as_scratch(onto)
            assert onto.report.stats.program == "compiled"
    assert len(told) == 8 and sum(told) >= 5
    assert all(not told[n - 1] for n in counted)  # counted only after a run whose keys were not told


@settings(max_examples=property_examples(40), deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(n=st.integers(1, 6), seed=st.integers(0, 3), declared=st.booleans(), steps=batches)
def test_the_step_keys_cover_the_changed_graphs(n: int, seed: int, declared: bool, steps: list) -> None:
    """Whatever the manipulations (inconsistent ones, differences, doors), a staged run's keys cover the keys
    of its changed graphs, and what they rule out the changed graphs rule out."""
    onto = new_map(n, seed, declared)
    assert_same_as_scratch(onto)
    with _Spy():
        for batch in steps:
            for op, *args in batch:
                op(onto, *args)
            assert_same_as_scratch(onto)
