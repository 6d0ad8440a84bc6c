"""PyBullet physics clients in DIRECT mode: one per use, always disconnected, never global.

The only module that imports pybullet. `PhysicsWorld` is one client holding the ground, the
Husky and the static obstacles; everything else in `sim/` speaks numpy to it.
"""

from __future__ import annotations

import math
import os
import sys
from collections.abc import Iterator, Sequence
from contextlib import contextmanager
from types import ModuleType

import numpy as np

from pytest_lasertest.model.body import HUSKY_BODY, Body
from pytest_lasertest.model.geometry import FloatArray, Pose2D
from pytest_lasertest.model.obstacles import Box, Obstacle
from pytest_lasertest.sim.bodies import (
    DROP_HEIGHT,
    TYRE_SIDEWAYS_FRICTION,
    built_body,
    wheel_joints,
)
from pytest_lasertest.sim.nearby import Nearby

# PyBullet's table of physics clients: ids run from 0 to this, and are reused once disconnected.
MAX_CLIENTS = 1024
# rayTestBatch refuses more rays than this in one call.
MAX_RAYS_PER_CALL = 16384
# Collision groups: rays look for the world group only, so they pass through the robot itself.
WORLD_GROUP, ROBOT_GROUP, ALL_GROUPS = 1, 2, 0xFFFF
HUSKY_URDF = "husky/husky.urdf"
# pybullet_data's Husky: its four wheel joints, left then right.
LEFT_WHEELS, RIGHT_WHEELS = (1, 3), (0, 2)
GRAVITY = 9.81  # m/s^2
WHEEL_TORQUE = 1000.0  # N m, more than the wheels ever need: the velocity target rules


def load_pybullet() -> ModuleType:
    """The pybullet module, imported on first use without its build-time banner."""
    if "pybullet" not in sys.modules:
        with _c_output_silenced():
            import pybullet  # noqa: F401
    return sys.modules["pybullet"]


class PhysicsClient:
    """A DIRECT physics client to build worlds in, one after another.

    Connecting a client costs up to 10 ms and resetting one 0.2 ms, and PyBullet leaks about
    0.3 MB for each client connected and disconnected while another stays connected: a process
    that runs many scenarios keeps one client and resets it for each world. Use it as a context
    manager: it disconnects on exit.
    """

    def __init__(self) -> None:
        self._pybullet = load_pybullet()
        self.id: int = self._pybullet.connect(self._pybullet.DIRECT)
        if self.id < 0:
            raise RuntimeError("pybullet could not start a DIRECT physics client")

    def __enter__(self) -> PhysicsClient:
        return self

    def __exit__(self, *exception: object) -> None:
        self.close()

    @property
    def closed(self) -> bool:
        """Whether the client has been disconnected."""
        return self.id < 0

    def close(self) -> None:
        """Disconnect the client; closing twice is harmless."""
        if self.id >= 0:
            self._pybullet.disconnect(physicsClientId=self.id)
            self.id = -1


class PhysicsWorld:
    """The ground, the robot's body (pybullet_data's Husky with its fixed links merged, its
    description's collision shapes, or a prism of its footprint) and static obstacles, in one
    DIRECT client stepped at a fixed time step.

    The world is built in `client`, reset for it, or in a client of its own. Use it as a
    context manager: on exit it disconnects a client of its own, and leaves a borrowed one
    for the next world.
    """

    def __init__(
        self,
        start: Pose2D,
        obstacles: Sequence[Obstacle],
        time_step: float,
        client: PhysicsClient | None = None,
        body: Body = HUSKY_BODY,
    ) -> None:
        self._pybullet = load_pybullet()
        self._borrowed = client is not None
        self._physics = client if client is not None else PhysicsClient()
        self._client = self._physics.id
        try:
            if self._borrowed:
                self._pybullet.resetSimulation(physicsClientId=self._client)
            self._setup(time_step, body)
            self.body = body
            husky = body.kind == "husky"
            self.robot = self._load_husky(start) if husky else self._load_built(start)
            lefts, rights = (LEFT_WHEELS, RIGHT_WHEELS) if husky else wheel_joints(body)
            # Made once: `step` runs at every physics step.
            self._wheels, self._sides = lefts + rights, (len(lefts), len(rights))
            self._torques = (WHEEL_TORQUE,) * len(self._wheels)
            self.obstacles = tuple(self._add_obstacle(obstacle) for obstacle in obstacles)
            self._nearby = Nearby(self.obstacles, obstacles, self._robot_reach(start))
            inertial = self._pybullet.getDynamicsInfo(self.robot, -1, physicsClientId=self._client)
            self._from_com = self._pybullet.invertTransform(*inertial[3:5])
        except BaseException:
            self.close()
            raise

    def __enter__(self) -> PhysicsWorld:
        return self

    def __exit__(self, *exception: object) -> None:
        self.close()

    @property
    def closed(self) -> bool:
        """Whether the world has been closed."""
        return self._client < 0

    def close(self) -> None:
        """Disconnect a client of its own, leave a borrowed one; closing twice is harmless."""
        if not self._borrowed:
            self._physics.close()
        self._client = -1

    def step(self, left: float, right: float) -> None:
        """Drive the left and right wheels at these speeds (rad/s) for one time step."""
        pybullet = self._pybullet
        lefts, rights = self._sides
        pybullet.setJointMotorControlArray(
            self.robot,
            self._wheels,
            pybullet.VELOCITY_CONTROL,
            targetVelocities=(left,) * lefts + (right,) * rights,
            forces=self._torques,
            physicsClientId=self._client,
        )
        pybullet.stepSimulation(physicsClientId=self._client)

    def glide(self, linear: float, angular: float, yaw: float) -> None:
        """Move a sliding body at this twist (m/s forward, rad/s), heading `yaw` (rad), for one
        time step: it slides on the ground and stops where it meets something."""
        pybullet, client = self._pybullet, self._client
        vertical = pybullet.getBaseVelocity(self.robot, physicsClientId=client)[0][2]
        pybullet.resetBaseVelocity(
            self.robot,
            (linear * math.cos(yaw), linear * math.sin(yaw), vertical),
            (0.0, 0.0, angular),
            physicsClientId=client,
        )
        pybullet.stepSimulation(physicsClientId=client)

    def base_pose(self) -> FloatArray:
        """The robot's base_footprint in the world plane, [x, y, yaw] (m, m, rad)."""
        pybullet = self._pybullet
        # PyBullet reports the base's centre of mass; the URDF frame sits where the inertial
        # frame says, relative to it.
        com, orientation = pybullet.getBasePositionAndOrientation(
            self.robot, physicsClientId=self._client
        )
        position, orientation = pybullet.multiplyTransforms(com, orientation, *self._from_com)
        yaw = pybullet.getEulerFromQuaternion(orientation)[2]
        return np.array([position[0], position[1], yaw])

    def base_twist(self, yaw: float) -> tuple[float, float]:
        """The base's forward speed (m/s) and turn rate (rad/s), heading `yaw` (rad)."""
        linear, angular = self._pybullet.getBaseVelocity(self.robot, physicsClientId=self._client)
        return linear[0] * math.cos(yaw) + linear[1] * math.sin(yaw), angular[2]

    def proximity(self, pose: FloatArray, within: float) -> tuple[float, bool]:
        """The least distance between the robot at `pose` and any obstacle (m, at most
        `within`), and whether they touch after the last step.

        PyBullet is asked only about the obstacles that can be that near (`nearby.py`).
        """
        near = self._nearby.bodies(float(pose[0]), float(pose[1]), within)
        if not near:
            return within, False
        pybullet, client = self._pybullet, self._client
        distances = [
            point[8]
            for body in near
            for point in pybullet.getClosestPoints(self.robot, body, within, physicsClientId=client)
        ]
        # PyBullet keeps contact points a little before the shapes meet (its breaking
        # threshold): only those at zero distance or less are touching.
        touching = any(
            point[8] <= 0.0
            for body in near
            for point in pybullet.getContactPoints(self.robot, body, physicsClientId=client)
        )
        return min(distances, default=within), touching

    def cast(self, starts: FloatArray, ends: FloatArray) -> FloatArray:
        """Where each ray from `starts` to `ends` (both (R, 3), m) first meets the world, as a
        fraction of its length, shape (R,); 1.0 where it meets nothing. The robot is transparent."""
        batches = [
            self._pybullet.rayTestBatch(
                starts[first : first + MAX_RAYS_PER_CALL].tolist(),
                ends[first : first + MAX_RAYS_PER_CALL].tolist(),
                collisionFilterMask=WORLD_GROUP,
                physicsClientId=self._client,
            )
            for first in range(0, len(starts), MAX_RAYS_PER_CALL)
        ]
        hits = [hit for batch in batches for hit in batch]
        return np.array([hit[2] if hit[0] >= 0 else 1.0 for hit in hits], dtype=float)

    def _setup(self, time_step: float, body: Body) -> None:
        pybullet = self._pybullet
        import pybullet_data

        pybullet.setAdditionalSearchPath(pybullet_data.getDataPath(), physicsClientId=self._client)
        pybullet.setGravity(0.0, 0.0, -GRAVITY, physicsClientId=self._client)
        pybullet.setPhysicsEngineParameter(
            fixedTimeStep=time_step,
            deterministicOverlappingPairs=1,
            # Under Bullet's friction cone a tyre's low sideways friction cuts its forward grip
            # too: a Jackal body whose wheels were set turning at 2 m/s from rest took 1.5 s to
            # reach 1.8 m/s, slewing 0.9 m aside; with two-direction friction it was at 1.96
            # m/s within 0.5 s, 4 cm aside. The Husky's runs keep the default.
            enableConeFriction=0 if body.wheels else 1,
            physicsClientId=self._client,
        )
        ground = pybullet.loadURDF("plane.urdf", physicsClientId=self._client)
        self._join(ground, WORLD_GROUP)

    def _load_husky(self, start: Pose2D) -> int:
        pybullet = self._pybullet
        orientation = pybullet.getQuaternionFromEuler((0.0, 0.0, start.yaw))
        with _c_output_silenced():
            robot: int = pybullet.loadURDF(
                HUSKY_URDF,
                (start.x, start.y, DROP_HEIGHT),
                orientation,
                # Its visual meshes are three quarters of the load time and nothing here
                # renders: the collision shapes and inertia are the same without them.
                flags=pybullet.URDF_MERGE_FIXED_LINKS | pybullet.URDF_IGNORE_VISUAL_SHAPES,
                physicsClientId=self._client,
            )
        self._join(robot, ROBOT_GROUP)
        for wheel in (*LEFT_WHEELS, *RIGHT_WHEELS):
            # The wheels turn about their own y axis: that is the axle.
            pybullet.changeDynamics(
                robot,
                wheel,
                anisotropicFriction=(1.0, TYRE_SIDEWAYS_FRICTION, 1.0),
                physicsClientId=self._client,
            )
        return robot

    def _load_built(self, start: Pose2D) -> int:
        """A description's shapes, on its wheels or sliding, or a prism (`bodies.py`)."""
        robot = built_body(self._pybullet, self._client, self.body, start)
        self._join(robot, ROBOT_GROUP)
        return robot

    def body_bounds(self) -> FloatArray:
        """The corners of the boxes that hold each of the body's links, aligned with the world's
        axes, shape (2 L, 3), m."""
        pybullet, client = self._pybullet, self._client
        links = range(-1, pybullet.getNumJoints(self.robot, physicsClientId=client))
        return np.array(
            [
                corner
                for link in links
                for corner in pybullet.getAABB(self.robot, link, physicsClientId=client)
            ]
        )

    def _robot_reach(self, start: Pose2D) -> float:
        """The radius of a circle around base_footprint that holds the whole robot (m)."""
        corners = self.body_bounds()
        return float(np.hypot(corners[:, 0] - start.x, corners[:, 1] - start.y).max())

    def _add_obstacle(self, obstacle: Obstacle) -> int:
        """A static body of the obstacle's exact shape, standing on the ground."""
        pybullet = self._pybullet
        if isinstance(obstacle, Box):
            half = (obstacle.length / 2.0, obstacle.width / 2.0, obstacle.height / 2.0)
            shape = pybullet.createCollisionShape(
                pybullet.GEOM_BOX, halfExtents=half, physicsClientId=self._client
            )
        else:
            shape = pybullet.createCollisionShape(
                pybullet.GEOM_CYLINDER,
                radius=obstacle.radius,
                height=obstacle.height,
                physicsClientId=self._client,
            )
        body: int = pybullet.createMultiBody(
            baseMass=0.0,
            baseCollisionShapeIndex=shape,
            basePosition=(obstacle.x, obstacle.y, obstacle.height / 2.0),
            baseOrientation=pybullet.getQuaternionFromEuler((0.0, 0.0, obstacle.yaw)),
            physicsClientId=self._client,
        )
        self._join(body, WORLD_GROUP)
        return body

    def _join(self, body: int, group: int) -> None:
        """Put every link of a body in a collision group that collides with all groups."""
        pybullet = self._pybullet
        links = range(-1, pybullet.getNumJoints(body, physicsClientId=self._client))
        for link in links:
            pybullet.setCollisionFilterGroupMask(
                body, link, group, ALL_GROUPS, physicsClientId=self._client
            )


def connected_clients() -> int:
    """How many physics clients this process has connected and not yet disconnected."""
    pybullet = load_pybullet()
    return sum(
        pybullet.getConnectionInfo(physicsClientId=client)["isConnected"]
        for client in range(MAX_CLIENTS)
    )


def self_test() -> str:
    """Start a DIRECT client, step it once, disconnect; describe the pybullet that did it."""
    pybullet = load_pybullet()
    with PhysicsClient() as client:
        pybullet.stepSimulation(physicsClientId=client.id)
        api = pybullet.getAPIVersion(physicsClientId=client.id)
    return f"pybullet API {api}: a DIRECT client started, stepped and disconnected"


@contextmanager
def _c_output_silenced() -> Iterator[None]:
    # pybullet's C code prints its build time at import, and warnings while it loads a URDF,
    # straight to file descriptors 1 and 2.
    sys.stdout.flush()
    sys.stderr.flush()
    saved = [os.dup(1), os.dup(2)]
    try:
        with open(os.devnull, "w") as devnull:
            os.dup2(devnull.fileno(), 1)
            os.dup2(devnull.fileno(), 2)
            yield
    finally:
        for descriptor, copy in zip((1, 2), saved, strict=True):
            os.dup2(copy, descriptor)
            os.close(copy)
