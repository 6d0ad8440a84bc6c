"""Nav2's velocity smoother, open loop, as Jazzy's nav2_bringup runs it (20 Hz) or as a params
file sets it (nav2_velocity_smoother/src/velocity_smoother.cpp, smootherTimer,
findEtaConstraint and applyConstraints, at jazzy f4108e5b). Our own code.

Each tick it clamps the latest command to the velocity limits and moves the last output toward
it by at most max_accel / smoothing_frequency while speeding up (the command's magnitude at
least the last's, same sign) and max_decel / smoothing_frequency otherwise; with
`scale_velocities`, every axis's change is first scaled by the one factor that brings the most
limited axis within its bound, so that the robot keeps the commanded direction. What it
publishes drops a speed below its axis's `deadband_velocity` to 0, while the next tick starts
from the speed before that (open loop: last_cmd_ is kept before the deadband). Between ticks the
output holds.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

Command = tuple[float, float]  # m/s, rad/s


@dataclass(frozen=True)
class SmootherSettings:
    """The smoother's parameters for x and the turn rate, with Jazzy's values."""

    smoothing_frequency: float = 20.0  # Hz
    max_velocity: tuple[float, float] = (0.5, 2.0)  # m/s, rad/s
    min_velocity: tuple[float, float] = (-0.5, -2.0)  # m/s, rad/s
    max_accel: tuple[float, float] = (2.5, 3.2)  # m/s^2, rad/s^2
    max_decel: tuple[float, float] = (-2.5, -3.2)  # m/s^2, rad/s^2
    scale_velocities: bool = False
    deadband_velocity: tuple[float, float] = (0.0, 0.0)  # m/s, rad/s
    # s: without a command for this long the smoother brakes to a stop; the stacks here command
    # every cycle, and a params file whose controller cycle is longer is refused (params.py).
    velocity_timeout: float = 1.0


class VelocitySmoother:
    """The smoother's state: its last output and when it next ticks."""

    def __init__(self, settings: SmootherSettings | None = None) -> None:
        self.settings = settings or SmootherSettings()
        self.last: Command = (0.0, 0.0)  # the last output before its deadband: the next's start
        self._published: Command = (0.0, 0.0)
        self._next = -math.inf  # s

    def due(self, time: float) -> bool:
        """Whether the smoother ticks at `time` s (its timer)."""
        return time >= self._next

    def step(self, command: Command, time: float) -> Command:
        """The output at `time` for the latest command."""
        s = self.settings
        if time < self._next:
            return self._published
        self._next = time + 1.0 / s.smoothing_frequency
        wanted = tuple(
            min(max(command[axis], s.min_velocity[axis]), s.max_velocity[axis]) for axis in (0, 1)
        )
        eta = self._eta(wanted) if s.scale_velocities else 1.0
        self.last = (
            self._axis(0, self.last[0], wanted[0], eta),
            self._axis(1, self.last[1], wanted[1], eta),
        )
        x, theta = (
            0.0 if abs(speed) < deadband else speed
            for speed, deadband in zip(self.last, s.deadband_velocity, strict=True)
        )
        self._published = (x, theta)
        return self._published

    def _eta(self, wanted: tuple[float, ...]) -> float:
        """findEtaConstraint over the axes: the factor on every change that brings the axis
        furthest out of its bound within it (1 where none is out)."""
        s, eta = self.settings, 1.0
        for axis in (0, 1):
            limits = (s.max_accel[axis], s.max_decel[axis])
            factor = eta_constraint(self.last[axis], wanted[axis], limits, s.smoothing_frequency)
            if factor > 0.0 and abs(1.0 - factor) > abs(1.0 - eta):
                eta = factor
        return eta

    def _axis(self, axis: int, current: float, wanted: float, eta: float) -> float:
        s = self.settings
        limits = (s.max_accel[axis], s.max_decel[axis])
        return apply_constraints(current, wanted, limits, s.smoothing_frequency, eta)


def change_bounds(
    current: float, wanted: float, limits: tuple[float, float], frequency: float
) -> tuple[float, float]:
    """The least and most change of a speed in one tick, `limits` (max_accel, max_decel) over
    the smoothing frequency (Hz): accelerating while the wanted speed is no smaller and of the
    same sign, braking otherwise."""
    accel, decel = limits
    if abs(wanted) >= abs(current) and current * wanted >= 0.0:
        return -accel / frequency, accel / frequency
    return decel / frequency, -decel / frequency


def eta_constraint(
    current: float, wanted: float, limits: tuple[float, float], frequency: float
) -> float:
    """findEtaConstraint: the factor that brings the change from `current` to `wanted` within a
    tick's bounds, or -1.0 where it is within them."""
    change = wanted - current
    least, most = change_bounds(current, wanted, limits, frequency)
    if change > most:
        return most / change
    if change < least:
        return least / change
    return -1.0


def apply_constraints(
    current: float, wanted: float, limits: tuple[float, float], frequency: float, eta: float
) -> float:
    """applyConstraints: the speed after one tick from `current` toward `wanted`, the change
    scaled by `eta`, then bounded."""
    least, most = change_bounds(current, wanted, limits, frequency)
    return current + min(max(eta * (wanted - current), least), most)
