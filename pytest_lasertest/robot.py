"""The robot under test, as far as the gate needs to know it."""

from __future__ import annotations

from dataclasses import dataclass

from pytest_lasertest.geometry import Pose3D


@dataclass(frozen=True)
class Robot:
    """A mobile robot base with one laser mount."""

    name: str
    laser_mount: Pose3D  # where a profile without its own pose is mounted, from base_link
    max_linear_velocity: float  # m/s
