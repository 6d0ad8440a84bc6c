"""Compiled kernels of the Nav2 stack: the collision monitor's getCollisionTime loop of
projectState, transformPoints and isPointInside (collision_monitor.py), and DWB's rollouts, its
MapGrid critics' distance transform and its reading of the cells under every rollout pose
(dwb_trajectories.py, dwb_critics.py): one call where the numpy code made hundreds.

Each operation is the numpy code's, in its order, with no fused multiply-add (numba compiles
without fastmath), and the cosines and sines are the C library's, as numpy's and Python's math
module's are: what each returns is the numpy code's to the bit (the distances are whole numbers,
exact in any order), which tests/nav/nav2/test_kernels.py and the DWB tests hold.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from pytest_lasertest.model.geometry import FloatArray
from pytest_lasertest.nav.move_base.kernels import CELLS, compiled

NO_COLLISION = -1.0  # s: what collision_time returns when no step's footprint holds min_points


@compiled(f"i8({CELLS}, {CELLS}, f8, f8, f8)")
def count_inside(points: FloatArray, polygon: FloatArray, x: float, y: float, yaw: float) -> int:
    """How many points (P, 2) m, seen from a frame at pose (x, y, yaw), lie inside the
    polygon (V, 2) m by isPointInside's ray crossings."""
    cos, sin = math.cos(yaw), math.sin(yaw)
    count = 0
    for point in range(points.shape[0]):
        moved_x, moved_y = points[point, 0] - x, points[point, 1] - y
        px, py = moved_x * cos + moved_y * sin, -moved_x * sin + moved_y * cos
        crossings, start = 0, polygon.shape[0] - 1  # edge start -> end, the last to the first first
        for end in range(polygon.shape[0]):
            sx, sy, ex, ey = polygon[start, 0], polygon[start, 1], polygon[end, 0], polygon[end, 1]
            if (py <= sy) == (py > ey) and sx + (py - sy) * (ex - sx) / (ey - sy) > px:
                crossings += 1
            start = end
        count += crossings % 2
    return count


@compiled(f"f8(f8, f8, {CELLS}, {CELLS}, f8, f8, i8)")
def collision_time(
    linear: float,
    angular: float,
    points: FloatArray,
    footprint: FloatArray,
    dt: float,
    horizon: float,
    min_points: int,
) -> float:
    """getCollisionTime: the robot moved at the command (linear m/s, angular rad/s) a step of
    dt s at a time, the velocity turning with it; the time (s) of the first step whose
    footprint (V, 2) m holds min_points of the points (P, 2) m, or NO_COLLISION."""
    x, y, yaw = 0.0, 0.0, 0.0
    vx, vy, time = linear, 0.0, 0.0
    while time <= horizon:  # the time accumulates as Nav2's loop does
        turn = angular * dt
        x, y, yaw = x + vx * dt, y + vy * dt, yaw + turn
        cos, sin = math.cos(turn), math.sin(turn)
        vx, vy = vx * cos - vy * sin, vx * sin + vy * cos
        if count_inside(points, footprint, x, y, yaw) >= min_points:
            return time
        time += dt
    return NO_COLLISION


ROLLOUTS = "UniTuple(f8[:, ::1], 3)"  # x, y and yaw (K, N)
TWISTS = "f8[::1], f8[::1], f8[::1]"  # vx, wz and steps (K,)


@compiled(f"{ROLLOUTS}(UniTuple(f8, 3), UniTuple(f8, 2), {TWISTS}, UniTuple(f8, 5), b1)")
def roll_out(
    pose: tuple[float, float, float],
    speed: tuple[float, float],
    vx: FloatArray,
    wz: FloatArray,
    steps: FloatArray,
    limits: tuple[float, float, float, float, float],
    include_last_point: bool,
) -> tuple[FloatArray, FloatArray, FloatArray]:
    """generateTrajectory for each of K commands (vx m/s, wz rad/s) from `pose` (m, m, rad) at
    `speed` (m/s, rad/s), in `steps` (K,) steps each: x, y and yaw (K, N) m, m, rad, a shorter
    trajectory's last pose repeated. `limits` holds sim_time (s), acc_lim_x, decel_lim_x
    (m/s^2), acc_lim_theta and decel_lim_theta (rad/s^2).
    dwb_trajectories.roll_out_in_numpy's operations, in its order."""
    sim_time, speed_x, speed_theta = limits[0], speed[0], speed[1]
    most = int(max(steps.max(), 1.0)) if len(steps) else 1
    poses = most + 2 if include_last_point else most + 1
    x, y, yaw = np.empty((len(vx), poses)), np.empty((len(vx), poses)), np.empty((len(vx), poses))
    for k in range(len(vx)):
        dt = sim_time / steps[k]
        x[k, 0], y[k, 0], yaw[k, 0] = pose
        linear, angular = speed_x, speed_theta
        linear_change = limits[1] * dt if speed_x < vx[k] else limits[2] * dt
        angular_change = limits[3] * dt if speed_theta < wz[k] else limits[4] * dt
        for step in range(most):
            # Past its last step the speeds run on unused, as numpy's whole rows do.
            linear, angular = linear + linear_change, angular + angular_change
            moving = step + 1 <= steps[k]
            if not moving:
                x[k, step + 1], y[k, step + 1] = x[k, step], y[k, step]
                yaw[k, step + 1] = yaw[k, step]
                continue
            v = min(linear, vx[k]) if speed_x < vx[k] else max(linear, vx[k])
            w = min(angular, wz[k]) if speed_theta < wz[k] else max(angular, wz[k])
            yaw[k, step + 1] = yaw[k, step] + w * dt
            x[k, step + 1] = x[k, step] + v * math.cos(yaw[k, step]) * dt
            y[k, step + 1] = y[k, step] + v * math.sin(yaw[k, step]) * dt
        if include_last_point:
            x[k, most + 1], y[k, most + 1] = x[k, most], y[k, most]
            yaw[k, most + 1] = yaw[k, most]
    return x, y, yaw


@compiled("f8[:, ::1](i8, i8, i8[::1], i8[::1])")
def l1_distances(height: int, width: int, rows: Any, columns: Any) -> FloatArray:
    """The Manhattan distance (cells) from each cell of a grid (H, W) to the nearest source cell
    (rows, columns), inf without one: a pass each way along every row, then along every
    column. Whole numbers, so exact in any order of operations."""
    distances = np.full((height, width), np.inf)
    for source in range(len(rows)):
        distances[rows[source], columns[source]] = 0.0
    for row in range(height):
        for column in range(1, width):
            distances[row, column] = min(distances[row, column], distances[row, column - 1] + 1.0)
        for column in range(width - 2, -1, -1):
            distances[row, column] = min(distances[row, column], distances[row, column + 1] + 1.0)
    for row in range(1, height):
        for column in range(width):
            distances[row, column] = min(distances[row, column], distances[row - 1, column] + 1.0)
    for row in range(height - 2, -1, -1):
        for column in range(width):
            distances[row, column] = min(distances[row, column], distances[row + 1, column] + 1.0)
    return distances


@compiled("i8[:, ::1](f8[:, ::1], f8[:, ::1], f8, f8, f8, i8, i8)")
def cells_under(
    x: FloatArray,
    y: FloatArray,
    origin_x: float,
    origin_y: float,
    resolution: float,
    height: int,
    width: int,
) -> Any:
    """Costmap2D::worldToMap of every pose (K, N) m as dwb_critics.world_to_map takes it: the
    flat index (row x width + column) of its cell, -1 off the grid, shape (K, N)."""
    flat = np.empty(x.shape, np.int64)
    for k in range(x.shape[0]):
        for n in range(x.shape[1]):
            column = (x[k, n] - origin_x) / resolution
            row = (y[k, n] - origin_y) / resolution
            on = x[k, n] >= origin_x and y[k, n] >= origin_y and column < width and row < height
            flat[k, n] = int(row) * width + int(column) if on else -1
    return flat


@compiled("Tuple((f8[::1], b1[::1]))(i8[:, ::1], f8[::1], f8[::1])")
def read_every_pose(flat: Any, values: FloatArray, failing: FloatArray) -> tuple[FloatArray, Any]:
    """A grid's `values` (H x W,) read under every pose's flat cell (K, N): the last pose's
    value (K,) (cell 0's off the grid, as worldToMap leaves it), and whether every pose is on
    the grid on a value not among `failing` (K,)."""
    last, legal = np.empty(flat.shape[0]), np.ones(flat.shape[0], np.bool_)
    for k in range(flat.shape[0]):
        for n in range(flat.shape[1]):
            cell = flat[k, n]
            legal[k] = cell >= 0
            for value in failing:
                legal[k] = legal[k] and values[cell] != value
            if not legal[k]:
                break
        last[k] = values[max(flat[k, flat.shape[1] - 1], 0)]
    return last, legal
