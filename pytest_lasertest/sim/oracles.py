"""The oracles of a run, each a small frozen verdict with a margin, never a bare bool.

- collision: any contact between the robot and an obstacle; margin = the least clearance.
- stuck: no progress toward the goal by more than `stuck_distance` within `stuck_window`
  (CARLA ScenarioRunner's ActorBlocked idea); margin = the least progress over a window, less
  the distance it had to make.
- goal: within `goal_tolerance` of the goal before the time limit; margin = the tolerance less
  the nearest approach.

A `Referee` watches the run step by step and says when it is decided, so a run that has
collided, stuck or arrived stops there.
"""

from __future__ import annotations

import itertools
import math
from collections import deque
from dataclasses import dataclass

from pytest_lasertest.model.geometry import Point2D


@dataclass(frozen=True)
class Rules:
    """What the oracles count as a failure."""

    goal_tolerance: float = 0.2  # m, the Husky's move_base xy_goal_tolerance
    stuck_distance: float = 0.1  # m of progress toward the goal ...
    stuck_window: float = 10.0  # s ... that must be made within this long
    clearance_horizon: float = 0.5  # m: a clearance beyond this is reported as this


@dataclass(frozen=True)
class Collision:
    """Whether the robot touched an obstacle, and how near it came."""

    time: float | None  # s, of the first contact; None for none
    clearance: float  # m, the least over the run, at most the rules' horizon; <= 0 on contact

    @property
    def passed(self) -> bool:
        return self.time is None

    @property
    def margin(self) -> float:
        """The least clearance (m)."""
        return self.clearance

    def describe(self) -> str:
        if self.time is None:
            return f"no collision, least clearance {self.clearance * 1000:.0f} mm"
        return f"collided at t = {self.time:.2f} s"


@dataclass(frozen=True)
class Stuck:
    """Whether the robot stopped making progress toward the goal."""

    time: float | None  # s, when a whole window passed without progress; None if never
    least_progress: float  # m, over any whole window (inf if the run was shorter than one)
    distance: float  # m, the progress a window needs
    window: float  # s

    @property
    def passed(self) -> bool:
        return self.time is None

    @property
    def margin(self) -> float:
        """How much more than the needed progress the slowest window made (m)."""
        return self.least_progress - self.distance

    def describe(self) -> str:
        if self.time is None:
            return "never stuck"
        # In mm, rounded down: a window that fell short by a hair must not read as enough.
        progress = math.floor(self.least_progress * 1e4) / 10.0
        return (
            f"stuck at t = {self.time:.2f} s: {progress:.1f} mm of progress in "
            f"{self.window:g} s, {self.distance * 1000:g} mm needed"
        )


@dataclass(frozen=True)
class Goal:
    """Whether the robot reached the goal in time."""

    time: float | None  # s, when it came within tolerance; None if it did not
    nearest: float  # m, the robot's least distance to the goal
    tolerance: float  # m

    @property
    def passed(self) -> bool:
        return self.time is not None

    @property
    def margin(self) -> float:
        """How far inside the tolerance the robot came (m); negative if it stayed out."""
        return self.tolerance - self.nearest

    def describe(self) -> str:
        if self.time is None:
            return f"goal not reached: {self.nearest:.2f} m away at best"
        return f"goal reached at t = {self.time:.2f} s"


@dataclass(frozen=True)
class Verdicts:
    """The three oracles' verdicts on one run."""

    collision: Collision
    stuck: Stuck
    goal: Goal

    @property
    def passed(self) -> bool:
        return self.collision.passed and self.stuck.passed and self.goal.passed

    def named(self) -> tuple[tuple[str, Collision | Stuck | Goal], ...]:
        """Each oracle's name and verdict, in the order they are judged."""
        return (("collision", self.collision), ("stuck", self.stuck), ("goal", self.goal))

    def failures(self) -> list[str]:
        """The failing oracles, described, in the order they are judged."""
        return [verdict.describe() for _, verdict in self.named() if not verdict.passed]


class Referee:
    """Watches one run, step by step, and decides it."""

    def __init__(
        self, rules: Rules, start: Point2D, route: tuple[Point2D, ...], time_step: float
    ) -> None:
        self.rules = rules
        self._goal = route[-1]
        corners = [(start.x, start.y), *((point.x, point.y) for point in route)]
        lengths = [math.dist(a, b) for a, b in itertools.pairwise(corners)]
        self._legs = [
            _Leg(a, b, length, sum(lengths[index + 1 :]))
            for index, ((a, b), length) in enumerate(
                zip(itertools.pairwise(corners), lengths, strict=True)
            )
        ]
        self._window_steps = max(1, round(rules.stuck_window / time_step))
        # The remaining route over the last window, oldest first.
        self._remaining: deque[float] = deque(maxlen=self._window_steps + 1)
        self._contact: float | None = None
        self._stuck: float | None = None
        self._arrived: float | None = None
        self._clearance = rules.clearance_horizon
        self._nearest = math.inf
        self._least_progress = math.inf

    def update(self, time: float, x: float, y: float, clearance: float, touching: bool) -> bool:
        """Record the robot at (x, y) m after the step ending at `time` s; True once decided."""
        self._clearance = min(self._clearance, clearance)
        if touching and self._contact is None:
            self._contact = time
        goal = self._goal
        self._nearest = min(self._nearest, math.hypot(goal.x - x, goal.y - y))
        if self._nearest <= self.rules.goal_tolerance and self._arrived is None:
            self._arrived = time
        self._judge_progress(time, self._remaining_route(x, y))
        return any(t is not None for t in (self._contact, self._stuck, self._arrived))

    def verdicts(self) -> Verdicts:
        """The verdicts on the run so far."""
        rules = self.rules
        return Verdicts(
            Collision(self._contact, self._clearance),
            Stuck(self._stuck, self._least_progress, rules.stuck_distance, rules.stuck_window),
            Goal(self._arrived, self._nearest, rules.goal_tolerance),
        )

    def _remaining_route(self, x: float, y: float) -> float:
        """How far the robot is from the goal along the route: over each leg, the way to its
        nearest point, then along it and the legs after it."""
        return min(leg.remaining(x, y) for leg in self._legs)

    def _judge_progress(self, time: float, remaining: float) -> None:
        self._remaining.append(remaining)
        if len(self._remaining) <= self._window_steps:
            return
        progress = self._remaining[0] - remaining
        self._least_progress = min(self._least_progress, progress)
        if progress <= self.rules.stuck_distance and self._stuck is None:
            self._stuck = time


@dataclass(frozen=True)
class _Leg:
    """A straight stretch of the route, and the route's length after it."""

    start: tuple[float, float]  # m
    end: tuple[float, float]  # m
    length: float  # m
    tail: float  # m, from its end to the goal

    def remaining(self, x: float, y: float) -> float:
        """The way from (x, y) to the leg's nearest point, then along the leg and its tail (m)."""
        (start_x, start_y), (end_x, end_y) = self.start, self.end
        fraction = 1.0
        if self.length > 0.0:
            along = (x - start_x) * (end_x - start_x) + (y - start_y) * (end_y - start_y)
            fraction = min(1.0, max(0.0, along / self.length**2))
        nearest_x = start_x + fraction * (end_x - start_x)
        nearest_y = start_y + fraction * (end_y - start_y)
        return math.hypot(x - nearest_x, y - nearest_y) + (1.0 - fraction) * self.length + self.tail
