"""The Husky's drive in PyBullet: commanded twists reached within its limits, at any time step."""

from __future__ import annotations

import numpy as np
import pytest

from pytest_lasertest.model.geometry import Pose2D
from pytest_lasertest.pairsfile.bundled import bundled_robots
from pytest_lasertest.pairsfile.robot import load_robot_file
from pytest_lasertest.sim.client import PhysicsWorld
from pytest_lasertest.sim.drive import Drive, Twist

HUSKY = load_robot_file(bundled_robots()["husky"])
TIME_STEPS = (0.005, 0.01, 0.02)  # s


def driven(command: Twist, step: float, seconds: float) -> np.ndarray:
    """Time, forward speed and turn rate after each step, shape (K, 3)."""
    drive, rows = Drive(HUSKY), []
    with PhysicsWorld(Pose2D(0.0, 0.0, 0.0), (), step) as world:
        for index in range(round(seconds / step)):
            measured = Twist(*world.base_twist(world.base_pose()[2]))
            world.step(*drive.wheel_speeds(command, measured, step))
            rows.append(((index + 1) * step, *world.base_twist(world.base_pose()[2])))
    return np.array(rows)


@pytest.mark.parametrize("step", TIME_STEPS)
@pytest.mark.parametrize("speed", [0.5, 1.0, -0.3])
def test_a_straight_command_is_reached_within_one_percent_at_any_time_step(
    speed: float, step: float
) -> None:
    run = driven(Twist(speed, 0.0), step, 3.0)
    steady = run[run[:, 0] >= 2.0]
    assert steady[:, 1].mean() == pytest.approx(speed, rel=0.01)
    assert abs(steady[:, 2].mean()) < 0.01


@pytest.mark.parametrize("step", TIME_STEPS)
def test_turning_in_place_is_reached_within_three_percent_at_any_time_step(step: float) -> None:
    run = driven(Twist(0.0, 0.5), step, 5.0)
    steady = run[run[:, 0] >= 4.0]
    assert steady[:, 2].mean() == pytest.approx(0.5, rel=0.03)
    assert abs(steady[:, 1].mean()) < 0.01


@pytest.mark.parametrize("step", TIME_STEPS)
def test_the_husky_speeds_up_no_faster_than_its_acceleration_limit(step: float) -> None:
    run = driven(Twist(0.5, 0.0), step, 1.0)
    limit = HUSKY.max_linear_acceleration  # 3 m/s^2: 0.5 m/s takes 0.17 s
    assert np.all(run[:, 1] <= limit * run[:, 0] + 0.02)
    reached = run[np.argmax(run[:, 1] >= 0.49), 0]
    assert reached == pytest.approx(0.5 / limit, abs=0.04)
    assert run[:, 1].max() < 0.52


def test_a_command_beyond_the_top_speed_is_held_to_it() -> None:
    run = driven(Twist(3.0, 0.0), 0.01, 3.0)
    assert run[run[:, 0] >= 2.0, 1].mean() == pytest.approx(HUSKY.max_linear_velocity, rel=0.01)


@pytest.mark.parametrize("step", TIME_STEPS)
@pytest.mark.parametrize("command", [(0.5, 0.5), (0.5, -1.0), (0.3, 1.0), (1.0, 0.5)])
def test_an_arc_is_driven_at_its_commanded_speed_and_turn_rate_within_three_percent(
    command: tuple[float, float], step: float
) -> None:
    # Up to the reference controller's cruising speed and turn rate, and past them.
    speed, turn_rate = command
    run = driven(Twist(speed, turn_rate), step, 6.0)
    steady = run[run[:, 0] >= 4.0]
    assert steady[:, 1].mean() == pytest.approx(speed, rel=0.03)
    assert steady[:, 2].mean() == pytest.approx(turn_rate, rel=0.03)
