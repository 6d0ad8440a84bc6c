"""Nav2's behaviour server as the default behaviour tree calls it: Spin, BackUp and Wait, each
checking ahead for collisions on the local costmap (nav2_behaviors at jazzy f4108e5b:
plugins/spin.cpp, plugins/drive_on_heading.hpp (BackUp drives on a heading backwards),
plugins/wait.cpp; nav2_params.yaml's behavior_server, `BehaviorSettings`). Our own code.

A behaviour is stepped at each scan with the robot's pose and the time; it answers a command,
or None once it has ended (`failed` says whether it failed).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field

Pose = tuple[float, float, float]  # m, m, rad
Collides = Callable[[Pose], bool]  # whether the footprint at a pose meets a lethal cell


@dataclass(frozen=True)
class BehaviorSettings:
    """The behaviour server's parameters, with Nav2's names and Jazzy's values."""

    cycle_frequency: float = 10.0  # Hz
    simulate_ahead_time: float = 2.0  # s
    max_rotational_vel: float = 1.0  # rad/s
    min_rotational_vel: float = 0.4  # rad/s
    rotational_acc_lim: float = 3.2  # rad/s^2

    @property
    def cycle_period(self) -> float:
        return 1.0 / self.cycle_frequency  # s

    @property
    def cycles_ahead(self) -> int:
        """How many cycles a collision check looks ahead."""
        return int(self.simulate_ahead_time / self.cycle_period)


TIME_ALLOWANCE = 10.0  # s, DriveOnHeading's and Spin's default time_allowance


def _turned(turned: float, last_yaw: float, yaw: float) -> float:
    """The signed angle turned so far plus the step from `last_yaw` to `yaw`, unwrapped as
    Spin::onCycleUpdate unwraps it (a step past pi taken the other way, signed as the last
    yaw)."""
    step = yaw - last_yaw
    if abs(step) > math.pi:
        step = math.copysign(2.0 * math.pi - abs(step), last_yaw)
    return turned + step


@dataclass
class Spin:
    """Turn `distance` rad in place (positive: counter-clockwise), slowing with the
    acceleration limit as it nears the end; fail when the turn ahead would collide or the time
    allowance runs out."""

    distance: float  # rad
    collides: Collides
    settings: BehaviorSettings = field(default_factory=BehaviorSettings)
    began: float | None = None  # s
    turned: float = 0.0  # rad
    last_yaw: float | None = None
    failed: bool = False

    def step(self, pose: Pose, time: float) -> tuple[float, float] | None:
        if self.began is None:
            self.began, self.last_yaw = time, pose[2]
        assert self.last_yaw is not None
        self.turned, self.last_yaw = _turned(self.turned, self.last_yaw, pose[2]), pose[2]
        remaining = abs(self.distance) - abs(self.turned)
        if remaining < 1e-6:
            return None
        if time - self.began > TIME_ALLOWANCE:
            self.failed = True
            return None
        s = self.settings
        speed = min(
            s.max_rotational_vel,
            max(s.min_rotational_vel, math.sqrt(2.0 * s.rotational_acc_lim * remaining)),
        )
        turn = math.copysign(speed, self.distance)
        if self._collides_ahead(pose, turn):
            self.failed = True
            return None
        return 0.0, turn

    def _collides_ahead(self, pose: Pose, turn: float) -> bool:
        """Spin::isCollisionFree: the poses of the next simulate_ahead_time of turning, one
        cycle apart from the robot's own; it stops once the change reaches the angle already
        turned, not the angle left, as Nav2 writes it (so the first cycle checks nothing)."""
        for cycle in range(self.settings.cycles_ahead):
            change = turn * cycle * self.settings.cycle_period
            if abs(self.turned) - abs(change) <= 0.0:
                break
            if self.collides((pose[0], pose[1], pose[2] + change)):
                return True
        return False


@dataclass
class BackUp:
    """Drive straight backwards `distance` m at `speed` m/s; fail when the path ahead would
    collide or the time allowance runs out."""

    distance: float  # m
    speed: float  # m/s
    collides: Collides
    settings: BehaviorSettings = field(default_factory=BehaviorSettings)
    start: Pose | None = None
    began: float | None = None  # s
    failed: bool = False

    def step(self, pose: Pose, time: float) -> tuple[float, float] | None:
        if self.start is None or self.began is None:
            self.start, self.began = pose, time
        travelled = math.hypot(pose[0] - self.start[0], pose[1] - self.start[1])
        if travelled >= self.distance:
            return None
        remaining = self.distance - travelled
        if time - self.began > TIME_ALLOWANCE:
            self.failed = True
            return None
        if self._collides_ahead(pose, remaining):
            self.failed = True
            return None
        return -self.speed, 0.0

    def _collides_ahead(self, pose: Pose, remaining: float) -> bool:
        """DriveOnHeading::isCollisionFree: the poses of the next simulate_ahead_time of
        driving, one cycle apart from the robot's own, short of the distance left."""
        for cycle in range(self.settings.cycles_ahead):
            moved = self.speed * cycle * self.settings.cycle_period
            if remaining - moved <= 0.0:
                break
            back = (
                pose[0] - moved * math.cos(pose[2]),
                pose[1] - moved * math.sin(pose[2]),
                pose[2],
            )
            if self.collides(back):
                return True
        return False


@dataclass
class Wait:
    """Stand still for `duration` s."""

    duration: float  # s
    began: float | None = None
    failed: bool = False

    def step(self, pose: Pose, time: float) -> tuple[float, float] | None:
        if self.began is None:
            self.began = time
        return None if time - self.began >= self.duration else (0.0, 0.0)
