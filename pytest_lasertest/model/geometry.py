"""Points, poses and angles in REP 103 frames: x forward, y left, z up, angles counter-clockwise.

Obstacles and the casts against them are in `obstacles.py`.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

FloatArray = npt.NDArray[np.float64]
IntArray = npt.NDArray[np.intp]
FULL_TURN = 2.0 * math.pi  # rad


@dataclass(frozen=True)
class Point2D:
    """A point in the world plane."""

    x: float  # m
    y: float  # m


@dataclass(frozen=True)
class Pose2D:
    """A robot pose in the world plane."""

    x: float  # m
    y: float  # m
    yaw: float  # rad


@dataclass(frozen=True)
class Pose3D:
    """A mount pose relative to the robot base, as URDF `<origin xyz rpy>`."""

    xyz: tuple[float, float, float] = (0.0, 0.0, 0.0)  # m
    rpy: tuple[float, float, float] = (0.0, 0.0, 0.0)  # rad, fixed-axis roll, pitch, yaw

    def rotation(self) -> FloatArray:
        """The 3x3 rotation matrix Rz(yaw) Ry(pitch) Rx(roll), as URDF composes it."""
        roll, pitch, yaw = self.rpy
        cr, sr = math.cos(roll), math.sin(roll)
        cp, sp = math.cos(pitch), math.sin(pitch)
        cy, sy = math.cos(yaw), math.sin(yaw)
        return np.array(
            [
                [cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
                [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
                [-sp, cp * sr, cp * cr],
            ]
        )

    def tilt(self) -> float:
        """Angle between the mounted frame's z axis and the base's z axis, up or down (rad)."""
        z_component = float(self.rotation()[2, 2])
        return math.acos(min(1.0, abs(z_component)))

    def is_upside_down(self) -> bool:
        """Whether the mounted frame's z axis points down, as a laser hung below its bracket."""
        return float(self.rotation()[2, 2]) < 0.0

    def then(self, child: Pose3D) -> Pose3D:
        """The pose `child`, given in this pose's frame, in the frame this pose is given in: the
        composition a URDF joint chain makes, parent first."""
        rotation = self.rotation()
        xyz = np.asarray(self.xyz) + rotation @ np.asarray(child.xyz)
        return _pose_from(rotation @ child.rotation(), xyz)

    def inverse(self) -> Pose3D:
        """The pose of the parent frame in this one."""
        rotation = self.rotation().T
        return _pose_from(rotation, -(rotation @ np.asarray(self.xyz)))


def _pose_from(rotation: FloatArray, xyz: FloatArray) -> Pose3D:
    """A Pose3D from a rotation matrix Rz(yaw) Ry(pitch) Rx(roll) and a translation."""
    roll = math.atan2(rotation[2, 1], rotation[2, 2])
    pitch = math.atan2(-rotation[2, 0], math.hypot(rotation[0, 0], rotation[1, 0]))
    yaw = math.atan2(rotation[1, 0], rotation[0, 0])
    x, y, z = (float(value) for value in xyz)
    # + 0.0 turns a -0.0 from atan2 into 0.0, which reads better in a printed profile.
    return Pose3D(xyz=(x, y, z), rpy=(roll + 0.0, pitch + 0.0, yaw + 0.0))


def wrap_angle(angle: float) -> float:
    """The angle in [-pi, pi) rad."""
    return (angle + math.pi) % FULL_TURN - math.pi


def wrap_angles(angles: FloatArray) -> FloatArray:
    """Angles, any shape, wrapped into [-pi, pi) rad: `wrap_angle` for arrays."""
    wrapped: FloatArray = (angles + math.pi) % FULL_TURN - math.pi
    return wrapped


def orientation(a: Sequence[float], b: Sequence[float], c: Sequence[float]) -> float:
    """Twice the signed area of the triangle a, b, c (m²): above zero where a -> b -> c turns
    counter-clockwise, below where it turns clockwise, zero where the three lie on one line."""
    return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])


def crossing_edges(corners: Sequence[Sequence[float]]) -> tuple[int, int] | None:
    """The first two edges of the closed outline through `corners` that cross each other, by
    index (edge i runs from corner i to the next, the last back to the first); None where no
    two do. Edges that only touch or run along each other do not cross: Nav2's own tests read a
    footprint of three points on one line. Quadratic in the corners, which are few."""
    count = len(corners)
    edges = [(corners[i], corners[(i + 1) % count]) for i in range(count)]
    for first, second in itertools.combinations(range(count), 2):
        # Neighbouring edges share a corner; the last edge neighbours the first.
        if second - first < 2 or second - first == count - 1:
            continue
        if _segments_cross(*edges[first], *edges[second]):
            return first, second
    return None


def _segments_cross(
    a: Sequence[float], b: Sequence[float], c: Sequence[float], d: Sequence[float]
) -> bool:
    """Whether the segments a-b and c-d cross at one point inside both."""
    return (
        orientation(a, b, c) * orientation(a, b, d) < 0.0
        and orientation(c, d, a) * orientation(c, d, b) < 0.0
    )
