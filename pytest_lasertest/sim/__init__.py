"""The simulator. Only `client` imports pybullet; `lidar` turns its ray casts into LaserScans."""

from __future__ import annotations

from pytest_lasertest.sim.client import self_test

__all__ = ["self_test"]
