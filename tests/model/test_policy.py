"""The policy's classes: how a trial's two runs are classified by which robots passed."""

from __future__ import annotations

import pytest

from pytest_lasertest.model.policy import classify


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
