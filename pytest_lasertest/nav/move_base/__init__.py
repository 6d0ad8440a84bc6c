"""An imitation of ROS move_base as the Husky runs it: costmaps, NavFn, DWA, recoveries."""

from __future__ import annotations

from pytest_lasertest.nav.move_base.move_base import MoveBase

__all__ = ["MoveBase"]
