"""The body the simulator drives: pybullet_data's Husky through its wheels, the collision geometry
of the robot's own description (through its wheel joints when it has them), or a prism of its
footprint; a body without wheels is moved at the commanded twist."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Literal

import numpy as np

from pytest_lasertest.model.geometry import FloatArray, Pose3D

Shape = Literal["box", "cylinder", "sphere"]
# The primitives URDF defines, by their tags.
SHAPES: dict[str, Shape] = {"box": "box", "cylinder": "cylinder", "sphere": "sphere"}
# No part of a wheeled robot is larger: a robot file's and a description's shapes alike.
MAX_SHAPE_LENGTH = 5.0  # m
# The lengths each shape is given by, in the order a description gives them.
SHAPE_SIZES: dict[Shape, tuple[str, ...]] = {
    "box": ("x", "y", "z"),
    "cylinder": ("radius", "length"),
    "sphere": ("radius",),
}
# How far a wheel's axle may lean from the base's y axis: a wheel rolls forward, and the
# descriptions' -1.57 rad for -pi/2 leaves 0.0008 rad.
WHEEL_AXLE_TOLERANCE = math.radians(5.0)  # rad
# How far above the body's lowest point a wheel's may be and still bear on the ground (a caster
# box, say, reaching a little lower).
WHEEL_GROUND_TOLERANCE = 0.005  # m


@dataclass(frozen=True)
class Collision:
    """One `<collision>` of a description: a primitive placed in base_footprint, a cylinder's
    axis its own z, as URDF and PyBullet take them."""

    shape: Shape
    size: tuple[float, ...]  # m: a box's x, y, z lengths; a cylinder's radius, length; a radius
    pose: Pose3D  # its centre and axes in base_footprint
    wheel: bool = False  # a cylinder driven about its own axis, by a continuous joint

    def axle(self) -> FloatArray:
        """The shape's own z axis in base_footprint, shape (3,): a cylinder's axis."""
        axis: FloatArray = self.pose.rotation()[:, 2]
        return axis

    def axle_fault(self) -> str | None:
        """Why this shape cannot be a wheel the base rolls on, or None when it can."""
        if self.shape != "cylinder":
            return f"a {self.shape} does not roll: a wheel is a cylinder"
        if abs(float(self.axle()[1])) < math.cos(WHEEL_AXLE_TOLERANCE):
            return (
                "its axis does not lie along the base's y axis (a wheel rolls forward): turn "
                "it with rpy, as a URDF wheel is, e.g. [-1.57, 0, 0]"
            )
        if abs(self.pose.xyz[1]) < self.size[1] / 2.0:
            return "it straddles the base's x axis: a wheel drives the left or the right side"
        return None

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
    collisions, through its wheels when it names them and as one rigid body otherwise; or a
    prism of its footprint. A body without wheels slides on the ground at the commanded twist."""

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

    def wheel_fault(self) -> str | None:
        """Why the wheels cannot drive the body, or None when they can (or it has none)."""
        wheels = self.wheels
        if wheels and not (
            any(w.pose.xyz[1] > 0.0 for w in wheels) and any(w.pose.xyz[1] < 0.0 for w in wheels)
        ):
            return "a body drives on wheels both left (y > 0) and right (y < 0) of its base"
        lowest = self.bottom(self.collisions)
        for wheel in wheels:
            above = wheel.pose.xyz[2] - wheel.vertical_reach() - lowest
            if above > WHEEL_GROUND_TOLERANCE:
                return (
                    f"the wheel at y = {wheel.pose.xyz[1]:g} m stops {above:.3f} m above the "
                    "body's lowest point: it would not touch the ground"
                )
        return None

    @staticmethod
    def top(collisions: tuple[Collision, ...]) -> float:
        """The highest point of the shapes above their base frame (m)."""
        return max(c.pose.xyz[2] + c.vertical_reach() for c in collisions)

    @staticmethod
    def bottom(collisions: tuple[Collision, ...]) -> float:
        """The lowest point of the shapes above their base frame (m): 0 where the frame is
        base_footprint, below it where the frame is a base_link above the ground."""
        return min(c.pose.xyz[2] - c.vertical_reach() for c in collisions)

    @property
    def wheels(self) -> tuple[Collision, ...]:
        """The description's wheels, each driven about its own axis; none for the others."""
        return tuple(c for c in self.collisions if c.wheel)

    @property
    def steering(self) -> str:
        """How it turns: `differential` with one wheel a side, `skid-steer` with more, or
        `moved at the commanded twist` without wheels."""
        if not self.wheels:
            return "moved at the commanded twist"
        return "differential" if len(self.wheels) == 2 else "skid-steer"

    def track(self) -> tuple[float, float]:
        """The wheels' radius and the distance between the left and the right ones (m, m),
        each the mean of its side's."""
        left = [w for w in self.wheels if w.pose.xyz[1] > 0.0]
        right = [w for w in self.wheels if w.pose.xyz[1] < 0.0]
        radius = sum(w.size[0] for w in self.wheels) / len(self.wheels)
        return radius, _mean_y(left) - _mean_y(right)

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
        shapes = f"its description's {len(self.collisions)} collision shapes, {size}"
        if not self.wheels:
            return f"{shapes}, moved at the commanded twist"
        return f"{shapes}, driven through its {len(self.wheels)} wheel joints ({self.steering})"


def _mean_y(wheels: list[Collision]) -> float:
    return sum(w.pose.xyz[1] for w in wheels) / len(wheels)


HUSKY_BODY = Body("husky")
