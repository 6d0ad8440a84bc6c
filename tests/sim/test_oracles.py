"""The referee: when a run is stuck, how far it got along its route, its first contact and least
clearance, and when it reached the goal."""

from __future__ import annotations

import math

import pytest

from pytest_lasertest.model.geometry import Point2D
from pytest_lasertest.sim.oracles import Referee, Rules, Stuck

ORIGIN = Point2D(0.0, 0.0)
GOAL = (Point2D(10.0, 0.0),)


def test_the_referee_says_stuck_after_a_whole_window_without_progress() -> None:
    rules = Rules(stuck_distance=0.1, stuck_window=1.0)
    referee = Referee(rules, ORIGIN, GOAL, time_step=0.1)
    decided = [referee.update(0.1 * step, 2.0, 0.0, 0.5, False) for step in range(1, 12)]
    assert decided == [False] * 10 + [True]
    stuck = referee.verdicts().stuck
    assert stuck.time == pytest.approx(1.1)
    assert stuck.margin == pytest.approx(-0.1)


def test_the_referee_measures_progress_along_the_route_through_its_waypoints() -> None:
    route = (Point2D(5.0, 0.0), Point2D(5.0, 5.0))
    referee = Referee(Rules(stuck_window=0.2), ORIGIN, route, time_step=0.1)
    # Driving away from the goal's straight line but along the route still counts as progress.
    for step, x in enumerate((1.0, 2.0, 3.0, 4.0)):
        referee.update(0.1 * (step + 1), x, 0.0, 0.5, False)
    verdicts = referee.verdicts()
    assert verdicts.stuck.passed
    assert verdicts.stuck.least_progress == pytest.approx(2.0)
    assert verdicts.goal.nearest == pytest.approx(math.hypot(1.0, 5.0))


def test_the_referee_keeps_the_first_contact_and_the_least_clearance() -> None:
    referee = Referee(Rules(), ORIGIN, GOAL, time_step=0.1)
    referee.update(0.1, 0.0, 0.0, 0.3, False)
    assert referee.update(0.2, 0.1, 0.0, -0.002, True)
    referee.update(0.3, 0.1, 0.0, 0.1, True)
    collision = referee.verdicts().collision
    assert collision.time == pytest.approx(0.2)
    assert collision.margin == pytest.approx(-0.002)
    assert not collision.passed
    assert "collided at t = 0.20 s" in collision.describe()


def test_the_referee_says_the_goal_is_reached_within_its_tolerance() -> None:
    referee = Referee(Rules(goal_tolerance=0.2), ORIGIN, GOAL, time_step=0.1)
    assert not referee.update(0.1, 9.7, 0.0, 0.5, False)
    assert referee.update(0.2, 9.85, 0.0, 0.5, False)
    goal = referee.verdicts().goal
    assert goal.passed
    assert goal.margin == pytest.approx(0.05)


def test_a_stuck_verdict_shows_its_progress_to_the_millimetre_so_it_never_reads_as_enough() -> None:
    stuck = Stuck(time=38.5, least_progress=0.09999, distance=0.1, window=30.0)
    assert stuck.describe() == "stuck at t = 38.50 s: 99.9 mm of progress in 30 s, 100 mm needed"
    stuck = Stuck(time=38.5, least_progress=0.0937, distance=0.1, window=30.0)
    assert stuck.describe() == "stuck at t = 38.50 s: 93.7 mm of progress in 30 s, 100 mm needed"
