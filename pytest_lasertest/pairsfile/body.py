"""A robot's `body:`, the body the simulator drives: `husky`, the collision shapes of its
description (`collisions:`, as a robot written around its description reads them and a repro
pins them), or a prism of its footprint (`height:`).

    body:
      collisions:                            # in base_footprint, as URDF places them
        - box: {size: [0.14, 0.14, 0.143]}   # m
          xyz: [-0.032, 0.0, 0.0815]         # m
        - cylinder: {radius: 0.033, length: 0.018}
          xyz: [0.0, 0.08, 0.033]
          rpy: [-1.57, 0.0, 0.0]             # rad; 0 0 0 when left out
          wheel: true                        # driven about its axis; false when left out

A body with wheels, left and right, is driven through them; one without slides at the
commanded twist.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from pytest_lasertest.inputs.node import Bounds, SpecNode
from pytest_lasertest.model.body import (
    HUSKY_BODY,
    MAX_SHAPE_LENGTH,
    SHAPE_SIZES,
    SHAPES,
    Body,
    Collision,
    Shape,
)
from pytest_lasertest.model.geometry import Pose3D
from pytest_lasertest.model.robot import MAX_FOOTPRINT_REACH
from pytest_lasertest.pairsfile.described import DescribedLaser

# A body's height: one the laser's rays pass over, or a tower no wheeled base is.
BODY_HEIGHT = Bounds(
    0.01,
    5.0,
    "m",
    "a body this flat is no robot",
    "no wheeled robot's base stands 5 m high",
)  # (the Husky's base: 0.39)
LENGTH = Bounds(
    0.0,
    MAX_SHAPE_LENGTH,
    "m",
    "a shape has a size",
    "no part of a wheeled robot is 5 m across",
    above_low=True,
)
MAX_COLLISIONS = 200  # a description has a few dozen links; PyBullet tests each shape per step
BODY_FIX = (
    "write `body: husky` (pybullet_data's Husky, driven through its wheels), "
    "`body: {collisions: [...]}` (its description's collision shapes, driven through those "
    "marked `wheel: true`) or `body: {height: H}` (a prism of the footprint, H m high, moved "
    "at the commanded twist)"
)
SHAPE_FIX = (
    "write one of `box: {size: [x, y, z]}`, `cylinder: {radius: R, length: L}` or "
    "`sphere: {radius: R}` (m), with `xyz: [x, y, z]` and optionally `rpy: [r, p, y]` and "
    "`wheel: true`"
)
WHEEL_FIX = (
    "mark `wheel: true` on the cylinders the base rolls on, one or more each side, each turned "
    "so that its axis lies along y (rpy [-1.57, 0, 0]); leave it out of every shape for a body "
    "moved at the commanded twist"
)


def read_body(node: SpecNode, footprint: tuple[tuple[float, float], ...]) -> Body:
    """The body a `body:` field names or describes; a prism is of the (unpadded) footprint."""
    if isinstance(node.value, str):
        if node.text() != "husky":
            raise node.error(f"{node.value!r} is not a body the simulator has", BODY_FIX)
        return HUSKY_BODY
    fields = node.mapping(("height", "collisions"), what="body fields")
    if not fields:
        raise node.missing("height", BODY_FIX)
    if len(fields) > 1:
        raise node.error("a body is given by its height or by its collisions, not both", BODY_FIX)
    if "height" in fields:
        return Body("prism", footprint, fields["height"].number_in(BODY_HEIGHT))
    shapes = fields["collisions"].items(what="collision shapes")
    if not shapes or len(shapes) > MAX_COLLISIONS:
        raise fields["collisions"].error(
            f"{len(shapes)} collision shapes: a body has from 1 to {MAX_COLLISIONS}", SHAPE_FIX
        )
    body = checked(node, tuple(_collision(shape) for shape in shapes))
    fault = body.wheel_fault()
    if fault is not None:
        raise fields["collisions"].error(fault, WHEEL_FIX)
    return body


def described_body(node: SpecNode, file_node: SpecNode, laser: DescribedLaser) -> Body:
    """The collision shapes of the description `file_node` names, as the robot's body."""
    collisions = laser.laser.collisions()
    if collisions is None:
        raise node.missing(
            "body",
            "the description's collision geometry cannot be read (it holds a mesh, or no "
            f"collision, or it is SDF): {BODY_FIX}",
        )
    return checked(file_node, collisions)


def checked(node: SpecNode, collisions: tuple[Collision, ...]) -> Body:
    """The body of these collisions, refused at `node` if it is no robot's height."""
    body = Body.described(collisions)
    BODY_HEIGHT.check(node, body.height)
    return body


def _collision(node: SpecNode) -> Collision:
    fields = node.mapping(
        ("box", "cylinder", "sphere", "xyz", "rpy", "wheel"), what="collision fields"
    )
    kinds = [SHAPES[key] for key in fields if key in SHAPES]
    if len(kinds) != 1:
        raise node.error("a collision is one shape", SHAPE_FIX)
    if "xyz" not in fields:
        raise node.missing("xyz", SHAPE_FIX)
    xyz = fields["xyz"].triple("m")
    if float(np.abs(xyz).max()) > MAX_FOOTPRINT_REACH:
        raise fields["xyz"].error(
            f"{list(xyz)} m lies more than {MAX_FOOTPRINT_REACH:g} m from the robot's base",
            SHAPE_FIX,
        )
    rpy = fields["rpy"].triple("rad") if "rpy" in fields else (0.0, 0.0, 0.0)
    collision = Collision(kinds[0], _size(fields[kinds[0]], kinds[0]), Pose3D(xyz, rpy))
    if "wheel" not in fields or not fields["wheel"].truth():
        return collision
    fault = collision.axle_fault()
    if fault is not None:
        raise fields["wheel"].error(f"this shape cannot be a wheel: {fault}", WHEEL_FIX)
    return dataclasses.replace(collision, wheel=True)


def _size(node: SpecNode, shape: Shape) -> tuple[float, ...]:
    if shape == "box":
        size = node.mapping(("size",), what="box fields")
        if "size" not in size:
            raise node.missing("size", SHAPE_FIX)
        return tuple(LENGTH.check(size["size"], length) for length in size["size"].triple("m"))
    names = SHAPE_SIZES[shape]
    fields = node.mapping(names, what=f"{shape} fields")
    for name in names:
        if name not in fields:
            raise node.missing(name, SHAPE_FIX)
    return tuple(fields[name].number_in(LENGTH) for name in names)


def body_fields(body: Body) -> object:
    """The body as `body:` writes it, each value in full (YAML round-trips a float's repr), so
    that a repro drives the same body after its description moves on."""
    if body.kind == "husky":
        return "husky"
    if body.kind == "prism":
        return {"height": float(body.height)}
    return {"collisions": [_written(collision) for collision in body.collisions]}


def _written(collision: Collision) -> dict[str, object]:
    size = [float(length) for length in collision.size]
    shape = (
        {"size": size}
        if collision.shape == "box"
        else dict(zip(SHAPE_SIZES[collision.shape], size, strict=True))
    )
    pose = collision.pose
    written: dict[str, object] = {
        collision.shape: shape,
        "xyz": [float(value) for value in pose.xyz],
        "rpy": [float(value) for value in pose.rpy],
    }
    return written | ({"wheel": True} if collision.wheel else {})
