"""Compiled kernels of the Nav2 stack: the collision monitor's getCollisionTime loop of
projectState, transformPoints and isPointInside (collision_monitor.py); DWB's rollouts, its
MapGrid critics' distance transform and its reading of the cells under every rollout pose
(dwb_trajectories.py, dwb_critics.py); MPPI's motion model and integration (motion_model.py),
its CostCritic and PathAlignCritic (critics.py), findPathFurthestReachedPoint and the softmax
update's sums (mppi.py): one call where the numpy code made hundreds.

Each operation is the numpy code's, in its order, with no fused multiply-add (numba compiles
without fastmath); the float64 cosines and sines are the C library's, as numpy's and Python's
math module's are, and the float32 ones stay numpy's; sums are added in numpy's order (a column
after another, or pairwise along a row, `nav.kernels.pairwise_sum`): what each returns is the
numpy code's to the bit, which tests/nav/nav2/test_kernels.py and the DWB tests hold.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from pytest_lasertest.model.geometry import FloatArray
from pytest_lasertest.nav.kernels import CELLS, compiled, pairwise_sum
from pytest_lasertest.nav.move_base.cost_values import INSCRIBED, LETHAL, UNKNOWN

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


# MPPI's samples, time-major (T, B) float32, as mppi.py keeps them; numba keeps float32
# arithmetic in float32, as numpy does for float32 arrays and float32 scalars.
SAMPLES = "f4[:, ::1]"


@compiled()
def _clip(value: Any, low: Any, high: Any) -> Any:
    """numpy's clip of one value: its _NPY_MIN(_NPY_MAX(value, low), high), which takes the
    bound where the value equals it (a zero takes the bound's sign)."""
    value = value if value > low else low
    return value if value < high else high


@compiled(f"UniTuple({SAMPLES}, 2)({SAMPLES}, {SAMPLES}, f4, f4, f4, f4, f4)")
def predict(
    noised_vx: Any, noised_wz: Any, vx0: Any, wz0: Any, up: Any, down: Any, turn: Any
) -> tuple[Any, Any]:
    """DiffDrive's predict over noised controls (T, B) m/s and rad/s, bounded in place: the
    speeds (T, B), from (vx0, wz0) at step 0; each later step's the noised control of the step
    before, clipped to at most `up` faster and `down` (negative) slower than the speed before
    it (mirrored when not moving forward) and `turn` either way. motion_model.predict_in_numpy's
    operations, its clip as numpy's (`_clip`)."""
    steps, batch = noised_vx.shape
    vx, wz = np.empty_like(noised_vx), np.empty_like(noised_wz)
    vx[0, :], wz[0, :] = vx0, wz0
    for step in range(1, steps):
        for b in range(batch):
            last_vx, last_wz = vx[step - 1, b], wz[step - 1, b]
            if last_vx > 0:
                low, high = last_vx + down, last_vx + up
            else:
                low, high = last_vx - up, last_vx - down
            vx[step, b] = _clip(noised_vx[step - 1, b], low, high)
            wz[step, b] = _clip(noised_wz[step - 1, b], last_wz - turn, last_wz + turn)
            noised_vx[step - 1, b], noised_wz[step - 1, b] = vx[step, b], wz[step, b]
    return vx, wz


@compiled(f"{SAMPLES}({SAMPLES}, f4, f4)")
def running_sum(rates: Any, dt: Any, start: Any) -> Any:
    """`start` plus the running sum of rates x dt (T, B) along time, a row after another."""
    total = np.empty_like(rates)
    for b in range(rates.shape[1]):
        total[0, b] = rates[0, b] * dt + start
    for step in range(1, rates.shape[0]):
        for b in range(rates.shape[1]):
            total[step, b] = total[step - 1, b] + rates[step, b] * dt
    return total


@compiled(f"UniTuple({SAMPLES}, 2)({SAMPLES}, {SAMPLES}, {SAMPLES}, f4, f4, f4)")
def advance(vx: Any, cos: Any, sin: Any, dt: Any, x0: Any, y0: Any) -> tuple[Any, Any]:
    """x and y (T, B) m from (x0, y0): each step moves vx dt (T, B) along the heading whose
    cosine and sine (T, B) are given, a running sum along time."""
    x, y = np.empty_like(vx), np.empty_like(vx)
    for step in range(vx.shape[0]):
        for b in range(vx.shape[1]):
            moved = vx[step, b] * dt
            x[step, b] = moved * cos[step, b] + (x0 if step == 0 else x[step - 1, b])
            y[step, b] = moved * sin[step, b] + (y0 if step == 0 else y[step - 1, b])
    return x, y


@compiled(f"Tuple((f4[::1], i8[::1]))({SAMPLES}, {SAMPLES}, i8, f8[::1], f4[:, ::1], b1[::1])")
def path_align_gaps(
    x: Any, y: Any, step: int, along: FloatArray, path: Any, valid: Any
) -> tuple[Any, Any]:
    """PathAlignCritic's sums over every step-th point but the first of each trajectory, from
    time-major positions (T, B) m: the distances (float32 m) from each point to the path point
    (P, 2) m as far along the path (`along` (P,) m, float64) as the trajectory has come, where
    that path point is `valid` (P,), summed as numpy's pairwise sum adds a row; and how many
    were counted, (B,) each. critics.path_align_gaps_in_numpy's operations, in its order; a
    step at a time over every trajectory, as the positions lie in memory."""
    batch, points = x.shape[1], (x.shape[0] + step - 1) // step
    gaps = np.zeros((batch, max(points - 1, 0)), np.float32)
    counted = np.zeros(batch, np.int64)
    travelled = np.zeros(batch, np.float32)
    after, nearest = np.zeros(batch, np.int64), np.zeros(batch, np.int64)
    last = along.shape[0] - 1
    for j in range(1, points):
        now, before_now = j * step, (j - 1) * step
        for b in range(batch):
            qx, qy = x[now, b], y[now, b]
            moved = math.hypot(qx - x[before_now, b], qy - y[before_now, b])
            come = travelled[b] = travelled[b] + np.float32(moved)
            beyond = after[b]  # kept in a register: the arrays hold it between steps
            while beyond <= last and along[beyond] <= come:  # searchsorted, side right
                beyond += 1
            after[b] = beyond
            before, capped = max(beyond - 1, 0), min(beyond, last)
            if beyond > last:
                closest = last
            elif come - along[before] < along[capped] - come:
                closest = before
            else:
                closest = capped
            point = nearest[b] = max(nearest[b], closest)
            if valid[point]:
                counted[b] += 1
                gaps[b, j - 1] = np.float32(math.hypot(path[point, 0] - qx, path[point, 1] - qy))
    summed = np.empty(batch, np.float32)
    for b in range(batch):
        summed[b] = np.float32(0.0) + pairwise_sum(gaps[b], 0, gaps.shape[1])
    return summed, counted


# CostCritic's grid and its reading: costs (H, W), origin x and y (m) and resolution (m).
GRID = "u1[:, ::1], f4, f4, f4"


@compiled(f"Tuple((f4[::1], b1[::1]))({SAMPLES}, {SAMPLES}, i8, i8, {GRID}, b1, f4, f8, b1)")
def cost_critic_sums(
    x: Any,
    y: Any,
    step: int,
    points: int,
    costs: Any,
    origin_x: Any,
    origin_y: Any,
    resolution: Any,
    tracking_unknown: bool,
    near_collision_cost: Any,
    critical_cost: float,
    near_goal: bool,
) -> tuple[Any, Any]:
    """CostCritic over the first `points` step-th points of each trajectory, from time-major
    positions (T, B) m: the sum of their costs (B,), critical_cost from near_collision_cost up
    and nothing else near the goal, and whether any point meets a lethal, inscribed or
    (untracked) unknown cell, (B,); off the grid reads as unknown. The cells as worldToMapFloat
    finds them, in float32; the sum a point after another, as numpy adds the columns of
    critics.cost_critic_sums_in_numpy, in float32, or near the goal in float64 (numpy's type
    for a choice between two Python floats)."""
    height, width = costs.shape
    batch = x.shape[1]
    sums, near = np.zeros(batch, np.float32), np.zeros(batch)  # near: the goal's, float64
    collided = np.zeros(batch, np.bool_)
    critical = np.float32(critical_cost)
    for j in range(points):
        for b in range(batch):
            px, py = x[j * step, b], y[j * step, b]
            column, row = (px - origin_x) / resolution, (py - origin_y) / resolution
            on = px >= origin_x and py >= origin_y and column < width and row < height
            cost = np.float32(costs[int(row), int(column)] if on else UNKNOWN)
            if cost in (LETHAL, INSCRIBED) or (cost == UNKNOWN and not tracking_unknown):
                collided[b] = True
            if near_goal:
                near[b] += critical_cost if cost >= near_collision_cost else 0.0
            else:
                sums[b] += critical if cost >= near_collision_cost else cost
    return (near.astype(np.float32) if near_goal else sums), collided


@compiled("i8(f4[::1], f4[::1], f4[:, ::1])")
def furthest_reached(end_x: Any, end_y: Any, path: Any) -> int:
    """findPathFurthestReachedPoint over trajectory ends (B,) m and a path (P, 2) m: trajectory
    by trajectory, the path point nearest its end (the first of equal squared distances, in
    float32) among those at or past the furthest found so far."""
    furthest = 0
    for b in range(end_x.shape[0]):
        nearest, least = furthest, np.float32(np.inf)
        for point in range(furthest, path.shape[0]):
            dx, dy = path[point, 0] - end_x[b], path[point, 1] - end_y[b]
            squared = dx * dx + dy * dy
            if squared < least:
                nearest, least = point, squared
        furthest = max(furthest, nearest)
    return furthest


@compiled(f"f4[::1](f4[::1], {SAMPLES})")
def control_costs(sequence: Any, noised: Any) -> Any:
    """MPPI's control cost before its factor gamma / std^2: for each sample, the sum over the
    steps of sequence (T,) x (noised (T, B) - sequence), (B,), a step after another, as numpy
    adds the columns of its (B, T) view."""
    total = np.zeros(noised.shape[1], np.float32)
    for step in range(noised.shape[0]):
        for b in range(noised.shape[1]):
            total[b] += sequence[step] * (noised[step, b] - sequence[step])
    return total


@compiled(f"f4[::1]({SAMPLES}, f4[::1])")
def weighted_means(noised: Any, weights: Any) -> Any:
    """The weighted sum over the samples of noised (T, B) by weights (B,), (T,): each step's
    products added by numpy's pairwise sum, as it adds the rows of its (B, T) view."""
    means, products = np.empty(noised.shape[0], np.float32), np.empty(noised.shape[1], np.float32)
    for step in range(noised.shape[0]):
        for b in range(noised.shape[1]):
            products[b] = noised[step, b] * weights[b]
        means[step] = np.float32(0.0) + pairwise_sum(products, 0, len(products))
    return means


@compiled(f"f4[::1]({SAMPLES}, {SAMPLES}, f4, f4)")
def mean_distances(x: Any, y: Any, goal_x: Any, goal_y: Any) -> Any:
    """GoalCritic's mean over the steps of each trajectory's distance (float32 m) from the goal,
    from time-major positions (T, B) m: summed a step after another, as numpy adds the columns
    of its (B, T) view, and divided by T in float64, as numpy's mean divides by its count."""
    total = np.zeros(x.shape[1], np.float32)
    for step in range(x.shape[0]):
        for b in range(x.shape[1]):
            total[b] += np.float32(math.hypot(x[step, b] - goal_x, y[step, b] - goal_y))
    means = np.empty(x.shape[1], np.float32)
    for b in range(x.shape[1]):
        means[b] = np.float32(np.float64(total[b]) / x.shape[0])
    return means


@compiled(f"f4[::1]({SAMPLES}, f4, f4)")
def speed_beyond(vx: Any, fastest: Any, slowest: Any) -> Any:
    """The sum over the steps of how far each sample's speed vx (T, B) m/s lies above `fastest`
    plus how far below `slowest` (float32 m/s), a step after another, as numpy adds the columns
    of its (B, T) view; each part clipped at 0 as numpy's maximum does (+0.0 for either zero).
    With fastest +inf and slowest 0, PreferForwardCritic's sum of reversing."""
    total = np.zeros(vx.shape[1], np.float32)
    zero = np.float32(0.0)
    for step in range(vx.shape[0]):
        for b in range(vx.shape[1]):
            above, below = vx[step, b] - fastest, slowest - vx[step, b]
            total[b] += (above if above > zero else zero) + (below if below > zero else zero)
    return total


@compiled("void(f4[::1], f4[::1], f4, f4, f4)")
def bound_steps(vx: Any, wz: Any, up: Any, down: Any, turn: Any) -> None:
    """applyControlSequenceConstraints' second part, in place: each step of the sequence (T,)
    m/s and rad/s held within `up` faster and `down` (negative) slower than the step before
    (mirrored when not moving forward), and `turn` either way, clipped as Python's min and max
    of float32 scalars clip (a value kept against an equal bound), as motion_model.limit's
    caller did."""
    for step in range(1, len(vx)):
        last_vx, last_wz = vx[step - 1], wz[step - 1]
        forward = last_vx > 0
        low, high = last_vx + (down if forward else -up), last_vx + (up if forward else -down)
        value = low if low > vx[step] else vx[step]
        vx[step] = high if high < value else value
        low, high = last_wz - turn, last_wz + turn
        value = low if low > wz[step] else wz[step]
        wz[step] = high if high < value else value
