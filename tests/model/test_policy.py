"""The policy's classes: how a trial's two runs are classified by which robots passed, and held
under further draws (scan noise, obstacle positions); and which classes each policy fails."""

from __future__ import annotations

import pytest

from pytest_lasertest.model.draws import redraw
from pytest_lasertest.model.obstacles import Cylinder
from pytest_lasertest.model.policy import JITTER, REDRAWS, classify, fails
from pytest_lasertest.model.seeds import noise_seed


@pytest.mark.parametrize(
    ("baseline", "candidate", "expected"),
    [
        (True, False, "regression"),
        (False, False, "pre-existing"),
        (False, True, "improvement"),
        (True, True, "unchanged"),
    ],
)
def test_a_trial_is_classified_by_which_robots_passed(
    baseline: bool, candidate: bool, expected: str
) -> None:
    assert classify(baseline, candidate) == expected


def test_a_regression_that_holds_under_every_further_draw_stays_a_regression() -> None:
    assert classify(True, False, [(True, False)] * REDRAWS) == "regression"


@pytest.mark.parametrize(
    "redrawn",
    [
        [(True, True)],  # the candidate passes under the next draw
        [(True, False), (False, False)],  # the baseline fails under the last draw
        [(True, False), (False, True)],
    ],
)
def test_a_regression_that_some_draw_undoes_is_marginal(redrawn: list[tuple[bool, bool]]) -> None:
    assert classify(True, False, redrawn) == "marginal"


@pytest.mark.parametrize(
    ("classification", "regression", "candidate"),
    [
        ("regression", True, True),
        ("marginal", False, True),
        ("pre-existing", False, True),
        ("improvement", False, False),
        ("unchanged", False, False),
    ],
)
def test_the_regression_policy_fails_only_regressions_and_the_candidate_policy_any_failure(
    classification: str, regression: bool, candidate: bool
) -> None:
    assert fails("regression", classification) is regression  # type: ignore[arg-type]
    assert fails("candidate", classification) is candidate  # type: ignore[arg-type]


def test_each_noise_draw_has_a_seed_of_its_own_and_the_first_is_the_runs() -> None:
    seeds = [noise_seed(7, draw) for draw in range(REDRAWS + 1)]
    assert seeds[0] == 7
    assert len(set(seeds)) == len(seeds)
    assert all(0 <= seed < 2**32 for seed in seeds)
    assert noise_seed(8, 1) != seeds[1]


def test_a_further_draw_is_the_same_on_every_call_and_moves_each_obstacle_within_a_centimetre() -> (
    None
):
    draw = redraw(7, 1, 3)
    assert draw == redraw(7, 1, 3)
    assert draw.noise == noise_seed(7, 1)
    assert len(draw.shifts) == 3
    assert all(abs(move) <= JITTER for shift in draw.shifts for move in shift)
    assert redraw(7, 2, 3).shifts != draw.shifts
    moved = draw.moved((Cylinder(1.0, 2.0, 0.05, 0.5),) * 3)
    assert [(obstacle.x - 1.0, obstacle.y - 2.0) for obstacle in moved] == [
        pytest.approx(shift) for shift in draw.shifts
    ]
    assert {obstacle.sides for obstacle in moved} == {(0.1, 0.1)}
