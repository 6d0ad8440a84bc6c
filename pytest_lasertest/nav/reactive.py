"""The reference controller: drive toward the goal, slow and steer away from readings in the
robot's path, stop if blocked.

Where nothing is in its way it drives the solver's nominal path: it turns on the spot toward
each waypoint (at the start, and once it crosses the line through the last one), then drives
straight at it.

It remembers nothing it has seen: each command comes from the latest scan alone. A thin
obstacle that falls between two beams as the robot closes in is, to it, gone. That is the
weakness of a sparse scanner the paper's "size" pair exposes; the costmap of the full navigation
stack remembers what it marked.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from pytest_lasertest.model.geometry import FloatArray, Point2D, wrap_angle
from pytest_lasertest.model.robot import Robot
from pytest_lasertest.nav.protocol import LaserScan, Odometry


@dataclass(frozen=True)
class ReactiveSettings:
    """How cautiously the reference controller drives."""

    goal_tolerance: float = 0.2  # m, the Husky's move_base xy_goal_tolerance
    side_margin: float = 0.05  # m beside the footprint that still counts as the robot's path
    stop_gap: float = 0.15  # m: a reading this near ahead of the front blocks the robot
    slow_gap: float = 1.5  # m: a path clear for less than this is driven slowly
    near_gap: float = 0.5  # m: a reading this near straight ahead slows the robot too
    heading_gain: float = 3.0  # 1/s, turn rate per rad of heading error
    turn_in_place: float = 1.6  # rad: a heading error above this is turned on the spot
    aligned: float = 0.05  # rad: at the start and at each waypoint it turns on the spot to this
    standstill: float = 0.05  # m/s: it turns on the spot only once slower than this
    # A waypoint this near dead ahead is driven at straight: the heading error shrinks only as
    # the robot closes in, and wheels at equal speeds cost PyBullet least to step.
    dead_ahead: float = 0.01  # rad
    widest_swerve: float = 0.8  # rad: the headings weighed lie this far either side
    headings: int = 33  # how many headings are weighed
    course_keeping: float = 0.5  # weight of a change of course against a heading error


class ReactiveController:
    """The reference controller for one run along a route of waypoints, the goal last."""

    def __init__(
        self, robot: Robot, route: tuple[Point2D, ...], settings: ReactiveSettings | None = None
    ) -> None:
        self.settings = settings or ReactiveSettings()
        self.route = route
        self.waypoint = 0
        # Where the leg to the current waypoint began (m); None until the first odometry.
        self._leg_start: tuple[float, float] | None = None
        # Turning on the spot toward the current waypoint before setting off, as the nominal
        # path does at the start and at each waypoint.
        self._aligning = True
        self._last_course: float | None = None  # rad, in the odometry frame
        footprint = robot.footprint_array()
        self._front = float(footprint[:, 0].max())  # m
        self._half_width = float(np.abs(footprint[:, 1]).max()) + self.settings.side_margin  # m
        self._speed = robot.nominal_speed  # m/s
        self._turn_rate = robot.nominal_turn_rate  # rad/s
        swerve = self.settings.widest_swerve
        self._headings = np.linspace(-swerve, swerve, self.settings.headings)  # rad
        # Rows: a point's distance along each heading, then across it; one product for both.
        cos, sin = np.cos(self._headings), np.sin(self._headings)
        self._axes = np.vstack([np.column_stack([cos, sin]), np.column_stack([-sin, cos])])
        self._open = np.full(len(self._headings), np.inf)
        # Readings further than this from the base cannot narrow a path below the slow gap.
        self._relevant = math.hypot(self._front + self.settings.slow_gap, self._half_width)  # m

    def observe(self, scan: LaserScan, odometry: Odometry, time: float) -> tuple[float, float]:
        """Along the clear heading nearest the current waypoint's, as fast as its room allows."""
        error = self._heading_error(odometry)
        if error is None:
            return 0.0, 0.0
        settings = self.settings
        self._aligning = self._aligning and abs(error) > settings.aligned
        if self._aligning or abs(error) > settings.turn_in_place:
            return self._turn_on_the_spot(error, odometry)
        reach = self._relevant + _scan_offset(scan)
        room = self._room(scan.points_in_base(within=reach, too_near=True))
        if room is self._open:
            # Nothing near: no side to keep to, only the waypoint, straight at it.
            self._last_course = odometry.yaw + error
            turn = 0.0 if abs(error) <= settings.dead_ahead else settings.heading_gain * error
            return self._speed, _clamp(turn, self._turn_rate)
        if room.max() <= settings.stop_gap:
            return 0.0, 0.0
        return self._around(room, error, odometry.yaw)

    def _turn_on_the_spot(self, error: float, odometry: Odometry) -> tuple[float, float]:
        """Turn toward the waypoint, once standing: a skid-steer robot told to turn while it
        rolls skids on along its course."""
        if abs(odometry.linear) > self.settings.standstill:
            return 0.0, 0.0
        return 0.0, _clamp(self.settings.heading_gain * error, self._turn_rate)

    def _around(self, room: FloatArray, error: float, yaw: float) -> tuple[float, float]:
        """Along the heading `_choice` picks among readings in the way."""
        settings = self.settings
        heading = self._choice(room, error, yaw)
        self._last_course = yaw + float(self._headings[heading])
        turn = settings.heading_gain * float(self._headings[heading])
        # The chosen path's room sets the pace; the room straight ahead, where the robot still
        # points while it turns, may cut it to a crawl or to turning on the spot.
        pace = min(
            _ramp(room[heading], settings.stop_gap, settings.slow_gap),
            _ramp(room[len(room) // 2], settings.stop_gap, settings.near_gap),
        )
        return self._speed * pace, _clamp(turn, self._turn_rate)

    def _heading_error(self, odometry: Odometry) -> float | None:
        """The turn toward the current waypoint (rad), or None once the goal is reached."""
        here = (odometry.x, odometry.y)
        if self._leg_start is None:
            self._leg_start = here
        while self._reached(here):
            if self.waypoint == len(self.route) - 1:
                return None
            self._leg_start = (self.route[self.waypoint].x, self.route[self.waypoint].y)
            self.waypoint += 1
            self._aligning = True
        target = self.route[self.waypoint]
        return wrap_angle(math.atan2(target.y - here[1], target.x - here[0]) - odometry.yaw)

    def _reached(self, here: tuple[float, float]) -> bool:
        """Whether the robot at `here` is done with the current waypoint: within the goal
        tolerance of the goal, or past the line across the leg through any other waypoint (as
        the nominal path, it turns at the waypoint, not short of it)."""
        target = self.route[self.waypoint]
        if self.waypoint == len(self.route) - 1 or self._leg_start is None:
            return math.dist(here, (target.x, target.y)) <= self.settings.goal_tolerance
        start_x, start_y = self._leg_start
        leg = (target.x - start_x, target.y - start_y)
        done = (here[0] - start_x) * leg[0] + (here[1] - start_y) * leg[1]
        return done >= leg[0] ** 2 + leg[1] ** 2

    def _room(self, points: FloatArray) -> FloatArray:
        """How far the robot's path along each weighed heading is clear beyond its front,
        shape (H,), m; inf where no reading lies in it."""
        if not len(points):
            return self._open
        projected = self._axes @ points.T
        count = len(self._headings)
        along, across = projected[:count], projected[count:]
        np.abs(across, out=across)
        outside = across > self._half_width
        outside |= along <= 0.0
        np.putmask(along, outside, np.inf)
        room: FloatArray = along.min(axis=1) - self._front
        return room

    def _choice(self, room: FloatArray, error: float, yaw: float) -> int:
        """The heading to drive: the one nearest the waypoint's among those clear for the slow
        gap, or else the clearest. Keeping to the last course counts too, so that an obstacle
        straight ahead is passed on one side, not dithered at."""
        settings = self.settings
        clear = room >= settings.slow_gap
        if not clear.any():
            return int(np.argmax(room))
        cost = np.abs(self._headings - error)
        if self._last_course is not None:
            turned = wrap_angle(yaw - self._last_course)
            change = np.abs(self._headings + turned)
            if abs(turned) + settings.widest_swerve > math.pi:
                # A change past half a turn is the shorter way round.
                change = np.minimum(change, 2.0 * math.pi - change)
            cost += settings.course_keeping * change
        np.putmask(cost, ~clear, np.inf)
        return int(np.argmin(cost))


def _scan_offset(scan: LaserScan) -> float:
    """How far the laser sits from the base origin (m)."""
    return math.hypot(*scan.mount.xyz[:2])


def _ramp(value: float, low: float, high: float) -> float:
    """0 at or below `low`, 1 at or above `high`, linear between."""
    return min(1.0, max(0.0, (float(value) - low) / (high - low)))


def _clamp(value: float, limit: float) -> float:
    return max(-limit, min(limit, value))
