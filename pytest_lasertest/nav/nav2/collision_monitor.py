"""Nav2's collision monitor as Jazzy's nav2_bringup runs it: one FootprintApproach polygon on
the scan, slowing the command so that the robot reaches an obstacle no sooner than
time_before_collision (nav2_collision_monitor at jazzy f4108e5b: src/collision_monitor_node.cpp
processApproach, src/polygon.cpp getCollisionTime and isPointInside, src/kinematics.cpp,
src/scan.cpp; nav2_params.yaml's collision_monitor). Our own code: numpy here, and the loop that
runs every control cycle compiled in kernels.py.

The scan's readings with range_min <= r <= range_max (inclusive, unlike the costmap's
laser_geometry projection) become points in the base frame, whatever the scanner's height: a
scan source reads no min_height or max_height (only a point cloud source does,
src/pointcloud.cpp). If min_points of them lie inside the footprint
now, the command becomes zero; else the robot is moved at the command, a simulation step at a
time up to time_before_collision, and at the first step whose footprint holds min_points, the
command is scaled by that step's time over time_before_collision.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from pytest_lasertest.model.geometry import FloatArray
from pytest_lasertest.nav.nav2.kernels import NO_COLLISION, collision_time, count_inside
from pytest_lasertest.nav.protocol import LaserScan

Command = tuple[float, float]  # m/s, rad/s
Pose = tuple[float, float, float]  # m, m, rad
Velocity = tuple[float, float, float]  # m/s along x and y of the frame moved in, rad/s
# m: covers rounding, so a point kept in doubt is tested as Nav2 tests it.
ROUNDING = 1e-9


@dataclass(frozen=True)
class CollisionMonitorSettings:
    """The FootprintApproach polygon and the scan source, with Nav2's names and Jazzy's values."""

    time_before_collision: float = 1.2  # s
    simulation_time_step: float = 0.1  # s
    min_points: int = 6


def scan_points(scan: LaserScan) -> FloatArray:
    """The scan's readings with range_min <= r <= range_max in the base frame, shape (P, 2) m."""
    ranges = np.asarray(scan.ranges)
    kept = (ranges >= scan.meta.range_min) & (ranges <= scan.meta.range_max)
    counted = LaserScan(scan.stamp, np.where(kept, ranges, np.inf), scan.meta, scan.mount)
    return counted.points_in_base()


def approach(
    command: Command, points: FloatArray, footprint: FloatArray, settings: CollisionMonitorSettings
) -> Command:
    """The command the monitor lets through, for points (P, 2) m in the base frame and the
    footprint (V, 2) m."""
    points = _reachable(command, points, footprint, settings)
    if len(points) < settings.min_points:
        return command  # no step's footprint can hold min_points
    return _process_approach(command, points, footprint, settings)


def _process_approach(
    command: Command, points: FloatArray, footprint: FloatArray, settings: CollisionMonitorSettings
) -> Command:
    """processApproach: stop if min_points lie in the footprint now, else slow the command by
    the time of the first step whose footprint holds them."""
    points, footprint = np.ascontiguousarray(points), np.ascontiguousarray(footprint)
    if count_inside(points, footprint, 0.0, 0.0, 0.0) >= settings.min_points:
        return 0.0, 0.0
    collision = collision_time(
        *command,
        points,
        footprint,
        settings.simulation_time_step,
        settings.time_before_collision,
        settings.min_points,
    )
    if collision == NO_COLLISION:
        return command
    ratio = collision / settings.time_before_collision
    return command[0] * ratio, command[1] * ratio


def _reachable(
    command: Command, points: FloatArray, footprint: FloatArray, settings: CollisionMonitorSettings
) -> FloatArray:
    """The points (P, 2) m that the footprint can hold at some step of `_collision_time`: within
    its reach of the base plus how far the command moves it. Nav2 tests every point at every
    step; the others lie outside every step's footprint, so the counts are the same."""
    reach = float(np.hypot(footprint[:, 0], footprint[:, 1]).max())  # m
    # The loop may take one step more than time_before_collision holds (it accumulates the
    # time), and turning the velocity keeps its length.
    moved = abs(command[0]) * (settings.time_before_collision + 2.0 * settings.simulation_time_step)
    near: FloatArray = points[np.hypot(points[:, 0], points[:, 1]) <= reach + moved + ROUNDING]
    return near


def collision_time_of(
    command: Command, points: FloatArray, footprint: FloatArray, settings: CollisionMonitorSettings
) -> float | None:
    """getCollisionTime: the robot moved at the command, step by step, the velocity turning
    with it; the time of the first step whose footprint holds min_points, or None. In numpy, as
    the reference of kernels.collision_time, which runs it."""
    pose: Pose = (0.0, 0.0, 0.0)
    velocity: Velocity = (command[0], 0.0, command[1])
    dt, time = settings.simulation_time_step, 0.0
    while time <= settings.time_before_collision:  # the time accumulates as Nav2's loop does
        pose, velocity = project_state(dt, pose, velocity)
        if inside(transform_points(pose, points), footprint) >= settings.min_points:
            return time
        time += dt
    return None


def transform_points(pose: Pose, points: FloatArray) -> FloatArray:
    """transformPoints: the points (P, 2) m seen from a frame at `pose` (kinematics.cpp)."""
    cos, sin = math.cos(pose[2]), math.sin(pose[2])
    moved_x, moved_y = points[:, 0] - pose[0], points[:, 1] - pose[1]
    return np.column_stack([moved_x * cos + moved_y * sin, -moved_x * sin + moved_y * cos])


def project_state(dt: float, pose: Pose, velocity: Velocity) -> tuple[Pose, Velocity]:
    """projectState: the pose moved by the velocity for dt and turned by its turn rate, and
    the velocity turned with it (kinematics.cpp)."""
    x, y, turn_rate = velocity
    turn = turn_rate * dt
    moved = (pose[0] + x * dt, pose[1] + y * dt, pose[2] + turn)
    cos, sin = math.cos(turn), math.sin(turn)
    return moved, (x * cos - y * sin, x * sin + y * cos, turn_rate)


def inside(points: FloatArray, polygon: FloatArray) -> int:
    """How many points (P, 2) lie inside the polygon (V, 2), by isPointInside's ray crossings. In
    numpy, as the reference of kernels.count_inside, which runs it."""
    if not len(points):
        return 0
    px, py = points[:, 0:1], points[:, 1:2]  # (P, 1)
    start, end = np.roll(polygon, 1, axis=0), polygon  # edge i -> j, the last to the first first
    between = (py <= start[:, 1]) == (py > end[:, 1])  # (P, V)
    with np.errstate(divide="ignore", invalid="ignore"):
        crossing = start[:, 0] + (py - start[:, 1]) * (end[:, 0] - start[:, 0]) / (
            end[:, 1] - start[:, 1]
        )
    crossings = (between & (crossing > px)).sum(axis=1)
    return int((crossings % 2 == 1).sum())
