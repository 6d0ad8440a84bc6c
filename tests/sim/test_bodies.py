"""The body a robot file names is the body that runs: a team's robot with `body: {height: H}` is a
prism of its own footprint, one with `body: {collisions: [...]}` (or written around its
description) is those shapes, not pybullet_data's Husky, moved at the commanded twist within its
limits; and each report says which body ran."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
import pytest

from pytest_lasertest.model.body import Body, Collision
from pytest_lasertest.model.geometry import Point2D, Pose2D, Pose3D
from pytest_lasertest.model.robot import Robot
from pytest_lasertest.nav.protocol import LaserScan, Odometry
from pytest_lasertest.pairsfile.bundled import bundled_robots
from pytest_lasertest.pairsfile.catalogue import load_catalogue
from pytest_lasertest.pairsfile.robot import load_robot_file
from pytest_lasertest.reports.drive import robot_line
from pytest_lasertest.sim.client import PhysicsWorld
from pytest_lasertest.sim.drive import Drive, Twist
from pytest_lasertest.sim.scenario import Scenario, run_scenario
from tests.helpers.bodies import STEP, WALL, WALL_FACE, first_touch
from tests.helpers.texts import MY_ROBOT


@pytest.fixture
def my_bot(tmp_path: Path) -> Robot:
    """MY_ROBOT: a 0.6 x 0.4 m footprint (0.3 m ahead of its origin), a 0.3 m prism."""
    (tmp_path / "robot.yaml").write_text(MY_ROBOT)
    return load_robot_file(tmp_path / "robot.yaml")


def test_a_prism_body_meets_a_wall_where_its_own_footprint_does(my_bot: Robot) -> None:
    touched = first_touch(my_bot, Twist(0.5, 0.0), 8.0)
    assert touched is not None
    # Its front edge, 0.3 m ahead of its origin, reaches the wall's face at 1.9 m.
    assert touched[0] == pytest.approx(WALL_FACE - 0.3, abs=0.01)
    assert abs(touched[1]) < 0.01


# A chassis 0.6 m long centred 0.1 m behind the origin, and a bumper on stalks whose front is
# 0.45 m ahead of it, above the footprint's 0.3 m.
BUMPERED = (
    Collision("box", (0.6, 0.4, 0.2), Pose3D((-0.1, 0.0, 0.1))),
    Collision("box", (0.05, 0.5, 0.05), Pose3D((0.425, 0.0, 0.15))),
    Collision("cylinder", (0.1, 0.05), Pose3D((0.0, 0.275, 0.1), (1.5708, 0.0, 0.0))),
)


def test_a_described_body_meets_a_wall_where_its_shapes_do_not_its_footprint(
    my_bot: Robot,
) -> None:
    robot = dataclasses.replace(my_bot, body=Body.described(BUMPERED))
    touched = first_touch(robot, Twist(0.5, 0.0), 8.0)
    assert touched is not None
    # The bumper's front, 0.45 m ahead of the origin, reaches the wall's face at 1.9 m.
    assert touched[0] == pytest.approx(WALL_FACE - 0.45, abs=0.01)
    with PhysicsWorld(Pose2D(0.0, 0.0, 0.0), (), STEP, body=robot.body) as world:
        low, high = world.body_bounds().min(axis=0), world.body_bounds().max(axis=0)
    # From the chassis's back to the bumper, from the bumper's right end to the wheel's side,
    # on the ground under its wheel (PyBullet's bounds hold a margin of a few millimetres).
    assert low == pytest.approx([-0.4, -0.25, 0.0], abs=0.015)
    assert high == pytest.approx([0.45, 0.3, 0.2], abs=0.015)


def test_a_prism_moves_at_the_commanded_twist_held_to_its_limits(my_bot: Robot) -> None:
    drive, speeds = Drive(my_bot), []
    with PhysicsWorld(Pose2D(0.0, 0.0, 0.0), (), STEP, body=my_bot.body) as world:
        for _ in range(round(3.0 / STEP)):
            yaw = float(world.base_pose()[2])
            world.glide(*drive.twist(Twist(5.0, 4.0), STEP), yaw)
            speeds.append(world.base_twist(float(world.base_pose()[2])))
    linear, angular = np.array(speeds).T
    # 0.8 m/s and 1.2 rad/s at most, reached at 1.5 m/s^2 and 3.0 rad/s^2.
    assert linear[-1] == pytest.approx(my_bot.max_linear_velocity, rel=0.01)
    assert angular[-1] == pytest.approx(my_bot.max_angular_velocity, rel=0.01)
    assert linear[9] == pytest.approx(10 * STEP * my_bot.max_linear_acceleration, rel=0.02)
    assert linear.max() < my_bot.max_linear_velocity * 1.01


class Ahead:
    """A controller that drives straight ahead at 0.5 m/s, whatever it reads."""

    def __init__(self, robot: Robot, route: tuple[Point2D, ...]) -> None:
        pass

    def observe(self, scan: LaserScan, odometry: Odometry, time: float) -> tuple[float, float]:
        return 0.5, 0.0


def test_a_run_of_the_prism_collides_at_its_footprint_and_records_the_twist_it_drove(
    my_bot: Robot,
) -> None:
    scenario = Scenario(
        robot=my_bot,
        profile=load_catalogue().entries["hokuyo_ust_10lx"].profile(my_bot.laser_mount),
        obstacles=(WALL,),
        start=Pose2D(0.0, 0.0, 0.0),
        route=(Point2D(4.0, 0.0),),
        time_limit=10.0,
        seed=0,
    )
    run = run_scenario(scenario, Ahead)
    assert not run.verdicts.collision.passed
    assert run.poses[-1, 0] == pytest.approx(1.6, abs=0.02)
    assert np.max(np.abs(run.driven[:, 0])) == pytest.approx(0.5)  # m/s, not a wheel's rad/s


def test_each_report_names_the_body_that_ran(my_bot: Robot) -> None:
    husky = load_robot_file(bundled_robots()["husky"])
    assert robot_line(my_bot) == (
        "  robot      My bot: a prism of its footprint, 0.60 x 0.40 x 0.30 m, moved at the "
        "commanded twist"
    )
    described = dataclasses.replace(my_bot, body=Body.described(BUMPERED))
    assert robot_line(described) == (
        "  robot      My bot: its description's 3 collision shapes, 0.85 x 0.55 x 0.20 m, "
        "moved at the commanded twist"
    )
    assert robot_line(husky) == (
        "  robot      Clearpath Husky A200: pybullet_data's Husky, driven through its wheels"
    )
