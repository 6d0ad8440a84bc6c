"""The body the simulator drives: pybullet_data's Husky through its wheels, the collision geometry
of the robot's own description, or a prism of its footprint; the last two moved at the commanded
twist."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Literal

import numpy as np

from pytest_lasertest.model.geometry import FloatArray, Pose3D

Shape = Literal["box", "cylinder", "sphere"]
# The primitives URDF defines, by their tags.
SHAPES: dict[str, Shape] = {"box": "box", "cylinder": "cylinder", "sphere": "sphere"}
# The lengths each shape is given by, in the order a description gives them.
SHAPE_SIZES: dict[Shape, tuple[str, ...]] = {
    "box": ("x", "y", "z"),
    "cylinder": ("radius", "length"),
    "sphere": ("radius",),
}


@dataclass(frozen=True)
class Collision:
    """One `<collision>` of a description: a primitive placed in base_footprint, a cylinder's
    axis its own z, as URDF and PyBullet take them."""

    shape: Shape
    size: tuple[float, ...]  # m: a box's x, y, z lengths; a cylinder's radius, length; a radius
    pose: Pose3D  # its centre and axes in base_footprint

    def corners(self) -> FloatArray:
        """The corners of the box around the shape, in base_footprint, shape (8, 3), m: exact
        for a box, and for the others the box around them in their own axes."""
        if self.shape == "box":
            half = np.array(self.size) / 2.0
        elif self.shape == "cylinder":
            radius, length = self.size
            half = np.array([radius, radius, length / 2.0])
        else:
            half = np.full(3, self.size[0])
        signs = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)])
        corners: FloatArray = (signs * half) @ self.pose.rotation().T + np.array(self.pose.xyz)
        return corners

    def vertical_reach(self) -> float:
        """How far (m) the shape reaches above and below its centre."""
        up = np.abs(self.pose.rotation()[2])  # the base's z along each of the shape's axes
        if self.shape == "box":
            return float(up @ (np.array(self.size) / 2.0))
        if self.shape == "sphere":
            return self.size[0]
        radius, length = self.size
        return float(up[2] * length / 2.0 + radius * math.sqrt(max(1.0 - up[2] ** 2, 0.0)))


@dataclass(frozen=True)
class Body:
    """What the simulator drives: pybullet_data's Husky through its wheels; its description's
    collisions as one rigid body; or a prism of its footprint. The last two slide on the ground
    at the commanded twist."""

    kind: Literal["husky", "description", "prism"]
    outline: tuple[tuple[float, float], ...] = ()  # m, the prism's footprint, unpadded
    height: float = 0.0  # m, how tall it is
    collisions: tuple[Collision, ...] = ()  # the description's

    @classmethod
    def described(cls, collisions: tuple[Collision, ...]) -> Body:
        """The body of a description's collisions, as tall as they reach from the lowest."""
        return cls(
            "description",
            height=cls.top(collisions) - cls.bottom(collisions),
            collisions=collisions,
        )

    @staticmethod
    def top(collisions: tuple[Collision, ...]) -> float:
        """The highest point of the shapes above their base frame (m)."""
        return max(c.pose.xyz[2] + c.vertical_reach() for c in collisions)

    @staticmethod
    def bottom(collisions: tuple[Collision, ...]) -> float:
        """The lowest point of the shapes above their base frame (m): 0 where the frame is
        base_footprint, below it where the frame is a base_link above the ground."""
        return min(c.pose.xyz[2] - c.vertical_reach() for c in collisions)

    def extent(self) -> FloatArray:
        """The body's [low, high] corners in base_footprint's plane, shape (2, 2), m; the
        Husky's is in pybullet_data's URDF, not known here."""
        if self.kind == "husky":
            raise ValueError("pybullet_data's Husky has no extent but PyBullet's")
        if self.kind == "prism":
            points = np.array(self.outline)
        else:
            points = np.vstack([c.corners()[:, :2] for c in self.collisions])
        return np.array([points.min(axis=0), points.max(axis=0)])

    def describe(self) -> str:
        """`pybullet_data's Husky, driven through its wheels`, or the body's size and kind."""
        if self.kind == "husky":
            return "pybullet_data's Husky, driven through its wheels"
        low, high = self.extent()
        length, width = high - low
        size = f"{length:.2f} x {width:.2f} x {self.height:.2f} m"
        if self.kind == "prism":
            return f"a prism of its footprint, {size}, moved at the commanded twist"
        return (
            f"its description's {len(self.collisions)} collision shapes, {size}, moved at the "
            "commanded twist"
        )


HUSKY_BODY = Body("husky")
