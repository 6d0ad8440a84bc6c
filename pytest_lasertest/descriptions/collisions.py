"""How high a URDF robot's collision geometry reaches above its base frame: the height of the
prism the simulator drives for a robot written around its description.

Each link's `<collision>` is placed by the link's pose in the base frame (`mounts.link_poses`,
every joint at zero) and the collision's `<origin>`, as urdfdom composes them. A box reaches up
by its half extents along its rotated axes, a cylinder (its axis its own z) by half its length
along the axis and its radius across it, a sphere by its radius. A mesh's extent is in its file,
which the gate does not read: a description with a collision mesh gives no height.
"""

from __future__ import annotations

import math

import numpy as np

from pytest_lasertest.descriptions.laser_block import Locate
from pytest_lasertest.descriptions.mounts import link_poses, urdf_origin
from pytest_lasertest.descriptions.xmlfile import XmlElement

PRIMITIVES = ("box", "cylinder", "sphere")


def collision_top(robot: XmlElement, base: str, locate: Locate) -> float | None:
    """The highest point (m) of the collision geometry joined to `base`, in its frame; None when
    a collision is a mesh (or of a shape URDF does not define), or there is none."""
    poses = link_poses(robot, base, locate)
    tops = []
    for link in robot.all("link"):
        pose = poses.get(link.get("name") or "")
        if pose is None:  # not joined to the base: no part of this robot
            continue
        for collision in link.all("collision"):
            geometry = collision.child("geometry")
            shape = geometry.children[0] if geometry is not None and geometry.children else None
            if shape is None or shape.tag not in PRIMITIVES:
                return None
            placed = pose.then(urdf_origin(collision, locate))
            tops.append(placed.xyz[2] + _reach_up(shape, placed.rotation(), locate))
    return max(tops) if tops else None


def _reach_up(shape: XmlElement, rotation: np.ndarray, locate: Locate) -> float:
    """How far (m) the shape reaches above its centre, its axes turned by `rotation` (3, 3)."""
    up = np.abs(rotation[2])  # the world's z along each of the shape's axes
    if shape.tag == "box":
        half = np.array(_lengths(shape, "size", 3, locate)) / 2.0
        return float(up @ half)
    radius = _lengths(shape, "radius", 1, locate)[0]
    if shape.tag == "sphere":
        return radius
    length = _lengths(shape, "length", 1, locate)[0]
    return float(up[2] * length / 2.0 + radius * math.sqrt(max(1.0 - up[2] ** 2, 0.0)))


def _lengths(shape: XmlElement, attribute: str, count: int, locate: Locate) -> tuple[float, ...]:
    """The shape's `attribute`: `count` positive lengths (m)."""
    words = (shape.get(attribute) or "").split()
    try:
        numbers = tuple(float(word) for word in words)
    except ValueError:
        numbers = ()
    if len(numbers) != count or not all(math.isfinite(n) and n > 0.0 for n in numbers):
        raise locate(shape).error(
            f'<{shape.tag} {attribute}="{" ".join(words)}"> is not {count} positive length'
            f"{'s' if count > 1 else ''}",
            f'write <{shape.tag} {attribute}="..."> in m, as URDF does',
        )
    return numbers
