"""Each bundled robot's simulated body against its robot file: the body PyBullet holds spans its
footprint, meets a wall where its footprint does, and a command beyond its limits drives it at
its top speed and turn rate."""

from __future__ import annotations

import numpy as np
import pytest

from pytest_lasertest.model.geometry import Pose2D
from pytest_lasertest.model.robot import Robot
from pytest_lasertest.pairsfile.bundled import bundled_robots
from pytest_lasertest.pairsfile.robot import load_robot_file
from pytest_lasertest.sim.client import PhysicsWorld
from pytest_lasertest.sim.drive import Drive, Twist, drive_step
from tests.helpers.bodies import STEP, WALL_FACE, first_touch

ROBOTS = {name: load_robot_file(path) for name, path in bundled_robots().items()}


def extent(world: PhysicsWorld) -> np.ndarray:
    """The body's length and width in the plane (m), over all its links, facing along x."""
    corners = world.body_bounds()[:, :2]
    return corners.max(axis=0) - corners.min(axis=0)


def outline(robot: Robot) -> np.ndarray:
    """The robot file's footprint as the body should have it, shape (V, 2), m: a prism's as
    written, before footprint_padding; the Husky's as written (its padding is 0.01 m)."""
    return np.array(robot.body.outline) if robot.body.kind == "prism" else robot.footprint_array()


def steady_twist(robot: Robot, command: Twist, seconds: float) -> tuple[float, float]:
    """The body's forward speed and turn rate (m/s, rad/s) at the end of `seconds` of `command`."""
    drive = Drive(robot)
    with PhysicsWorld(Pose2D(0.0, 0.0, 0.0), (), STEP, body=robot.body) as world:
        for _ in range(round(seconds / STEP)):
            yaw = float(world.base_pose()[2])
            measured = Twist(*world.base_twist(yaw))
            drive_step(world, drive, command, measured, yaw, STEP)
        return world.base_twist(float(world.base_pose()[2]))


@pytest.mark.parametrize("name", ROBOTS)
def test_a_bundled_robots_body_spans_its_footprint(name: str) -> None:
    robot = ROBOTS[name]
    with PhysicsWorld(Pose2D(0.0, 0.0, 0.0), (), STEP, body=robot.body) as world:
        spans = extent(world)
    footprint = outline(robot)
    assert spans == pytest.approx(footprint.max(axis=0) - footprint.min(axis=0), abs=0.03)


@pytest.mark.parametrize("name", ROBOTS)
def test_a_bundled_robot_drives_at_its_top_speed_and_no_faster(name: str) -> None:
    robot = ROBOTS[name]
    linear, _ = steady_twist(robot, Twist(50.0, 0.0), 4.0)
    assert linear == pytest.approx(robot.max_linear_velocity, rel=0.02)
    _, angular = steady_twist(robot, Twist(0.0, 50.0), 4.0)
    assert angular == pytest.approx(robot.max_angular_velocity, rel=0.05)


@pytest.mark.parametrize("name", ROBOTS)
def test_a_bundled_robot_meets_a_wall_where_its_footprint_does(name: str) -> None:
    robot = ROBOTS[name]
    touched = first_touch(robot, Twist(min(0.5, robot.max_linear_velocity), 0.0), 15.0)
    assert touched is not None
    front = outline(robot)[:, 0].max()  # m ahead of base_footprint
    assert touched[0] == pytest.approx(WALL_FACE - front, abs=0.02)
