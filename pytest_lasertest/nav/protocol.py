"""What a controller sees and answers: ROS's LaserScan and Odometry in, a velocity command out.

A scenario makes one controller per run (`ControllerFactory`) and calls `observe` with each scan
at the scanner's update rate; the command it returns holds until the next scan, as a ROS node's
cmd_vel holds until the next message. The simulator holds a controller to this (`sim/guard.py`):
a command is two finite numbers (a tuple, a list or a numpy array of two), and a controller that
raises, answers anything else, or takes more wall-clock time than 5 s plus the simulated time
driven, fails the drive. A controller may also have a `goal_tolerance` (m), how near the goal
its own goal checker counts it arrived: the goal oracle then judges the run by it instead of
the rules' (`sim/oracles.py`), so that a stack that stops where its goal checker says is not
failed for stopping there.

It may have a `stuck_window` (s): how long it may make no progress while it still tries by its
own logic (Nav2's progress checker waits 10 s before a recovery); the stuck oracle then waits
that long, if longer than its own window. It may have a `control_frequency` (Hz): its own
clocks run faster than the scans come (Nav2's controller server runs at 20 Hz whatever the
scanner's rate), and the simulator then calls `observe` between scans too, at that rate, with
the last scan again (the same object, its stamp unchanged), as a ROS node's timers fire
between messages. And it may have an `activity`, a list of (time s, text) pairs of
what it did that a reader of a failure should know (a recovery begun, a safety stop): each
failing run's report lists them, e.g. `stack did: Spin at t = 12.10 s`.

In a world with walls, a controller with a `receive_map` method is given the world's map once,
as a nav_msgs/OccupancyGrid (`OccupancyGrid`), after it is made and before its first scan:
map_server latches /map, so a node that subscribes has it before it drives. A controller
without one navigates by its scans alone.

A controller with a `published_costmap` method returns the costmap its planner plans in, as
costmap_2d publishes it on global_costmap/costmap: an `OccupancyGrid` of 0 (free) to 98
(inflated), 99 (inscribed), 100 (lethal) and -1 (unknown), or None before it has one; one
with a `published_plan` method returns its global plan, points (N, 2) m in the odom frame (a
nav_msgs/Path's positions), or None. A recorded run (a failure's) takes both once a simulated
second and when the drive is decided: its rosbag2 holds them, and its picture draws the
costmap's lethal and inscribed cells at the moment the drive failed.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Protocol

import numpy as np

from pytest_lasertest.model.geometry import FloatArray, Point2D, Pose3D
from pytest_lasertest.model.occupancy import OccupancyGrid
from pytest_lasertest.model.robot import Robot
from pytest_lasertest.model.sensor import LaserScanMeta

__all__ = [
    "OPTIONAL",
    "Controller",
    "ControllerFactory",
    "InFront",
    "LaserScan",
    "OccupancyGrid",
    "Odometry",
]

_NO_POINTS: FloatArray = np.zeros((0, 2))


@dataclass(frozen=True, eq=False)
class LaserScan:
    """One sensor_msgs/LaserScan, with where its laser sits on the robot (what tf would say)."""

    stamp: float  # s
    ranges: FloatArray  # (N,) m in beam order; +inf no return, -inf nearer than range_min
    meta: LaserScanMeta
    mount: Pose3D  # the laser frame in the robot's base_footprint

    def points_in_base(self, within: float = math.inf, too_near: bool = False) -> FloatArray:
        """Where each reading from range_min to nearer than `within` m lies in the robot's base
        frame, shape (M, 2), m; with `too_near`, also each reading nearer than range_min (-inf),
        placed at range_min: something is there, at most that far. A reading below range_min
        that is not -inf (a driver's 0.0) and NaN are no readings, as LaserScan says."""
        ranges = self.ranges
        if too_near:
            ranges = np.where(ranges == -np.inf, self.meta.range_min, ranges)
        beams = ((ranges >= self.meta.range_min) & (ranges < within)).nonzero()[0]
        if not len(beams):
            return _NO_POINTS
        directions, origin = _beam_directions(self.meta, self.mount, len(ranges))
        points: FloatArray = ranges[beams][:, np.newaxis] * directions[beams] + origin
        return points


# Bounded: a scanner's mount is fixed, but a controller that moves it per scan (a filter placing
# a scan where its sweep ended) must not grow the process without end.
@functools.lru_cache(maxsize=64)
def _beam_directions(
    meta: LaserScanMeta, mount: Pose3D, count: int
) -> tuple[FloatArray, FloatArray]:
    """The unit direction of each of the `count` beams in the base frame, shape (N, 2), and the
    laser's position there (2,) m. The scan plane is level: only the mount's turn within it
    matters."""
    angles = meta.angle_min + np.arange(count) * meta.angle_increment
    in_laser = np.stack([np.cos(angles), np.sin(angles)])
    directions: FloatArray = (mount.rotation()[:2, :2] @ in_laser).T
    return directions, np.array(mount.xyz[:2])


@dataclass(frozen=True)
class Odometry:
    """nav_msgs/Odometry in the plane: the base's pose in the odom frame and its twist."""

    x: float  # m
    y: float  # m
    yaw: float  # rad
    linear: float  # m/s, forward
    angular: float  # rad/s, counter-clockwise


class Controller(Protocol):
    """A robot's navigation: a velocity command for each scan."""

    def observe(self, scan: LaserScan, odometry: Odometry, time: float) -> tuple[float, float]:
        """The forward speed (m/s) and turn rate (rad/s) to drive at until the next scan:
        finite numbers (the robot's velocity limits cut larger ones; NaN and infinity fail the
        drive, as the Husky's diff_drive_controller ignores them)."""
        ...


# Makes the controller of one run: the robot it drives and its route, the goal last.
ControllerFactory = Callable[[Robot, tuple[Point2D, ...]], Controller]


# The attributes a controller may have besides `observe` (this module's docstring).
OPTIONAL = frozenset(
    {
        "goal_tolerance",
        "control_frequency",
        "stuck_window",
        "activity",
        "receive_map",
        "published_costmap",
        "published_plan",
    }
)
Command = tuple[float, float]  # m/s, rad/s


@dataclass
class InFront:
    """A controller with something in front of it: each scan passes `scans` (a laser_filters
    chain, a fault) before `inner` sees it, and each command `commands` after, if given; every
    optional attribute `inner` has (`OPTIONAL`) is `inner`'s own, so that the wrapped stack
    keeps its clocks, goal checker, stuck window, map and report. A call between scans (the
    inner's `control_frequency`) passes the same scan object again: it goes through `scans`
    once, and its result is handed on again, as a filter chain runs once per message."""

    inner: Controller
    scans: Callable[[LaserScan, Odometry, float], LaserScan]
    commands: Callable[[Command, LaserScan], Command] | None = None
    _last: tuple[LaserScan, LaserScan] | None = None  # (as received, as passed on)

    def observe(self, scan: LaserScan, odometry: Odometry, time: float) -> Command:
        if self._last is None or self._last[0] is not scan:
            self._last = (scan, self.scans(scan, odometry, time))
        command = self.inner.observe(self._last[1], odometry, time)
        return command if self.commands is None else self.commands(command, scan)

    def __getattr__(self, name: str) -> object:
        # Only missing attributes come here: the optional ones are the inner controller's.
        if name in OPTIONAL and "inner" in self.__dict__:
            return getattr(self.inner, name)
        raise AttributeError(name)
