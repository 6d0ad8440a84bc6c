"""A rolling-window costmap with the semantics of ROS costmap_2d's obstacle and inflation layers.

Each update does what the ObstacleLayer does with one laser scan:

1. the window moves with the robot by whole cells, keeping what it still covers (a view that
   slides over a larger buffer: the cells are moved only once it reaches the buffer's edge);
2. the scan becomes points: with `inf_is_valid`, +inf reads range_max - 1e-4, and only readings
   with range_min <= r < range_max are kept (laser_geometry's projection);
3. clearing comes first: the ray from the laser to each point, clipped to the window and to
   `raytrace_range`, is traced with Bresenham's algorithm and its cells freed, the last cell
   too, as costmap_2d's bresenham2D does;
4. marking comes next, so a point's own cell ends lethal: each point nearer the laser than
   `obstacle_range` marks its cell;
5. the cells under the robot's footprint are freed.

With `track_unknown_space`, cells never seen are unknown (255), not free, until a ray clears
them. `costs()` then inflates, as the InflationLayer does: a cell d m from the nearest lethal
cell costs 253 (inscribed) within the footprint's inscribed radius, 252 exp(-cost_scaling_factor
(d - inscribed)) out to `inflation_radius`, and keeps its own cost beyond; an unknown cell stays
unknown unless it lies within the inscribed radius.

Given the world's map (`receive_map`), a static layer (`static_layer.py`) lies under the obstacle
layer, and `costs()` combines the two afresh before inflating.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass
from typing import ClassVar

import numpy as np
import numpy.typing as npt

from pytest_lasertest.model.geometry import FloatArray, IntArray
from pytest_lasertest.model.occupancy import OccupancyGrid
from pytest_lasertest.model.route import place
from pytest_lasertest.nav.move_base.cost_values import FREE, INSCRIBED, LETHAL, UNKNOWN, Grid
from pytest_lasertest.nav.move_base.kernels import distances_to_lethal
from pytest_lasertest.nav.move_base.static_layer import StaticLayer, StaticLayerSettings, with_max
from pytest_lasertest.nav.protocol import LaserScan
from pytest_lasertest.nav.raytrace import clipped, ray_indices

# costmap_2d's laserScanValidInfCallback: a tenth of a millimetre short of range_max.
INF_EPSILON = 1e-4  # m


@dataclass(frozen=True)
class CostmapSettings:
    """A costmap's parameters, with costmap_2d's names; the defaults are its own."""

    size: float = 6.0  # m, the rolling window's width and height
    resolution: float = 0.05  # m per cell
    obstacle_range: float = 2.5  # m
    raytrace_range: float = 3.0  # m
    inf_is_valid: bool = False
    inflation_radius: float = 0.55  # m
    cost_scaling_factor: float = 10.0  # 1/m
    footprint_clearing: bool = True
    track_unknown_space: bool = False
    update_frequency: float = 5.0  # Hz: each update takes the latest scan

    @property
    def cells(self) -> int:
        """How many cells the window has along each side."""
        return round(self.size / self.resolution)


class Costmap:
    """The rolling costmap of one robot, updated scan by scan."""

    # Cells the window may slide each way over its buffer before its cells are moved: the
    # robot crosses a cell or two per update, and a 100 m global costmap holds 2.8 MB.
    slack: ClassVar[int] = 64

    def __init__(self, settings: CostmapSettings, footprint: FloatArray) -> None:
        self.settings = settings
        self.footprint = footprint  # (V, 2) m, counter-clockwise in the base frame
        self.unseen = UNKNOWN if settings.track_unknown_space else FREE
        self._buffer, self._corner = self._new_buffer()
        self.grid: Grid = self._window()
        self.origin = (0.0, 0.0)  # m, the world position of cell (0, 0)'s lower left corner
        self.inflation = InflationCost.of(settings, footprint)
        self.static: StaticLayer | None = None  # the map's layer, under `grid`, once given one

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

    def centres(self, x: IntArray, y: IntArray) -> FloatArray:
        """The world positions (K, 2) m of the centres of cells (x, y), (K,) each."""
        cells = np.column_stack([x, y]).astype(np.float64)
        centres: FloatArray = (cells + 0.5) * self.settings.resolution + np.array(self.origin)
        return centres

    def receive_map(self, grid: OccupancyGrid, settings: StaticLayerSettings) -> None:
        """Lay the map under the obstacle layer as a static layer (see the module docstring)."""
        self.static = StaticLayer(grid, settings, self.unseen)

    def combined(self, columns: slice = slice(None), rows: slice = slice(None)) -> Grid:
        """The layers' costs in the window's block of `columns` and `rows`, indexed [y, x],
        before inflation: the obstacle layer's grid alone (a view of it) without a map, else the
        static layer's costs raised by the obstacle layer's (updateWithMax)."""
        own = self.grid[rows, columns]
        if self.static is None:
            return own
        cells = self.settings.cells
        block = range(*columns.indices(cells)), range(*rows.indices(cells))
        static = self.static.block(self.origin, self.settings.resolution, *block)
        return with_max(static, own)

    def costs(self, columns: slice = slice(None), rows: slice = slice(None)) -> Grid:
        """The costs of the window's block of `columns` and `rows` (all by default) with the
        lethal cells inflated, indexed [y, x]."""
        cells = self.settings.cells
        (x0, x1, _), (y0, y1, _) = columns.indices(cells), rows.indices(cells)
        reach = math.ceil(self.settings.inflation_radius / self.settings.resolution)  # cells
        # Lethal cells up to `reach` outside the block inflate into it.
        low_x, low_y = max(x0 - reach, 0), max(y0 - reach, 0)
        padded = self.combined(
            slice(low_x, min(x1 + reach, cells)), slice(low_y, min(y1 + reach, cells))
        )
        inflated = self._inflation(padded == LETHAL, reach)
        inflated = inflated[y0 - low_y : y1 - low_y, x0 - low_x : x1 - low_x]
        own = padded[y0 - low_y : y1 - low_y, x0 - low_x : x1 - low_x]
        # The InflationLayer writes over an unknown cell only from the inscribed cost up.
        over_unknown = np.where(inflated >= INSCRIBED, inflated, UNKNOWN)
        costs: Grid = np.where(own == UNKNOWN, over_unknown, np.maximum(own, inflated))
        return costs.astype(np.uint8)

    def clear_outside(self, x: float, y: float, size: float) -> None:
        """Forget every cell outside the square `size` m wide around (x, y) m, as
        clear_costmap_recovery resets the obstacle layer: what it forgets is unseen again."""
        cells = self.settings.cells
        low_x, low_y, _ = self.cell_of(np.array([[x - size / 2.0, y - size / 2.0]]))
        high_x, high_y, _ = self.cell_of(np.array([[x + size / 2.0, y + size / 2.0]]))
        kept = self.grid.copy()
        self.grid[:] = self.unseen
        # The cells strictly between the corners' cells are kept, as the recovery keeps them.
        columns = slice(max(int(low_x[0]) + 1, 0), max(min(int(high_x[0]), cells), 0))
        rows = slice(max(int(low_y[0]) + 1, 0), max(min(int(high_y[0]), cells), 0))
        self.grid[rows, columns] = kept[rows, columns]

    def _inflation(self, lethal: npt.NDArray[np.bool_], reach: int) -> Grid:
        """The InflationLayer's cost of each cell, shape of `lethal`: inflated only around the
        lethal cells' bounding box, as a cell further than `reach` from all of them costs
        nothing (a placement's costmap holds one obstacle in a plan's hundred thousand cells)."""
        grid: Grid = np.zeros(lethal.shape, dtype=np.uint8)
        rows, columns = np.flatnonzero(lethal.any(axis=1)), np.flatnonzero(lethal.any(axis=0))
        if not len(rows):
            return grid
        block = (
            slice(max(int(rows[0]) - reach, 0), int(rows[-1]) + reach + 1),
            slice(max(int(columns[0]) - reach, 0), int(columns[-1]) + reach + 1),
        )
        distance = lethal_distances(lethal[block], reach) * self.settings.resolution
        grid[block] = self.inflation(distance).astype(np.uint8)
        return grid

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
        corner_x, corner_y = self._corner[0] + shift_x, self._corner[1] + shift_y
        if 0 <= corner_x <= 2 * self.slack and 0 <= corner_y <= 2 * self.slack:
            self._corner = (corner_x, corner_y)
            self.grid = self._window()
            self._forget_entering(shift_x, shift_y)
        else:
            self._move_cells(shift_x, shift_y)
        self.origin = (self.origin[0] + shift_x * resolution, self.origin[1] + shift_y * resolution)

    def _new_buffer(self) -> tuple[Grid, tuple[int, int]]:
        """A buffer of unseen cells `slack` cells wider than the window on every side, and the cell
        (x, y) of the buffer where the window's lower left corner lies."""
        width = self.settings.cells + 2 * self.slack
        return np.full((width, width), self.unseen, dtype=np.uint8), (self.slack, self.slack)

    def _window(self) -> Grid:
        """The window: a view of the buffer."""
        (x, y), cells = self._corner, self.settings.cells
        return self._buffer[y : y + cells, x : x + cells]

    def _forget_entering(self, shift_x: int, shift_y: int) -> None:
        """Make the cells the window slid onto unseen: the buffer may remember them from an
        earlier visit, which a rolling window forgets."""
        cells = self.settings.cells
        # The window's cells the old one also covered; the rest entered.
        kept_x, kept_y = _overlap(-shift_x, cells), _overlap(-shift_y, cells)
        columns = slice(kept_x.stop, cells) if shift_x > 0 else slice(0, kept_x.start)
        rows = slice(kept_y.stop, cells) if shift_y > 0 else slice(0, kept_y.start)
        self.grid[:, columns] = self.unseen
        self.grid[rows, :] = self.unseen

    def _move_cells(self, shift_x: int, shift_y: int) -> None:
        """Move the cells the window keeps into a fresh buffer, the window at its middle."""
        cells, old = self.settings.cells, self.grid
        self._buffer, self._corner = self._new_buffer()
        self.grid = self._window()
        source, target = _overlap(shift_x, cells), _overlap(-shift_x, cells)
        rows_source, rows_target = _overlap(shift_y, cells), _overlap(-shift_y, cells)
        self.grid[rows_target, target] = old[rows_source, source]

    def _clear(self, laser: tuple[float, float], points: FloatArray) -> None:
        """Free the cells on each ray from the laser to a point, up to `raytrace_range`."""
        start_x, start_y, inside = self.cell_of(np.array([laser]))
        if not inside[0] or not len(points):
            return
        end_x, end_y, valid = self.cell_of(self._clipped(laser, points))
        cells = self.settings.cells
        # Rays that end in one cell visit the same cells: far out, beams outnumber cells.
        ends = np.unique(end_x[valid] + end_y[valid] * cells)
        longest = math.ceil(self.settings.raytrace_range / self.settings.resolution)
        # Traced in the buffer's cells: the window is a view of it, not a block of its own.
        (corner_x, corner_y), stride = self._corner, self._buffer.shape[1]
        start = (int(start_x[0]) + corner_x, int(start_y[0]) + corner_y)
        ends_x, ends_y = ends % cells + corner_x, ends // cells + corner_y
        index = ray_indices(*start, ends_x, ends_y, stride, longest)
        self._buffer.reshape(-1)[index] = FREE

    def _clipped(self, laser: tuple[float, float], points: FloatArray) -> FloatArray:
        """The points moved back along their rays onto the window where they lie beyond it."""
        size = self.settings.cells * self.settings.resolution
        return clipped(laser, points, self.origin, (self.origin[0] + size, self.origin[1] + size))

    def _mark(self, laser: tuple[float, float], points: FloatArray) -> None:
        """Mark the cell of each point nearer the laser than `obstacle_range` lethal."""
        squared = ((points - laser) ** 2).sum(axis=1)
        near = points[squared < self.settings.obstacle_range**2]
        x, y, inside = self.cell_of(near)
        self.grid[y[inside], x[inside]] = LETHAL

    def _free_footprint(self, robot: tuple[float, float, float]) -> None:
        """Free the cells the footprint at pose [x, y, yaw] covers: each column between its
        outline's lowest and highest cell, as costmap_2d's convexFillCells does; none where a
        corner lies off the window, as setConvexPolygonCost gives up then (costmap_2d.cpp:324
        at noetic 9ad64419)."""
        corners_x, corners_y, on = self.cell_of(place(self.footprint, np.array(robot)))
        if not on.all():
            return
        left, bottom = int(corners_x.min()), int(corners_y.min())
        box = tuple((corners_x - left).tolist()), tuple((corners_y - bottom).tolist())
        columns, rows = _convex_fill(*box)
        self.grid[rows + bottom, columns + left] = FREE


@functools.lru_cache(maxsize=4096)
def _convex_fill(box_x: tuple[int, ...], box_y: tuple[int, ...]) -> tuple[IntArray, IntArray]:
    """The cells (columns, rows) of the polygon with corner cells `box_x`, `box_y` (counted
    from their lowest), filled as convexFillCells does. A robot driving on meets the same
    corner cells again and again, so the fills are remembered."""
    corners_x, corners_y = np.array(box_x), np.array(box_y)
    width = int(corners_x.max()) + 1
    # The outline, edge by edge from each corner to the next, stays in the corners' box.
    following = np.roll(np.arange(len(corners_x)), -1)
    outline = ray_indices(corners_x, corners_y, corners_x[following], corners_y[following], width)
    rows, columns = np.divmod(outline, width)
    low, high = np.full(width, np.iinfo(np.int32).max), np.full(width, -1)
    np.minimum.at(low, columns, rows)
    np.maximum.at(high, columns, rows)
    row = np.arange(int(high.max()) + 1)[:, np.newaxis]
    covered_rows, covered_columns = np.nonzero((row >= low) & (row <= high))
    for remembered in (covered_columns, covered_rows):
        remembered.setflags(write=False)  # shared by every later call
    return covered_columns, covered_rows


@dataclass(frozen=True)
class InflationCost:
    """The InflationLayer's cost of a cell d m from the nearest lethal cell: 254 on it, 253
    within the inscribed radius, 252 exp(-cost_scaling_factor (d - inscribed)) out to the
    inflation radius, 0 beyond."""

    inscribed: float  # m, the footprint's inscribed radius
    inflation_radius: float  # m
    cost_scaling_factor: float  # 1/m

    @classmethod
    def of(cls, settings: CostmapSettings, footprint: FloatArray) -> InflationCost:
        """The inflation of a costmap with `settings` around `footprint` (V, 2) m."""
        # costmap_2d inflates out to a whole number of cells.
        cells = math.ceil(settings.inflation_radius / settings.resolution)
        radius = cells * settings.resolution
        return cls(_inscribed_radius(footprint), radius, settings.cost_scaling_factor)

    def __call__(self, distance: FloatArray) -> FloatArray:
        """The cost at each distance (m), same shape."""
        falloff = (INSCRIBED - 1) * np.exp(-self.cost_scaling_factor * (distance - self.inscribed))
        cost = np.where(distance <= self.inflation_radius, np.floor(falloff), FREE)
        cost = np.where(distance <= self.inscribed, INSCRIBED, cost)
        costs: FloatArray = np.where(distance <= 0.0, LETHAL, cost)
        return costs


def _overlap(shift: int, cells: int) -> slice:
    """The cells of a window shifted by `shift` cells that the old window also covered."""
    if shift >= 0:
        return slice(shift, cells) if shift < cells else slice(0, 0)
    return slice(0, cells + shift) if -shift < cells else slice(0, 0)


def lethal_distances(lethal: npt.NDArray[np.bool_], reach: int) -> FloatArray:
    """Each cell's distance in cells to the nearest lethal cell, shape (N, N): exact up to
    `reach`, and more than `reach` (or inf) beyond it (compiled: kernels.distances_to_lethal).
    """
    distance: FloatArray = distances_to_lethal(np.ascontiguousarray(lethal), reach)
    return distance


def _inscribed_radius(footprint: FloatArray) -> float:
    """The distance (m) from the base origin to the nearest edge of the footprint (V, 2)."""
    starts, ends = footprint, np.roll(footprint, -1, axis=0)
    edges = ends - starts
    lengths = np.hypot(edges[:, 0], edges[:, 1])
    # The distance to each edge's line: the footprint is convex around its origin.
    cross = np.abs(edges[:, 0] * starts[:, 1] - edges[:, 1] * starts[:, 0])
    return float(np.min(cross / lengths))
