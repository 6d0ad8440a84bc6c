"""The PyBullet world: static obstacles the robot cannot push, the clearance it measures, and
clients and memory released."""

from __future__ import annotations

import multiprocessing
from pathlib import Path

import pytest

from pytest_lasertest.model.geometry import Pose2D
from pytest_lasertest.model.obstacles import Box, Cylinder
from pytest_lasertest.sim.client import (
    PhysicsClient,
    PhysicsWorld,
    connected_clients,
    load_pybullet,
)
from tests.helpers.sim import TIME_STEP


def test_obstacles_are_static_the_robot_cannot_push_them() -> None:
    box = Box(1.5, 0.0, 0.0, 0.3, 1.0, 0.5)
    with PhysicsWorld(Pose2D(0.0, 0.0, 0.0), (box,), TIME_STEP) as world:
        touched = 0
        for _ in range(300):
            world.step(8.0, 8.0)
            touched += world.proximity(world.base_pose(), within=1.0)[1]
        reached = world.base_pose()
        clearance, touching = world.proximity(reached, within=1.0)
    assert touched > 0
    assert touching
    assert clearance < 0.001
    # Pushing with all its torque for 3 s, the Husky's bumper (0.505 m ahead of its base, give
    # or take the pitch it pushes with) is still at the box's near face.
    assert reached[0] + 0.505 == pytest.approx(box.x - box.length / 2, abs=0.02)


def _resident_bytes() -> int:
    return int(Path("/proc/self/statm").read_text().split()[1]) * 4096


def _worlds(count: int) -> PhysicsWorld:
    obstacles = (Box(2.0, 0.0, 0.3, 0.2, 0.2, 1.0), Cylinder(3.0, 1.0, 0.1, 1.0))
    for _ in range(count):
        with PhysicsWorld(Pose2D(0.0, 0.0, 0.0), obstacles, TIME_STEP) as world:
            world.step(1.0, 1.0)
    return world


def _growth_over_worlds() -> tuple[int, bool, int]:
    """In a fresh process: the resident memory 200 worlds grew after 100 (bytes), whether the
    last was closed, and the clients left connected."""
    # PyBullet keeps what it read of the Husky's files after the first worlds (about 35 MB).
    _worlds(100)
    before = _resident_bytes()
    last = _worlds(200)
    return _resident_bytes() - before, last.closed, connected_clients()


def test_worlds_release_their_clients_and_memory() -> None:
    # A fresh process: in this one, what earlier tests freed (Nav2's large arrays, its noise
    # threads' arenas) changes how malloc places PyBullet's next allocations, once.
    with multiprocessing.get_context("spawn").Pool(1) as pool:
        growth, closed, connected = pool.apply(_growth_over_worlds)
    assert closed
    assert connected == 0
    assert growth < 10 * 2**20


def test_proximity_is_the_clearance_pybullet_measures_capped_at_the_horizon() -> None:
    near, far = Box(1.2, 0.0, 0.0, 0.2, 0.2, 1.0), Cylinder(9.0, 0.0, 0.1, 1.0)
    with PhysicsWorld(Pose2D(0.0, 0.0, 0.0), (near, far), TIME_STEP) as world:
        clearance, touching = world.proximity(world.base_pose(), within=1.0)
        capped, _ = world.proximity(world.base_pose(), within=0.5)
    # The Husky's collision box reaches 0.504 m ahead of base_footprint; the box starts at 1.1.
    assert clearance == pytest.approx(1.1 - 0.504, abs=0.01)
    assert not touching
    assert capped == 0.5


def test_proximity_along_a_long_wall_is_what_asking_pybullet_about_every_obstacle_gives() -> None:
    # A 12 m wall beside the route, another 4 m off it, and a block the robot passes: the
    # obstacles near the robot are found again as it drives, and none that matters is missed.
    wall, far = Box(6.0, 0.8, 0.0, 12.0, 0.1, 1.0), Box(6.0, -4.0, 0.0, 12.0, 0.1, 1.0)
    block = Box(3.0, -0.9, 0.0, 0.4, 0.4, 1.0)
    pybullet, measured = load_pybullet(), []
    with (
        PhysicsClient() as client,
        PhysicsWorld(Pose2D(0.0, 0.0, 0.0), (wall, far, block), TIME_STEP, client) as world,
    ):
        for _ in range(500):
            world.step(6.0, 6.0)
            clearance, _ = world.proximity(world.base_pose(), within=0.5)
            every = [
                point[8]
                for body in world.obstacles
                for point in pybullet.getClosestPoints(
                    world.robot, body, 0.5, physicsClientId=client.id
                )
            ]
            assert clearance == min(every, default=0.5)
            measured.append(clearance)
        travelled = world.base_pose()[0]
    assert travelled > 4.0
    assert min(measured) < 0.4  # the wall and the block come within the horizon
