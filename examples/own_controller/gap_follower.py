"""A team's own controller, gated by pytest-lasertest: follow the widest gap toward the waypoint.

Of the headings within 1 rad either side of the next waypoint's, it keeps those whose corridor
(the robot's width and a margin) the scan shows clear for 3 m, takes the widest run of them (the
widest gap), and steers to the heading of that gap nearest the waypoint's, kept off the gap's
edges. It slows in proportion to the nearest reading straight ahead; when that is within 0.3 m
of its front it stands and turns toward the gap, and it stands still when there is no gap. A
waypoint more than 1 rad off its bow it turns to on the spot. It remembers nothing between scans.

`controller: gap_follower:make_controller` in a pairs file next to this module (see
gap_follower.lasertest.yaml) makes the gate drive both robots of every pair with it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from pytest_lasertest.model.geometry import FloatArray, Point2D
from pytest_lasertest.model.robot import Robot
from pytest_lasertest.nav.protocol import Controller, LaserScan, Odometry


@dataclass(frozen=True)
class GapSettings:
    """How the gap follower looks and drives."""

    window: float = 1.0  # rad either side of the waypoint's heading searched for a gap
    headings: int = 41  # headings weighed across that window
    lookahead: float = 3.0  # m beyond the front that a free heading's corridor is clear for
    margin: float = 0.1  # m either side of the footprint that the corridor holds too
    stop: float = 0.3  # m: a reading this near ahead of the front stops the robot
    slow: float = 2.0  # m: a reading nearer than this ahead slows it in proportion
    edge: int = 4  # headings kept between the course and the edge of its gap
    gain: float = 2.0  # 1/s of turn rate per rad of heading error
    reach: float = 0.15  # m: a waypoint this near is reached; the goal ends the drive


class GapFollower:
    """Follow the gap along a route of waypoints, the goal last."""

    def __init__(self, robot: Robot, route: tuple[Point2D, ...], settings: GapSettings) -> None:
        self.settings = settings
        self.route = route
        self.waypoint = 0
        footprint = robot.footprint_array()
        self.front = float(footprint[:, 0].max())  # m
        self.half_width = float(np.abs(footprint[:, 1]).max()) + settings.margin  # m
        self.speed = robot.nominal_speed  # m/s
        self.turn_rate = robot.nominal_turn_rate  # rad/s
        self.offsets = np.linspace(-settings.window, settings.window, settings.headings)  # rad

    def observe(self, scan: LaserScan, odometry: Odometry, time: float) -> tuple[float, float]:
        """Toward the waypoint through the widest gap, as fast as the reading ahead allows."""
        bearing = self._bearing(odometry)
        if bearing is None:
            return 0.0, 0.0
        if abs(bearing) > self.settings.window:
            return 0.0, self._turn(bearing)
        # Readings nearer than range_min (-inf) are something at range_min: not a free way.
        points = scan.points_in_base(within=self.front + self.settings.lookahead, too_near=True)
        heading = self._gap(points, bearing)
        if heading is None:
            return 0.0, 0.0
        ahead = self._ahead(points)
        if ahead <= self.settings.stop:
            # Blocked: stand, and turn toward the gap, which leaves the reading ahead behind.
            return 0.0, self._turn(heading)
        pace = min(1.0, (ahead - self.settings.stop) / (self.settings.slow - self.settings.stop))
        return self.speed * pace * max(0.0, math.cos(heading)), self._turn(heading)

    def _bearing(self, odometry: Odometry) -> float | None:
        """The waypoint's bearing off the bow (rad); None once the goal is reached."""
        while True:
            target = self.route[self.waypoint]
            dx, dy = target.x - odometry.x, target.y - odometry.y
            if math.hypot(dx, dy) > self.settings.reach:
                return (math.atan2(dy, dx) - odometry.yaw + math.pi) % (2 * math.pi) - math.pi
            if self.waypoint == len(self.route) - 1:
                return None
            self.waypoint += 1

    def _gap(self, points: FloatArray, bearing: float) -> float | None:
        """The heading (rad off the bow) through the widest gap, nearest the waypoint's."""
        headings = bearing + self.offsets
        along = np.outer(points[:, 0], np.cos(headings)) + np.outer(points[:, 1], np.sin(headings))
        across = np.outer(points[:, 1], np.cos(headings)) - np.outer(points[:, 0], np.sin(headings))
        blocked = (along > 0.0) & (np.abs(across) < self.half_width)
        free = ~blocked.any(axis=0)
        # Runs of free headings: [start, end) pairs from where `free` switches on and off.
        edges = np.flatnonzero(np.diff(np.concatenate([[0], free.astype(int), [0]])))
        if not len(edges):
            return None
        starts, ends = edges[0::2], edges[1::2]
        middle = len(headings) // 2
        # The widest; of two as wide, the one whose middle lies nearer the waypoint's heading.
        widest = max(
            range(len(starts)),
            key=lambda i: (ends[i] - starts[i], -abs(starts[i] + ends[i] - 1 - 2 * middle)),
        )
        start, end = int(starts[widest]), int(ends[widest]) - 1
        if end - start < 2 * self.settings.edge:
            return float(headings[(start + end) // 2])
        return float(
            headings[min(max(middle, start + self.settings.edge), end - self.settings.edge)]
        )

    def _ahead(self, points: FloatArray) -> float:
        """How far the nearest reading in the robot's width lies ahead of its front (m)."""
        in_way = (points[:, 0] > 0.0) & (np.abs(points[:, 1]) < self.half_width)
        return float(points[in_way, 0].min()) - self.front if in_way.any() else math.inf

    def _turn(self, heading: float) -> float:
        return max(-self.turn_rate, min(self.turn_rate, self.settings.gain * heading))


def make_controller(robot: Robot, route: tuple[Point2D, ...]) -> Controller:
    """The factory the pairs file names: one gap follower per drive."""
    return GapFollower(robot, route, GapSettings())
