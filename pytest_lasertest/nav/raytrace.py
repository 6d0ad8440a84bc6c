"""costmap_2d's ray tracing, which ROS 1's costmap_2d and Nav2's nav2_costmap_2d share: the
points of a scan moved back onto a costmap's window (raytraceFreespace), and the cells
Bresenham's line visits from the laser's cell toward each (raytraceLine, bresenham2D), every
ray at once.
"""

from __future__ import annotations

import numpy as np

from pytest_lasertest.model.geometry import FloatArray, IntArray
from pytest_lasertest.nav import kernels


def clipped(
    laser: tuple[float, float],
    points: FloatArray,
    low: tuple[float, float],
    high: tuple[float, float],
) -> FloatArray:
    """The points (P, 2) m moved back along their rays from `laser` onto the window from `low`
    to `high` (m) where they lie beyond it, as costmap_2d's raytraceFreespace does: low edges
    first, then high ones, a millimetre inside."""
    (origin_x, origin_y), (low_x, low_y), (high_x, high_y) = laser, low, high
    (least_x, least_y), (most_x, most_y) = points.min(axis=0), points.max(axis=0)
    if least_x >= low_x and least_y >= low_y and most_x <= high_x and most_y <= high_y:
        return points  # all on the window: a global costmap's scans mostly are
    run_x, run_y = points[:, 0] - origin_x, points[:, 1] - origin_y
    x, y = points[:, 0].copy(), points[:, 1].copy()
    with np.errstate(divide="ignore", invalid="ignore"):
        out = x < low_x
        y[out], x[out] = origin_y + run_y[out] * (low_x - origin_x) / run_x[out], low_x
        out = y < low_y
        x[out], y[out] = origin_x + run_x[out] * (low_y - origin_y) / run_y[out], low_y
        out = x > high_x
        y[out] = origin_y + run_y[out] * (high_x - origin_x) / run_x[out]
        x[out] = high_x - 0.001
        out = y > high_y
        x[out] = origin_x + run_x[out] * (high_y - origin_y) / run_y[out]
        y[out] = high_y - 0.001
    return np.column_stack([x, y])


def ray_indices(
    start_x: int | IntArray,
    start_y: int | IntArray,
    end_x: IntArray,
    end_y: IntArray,
    stride: int,
    longest: int | None = None,
) -> IntArray:
    """The cells costmap_2d's raytraceLine visits from a start cell to each end cell (K,), as
    flat indices x + y * stride into a grid `stride` cells wide, shape (M,): steps along the
    longer axis, the other stepping when its error wraps, then the last cell; at most
    `longest` cells of length (scaled along the longer axis). Each ray may start at a cell of
    its own (K,)."""
    dx, dy = end_x - start_x, end_y - start_y
    major = np.maximum(np.abs(dx), np.abs(dy))
    steps = major
    if longest is not None:
        length = np.hypot(dx, dy)
        scale = np.minimum(1.0, longest / np.where(length == 0.0, 1.0, length))
        steps = np.minimum((scale * major).astype(np.int64), major)
    return bresenham(start_x, start_y, end_x, end_y, steps, stride)


def bresenham(
    start_x: int | IntArray,
    start_y: int | IntArray,
    end_x: IntArray,
    end_y: IntArray,
    steps: IntArray,
    stride: int,
) -> IntArray:
    """The cells costmap_2d's bresenham2D visits on the line from a start cell toward each end
    cell (K,) in `steps` (K,) steps along its longer axis, and the cell it then stands on, as
    flat indices x + y * stride, shape (M,), compiled (`kernels.bresenham`)."""

    def ints(values: int | IntArray) -> IntArray:
        return np.array(np.broadcast_to(values, np.shape(end_x)), dtype=np.int64)  # writable

    cells: IntArray = kernels.bresenham(
        ints(start_x), ints(start_y), ints(end_x), ints(end_y), ints(steps), stride
    )
    return cells


def bresenham_in_numpy(
    start_x: int | IntArray,
    start_y: int | IntArray,
    end_x: IntArray,
    end_y: IntArray,
    steps: IntArray,
    stride: int,
) -> IntArray:
    """`bresenham` in numpy, the reference its kernel is tested against. Every ray is stepped
    at once: each visited cell is the start, `step` cells along the ray's longer axis and
    `wraps` along the other, and `wraps` is Bresenham's error count."""
    dx, dy = end_x - start_x, end_y - start_y
    along_x = np.abs(dx) >= np.abs(dy)
    major, minor = np.maximum(np.abs(dx), np.abs(dy)), np.minimum(np.abs(dx), np.abs(dy))
    unit_x, unit_y = np.where(dx > 0, 1, -1), np.where(dy > 0, stride, -stride)
    counts = steps + 1
    # int32 halves the time of the per-cell arithmetic; a window holds far fewer cells.
    step = np.arange(counts.sum(), dtype=np.int32)
    step -= np.repeat((np.cumsum(counts) - counts).astype(np.int32), counts)
    wraps = np.repeat((major // 2).astype(np.int32), counts)
    wraps += step * np.repeat(minor.astype(np.int32), counts)
    wraps //= np.repeat(np.maximum(major, 1).astype(np.int32), counts)
    index = step * np.repeat(np.where(along_x, unit_x, unit_y).astype(np.int32), counts)
    index += wraps * np.repeat(np.where(along_x, unit_y, unit_x).astype(np.int32), counts)
    origin = np.asarray(start_x + start_y * stride)
    cells: IntArray = index + (np.repeat(origin, counts) if origin.ndim else origin)
    return cells
