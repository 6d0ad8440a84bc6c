"""A controller's own goal tolerance and stuck window: the oracles judge the run by them, and
one that is not a positive number fails the drive, named."""

from __future__ import annotations

import math

import pytest

from pytest_lasertest.model.geometry import Point2D, Pose2D
from pytest_lasertest.model.robot import Robot
from pytest_lasertest.nav.protocol import LaserScan, Odometry
from pytest_lasertest.pairsfile import load_pairs_file
from pytest_lasertest.sim.scenario import ControllerError, Scenario, run_scenario
from tests.helpers import EXAMPLES

PAPER = load_pairs_file(EXAMPLES / "paper.lasertest.yaml")
PROFILE = PAPER.pairs[0].baseline.profile
GOAL = (Point2D(3.0, 0.0),)


class StopsShort:
    """Drives straight at the goal and stops 0.4 m before it."""

    def __init__(self, tolerance: object) -> None:
        if tolerance is not None:
            self.goal_tolerance = tolerance

    def observe(self, scan: LaserScan, odometry: Odometry, time: float) -> tuple[float, float]:
        return (0.5, 0.0) if math.dist((odometry.x, odometry.y), (3.0, 0.0)) > 0.4 else (0.0, 0.0)


def drive(tolerance: object) -> bool:
    """Whether the goal oracle passes the run of a StopsShort declaring `tolerance`."""

    def make(robot: Robot, route: tuple[Point2D, ...]) -> StopsShort:
        return StopsShort(tolerance)

    scenario = Scenario(PAPER.robot, PROFILE, (), Pose2D(0.0, 0.0, 0.0), GOAL, 12.0, seed=0)
    return run_scenario(scenario, make).verdicts.goal.passed


def test_a_controller_that_counts_half_a_metre_as_arrived_is_judged_by_it() -> None:
    assert drive(0.5)
    assert not drive(None)  # the rules' 0.2 m


@pytest.mark.parametrize("tolerance", [0.0, -0.2, math.inf, math.nan, "far", True])
def test_a_goal_tolerance_that_is_not_a_positive_number_of_metres_fails_the_drive(
    tolerance: object,
) -> None:
    with pytest.raises(ControllerError, match="goal_tolerance"):
        drive(tolerance)


class Pauses:
    """Stands for the first 15 s, then drives to the goal; declares `stuck_window`."""

    def __init__(self, window: object) -> None:
        self.stuck_window = window

    def observe(self, scan: LaserScan, odometry: Odometry, time: float) -> tuple[float, float]:
        return (0.0, 0.0) if time < 15.0 else (0.5, 0.0)


def pause(window: object) -> bool:
    """Whether the stuck oracle passes the run of a Pauses declaring `window`."""

    def make(robot: Robot, route: tuple[Point2D, ...]) -> Pauses:
        return Pauses(window)

    scenario = Scenario(PAPER.robot, PROFILE, (), Pose2D(0.0, 0.0, 0.0), GOAL, 25.0, seed=0)
    return run_scenario(scenario, make).verdicts.stuck.passed


def test_a_controller_that_still_tries_for_20_s_is_not_judged_stuck_within_them() -> None:
    assert pause(20.0)
    assert not pause(None)  # the rules' 10 s
    assert not pause(5.0)  # never shorter than the rules'


@pytest.mark.parametrize("window", [0.0, -1.0, math.inf, math.nan, "long", False])
def test_a_stuck_window_that_is_not_a_positive_number_of_seconds_fails_the_drive(
    window: object,
) -> None:
    with pytest.raises(ControllerError, match="stuck_window"):
        pause(window)


class TicksFast(StopsShort):
    """StopsShort with a clock that asks for a call a billion times a second."""

    control_frequency = 1.0e9

    def __init__(self) -> None:
        super().__init__(None)
        self.calls = 0

    def observe(self, scan: LaserScan, odometry: Odometry, time: float) -> tuple[float, float]:
        self.calls += 1
        return super().observe(scan, odometry, time)


def test_a_controller_clock_faster_than_the_physics_is_called_once_a_step_without_hanging() -> None:
    made: list[TicksFast] = []

    def make(robot: Robot, route: tuple[Point2D, ...]) -> TicksFast:
        made.append(TicksFast())
        return made[0]

    scenario = Scenario(PAPER.robot, PROFILE, (), Pose2D(0.0, 0.0, 0.0), GOAL, 2.0, seed=0)
    run_scenario(scenario, make)
    # 2 s of 0.02 s steps: a call at each, not a billion a second.
    assert 100 <= made[0].calls <= 102
