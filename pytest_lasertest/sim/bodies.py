"""The bodies built from a robot file: a description's collision shapes, driven through its wheel
joints when it has wheels and sliding at the commanded twist when not, or a prism of the
footprint, sliding. A sliding body stands with its mass over its base origin, so that it turns
on the spot about it, and too stiff to tip; a wheeled one stands on its wheels, its mass over
the middle of its extent (so a TurtleBot3 leans on its caster, as the real one does).

Wheels are links on joints about their axles, driven by velocity as gazebo_ros's diff_drive
plugin drives the joints it is given (ros-simulation/gazebo_ros_pkgs
gazebo_plugins/src/gazebo_ros_diff_drive.cpp, 003fd3146df58fc8846a85b002e55b2f6f223e1b:
getWheelVelocities splits the twist as v -+ w separation / 2, and UpdateChild sets each joint's
"vel" to that over the wheel's radius, its force limited by wheelTorque). The tyres keep
PyBullet's friction of 0.5; the rest of the body glides without friction. (The TurtleBot3's
Gazebo tags give its caster the wheels' friction, 0.1: turtlebot3_burger.gazebo.xacro, noetic
bd0163a4adfb8472e6046bf737355b6a692a572e. The body's mass here is not the robot's, so a drag
proportional to it would be no truer than none.)
"""

from __future__ import annotations

from types import ModuleType

from pytest_lasertest.model.body import Body, Collision
from pytest_lasertest.model.geometry import Pose2D

# A body's lowest point starts this close to the ground: placed there, it starts at rest instead
# of falling (the Husky's base_footprint rests so on its wheels).
DROP_HEIGHT = 0.0005  # m
# Its mass only sets how hard it pushes what it meets (the Husky's base, about).
SLIDING_MASS = 50.0  # kg
# Inertia about its roll and pitch axes, so large that a push low or high does not tip it.
UNTIPPABLE = 1.0e6  # kg m^2
# A wheel's own mass: its inertia about its axle is all the velocity motor has to overcome.
WHEEL_MASS = 1.0  # kg
# A skid-steer robot turns by sliding its tyres sideways. With PyBullet's isotropic friction they
# grip so hard that the turn rate jumps with the wheel speeds (0.4 rad/s for 0.25 commanded, 2.3
# for 1.0, on the Husky); friction along the axle scaled by this factor lets them slide and the
# rate follow.
TYRE_SIDEWAYS_FRICTION = 0.05


def built_body(pybullet: ModuleType, client: int, body: Body, start: Pose2D) -> int:
    """The body, a description's or a prism, at `start` in `client`: its PyBullet id."""
    if body.kind == "description":
        chassis = tuple(c for c in body.collisions if not c.wheel)
        shape = _collision_shapes(pybullet, client, chassis) if chassis else -1
        robot = _placed(pybullet, client, body, shape, start)
        _grip(pybullet, client, robot, body)
        return robot
    corners = [(x, y, z) for z in (0.0, body.height) for x, y in body.outline]
    shape = pybullet.createCollisionShape(
        pybullet.GEOM_MESH, vertices=corners, physicsClientId=client
    )
    return _placed(pybullet, client, body, shape, start)


def wheel_joints(body: Body) -> tuple[tuple[int, ...], tuple[int, ...]]:
    """The PyBullet joints of the body's wheels, left then right: one joint a wheel, in the
    order the body lists them."""
    wheels = body.wheels
    left = tuple(index for index, wheel in enumerate(wheels) if wheel.pose.xyz[1] > 0.0)
    right = tuple(index for index, wheel in enumerate(wheels) if wheel.pose.xyz[1] < 0.0)
    return left, right


def _collision_shapes(pybullet: ModuleType, client: int, collisions: tuple[Collision, ...]) -> int:
    """The collision shapes as one compound shape, in the base frame."""
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


def _placed(pybullet: ModuleType, client: int, body: Body, shape: int, start: Pose2D) -> int:
    """A body of `shape`, with its wheels as links, dropped onto the ground at `start`. A
    description whose base frame is not on the ground (the Jackal's base_link) stands on its
    lowest shape all the same."""
    bottom = Body.bottom(body.collisions) if body.kind == "description" else 0.0
    robot: int = pybullet.createMultiBody(
        baseMass=SLIDING_MASS,
        baseCollisionShapeIndex=shape,
        basePosition=(start.x, start.y, DROP_HEIGHT - bottom),
        baseOrientation=pybullet.getQuaternionFromEuler((0.0, 0.0, start.yaw)),
        baseInertialFramePosition=_centre_of_mass(body, bottom),
        physicsClientId=client,
        **_wheel_links(pybullet, client, body.wheels),
    )
    # Whatever else touches the ground (a caster, a sliding body's underside) glides.
    pybullet.changeDynamics(robot, -1, lateralFriction=0.0, physicsClientId=client)
    if not body.wheels:
        twist_inertia = pybullet.getDynamicsInfo(robot, -1, physicsClientId=client)[2][2]
        pybullet.changeDynamics(
            robot,
            -1,
            localInertiaDiagonal=(UNTIPPABLE, UNTIPPABLE, twist_inertia),
            physicsClientId=client,
        )
    return robot


def _centre_of_mass(body: Body, bottom: float) -> tuple[float, float, float]:
    """Half way up the body (m, in its base frame): over its base origin when it slides, so that
    it turns about it; over the middle of its extent when it stands on wheels, so that a robot
    on two wheels and a caster leans on its caster, as the TurtleBot3's does."""
    if not body.wheels:
        return (0.0, 0.0, bottom + body.height / 2.0)
    x, y = body.extent().mean(axis=0)
    return (float(x), float(y), bottom + body.height / 2.0)


def _wheel_links(
    pybullet: ModuleType, client: int, wheels: tuple[Collision, ...]
) -> dict[str, list[object]]:
    """createMultiBody's link arguments for the wheels: each a link at its cylinder's centre,
    turned as the base is, holding the cylinder as the description turns it, on a joint about
    the base's y axis (the cylinder's own, within `WHEEL_AXLE_TOLERANCE`). So a positive speed
    rolls each forward, and the axle is each link's y, as the Husky's wheels are."""
    count = len(wheels)
    shapes = [
        pybullet.createCollisionShape(
            pybullet.GEOM_CYLINDER,
            radius=w.size[0],
            height=w.size[1],
            collisionFrameOrientation=pybullet.getQuaternionFromEuler(w.pose.rpy),
            physicsClientId=client,
        )
        for w in wheels
    ]
    return {
        "linkMasses": [WHEEL_MASS] * count,
        "linkCollisionShapeIndices": shapes,
        "linkVisualShapeIndices": [-1] * count,
        "linkPositions": [w.pose.xyz for w in wheels],
        "linkOrientations": [(0.0, 0.0, 0.0, 1.0)] * count,
        "linkInertialFramePositions": [(0.0, 0.0, 0.0)] * count,
        "linkInertialFrameOrientations": [(0.0, 0.0, 0.0, 1.0)] * count,
        "linkParentIndices": [0] * count,
        "linkJointTypes": [pybullet.JOINT_REVOLUTE] * count,
        "linkJointAxis": [(0.0, 1.0, 0.0)] * count,
    }


def _grip(pybullet: ModuleType, client: int, robot: int, body: Body) -> None:
    """Let a skid-steer body's tyres slide sideways, along each wheel link's y."""
    if body.steering != "skid-steer":
        return
    for joint in range(len(body.wheels)):
        pybullet.changeDynamics(
            robot,
            joint,
            anisotropicFriction=(1.0, TYRE_SIDEWAYS_FRICTION, 1.0),
            physicsClientId=client,
        )
