"""The only package that imports pybullet, in one module: `client`."""

from __future__ import annotations

from pytest_lasertest.sim.client import self_test

__all__ = ["self_test"]
