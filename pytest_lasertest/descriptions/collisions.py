"""A URDF robot's collision geometry, placed in its base frame: the body the simulator drives for
a robot written around its description.

Each link's `<collision>` is placed by the link's pose in the base frame (`mounts.link_poses`,
every joint at zero) and the collision's `<origin>`, as urdfdom composes them. Boxes, cylinders
(their axis their own z) and spheres are read as they are. A mesh's extent is in its file, which
the gate does not read: a description with a collision mesh gives no body.

A cylinder on a link that a `continuous` joint turns, its axis along the base's y, is a wheel:
the simulator drives the body through such wheels, as gazebo_ros's diff_drive plugin drives the
joints it is given (`sim/bodies.py`). When the wheels cannot drive the body (all on one side, or
off the ground), the body slides at the commanded twist instead, and says so.
"""

from __future__ import annotations

import dataclasses
import math

from pytest_lasertest.descriptions.laser_block import Locate
from pytest_lasertest.descriptions.mounts import link_poses, spinning_links, urdf_origin
from pytest_lasertest.descriptions.xmlfile import XmlElement
from pytest_lasertest.model.body import MAX_SHAPE_LENGTH, SHAPES, Body, Collision


def collisions(robot: XmlElement, base: str, locate: Locate) -> tuple[Collision, ...] | None:
    """Every collision of the links joined to `base`, in its frame; None when one is a mesh (or
    of a shape URDF does not define), or there is none."""
    poses, spinning = link_poses(robot, base, locate), spinning_links(robot, locate)
    placed = []
    for link in robot.all("link"):
        pose = poses.get(link.get("name") or "")
        if pose is None:  # not joined to the base: no part of this robot
            continue
        for collision in link.all("collision"):
            geometry = collision.child("geometry")
            shape = geometry.children[0] if geometry is not None and geometry.children else None
            kind = SHAPES.get(shape.tag) if shape is not None else None
            if shape is None or kind is None:
                return None
            origin = pose.then(urdf_origin(collision, locate))
            placed.append(Collision(kind, _size(shape, locate), origin))
            if link.get("name") in spinning and placed[-1].axle_fault() is None:
                placed[-1] = dataclasses.replace(placed[-1], wheel=True)
    if not placed:
        return None
    if Body.described(tuple(placed)).wheel_fault() is not None:
        return tuple(dataclasses.replace(c, wheel=False) for c in placed)
    return tuple(placed)


def _size(shape: XmlElement, locate: Locate) -> tuple[float, ...]:
    """A box's size, a cylinder's radius and length, a sphere's radius (m)."""
    if shape.tag == "box":
        return _lengths(shape, "size", 3, locate)
    radius = _lengths(shape, "radius", 1, locate)
    if shape.tag == "sphere":
        return radius
    return radius + _lengths(shape, "length", 1, locate)


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
    if max(numbers) > MAX_SHAPE_LENGTH:
        raise locate(shape).error(
            f'<{shape.tag} {attribute}="{" ".join(words)}"> is larger than the '
            f"{MAX_SHAPE_LENGTH:g} m any part of a wheeled robot is (the simulator would drive "
            "it as the robot's body)",
            f'write <{shape.tag} {attribute}="..."> in m, as URDF does',
        )
    return numbers
