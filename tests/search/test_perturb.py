"""The Hypothesis search around a witness, driven with trials that need no simulator."""

from __future__ import annotations

from pathlib import Path

import pytest

from pytest_lasertest.search.budgets import Budget
from pytest_lasertest.search.offsets import AXES, Offset, OffsetBox, Untested
from pytest_lasertest.search.perturb import search

BOX = OffsetBox(Offset(-0.1, -0.1, -0.2, 0.0, -0.05), Offset(0.1, 0.1, 0.2, 0.02, 0.1))
BUDGET = Budget(examples=50, shrink_simulations=1000, explain=False)


class Failed(Exception):
    """What the fake trials raise for a failing offset."""


class Recorder:
    """A trial that fails beyond `threshold` on x, and remembers every offset it was given."""

    def __init__(self, threshold: float = 0.05) -> None:
        self.threshold = threshold
        self.seen: list[Offset] = []

    def __call__(self, offset: Offset) -> str:
        self.seen.append(offset)
        if offset.x > self.threshold:
            raise Failed(offset)
        return "passed"


def run(trial: Recorder, database: Path | None = None, key: str = "item", seed: int = 0) -> object:
    return search(BOX, trial, Failed, BUDGET, key=key, seed=seed, database=database).failure


def test_the_witness_itself_is_the_first_offset_tried() -> None:
    trial = Recorder()
    run(trial)
    assert trial.seen[0] == Offset()


def test_every_offset_drawn_lies_inside_the_box() -> None:
    trial = Recorder(threshold=1.0)
    run(trial)
    assert len(trial.seen) == BUDGET.examples
    for offset in trial.seen:
        for name in AXES:
            low, high = BOX.bounds(name)
            assert low <= offset.axis(name) <= high


def test_a_failure_shrinks_to_the_witness_plus_the_smallest_change_that_fails() -> None:
    failure = run(Recorder(threshold=0.05))
    assert isinstance(failure, Failed)
    (offset,) = failure.args
    # Hypothesis shrinks floats toward simple ones (here 1/16), not to the exact threshold.
    assert 0.05 < offset.x < 0.07
    assert [offset.axis(name) for name in AXES if name != "x"] == [0.0] * 4


def test_a_search_that_finds_nothing_returns_no_failure() -> None:
    assert run(Recorder(threshold=1.0)) is None


def test_a_stored_failure_is_the_first_offset_tried_on_the_next_search(tmp_path: Path) -> None:
    first = Recorder()
    failure = run(first, tmp_path)
    assert isinstance(failure, Failed)
    second = Recorder()
    run(second, tmp_path, seed=1)
    assert second.seen[0] == failure.args[0]
    assert len(second.seen) < len(first.seen)


def test_each_item_replays_only_its_own_failures(tmp_path: Path) -> None:
    run(Recorder(), tmp_path, key="paper.lasertest.yaml::size[candidate-misses-0]")
    other = Recorder()
    run(other, tmp_path, key="paper.lasertest.yaml::size[candidate-misses-1]")
    assert other.seen[0] == Offset()


def test_the_same_seed_tries_the_same_offsets() -> None:
    first, second = Recorder(threshold=1.0), Recorder(threshold=1.0)
    run(first, seed=7)
    run(second, seed=7)
    assert first.seen == second.seen


def test_untested_offsets_are_rejected_and_never_fail_the_search() -> None:
    seen: list[Offset] = []

    def trial(offset: Offset) -> str:
        seen.append(offset)
        if offset.y > 0.0:
            raise Untested("rejected: no longer discriminating")
        return "passed"

    outcome = search(BOX, trial, Failed, BUDGET, key="item", seed=0, database=None)
    assert outcome.failure is None
    assert any(offset.y > 0.0 for offset in seen)
    assert "rejected: no longer discriminating" in outcome.statistics


def test_a_box_of_zero_width_tries_the_witness_alone() -> None:
    trial = Recorder(threshold=1.0)
    search(OffsetBox(Offset(), Offset()), trial, Failed, BUDGET, key="k", seed=0, database=None)
    assert set(trial.seen) == {Offset()}


def test_an_unexpected_error_in_a_trial_propagates() -> None:
    def trial(offset: Offset) -> str:
        raise ZeroDivisionError

    with pytest.raises(ZeroDivisionError):
        search(BOX, trial, Failed, BUDGET, key="k", seed=0, database=None)


def test_the_statistics_count_each_outcome() -> None:
    outcome = search(BOX, Recorder(threshold=1.0), Failed, BUDGET, key="k", seed=0, database=None)
    assert "passed" in outcome.statistics
    assert f"{BUDGET.examples} passing" in outcome.statistics


def test_a_search_whose_every_draw_is_rejected_ends_without_a_failure() -> None:
    def refuse(offset: Offset) -> str:
        raise Untested("rejected: no longer discriminating")

    outcome = search(BOX, refuse, Failed, BUDGET, key="item", seed=0, database=None)
    assert outcome.failure is None


def test_the_same_seed_tries_the_same_offsets_whatever_modules_the_process_imported(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    # Hypothesis draws some floats from constants it reads in every local module imported so
    # far; which those are depends on what ran before in the process (Nav2 before move_base,
    # pytest-xdist's distribution). A module full of constants inside the box must change nothing.
    before = Recorder(threshold=1.0)
    run(before, seed=3)
    constants = ", ".join(f"{0.001 * k:.3f}" for k in range(1, 100))
    (tmp_path / "lasertest_constants_probe.py").write_text(f"VALUES = ({constants})\n")
    monkeypatch.syspath_prepend(str(tmp_path))
    __import__("lasertest_constants_probe")
    after = Recorder(threshold=1.0)
    run(after, seed=3)
    assert after.seen == before.seen
