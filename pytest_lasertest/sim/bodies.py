"""The bodies that slide at the commanded twist: a description's collision shapes as one rigid
body, or a prism of the footprint. Each stands on the ground with its mass over its base origin,
so that it turns on the spot about it, without friction, and too stiff to tip."""

from __future__ import annotations

from types import ModuleType

from pytest_lasertest.model.body import Body
from pytest_lasertest.model.geometry import Pose2D

# A body's lowest point starts this close to the ground: placed there, it starts at rest instead
# of falling (the Husky's base_footprint rests so on its wheels).
DROP_HEIGHT = 0.0005  # m
# Its mass only sets how hard it pushes what it meets (the Husky's base, about).
SLIDING_MASS = 50.0  # kg
# Inertia about its roll and pitch axes, so large that a push low or high does not tip it.
UNTIPPABLE = 1.0e6  # kg m^2


def sliding_body(pybullet: ModuleType, client: int, body: Body, start: Pose2D) -> int:
    """The body, a description's or a prism, at `start` in `client`: its PyBullet id."""
    if body.kind == "description":
        return _slider(pybullet, client, body, _collision_shapes(pybullet, client, body), start)
    corners = [(x, y, z) for z in (0.0, body.height) for x, y in body.outline]
    shape = pybullet.createCollisionShape(
        pybullet.GEOM_MESH, vertices=corners, physicsClientId=client
    )
    return _slider(pybullet, client, body, shape, start)


def _collision_shapes(pybullet: ModuleType, client: int, body: Body) -> int:
    """The description's collision shapes as one compound shape, in its base frame."""
    collisions = body.collisions
    geometries = {
        "box": pybullet.GEOM_BOX,
        "cylinder": pybullet.GEOM_CYLINDER,
        "sphere": pybullet.GEOM_SPHERE,
    }
    shape: int = pybullet.createCollisionShapeArray(
        shapeTypes=[geometries[c.shape] for c in collisions],
        radii=[c.size[0] if c.shape != "box" else 0.0 for c in collisions],
        halfExtents=[
            [length / 2.0 for length in c.size] if c.shape == "box" else [0.0] * 3
            for c in collisions
        ],
        lengths=[c.size[1] if c.shape == "cylinder" else 0.0 for c in collisions],
        collisionFramePositions=[c.pose.xyz for c in collisions],
        collisionFrameOrientations=[
            pybullet.getQuaternionFromEuler(c.pose.rpy) for c in collisions
        ],
        physicsClientId=client,
    )
    return shape


def _slider(pybullet: ModuleType, client: int, body: Body, shape: int, start: Pose2D) -> int:
    """A body of `shape` dropped onto the ground at `start`. A description whose base frame is
    not on the ground (the Jackal's base_link) stands on its lowest shape all the same."""
    bottom = Body.bottom(body.collisions) if body.kind == "description" else 0.0
    robot: int = pybullet.createMultiBody(
        baseMass=SLIDING_MASS,
        baseCollisionShapeIndex=shape,
        basePosition=(start.x, start.y, DROP_HEIGHT - bottom),
        baseOrientation=pybullet.getQuaternionFromEuler((0.0, 0.0, start.yaw)),
        baseInertialFramePosition=(0.0, 0.0, bottom + body.height / 2.0),
        physicsClientId=client,
    )
    twist_inertia = pybullet.getDynamicsInfo(robot, -1, physicsClientId=client)[2][2]
    pybullet.changeDynamics(
        robot,
        -1,
        lateralFriction=0.0,
        localInertiaDiagonal=(UNTIPPABLE, UNTIPPABLE, twist_inertia),
        physicsClientId=client,
    )
    return robot
