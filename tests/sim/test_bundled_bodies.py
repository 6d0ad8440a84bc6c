"""Each bundled robot's simulated body against its description: the Jackal's and the
TurtleBot3s' bodies are the collision shapes their descriptions hold (read from the real files
by the gate's own reader), wheels where their continuous joints turn cylinders; PyBullet's body
spans them, rolls on those wheels, meets a wall where they do, and a command beyond the robot's
limits drives it at its top speed and turn rate."""

from __future__ import annotations

import dataclasses
import os
import shutil
from pathlib import Path

import numpy as np
import pytest

from pytest_lasertest.descriptions.profile import read_profile
from pytest_lasertest.model.body import Body, Collision
from pytest_lasertest.model.geometry import Pose2D, Pose3D
from pytest_lasertest.model.robot import Robot
from pytest_lasertest.pairsfile.bundled import bundled_robots
from pytest_lasertest.pairsfile.robot import load_robot_file
from pytest_lasertest.sim.client import PhysicsWorld
from pytest_lasertest.sim.drive import Drive, Twist, drive_step
from tests.descriptions.corpus import LMS1XX, ROBOT_ENVIRONMENT, STUBS, TURTLEBOT3
from tests.helpers import DATA
from tests.helpers.bodies import STEP, WALL_FACE, first_touch

ROBOTS = {name: load_robot_file(path) for name, path in bundled_robots().items()}
DESCRIBED = ("jackal", "turtlebot3_burger", "turtlebot3_waffle")
DESCRIPTIONS = DATA / "descriptions"
JACKAL = DESCRIPTIONS / "jackal/noetic-devel/jackal_description"
# The packages jackal_description's accessories include whatever is fitted: stand-ins.
JACKAL_STUBS = ("sick_tim", "velodyne_description", "pointgrey_camera_description")
# The Jackal of robots/jackal: accessories.urdf.xacro's front Hokuyo UTM-30LX.
JACKAL_ENVIRONMENT = {"JACKAL_LASER": "1", "JACKAL_LASER_MODEL": "utm30"}


@pytest.fixture(scope="module")
def turtlebot3(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """turtlebot3_description as a checkout holds it: the corpus's files, the Waffle's, and the
    stand-in for common_properties.xacro."""
    package = tmp_path_factory.mktemp("packages") / "turtlebot3_description"
    waffle = DESCRIPTIONS / "turtlebot3/noetic/turtlebot3_description"
    for source in (TURTLEBOT3, STUBS / "turtlebot3_description", waffle):
        shutil.copytree(source, package, dirs_exist_ok=True, copy_function=shutil.copyfile)
    return package


@pytest.fixture
def jackal_environment(monkeypatch: pytest.MonkeyPatch) -> None:
    """The robot environment robots/jackal's Jackal is described with, and no other."""
    for name in [name for name in os.environ if name.startswith(ROBOT_ENVIRONMENT)]:
        monkeypatch.delenv(name)
    for name, value in JACKAL_ENVIRONMENT.items():
        monkeypatch.setenv(name, value)


def described(name: str, turtlebot3: Path) -> tuple[Collision, ...]:
    """The collision shapes the robot's description holds, in base_footprint: a description
    whose root is base_link above the ground stands on its wheels, as its robot file composes
    base_footprint."""
    if name == "jackal":
        packages = {"jackal_description": JACKAL, "lms1xx": LMS1XX}
        packages |= {stub: STUBS / stub for stub in (*JACKAL_STUBS, "flir_camera_description")}
        path = JACKAL / "urdf/jackal.urdf.xacro"
    else:
        packages = {"turtlebot3_description": turtlebot3}
        path = turtlebot3 / f"urdf/{name}.urdf.xacro"
    read = read_profile(path, sensor=None, ref=None, args={}, packages=packages)
    collisions = read.laser.collisions()
    assert collisions is not None
    ground = Body.bottom(collisions)
    return tuple(_raised(collision, -ground) for collision in collisions)


def _raised(collision: Collision, height: float) -> Collision:
    x, y, z = collision.pose.xyz
    return dataclasses.replace(collision, pose=Pose3D((x, y, z + height), collision.pose.rpy))


def _key(collision: Collision) -> tuple[str, tuple[float, ...], tuple[float, ...]]:
    return collision.shape, collision.size, tuple(round(v, 4) for v in collision.pose.xyz)


@pytest.mark.usefixtures("jackal_environment")
@pytest.mark.parametrize("name", DESCRIBED)
def test_a_bundled_robots_body_is_the_collision_shapes_of_its_description(
    name: str, turtlebot3: Path
) -> None:
    body = ROBOTS[name].body
    assert body.kind == "description"
    bundled = sorted(body.collisions, key=_key)
    read = sorted(described(name, turtlebot3), key=_key)
    assert [(c.shape, c.size, c.wheel) for c in bundled] == [
        (c.shape, c.size, c.wheel) for c in read
    ]
    for ours, theirs in zip(bundled, read, strict=True):
        assert ours.pose.xyz == pytest.approx(theirs.pose.xyz, abs=1e-5)
        assert ours.pose.rpy == pytest.approx(theirs.pose.rpy, abs=1e-9)


def extent(world: PhysicsWorld) -> np.ndarray:
    """The body's length and width in the plane (m), over all its links, facing along x."""
    corners = world.body_bounds()[:, :2]
    return corners.max(axis=0) - corners.min(axis=0)


def plan_extent(robot: Robot) -> np.ndarray:
    """The [low, high] corners (2, 2) m the body should span: its description's shapes; the
    Husky's footprint as written (its padding is 0.01 m)."""
    if robot.body.kind == "husky":
        footprint = robot.footprint_array()
        return np.array([footprint.min(axis=0), footprint.max(axis=0)])
    return robot.body.extent()


@pytest.mark.parametrize("name", ROBOTS)
def test_a_bundled_robots_body_spans_its_description(name: str) -> None:
    robot = ROBOTS[name]
    with PhysicsWorld(Pose2D(0.0, 0.0, 0.0), (), STEP, body=robot.body) as world:
        spans = extent(world)
    low, high = plan_extent(robot)
    assert spans == pytest.approx(high - low, abs=0.03)


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
def test_a_bundled_robot_drives_at_its_top_speed_and_no_faster(name: str) -> None:
    robot = ROBOTS[name]
    linear, _ = steady_twist(robot, Twist(50.0, 0.0), 4.0)
    assert linear == pytest.approx(robot.max_linear_velocity, rel=0.02)
    _, angular = steady_twist(robot, Twist(0.0, 50.0), 4.0)
    assert angular == pytest.approx(robot.max_angular_velocity, rel=0.05)


@pytest.mark.parametrize("name", ROBOTS)
def test_a_bundled_robot_meets_a_wall_where_its_body_does(name: str) -> None:
    robot = ROBOTS[name]
    touched = first_touch(robot, Twist(min(0.5, robot.max_linear_velocity), 0.0), 15.0)
    assert touched is not None
    front = plan_extent(robot)[1, 0]  # m ahead of base_footprint
    assert touched[0] == pytest.approx(WALL_FACE - front, abs=0.02)


# Each described robot's wheels: how many, and how they steer.
STEERING = {
    "jackal": "driven through its 4 wheel joints (skid-steer)",
    "turtlebot3_burger": "driven through its 2 wheel joints (differential)",
    "turtlebot3_waffle": "driven through its 2 wheel joints (differential)",
}


@pytest.mark.parametrize("name", DESCRIBED)
def test_a_described_robot_rolls_on_its_wheels_at_the_speed_they_turn(name: str) -> None:
    robot = ROBOTS[name]
    assert robot.body.describe().endswith(STEERING[name])
    radius, _ = robot.body.track()
    speed = min(0.3, robot.max_linear_velocity)  # m/s
    drive = Drive(robot)
    with PhysicsWorld(Pose2D(0.0, 0.0, 0.0), (), STEP, body=robot.body) as world:
        for _ in range(round(3.0 / STEP)):
            yaw = float(world.base_pose()[2])
            measured = Twist(*world.base_twist(yaw))
            wheels = drive_step(world, drive, Twist(speed, 0.0), measured, yaw, STEP)
        linear, _ = world.base_twist(float(world.base_pose()[2]))
        _, y, yaw = world.base_pose()
    # What drove it is wheel speeds (rad/s), not a twist: the tyres roll it, hardly slipping.
    assert wheels == pytest.approx((speed / radius, speed / radius), rel=0.03)
    assert linear == pytest.approx(speed, rel=0.01)
    # Straight ahead, it stays on its line.
    assert abs(y) < 0.01
    assert abs(yaw) < 0.01


@pytest.mark.parametrize("name", DESCRIBED)
def test_a_described_robot_drives_the_arc_it_is_commanded(name: str) -> None:
    robot = ROBOTS[name]
    command = Twist(min(0.3, robot.max_linear_velocity), 0.5)
    assert steady_twist(robot, command, 3.0) == pytest.approx(
        (command.linear, command.angular), rel=0.03
    )
