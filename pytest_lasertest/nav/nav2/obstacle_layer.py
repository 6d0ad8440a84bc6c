"""Nav2's ObstacleLayer for one laser source: which readings mark their cell lethal, and which
cells each reading's ray frees, as each release does it.

Read in ros-navigation/navigation2, nav2_costmap_2d (plugins/obstacle_layer.cpp: updateBounds,
raytraceFreespace, laserScanValidInfCallback; include/nav2_costmap_2d/costmap_2d.hpp:
raytraceLine, bresenham2D; src/costmap_2d.cpp: cellDistance, worldToMap) at jazzy f4108e5b
(release 1.3.13), kilted 71a1d84f, and the commits that changed the marking on jazzy: 3320ebf
(#5775, the backport of PR #5697, first in 1.3.11) and 6be3614 (#6119, which brought PR #6092,
first in 1.3.12). Our own numpy code.

Marking differs by release (`Marking`):
- EUCLIDEAN (kilted; jazzy up to 1.3.10): a point marks unless its squared distance from the
  sensor is >= obstacle_max_range^2 or < obstacle_min_range^2.
- CELLS (jazzy 1.3.11): the distance is measured in cells, hypot(dx, dy) of the cell offsets
  truncated to a whole number, against cellDistance(range) = ceil(range / resolution), so that
  marking reaches as far as clearing does (navigation2 #5476: an obstacle just beyond
  obstacle_max_range was cleared by the ray to it and not marked again). A point 0.7999 m away
  can then lie 14 cells out when obstacle_max_range is 0.70 m: spurious lethal cells
  (navigation2 #6084, with inf_is_valid turning every no-return into range_max - 1e-4).
- CELLS_PREFILTERED (jazzy from 1.3.12): the world distance is checked first, then the cells.

Clearing is the same in both: the ray from the sensor's cell to each point (clipped onto the
window) starts raytrace_min_range cells out and is scaled to raytrace_max_range cells, the cell
it ends on freed too (bresenham2D's last step); marking follows clearing. The scan plane is
level, so the sensor and its points share a height and every distance is planar. The points are
float32, as a PointCloud2 holds them: at a cell's edge that decides the cell.
"""

from __future__ import annotations

import enum
import math
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from pytest_lasertest.model.geometry import FloatArray, IntArray
from pytest_lasertest.nav.raytrace import bresenham, clipped


class Marking(enum.Enum):
    """How a release decides that a point is near enough to mark (see the module docstring)."""

    EUCLIDEAN = "squared distance in the world"
    CELLS = "truncated distance in cells"
    CELLS_PREFILTERED = "distance in the world, then in cells"


@dataclass(frozen=True)
class ObservationSource:
    """One observation source's parameters, with Nav2's names and defaults
    (ObstacleLayer::onInitialize)."""

    obstacle_max_range: float = 2.5  # m
    obstacle_min_range: float = 0.0  # m
    raytrace_max_range: float = 3.0  # m
    raytrace_min_range: float = 0.0  # m
    marking: bool = True
    clearing: bool = True
    # The source's heights (ObservationBuffer keeps points with min <= z <= max, for marking
    # and clearing alike), then the layer's, for marking only (updateBounds skips z < min and
    # z > max; a VoxelLayer's grid also ends at origin_z + z_voxels * z_resolution).
    min_obstacle_height: float = 0.0  # m
    max_obstacle_height: float = 2.0  # m
    layer_min_obstacle_height: float = 0.0  # m
    layer_max_obstacle_height: float = 2.0  # m

    def sees(self, height: float) -> bool:
        """Whether a level scan `height` m above the ground enters the source at all."""
        return self.min_obstacle_height <= height <= self.max_obstacle_height

    def marks_at(self, height: float) -> bool:
        """Whether the layer marks the points of a level scan `height` m above the ground."""
        return self.sees(height) and (
            self.layer_min_obstacle_height <= height <= self.layer_max_obstacle_height
        )


@dataclass(frozen=True)
class Window:
    """Where a costmap's cells lie: cell (0, 0)'s lower left corner, their size and count."""

    origin_x: float  # m
    origin_y: float  # m
    resolution: float  # m per cell
    size_x: int  # cells
    size_y: int  # cells

    def cell_distance(self, distance: float) -> int:
        """Costmap2D::cellDistance: a world distance (m) in whole cells, rounded up."""
        return int(max(0.0, math.ceil(distance / self.resolution)))

    def cells_of(
        self, x: FloatArray, y: FloatArray
    ) -> tuple[IntArray, IntArray, npt.NDArray[np.bool_]]:
        """Costmap2D::worldToMap of points (P,) each: their cells and which lie on the window."""
        cell_x = ((x - self.origin_x) / self.resolution).astype(np.int64)
        cell_y = ((y - self.origin_y) / self.resolution).astype(np.int64)
        inside = (x >= self.origin_x) & (y >= self.origin_y)
        inside &= (cell_x < self.size_x) & (cell_y < self.size_y)
        return cell_x, cell_y, inside


def marked(
    window: Window,
    sensor: tuple[float, float],
    points: FloatArray,
    source: ObservationSource,
    marking: Marking,
) -> IntArray:
    """The flat indices (x + y * size_x) of the cells that the points (P, 2) m, read from
    `sensor` (m), mark lethal; shape (M,)."""
    if not source.marking or not len(points):
        return np.zeros(0, dtype=np.int64)
    x, y = (column.astype(np.float64) for column in points.astype(np.float32).T)
    near = np.ones(len(x), dtype=bool)
    if marking is not Marking.CELLS:
        squared = (x - sensor[0]) ** 2 + (y - sensor[1]) ** 2
        near = (
            (squared < source.obstacle_max_range**2)
            if marking is Marking.EUCLIDEAN
            else (squared <= source.obstacle_max_range**2)
        )
        near &= squared >= source.obstacle_min_range**2
    cell_x, cell_y, inside = window.cells_of(x, y)
    near &= inside
    if marking is not Marking.EUCLIDEAN:
        near &= _within_cells(window, sensor, cell_x, cell_y, source)
    flat: IntArray = cell_x[near] + cell_y[near] * window.size_x
    return flat


def _within_cells(
    window: Window,
    sensor: tuple[float, float],
    cell_x: IntArray,
    cell_y: IntArray,
    source: ObservationSource,
) -> npt.NDArray[np.bool_]:
    """Whether each cell's truncated distance in cells from the sensor's cell lies within the
    source's ranges in cells; none when the sensor is off the window."""
    start_x, start_y, on = window.cells_of(np.array([sensor[0]]), np.array([sensor[1]]))
    if not on[0]:
        return np.zeros(len(cell_x), dtype=bool)
    cells = np.hypot(cell_x - start_x[0], cell_y - start_y[0]).astype(np.int64)
    within: npt.NDArray[np.bool_] = (cells <= window.cell_distance(source.obstacle_max_range)) & (
        cells >= window.cell_distance(source.obstacle_min_range)
    )
    return within


def cleared(
    window: Window, sensor: tuple[float, float], points: FloatArray, source: ObservationSource
) -> IntArray:
    """The flat indices of the cells that the rays from `sensor` (m) to the points (P, 2) m
    free (raytraceFreespace), with repeats; none when the sensor is off the window."""
    start_x, start_y, on = window.cells_of(np.array([sensor[0]]), np.array([sensor[1]]))
    if not source.clearing or not len(points) or not on[0]:
        return np.zeros(0, dtype=np.int64)
    high = (
        window.origin_x + window.size_x * window.resolution,
        window.origin_y + window.size_y * window.resolution,
    )
    low = (window.origin_x, window.origin_y)
    ends = clipped(sensor, points.astype(np.float32).astype(np.float64), low, high)
    end_x, end_y, legal = window.cells_of(ends[:, 0], ends[:, 1])
    return _raytrace(window, (int(start_x[0]), int(start_y[0])), end_x[legal], end_y[legal], source)


def _raytrace(
    window: Window,
    start: tuple[int, int],
    end_x: IntArray,
    end_y: IntArray,
    source: ObservationSource,
) -> IntArray:
    """raytraceLine from the start cell to each end cell (K,): a ray shorter than the minimum
    length in cells is skipped; the rest start that many cells out along the ray (truncated)
    and take the share of their steps from there that the maximum length is of the whole ray."""
    longest = window.cell_distance(source.raytrace_max_range)
    shortest = window.cell_distance(source.raytrace_min_range)
    run_x, run_y = end_x - start[0], end_y - start[1]
    length = np.hypot(run_x, run_y)
    kept = length >= shortest
    run_x, run_y, length = run_x[kept], run_y[kept], length[kept]
    end_x, end_y = end_x[kept], end_y[kept]
    # As raytraceLine computes it, x0 + dx / dist * min_length, so a cell's edge falls alike.
    safe = np.where(length > 0.0, length, 1.0)
    from_x = (start[0] + run_x / safe * shortest).astype(np.int64)
    from_y = (start[1] + run_y / safe * shortest).astype(np.int64)
    scale = np.where(length > 0.0, np.minimum(1.0, longest / safe), 1.0)
    major = np.maximum(np.abs(end_x - from_x), np.abs(end_y - from_y))
    steps = (scale * major).astype(np.int64)
    return bresenham(from_x, from_y, end_x, end_y, steps, window.size_x)
