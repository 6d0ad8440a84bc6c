"""Nav2's velocity smoother as Jazzy's nav2_bringup runs it: open loop, 20 Hz, velocities and
accelerations bounded axis by axis (nav2_velocity_smoother/src/velocity_smoother.cpp,
smootherTimer and applyConstraints, at jazzy f4108e5b; scale_velocities false, deadbands 0).
Our own code.

Each tick it clamps the latest command to the velocity limits and moves the last output toward
it by at most max_accel / 20 Hz while speeding up (the command's magnitude at least the last's,
same sign) and max_decel / 20 Hz otherwise; between ticks the output holds.
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


class VelocitySmoother:
    """The smoother's state: its last output and when it next ticks."""

    def __init__(self, settings: SmootherSettings | None = None) -> None:
        self.settings = settings or SmootherSettings()
        self.last: Command = (0.0, 0.0)
        self._next = -math.inf  # s

    def due(self, time: float) -> bool:
        """Whether the smoother ticks at `time` s (its 20 Hz timer)."""
        return time >= self._next

    def step(self, command: Command, time: float) -> Command:
        """The output at `time` for the latest command."""
        s = self.settings
        if time < self._next:
            return self.last
        self._next = time + 1.0 / s.smoothing_frequency
        self.last = (
            self._axis(0, self.last[0], command[0]),
            self._axis(1, self.last[1], command[1]),
        )
        return self.last

    def _axis(self, axis: int, current: float, wanted: float) -> float:
        s = self.settings
        wanted = min(max(wanted, s.min_velocity[axis]), s.max_velocity[axis])
        speeding_up = abs(wanted) >= abs(current) and current * wanted >= 0.0
        if speeding_up:
            most = s.max_accel[axis] / s.smoothing_frequency
            least = -most
        else:
            most = -s.max_decel[axis] / s.smoothing_frequency
            least = s.max_decel[axis] / s.smoothing_frequency
        return current + min(max(wanted - current, least), most)
