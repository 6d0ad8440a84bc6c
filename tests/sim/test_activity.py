"""What a controller says it did (its `activity`): carried on the run and shown in the report
of a failing drive; an activity that is not (time, text) pairs fails the drive, named."""

from __future__ import annotations

import math

import pytest

from pytest_lasertest.model.geometry import Point2D, Pose2D
from pytest_lasertest.model.robot import Robot
from pytest_lasertest.nav.protocol import LaserScan, Odometry
from pytest_lasertest.pairsfile import load_pairs_file
from pytest_lasertest.reports.formats import activity_lines, run_line
from pytest_lasertest.sim.scenario import ControllerError, Run, Scenario, run_scenario
from tests.helpers import EXAMPLES

PAPER = load_pairs_file(EXAMPLES / "paper.lasertest.yaml")
PROFILE = PAPER.pairs[0].baseline.profile


class Hesitant:
    """Stands, and says at each second that it waited."""

    def __init__(self, activity: object = None) -> None:
        kept: list[tuple[float, str]] = []
        self._kept = kept if activity is None else None
        self.activity = kept if activity is None else activity

    def observe(self, scan: LaserScan, odometry: Odometry, time: float) -> tuple[float, float]:
        if self._kept is not None and time >= len(self._kept) + 1.0:
            self._kept.append((time, "Wait"))
        return 0.0, 0.0


def drive(activity: object = None) -> Run:
    def make(robot: Robot, route: tuple[Point2D, ...]) -> Hesitant:
        return Hesitant(activity)

    start = Pose2D(0.0, 0.0, 0.0)
    scenario = Scenario(PAPER.robot, PROFILE, (), start, (Point2D(3.0, 0.0),), 3.5, seed=0)
    return run_scenario(scenario, make)


def test_a_controllers_activity_is_carried_on_its_run_and_listed_in_its_report() -> None:
    run = drive()
    assert [what for _, what in run.activity] == ["Wait", "Wait", "Wait"]
    assert [round(time) for time, _ in run.activity] == [1, 2, 3]
    report = run_line("candidate", "sick_lms111", run)
    # The same event again and again is one entry.
    assert report.splitlines()[1].strip() == "stack did: Wait 3 times from t = 1.00 s to 3.00 s"


def test_a_report_lists_different_events_in_order_and_counts_those_past_eight() -> None:
    activity = tuple((float(time), name) for time, name in enumerate(["Spin", "Wait"] * 5))
    (line,) = activity_lines(activity)
    assert line.startswith("stack did: Spin at t = 0.00 s, Wait at t = 1.00 s, Spin at t = 2.00 s")
    assert line.endswith("Wait at t = 7.00 s, and 2 more")


def test_a_run_whose_controller_says_nothing_has_no_activity_line() -> None:
    run = drive([])
    assert run.activity == ()
    assert "\n" not in run_line("candidate", "sick_lms111", run)


@pytest.mark.parametrize(
    "activity", ["Spin", [("soon", "Spin")], [(1.0, 2.0)], [(math.nan, "Spin")], [(1.0,)], 3]
)
def test_an_activity_that_is_not_time_and_text_pairs_fails_the_drive(activity: object) -> None:
    with pytest.raises(ControllerError, match="activity"):
        drive(activity)
