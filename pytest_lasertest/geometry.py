"""Poses in REP 103 frames: x forward, y left, z up, angles counter-clockwise."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

FloatArray = npt.NDArray[np.float64]


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


def wrap_angle(angles: FloatArray) -> FloatArray:
    """Angles wrapped into [-pi, pi)."""
    wrapped: FloatArray = (angles + math.pi) % (2.0 * math.pi) - math.pi
    return wrapped
