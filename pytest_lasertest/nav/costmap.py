"""A rolling-window costmap with the semantics of ROS costmap_2d's obstacle and inflation layers.

Each update does what the ObstacleLayer does with one laser scan:

1. the window moves with the robot by whole cells, keeping what it still covers;
2. the scan becomes points: with `inf_is_valid`, +inf reads range_max - 1e-4, and only readings
   with range_min <= r < range_max are kept (laser_geometry's projection);
3. clearing comes first: the ray from the laser to each point, clipped to the window and to
   `raytrace_range`, is traced with Bresenham's algorithm and its cells freed, the last cell
   too, as costmap_2d's bresenham2D does;
4. marking comes next, so a point's own cell ends lethal: each point nearer the laser than
   `obstacle_range` marks its cell;
5. the cells under the robot's footprint are freed.

`costs()` then inflates, as the InflationLayer does: a cell d m from the nearest lethal cell
costs 253 (inscribed) within the footprint's inscribed radius, 252 exp(-cost_scaling_factor
(d - inscribed)) out to `inflation_radius`, and keeps its own cost beyond.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from pytest_lasertest.geometry import FloatArray, IntArray
from pytest_lasertest.nav.protocol import LaserScan
from pytest_lasertest.path import place

FREE, INSCRIBED, LETHAL = 0, 253, 254
# costmap_2d's laserScanValidInfCallback: a tenth of a millimetre short of range_max.
INF_EPSILON = 1e-4  # m
Grid = npt.NDArray[np.uint8]  # (N, N) costs, indexed [y, x]


@dataclass(frozen=True)
class CostmapSettings:
    """The local costmap's parameters, with costmap_2d's names; the defaults are its own."""

    size: float = 6.0  # m, the rolling window's width and height
    resolution: float = 0.05  # m per cell
    obstacle_range: float = 2.5  # m
    raytrace_range: float = 3.0  # m
    inf_is_valid: bool = False
    inflation_radius: float = 0.55  # m
    cost_scaling_factor: float = 10.0  # 1/m
    footprint_clearing: bool = True

    @property
    def cells(self) -> int:
        """How many cells the window has along each side."""
        return round(self.size / self.resolution)


class Costmap:
    """The local costmap of one robot, updated scan by scan."""

    def __init__(self, settings: CostmapSettings, footprint: FloatArray) -> None:
        self.settings = settings
        self.footprint = footprint  # (V, 2) m, counter-clockwise in the base frame
        self.grid: Grid = np.zeros((settings.cells, settings.cells), dtype=np.uint8)
        self.origin = (0.0, 0.0)  # m, the world position of cell (0, 0)'s lower left corner
        self._inscribed = _inscribed_radius(footprint)

    def update(self, scan: LaserScan, robot: tuple[float, float, float]) -> None:
        """One scan's update, the robot at pose [x, y, yaw] (m, m, rad) in the odom frame."""
        laser, points = self._observation(scan, robot)
        self._follow(robot[0], robot[1])
        self._clear(laser, points)
        self._mark(laser, points)
        if self.settings.footprint_clearing:
            self._free_footprint(robot)

    def cell_of(self, points: FloatArray) -> tuple[IntArray, IntArray, npt.NDArray[np.bool_]]:
        """The cells (x, y) holding world points (P, 2), and which lie inside the window."""
        resolution = self.settings.resolution
        x = np.floor((points[:, 0] - self.origin[0]) / resolution).astype(np.int64)
        y = np.floor((points[:, 1] - self.origin[1]) / resolution).astype(np.int64)
        cells = self.settings.cells
        return x, y, (x >= 0) & (x < cells) & (y >= 0) & (y < cells)

    def costs(self) -> Grid:
        """The window's costs with the lethal cells inflated, shape (N, N), indexed [y, x]."""
        settings = self.settings
        reach = math.ceil(settings.inflation_radius / settings.resolution)  # cells
        distance = lethal_distances(self.grid == LETHAL, reach) * settings.resolution
        within = distance <= reach * settings.resolution
        falloff = np.exp(-settings.cost_scaling_factor * (distance - self._inscribed))
        inflated = np.where(
            distance <= self._inscribed, INSCRIBED, ((INSCRIBED - 1) * falloff).astype(np.int64)
        )
        inflated = np.where(within, inflated, FREE)
        inflated[distance == 0.0] = LETHAL
        costs: Grid = np.maximum(self.grid, inflated).astype(np.uint8)
        return costs

    def _observation(
        self, scan: LaserScan, robot: tuple[float, float, float]
    ) -> tuple[tuple[float, float], FloatArray]:
        """Where the laser is, and the scan's points (P, 2) m, in the odom frame, as costmap_2d
        projects a scan: +inf at range_max - 1e-4 with `inf_is_valid`, and only readings with
        range_min <= r < range_max."""
        ranges, meta = scan.ranges, scan.meta
        if self.settings.inf_is_valid:
            ranges = np.where(ranges == np.inf, meta.range_max - INF_EPSILON, ranges)
        kept = (ranges >= meta.range_min) & (ranges < meta.range_max)
        projected = LaserScan(scan.stamp, np.where(kept, ranges, np.inf), meta, scan.mount)
        pose = np.array(robot)
        laser = place(np.array([scan.mount.xyz[:2]]), pose)[0]
        return (float(laser[0]), float(laser[1])), place(projected.points_in_base(), pose)

    def _follow(self, x: float, y: float) -> None:
        """Centre the window on (x, y) by whole cells, keeping the cells it still covers."""
        resolution, cells = self.settings.resolution, self.settings.cells
        # costmap_2d centres on (size - 0.5) cells and truncates the shift toward zero.
        half = (cells - 0.5) * resolution / 2.0
        shift_x = int((x - half - self.origin[0]) / resolution)
        shift_y = int((y - half - self.origin[1]) / resolution)
        if shift_x == 0 and shift_y == 0:
            return
        kept = np.zeros_like(self.grid)
        source, target = _overlap(shift_x, cells), _overlap(-shift_x, cells)
        rows_source, rows_target = _overlap(shift_y, cells), _overlap(-shift_y, cells)
        kept[rows_target, target] = self.grid[rows_source, source]
        self.grid = kept
        self.origin = (self.origin[0] + shift_x * resolution, self.origin[1] + shift_y * resolution)

    def _clear(self, laser: tuple[float, float], points: FloatArray) -> None:
        """Free the cells on each ray from the laser to a point, up to `raytrace_range`."""
        start_x, start_y, inside = self.cell_of(np.array([laser]))
        if not inside[0] or not len(points):
            return
        ends = self._clipped(laser, points)
        end_x, end_y, valid = self.cell_of(ends)
        longest = math.ceil(self.settings.raytrace_range / self.settings.resolution)
        x, y = ray_cells(int(start_x[0]), int(start_y[0]), end_x[valid], end_y[valid], longest)
        self.grid[y, x] = FREE

    def _clipped(self, laser: tuple[float, float], points: FloatArray) -> FloatArray:
        """The points moved back along their rays onto the window where they lie beyond it, as
        costmap_2d's raytraceFreespace does: low edges first, then high ones, a millimetre
        inside."""
        (origin_x, origin_y), size = laser, self.settings.cells * self.settings.resolution
        run_x, run_y = points[:, 0] - origin_x, points[:, 1] - origin_y
        x, y = points[:, 0].copy(), points[:, 1].copy()
        low_x, low_y = self.origin
        high_x, high_y = low_x + size, low_y + size
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

    def _mark(self, laser: tuple[float, float], points: FloatArray) -> None:
        """Mark the cell of each point nearer the laser than `obstacle_range` lethal."""
        squared = ((points - laser) ** 2).sum(axis=1)
        near = points[squared < self.settings.obstacle_range**2]
        x, y, inside = self.cell_of(near)
        self.grid[y[inside], x[inside]] = LETHAL

    def _free_footprint(self, robot: tuple[float, float, float]) -> None:
        """Free the cells the footprint at pose [x, y, yaw] covers: each column between its
        outline's lowest and highest cell, as costmap_2d's convexFillCells does."""
        corners = place(self.footprint, np.array(robot))
        cell_x, cell_y, _ = self.cell_of(corners)
        outline_x, outline_y = [], []
        for index in range(len(corners)):
            following = (index + 1) % len(corners)
            xs, ys = ray_cells(
                int(cell_x[index]),
                int(cell_y[index]),
                cell_x[following : following + 1],
                cell_y[following : following + 1],
            )
            outline_x.append(xs)
            outline_y.append(ys)
        columns, rows = np.concatenate(outline_x), np.concatenate(outline_y)
        cells = self.settings.cells
        for column in np.unique(columns[(columns >= 0) & (columns < cells)]):
            in_column = rows[columns == column]
            low, high = max(int(in_column.min()), 0), min(int(in_column.max()), cells - 1)
            self.grid[low : high + 1, column] = FREE


def ray_cells(
    start_x: int, start_y: int, end_x: IntArray, end_y: IntArray, longest: int | None = None
) -> tuple[IntArray, IntArray]:
    """The cells costmap_2d's raytraceLine visits from one start cell to each end cell (K,):
    steps along the longer axis, the other stepping when its error wraps, then the last cell;
    at most `longest` cells of length (scaled along the longer axis), shape (M,) each."""
    dx, dy = end_x - start_x, end_y - start_y
    along_x = np.abs(dx) >= np.abs(dy)
    major = np.where(along_x, np.abs(dx), np.abs(dy))
    minor = np.where(along_x, np.abs(dy), np.abs(dx))
    steps = major
    if longest is not None:
        length = np.hypot(dx, dy)
        scale = np.minimum(1.0, longest / np.where(length == 0.0, 1.0, length))
        steps = np.minimum((scale * major).astype(np.int64), major)
    # Each ray visits cells 0..steps: one row per visited cell.
    ray = np.repeat(np.arange(len(steps)), steps + 1)
    first = np.cumsum(steps + 1) - (steps + 1)
    step = np.arange(len(ray)) - first[ray]
    wraps = (major[ray] // 2 + step * minor[ray]) // np.maximum(major[ray], 1)
    sign_x = np.where(dx[ray] > 0, 1, -1)
    sign_y = np.where(dy[ray] > 0, 1, -1)
    x = np.where(along_x[ray], start_x + sign_x * step, start_x + sign_x * wraps)
    y = np.where(along_x[ray], start_y + sign_y * wraps, start_y + sign_y * step)
    return x.astype(np.int64), y.astype(np.int64)


def _overlap(shift: int, cells: int) -> slice:
    """The cells of a window shifted by `shift` cells that the old window also covered."""
    if shift >= 0:
        return slice(shift, cells) if shift < cells else slice(0, 0)
    return slice(0, cells + shift) if -shift < cells else slice(0, 0)


def lethal_distances(lethal: npt.NDArray[np.bool_], reach: int) -> FloatArray:
    """Each cell's distance in cells to the nearest lethal cell, shape (N, N): exact up to
    `reach`, and more than `reach` (or inf) beyond it.

    Separable: the distance along each column first, then the least of
    dx^2 + column distance^2 over the columns within `reach` either side.
    """
    rows = lethal.shape[0]
    index = np.arange(rows)[:, np.newaxis]
    far = rows + reach + 1
    above = np.maximum.accumulate(np.where(lethal, index, -far), axis=0)
    below = np.flip(np.minimum.accumulate(np.flip(np.where(lethal, index, 2 * far), 0), 0), 0)
    column = np.minimum(index - above, below - index).astype(np.float64)
    column[column > reach] = np.inf
    squared = column**2
    best = squared.copy()
    for shift in range(1, reach + 1):
        best[:, shift:] = np.minimum(best[:, shift:], squared[:, :-shift] + shift**2)
        best[:, :-shift] = np.minimum(best[:, :-shift], squared[:, shift:] + shift**2)
    distance: FloatArray = np.sqrt(best)
    return distance


def _inscribed_radius(footprint: FloatArray) -> float:
    """The distance (m) from the base origin to the nearest edge of the footprint (V, 2)."""
    starts, ends = footprint, np.roll(footprint, -1, axis=0)
    edges = ends - starts
    lengths = np.hypot(edges[:, 0], edges[:, 1])
    # The distance to each edge's line: the footprint is convex around its origin.
    cross = np.abs(edges[:, 0] * starts[:, 1] - edges[:, 1] * starts[:, 0])
    return float(np.min(cross / lengths))
