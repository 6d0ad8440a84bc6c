"""move_base's recovery behaviours, and the back-up one it lacks.

Each runs to its end before move_base plans again, as a ROS recovery blocks move_base: `step`
answers the command to drive until the next call, or None once the behaviour is over. Those
that move check the local costmap first and stop short of a collision, as RotateRecovery does.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Protocol

import numpy as np

from pytest_lasertest.model.geometry import FloatArray, wrap_angle
from pytest_lasertest.nav.move_base.costmap import Costmap

Pose = tuple[float, float, float]  # [x, y, yaw] m, m, rad in the odom frame
# Whether the footprint at each pose (P, 3) is clear of lethal cells.
Clear = Callable[[FloatArray], bool]


class Recovery(Protocol):
    """A behaviour move_base runs when it cannot plan or control."""

    name: str

    def step(self, pose: Pose, time: float) -> tuple[float, float] | None:
        """The command [m/s, rad/s] to drive until the next call, or None once done."""
        ...


@dataclass
class ClearCostmap:
    """clear_costmap_recovery: forget what the costmap holds beyond a square around the
    robot, `reset_distance` m wide."""

    name: str
    costmap: Costmap
    reset_distance: float  # m

    def step(self, pose: Pose, time: float) -> tuple[float, float] | None:
        self.costmap.clear_outside(pose[0], pose[1], self.reset_distance)
        return None


@dataclass(frozen=True)
class RotateSettings:
    """rotate_recovery's parameters, with its names; the defaults are its own."""

    frequency: float = 20.0  # Hz
    sim_granularity: float = 0.017  # rad between the footprints it checks
    tolerance: float = 0.1  # rad
    max_rotational_vel: float = 1.0  # rad/s
    min_in_place_rotational_vel: float = 0.4  # rad/s
    acc_lim_th: float = 3.2  # rad/s^2


class RotateInPlace:
    """rotate_recovery: one full turn counter-clockwise on the spot, past the half turn and
    back to where it began; it gives up as soon as the rest of the turn would collide."""

    name = "rotate_recovery"

    def __init__(self, clear: Clear, settings: RotateSettings | None = None) -> None:
        self.settings = settings or RotateSettings()
        self.clear = clear
        self._start: float | None = None  # rad
        self._half_way = False
        self._next = -math.inf  # s, when it next decides
        self._command: tuple[float, float] | None = (0.0, 0.0)

    def step(self, pose: Pose, time: float) -> tuple[float, float] | None:
        if time >= self._next:
            self._next = time + 1.0 / self.settings.frequency
            self._command = self._decide(pose)
        return self._command

    def _decide(self, pose: Pose) -> tuple[float, float] | None:
        settings, yaw = self.settings, pose[2]
        if self._start is None:
            self._start = yaw
        to_half = abs(wrap_angle(yaw - (self._start + math.pi)))
        self._half_way = self._half_way or to_half < settings.tolerance
        left = abs(wrap_angle(yaw - self._start)) if self._half_way else math.pi + to_half
        if self._half_way and left <= settings.tolerance:
            return None
        turns = yaw + np.arange(0.0, left, settings.sim_granularity)
        if not self.clear(
            np.column_stack([np.full_like(turns, pose[0]), np.full_like(turns, pose[1]), turns])
        ):
            return None
        speed = math.sqrt(2.0 * settings.acc_lim_th * left)
        speed = min(max(speed, settings.min_in_place_rotational_vel), settings.max_rotational_vel)
        return 0.0, speed


class BackUp:
    """Ours, not move_base's: reverse straight back `distance` m at `speed`, checking the way
    back first, as the back-up recovery of ROS 2's nav2 does."""

    name = "back_up_recovery"

    def __init__(self, clear: Clear, distance: float, speed: float) -> None:
        self.clear = clear
        self.distance = distance  # m
        self.speed = speed  # m/s
        self._start: tuple[float, float] | None = None  # m

    def step(self, pose: Pose, time: float) -> tuple[float, float] | None:
        if self._start is None:
            self._start = (pose[0], pose[1])
        left = self.distance - math.dist(self._start, pose[:2])
        if left <= 0.0:
            return None
        back = -np.arange(0.0, left + 0.025, 0.025)  # m, a step at most half a cell
        way = np.column_stack(
            [
                pose[0] + back * math.cos(pose[2]),
                pose[1] + back * math.sin(pose[2]),
                np.full_like(back, pose[2]),
            ]
        )
        if not self.clear(way):
            return None
        return -self.speed, 0.0
