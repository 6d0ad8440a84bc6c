"""Compiled kernels of move_base's planners: navfn's potential and its descent (navfn.py), the
inflation's distances to lethal cells (costmap.py) and DWA's footprint check (clearance.py).

navfn's potential is each cell's cheapest-path cost from the start, found by Dijkstra's
algorithm over the integer entry costs navfn.py lays out. Cheapest-path costs are unique, so any
correct search finds these to the unit; tests/nav/move_base/test_navfn.py holds them to a plain
Python Dijkstra's. The descent takes each cell's first cheapest predecessor in a fixed order,
as the numpy code did.

The inflation's distances are whole squared distances added and rooted, exact in any order:
the numpy code's to the bit, which tests/nav/move_base/test_costmap.py holds.

The footprint check takes the least signed distance from a footprint, over each group of poses,
to lethal cell centres, measuring only the cells that can be nearest. The cells are grouped in
squares. The signed distance is a maximum of functions of slope 1, so it changes by no more than
a point moves: a square's cells lie within its radius of its centre, and lie no nearer than the
centre's signed distance less that radius. At each pose every square's bound is taken (the edge
lines turned into the odom frame once per pose, five operations an edge), the square with the
least bound is measured first, and then only the squares whose bound is below the least so far;
a group's least carries from pose to pose. A cell that is measured is measured by the operations
of clearance.py's docstring, in their order, with no fused multiply-add (numba compiles without
fastmath), so the least is the direct computation's to the bit;
tests/nav/move_base/test_clearance.py holds them equal.
"""

from __future__ import annotations

import heapq
import math
from typing import Any

import numpy as np

from pytest_lasertest.model.geometry import FloatArray, IntArray
from pytest_lasertest.nav.kernels import CELLS, compiled


@compiled("void(u1[::1], i8, i8[::1], i8[::1], i8, i8, i8, i8[::1])")
def cheapest_costs(
    costs: Any,
    width: int,
    axis_of: IntArray,
    diagonal_of: IntArray,
    blocked: int,
    start: int,
    goal: int,
    potential: IntArray,
) -> None:
    """Fill `potential` (B,) with the cheapest cost of reaching each flat cell from `start`, or
    `blocked` where none: over navfn's entry costs (B,) (0: never entered), rows of `width`
    cells, a step into a cell of cost c costing axis_of[c] along an axis and diagonal_of[c]
    diagonally, a diagonal step only between two enterable cells beside it.

    Once cell `goal` is settled (-1: never) the search stops: every cell cheaper than the goal
    is exact, and every other no cheaper than the goal, which is all a descent from the goal
    reads."""
    potential[:] = blocked
    potential[start] = 0
    # The 8 steps: the flat offset, and its parts along x and along y (0 along an axis).
    steps = np.array(
        [[1, 0, 0], [-1, 0, 0], [width, 0, 0], [-width, 0, 0]]
        + [[s * (width + t), s * t, s * width] for s in (1, -1) for t in (1, -1)],
        dtype=np.int64,
    )
    heap = [(np.int64(0), np.int64(start))]
    while heap:
        cost, cell = heapq.heappop(heap)
        if cost > potential[cell]:
            continue  # reached more cheaply since it was queued
        if cell == goal:
            return
        for step, along_x, along_y in steps:
            entered = cell + step
            if entered < 0 or entered >= len(costs) or costs[entered] == 0:
                continue
            if along_x == 0:
                reached = cost + axis_of[costs[entered]]
            elif costs[cell + along_x] == 0 or costs[cell + along_y] == 0:
                continue  # a diagonal step may not cut a blocked cell's corner
            else:
                reached = cost + diagonal_of[costs[entered]]
            if reached < potential[entered]:
                potential[entered] = reached
                heapq.heappush(heap, (reached, entered))


@compiled("i8[::1](u1[::1], i8, i8[::1], i8[::1], i8[::1], i8)")
def descend(
    costs: Any, width: int, axis_of: IntArray, diagonal_of: IntArray, potential: IntArray, end: int
) -> IntArray:
    """The flat cells (K,) of a cheapest path from the potential's zero to flat cell `end`: each
    cell's predecessor the neighbour its potential was reached from, the first such in the
    order -1, -width, -(width + 1), -(width - 1), then the same steps forward. The entry costs
    are cheapest_costs's; the potential (B,) falls strictly along the way."""
    # The steps to the predecessor: the flat offset, and its parts along x and y (0: an axis).
    steps = np.array(
        [
            [-1, 0, 0],
            [-width, 0, 0],
            [-width - 1, -1, -width],
            [-width + 1, 1, -width],
            [1, 0, 0],
            [width, 0, 0],
            [width + 1, 1, width],
            [width - 1, -1, width],
        ],
        dtype=np.int64,
    )
    path = [end]
    cell = end
    while potential[cell] > 0:
        best, before = -1, 0
        for step, along_x, along_y in steps:
            if along_x == 0:
                entry = axis_of[costs[cell]]
            elif costs[cell + along_x] == 0 or costs[cell + along_y] == 0:
                entry = axis_of[0]  # blocked: a diagonal step may not cut a corner
            else:
                entry = diagonal_of[costs[cell]]
            reached = potential[cell + step] + entry
            if best < 0 or reached < best:
                best, before = reached, cell + step
        cell = before
        path.append(cell)
    return np.array(path[::-1], dtype=np.int64)


@compiled("f8[:, ::1](b1[:, ::1], i8)")
def distances_to_lethal(lethal: Any, reach: int) -> FloatArray:
    """Each cell's distance in cells to the nearest lethal cell (R, C): the square root of the
    least whole dx^2 + dy^2 over the lethal cells within `reach` rows above or below and
    `reach` columns either side, inf where there is none (so more than `reach`, or inf,
    beyond `reach`)."""
    rows, columns = lethal.shape
    squared = np.full((rows, columns), np.inf)  # dy^2 to the nearest lethal cell in the column
    for column in range(columns):
        above = -1
        for row in range(rows):  # downward: the nearest above, then the nearest below
            if lethal[row, column]:
                above = row
            if above >= 0 and row - above <= reach:
                squared[row, column] = float((row - above) ** 2)
        below = -1
        for row in range(rows - 1, -1, -1):
            if lethal[row, column]:
                below = row
            if below >= 0 and below - row <= reach:
                squared[row, column] = min(squared[row, column], float((below - row) ** 2))
    distance = np.empty((rows, columns))
    for row in range(rows):
        for column in range(columns):
            best = squared[row, column]
            for shift in range(1, reach + 1):
                if column >= shift:
                    best = min(best, squared[row, column - shift] + float(shift * shift))
                if column + shift < columns:
                    best = min(best, squared[row, column + shift] + float(shift * shift))
            distance[row, column] = math.sqrt(best)
    return distance


@compiled()
def _squares(lethal: FloatArray, side: float, rounding: float) -> tuple[Any, ...]:
    """The cells (N, 2) grouped by the `side` m square of the plane each lies in: the cells' x
    and y (N,) m in square order, where each square starts among them (B + 1,), its centre's x
    and y (B,) m and its radius (B,) m to its furthest cell, `rounding` m added."""
    column = np.floor(lethal[:, 0] / side)
    row = np.floor(lethal[:, 1] / side)
    key = (column - column.min()) * (row.max() - row.min() + 1.0) + (row - row.min())
    order = np.argsort(key, kind="mergesort")
    cell_x, cell_y, ordered = lethal[order, 0].copy(), lethal[order, 1].copy(), key[order]
    starts = [0]
    for index in range(1, len(ordered)):
        if ordered[index] != ordered[index - 1]:
            starts.append(index)
    starts.append(len(ordered))
    squares = len(starts) - 1
    centre_x, centre_y, radius = np.empty(squares), np.empty(squares), np.empty(squares)
    for square in range(squares):
        xs, ys = (
            cell_x[starts[square] : starts[square + 1]],
            cell_y[starts[square] : starts[square + 1]],
        )
        centre_x[square] = (xs.min() + xs.max()) / 2.0
        centre_y[square] = (ys.min() + ys.max()) / 2.0
        radius[square] = np.hypot(xs - centre_x[square], ys - centre_y[square]).max() + rounding
    return cell_x, cell_y, np.array(starts), centre_x, centre_y, radius


@compiled()
def _bounds(
    turned: FloatArray,
    centre_x: FloatArray,
    centre_y: FloatArray,
    radius: FloatArray,
    lower: FloatArray,
) -> int:
    """Fill `lower` (B,) m with how near each square's cells can be to the footprint, its edge
    lines `turned` (3, V) into the odom frame (normal x, normal y, offset): the centre's signed
    distance less the radius (which covers this way's rounding). The square whose bound is
    least."""
    lower[:] = -np.inf
    for edge in range(turned.shape[1]):
        normal_x, normal_y, offset = turned[0, edge], turned[1, edge], turned[2, edge]
        for square in range(len(lower)):
            line = normal_x * centre_x[square] + normal_y * centre_y[square] - offset
            if line > lower[square]:
                lower[square] = line
    lower -= radius
    return int(np.argmin(lower))


@compiled()
def _measure(
    normals: FloatArray,
    frame: FloatArray,
    grown: FloatArray,
    squares: tuple[Any, ...],
    square: int,
    best: float,
) -> float:
    """The least of `best` and the signed distances of the square's cells from the footprint
    in `frame` (x, y, cos, sin), its edges' offsets `grown` (V,) m: each cell in the frame, then
    the largest of the edge lines, as clearance.py's docstring writes them."""
    cell_x, cell_y, starts = squares[0], squares[1], squares[2]
    x, y, cos, sin = frame[0], frame[1], frame[2], frame[3]
    for index in range(starts[square], starts[square + 1]):
        dx, dy = cell_x[index] - x, cell_y[index] - y
        forward = dx * cos + dy * sin
        left = dy * cos - dx * sin
        signed = -np.inf
        for edge in range(len(grown)):
            line = normals[edge, 0] * forward + normals[edge, 1] * left - grown[edge]
            if line > signed:
                signed = line
        if signed < best:
            best = signed
    return best


@compiled()
def _least_of_group(
    normals: FloatArray,
    offsets: FloatArray,
    poses: FloatArray,
    first: int,
    count: int,
    squares: tuple[Any, ...],
) -> float:
    """The least over poses first .. first + count - 1: at each, the square that may be
    nearest first, so that its least rules out the others, then those still in doubt."""
    centre_x, centre_y, radius = squares[3], squares[4], squares[5]
    lower, frame = np.empty(len(radius)), np.empty(4)
    grown, turned = np.empty(len(offsets)), np.empty((3, len(offsets)))
    best = np.inf
    for pose in range(first, first + count):
        if pose > first and _repeats(poses, pose):
            continue  # a short rollout's tail stays at its last pose: it changes no least
        _frame(normals, offsets, poses, pose, frame, grown, turned)
        nearest = _bounds(turned, centre_x, centre_y, radius, lower)
        if lower[nearest] >= best:
            continue
        best = _measure(normals, frame, grown, squares, nearest, best)
        for square in range(len(lower)):
            if lower[square] < best and square != nearest:
                best = _measure(normals, frame, grown, squares, square, best)
    return best


@compiled()
def _frame(
    normals: FloatArray,
    offsets: FloatArray,
    poses: FloatArray,
    pose: int,
    frame: FloatArray,
    grown: FloatArray,
    turned: FloatArray,
) -> None:
    """Fill in the pose's frame (x, y, cos, sin), its edges' offsets `grown` (V,) m by its
    scale, and its edge lines `turned` (3, V) into the odom frame."""
    x, y, cos, sin, scale = (
        poses[0, pose],
        poses[1, pose],
        poses[3, pose],
        poses[4, pose],
        poses[5, pose],
    )
    frame[0], frame[1], frame[2], frame[3] = x, y, cos, sin
    for edge in range(len(offsets)):
        grown[edge] = scale * offsets[edge]
        turned[0, edge] = normals[edge, 0] * cos - normals[edge, 1] * sin
        turned[1, edge] = normals[edge, 0] * sin + normals[edge, 1] * cos
        turned[2, edge] = turned[0, edge] * x + turned[1, edge] * y + grown[edge]


@compiled()
def _repeats(poses: FloatArray, pose: int) -> bool:
    """Whether `pose` is the pose before it, grown alike."""
    before = pose - 1
    return bool(
        poses[0, pose] == poses[0, before]
        and poses[1, pose] == poses[1, before]
        and poses[2, pose] == poses[2, before]
        and poses[5, pose] == poses[5, before]
    )


@compiled(f"f8[::1]({CELLS}, f8[::1], f8[:, ::1], i8, {CELLS}, f8, f8)")
def least_per_group(
    normals: FloatArray,
    offsets: FloatArray,
    poses: FloatArray,
    groups: int,
    lethal: FloatArray,
    side: float,
    rounding: float,
) -> FloatArray:
    """The least signed distance (m) from the footprint, edges `normals` (V, 2) and `offsets`
    (V,) m, at any pose of each group to a lethal cell centre (N, 2) m, shape (G,); inf where
    there is no cell. `poses` (6, P) holds x, y, yaw, cos(yaw), sin(yaw) and scale, in G groups
    of P / G consecutive poses; cells are grouped in squares of `side` m; `rounding` m covers
    the rounding of the bounds."""
    least = np.full(groups, np.inf)
    if len(lethal) == 0:
        return least
    squares = _squares(lethal, side, rounding)
    per_group = poses.shape[1] // groups
    for group in range(groups):
        least[group] = _least_of_group(
            normals, offsets, poses, group * per_group, per_group, squares
        )
    return least


@compiled(f"b1[::1]({CELLS}, {CELLS}, f8)")
def any_within(points: FloatArray, lethal: FloatArray, reach: float) -> Any:
    """Whether a lethal cell centre (N, 2) m lies within `reach` m of each point (P, 2) m, shape
    (P,): the distance as numpy's hypot takes it (both call the C library's), and a cell
    further than `reach` along either axis never measured (hypot is no less than either)."""
    near = np.zeros(len(points), np.bool_)
    for point in range(len(points)):
        for cell in range(len(lethal)):
            dx = points[point, 0] - lethal[cell, 0]
            if abs(dx) > reach:
                continue
            dy = points[point, 1] - lethal[cell, 1]
            if abs(dy) <= reach and np.hypot(dx, dy) <= reach:
                near[point] = True
                break
    return near


ROLLOUT = "UniTuple(f8[:, ::1], 3)"  # x, y and yaw (S, T)


@compiled(f"{ROLLOUT}(UniTuple(f8, 3), f8[::1], f8[::1], i8[::1], f8[::1])")
def dwa_rollouts(
    pose: tuple[float, float, float],
    linear: FloatArray,
    angular: FloatArray,
    steps: IntArray,
    dt: FloatArray,
) -> tuple[FloatArray, FloatArray, FloatArray]:
    """DWA's rollouts from `pose` (m, m, rad) of S samples (linear m/s, angular rad/s), in
    `steps` (S,) steps of dt (S,) s: x, y and yaw (S, T) m, m, rad after each step, a rollout's
    last pose repeated past its end; each step moves along the heading of the step before.
    dwa.roll_out_in_numpy's operations, in its order (its running sum along each row)."""
    count, longest = len(linear), max(int(steps.max()) if len(steps) else 1, 1)
    x, y, yaw = np.empty((count, longest)), np.empty((count, longest)), np.empty((count, longest))
    for s in range(count):
        turn, advance = angular[s] * dt[s], linear[s] * dt[s]
        along_x, along_y = 0.0, 0.0
        for j in range(longest):
            yaw[s, j] = pose[2] + turn * min(j, steps[s] - 1)
            moving = 0 < j < steps[s]
            heading = pose[2] if j == 0 else yaw[s, j - 1]
            moved = advance * (1.0 if moving else 0.0)
            step_x = moved * (math.cos(heading) if moving else 0.0)
            step_y = moved * (math.sin(heading) if moving else 0.0)
            along_x, along_y = (step_x, step_y) if j == 0 else (along_x + step_x, along_y + step_y)
            x[s, j], y[s, j] = pose[0] + along_x, pose[1] + along_y
    return x, y, yaw
