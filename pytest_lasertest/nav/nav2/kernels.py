"""Compiled kernels of the collision monitor (collision_monitor.py): getCollisionTime's loop of
projectState, transformPoints and isPointInside, one call a control cycle instead of a few
hundred numpy calls.

Each operation is collision_monitor.py's, in its order, with no fused multiply-add (numba
compiles without fastmath), and the cosines and sines are the C library's, as Python's math
module takes them: the time found is the numpy code's to the bit, which
tests/nav/nav2/test_kernels.py holds.
"""

from __future__ import annotations

import math

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
