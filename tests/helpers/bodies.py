"""Driving a robot's simulated body at a wall: where it first touches."""

from __future__ import annotations

import numpy as np

from pytest_lasertest.model.geometry import Pose2D
from pytest_lasertest.model.obstacles import Box
from pytest_lasertest.model.robot import Robot
from pytest_lasertest.sim.client import PhysicsWorld
from pytest_lasertest.sim.drive import Drive, Twist, drive_step

STEP = 0.02  # s
# A wall across the way, its near face 1.9 m ahead of the start.
WALL = Box(x=2.0, y=0.0, yaw=0.0, length=0.2, width=2.0, height=1.0)
WALL_FACE = 1.9  # m


def first_touch(robot: Robot, command: Twist, seconds: float) -> np.ndarray | None:
    """The body's pose when it first touches WALL, driving `command` from the origin."""
    drive = Drive(robot)
    with PhysicsWorld(Pose2D(0.0, 0.0, 0.0), (WALL,), STEP, body=robot.body) as world:
        for _ in range(round(seconds / STEP)):
            pose = world.base_pose()
            measured = Twist(*world.base_twist(float(pose[2])))
            drive_step(world, drive, command, measured, float(pose[2]), STEP)
            pose = world.base_pose()
            if world.proximity(pose, 1.0)[1]:
                return pose
    return None
