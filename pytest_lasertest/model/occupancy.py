"""A map as ROS publishes it on /map: nav_msgs/OccupancyGrid, and the wall boxes its occupied
cells make.

The grid's data is row-major from the cell at its origin, the lower left corner of the map (REP
103: x right, y up), each cell -1 (unknown), 0 (free) to 100 (occupied), as map_server
publishes it (nav2_map_server/src/map_io.cpp at a3a97043: the image is flipped so that its
bottom row comes first).
"""

from __future__ import annotations

import functools
import hashlib
import math
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from pytest_lasertest.model.geometry import FloatArray
from pytest_lasertest.model.obstacles import Box, box_holds

UNKNOWN, FREE, OCCUPIED = -1, 0, 100
Cells = npt.NDArray[np.int8]


@dataclass(frozen=True, eq=False)
class OccupancyGrid:
    """nav_msgs/OccupancyGrid in the map frame (taken as the world frame): no yaw, as Nav2's
    static layer assumes."""

    resolution: float  # m per cell
    origin: tuple[float, float]  # m, the lower left corner of cell [0, 0]
    data: Cells  # (height, width), indexed [y, x]: row 0 is the map's bottom row

    def __post_init__(self) -> None:
        # A value object: its cells never change after it is made.
        data = np.array(self.data, dtype=np.int8)
        data.setflags(write=False)
        object.__setattr__(self, "data", data)

    @property
    def width(self) -> int:
        """Cells along x."""
        return int(self.data.shape[1])

    @property
    def height(self) -> int:
        """Cells along y."""
        return int(self.data.shape[0])

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, OccupancyGrid):
            return NotImplemented
        same_frame = (self.resolution, self.origin) == (other.resolution, other.origin)
        return same_frame and np.array_equal(self.data, other.data)

    def __hash__(self) -> int:
        return hash((self.resolution, self.origin, self.digest()))

    def digest(self) -> str:
        """A hash of the cells and where they lie, equal for equal maps."""
        hashed = hashlib.sha256(np.ascontiguousarray(self.data).tobytes())
        hashed.update(repr((self.resolution, self.origin, self.data.shape)).encode())
        return hashed.hexdigest()

    def values_at(self, points: FloatArray) -> Cells:
        """The value of the cell holding each world point, shape (P, 2) m -> (P,); UNKNOWN off
        the map, as a static layer leaves what its map does not cover."""
        x = np.floor((points[:, 0] - self.origin[0]) / self.resolution).astype(np.int64)
        y = np.floor((points[:, 1] - self.origin[1]) / self.resolution).astype(np.int64)
        inside = (x >= 0) & (x < self.width) & (y >= 0) & (y < self.height)
        values = np.full(len(points), UNKNOWN, dtype=np.int8)
        values[inside] = self.data[y[inside], x[inside]]
        return values

    def cell_centre(self, x: int, y: int) -> tuple[float, float]:
        """The world position of cell [y, x]'s centre (m)."""
        return (
            self.origin[0] + (x + 0.5) * self.resolution,
            self.origin[1] + (y + 0.5) * self.resolution,
        )

    def wall_boxes(self, height: float) -> tuple[Box, ...]:
        """Boxes `height` m high that cover exactly the occupied cells: each row's runs of
        occupied cells, runs of the same columns in neighbouring rows merged into one box."""
        boxes = [self._box(*rectangle, height) for rectangle in self._occupied_rectangles]
        return tuple(sorted(boxes, key=lambda box: (box.y, box.x)))

    @property
    def wall_box_count(self) -> int:
        """How many boxes `wall_boxes` makes, without making them."""
        return len(self._occupied_rectangles)

    @functools.cached_property
    def _occupied_rectangles(self) -> tuple[tuple[tuple[int, int], int, int], ...]:
        """The wall boxes' cells, ((first, last column), first row, end row) each: once for a
        map, whose reader counts them and whose walls are made of them (0.3 s for a speckled
        800 x 800 map)."""
        rectangles = []
        open_runs: dict[tuple[int, int], int] = {}  # (first, last column) -> first row
        for row in range(self.height + 1):
            runs = set(_runs(self.data[row] >= OCCUPIED)) if row < self.height else set()
            for run in [run for run in open_runs if run not in runs]:
                rectangles.append((run, open_runs.pop(run), row))
            for run in runs:
                open_runs.setdefault(run, row)
        return tuple(rectangles)

    def _box(self, columns: tuple[int, int], first: int, end: int, height: float) -> Box:
        """The box over cells [first, end) x [columns[0], columns[1]]."""
        (x0, y0), r = self.origin, self.resolution
        low_x, high_x = x0 + columns[0] * r, x0 + (columns[1] + 1) * r
        low_y, high_y = y0 + first * r, y0 + end * r
        return Box(
            (low_x + high_x) / 2.0,
            (low_y + high_y) / 2.0,
            0.0,
            high_x - low_x,
            high_y - low_y,
            height,
        )


def rasterised(
    boxes: tuple[Box, ...],
    resolution: float,
    margin: float,
    covering: tuple[tuple[float, float], ...] = (),
) -> OccupancyGrid:
    """A grid at `resolution` m, reaching `margin` m past the boxes and the points `covering`
    (m), whose cells are occupied where a box covers any part of them and free elsewhere: what
    a map of these walls drawn at that resolution shows, of the ground the robot drives."""
    corners = np.array([*(corner for box in boxes for corner in box.corners()), *covering])
    low = np.floor((corners.min(axis=0) - margin) / resolution) * resolution
    high = corners.max(axis=0) + margin
    width, height = (math.ceil(extent) for extent in (high - low) / resolution)
    empty = np.full((height, width), FREE, dtype=np.int8)
    return drawn(OccupancyGrid(resolution, (float(low[0]), float(low[1])), empty), boxes)


def drawn(grid: OccupancyGrid, boxes: tuple[Box, ...]) -> OccupancyGrid:
    """The grid with every cell a box covers any part of occupied."""
    data = grid.data.copy()
    for box in boxes:
        # A cell overlaps the box when its centre lies within the box grown by half a cell's
        # diagonal along each of the box's own axes (exact for an axis-aligned box). Only the
        # cells round the grown box are tested: a map holds millions.
        turn = abs(math.cos(box.yaw)) + abs(math.sin(box.yaw))
        grown = box.grown(grid.resolution / 2.0 * turn)
        x0, x1 = _cells_within(grid, 0, box.x, grown.bounding_radius)
        y0, y1 = _cells_within(grid, 1, box.y, grown.bounding_radius)
        ys, xs = np.mgrid[y0:y1, x0:x1]
        cells = np.column_stack([xs.ravel(), ys.ravel()])
        centres = (cells + 0.5) * grid.resolution + grid.origin
        held = box_holds(grown, centres).reshape(ys.shape)
        data[y0:y1, x0:x1][held] = OCCUPIED
    return OccupancyGrid(grid.resolution, grid.origin, data)


def _cells_within(grid: OccupancyGrid, axis: int, centre: float, reach: float) -> tuple[int, int]:
    """The cells [first, last + 1) along `axis` (0: x, 1: y) whose centres may lie within
    `reach` m of `centre` m, clipped to the grid."""
    cells = grid.width if axis == 0 else grid.height
    low = math.floor((centre - reach - grid.origin[axis]) / grid.resolution)
    high = math.ceil((centre + reach - grid.origin[axis]) / grid.resolution) + 1
    return min(max(low, 0), cells), min(max(high, 0), cells)


def _runs(occupied: npt.NDArray[np.bool_]) -> list[tuple[int, int]]:
    """The first and last index of each run of True, in order."""
    padded = np.concatenate([[False], occupied, [False]]).astype(np.int8)
    edges = np.flatnonzero(np.diff(padded))
    return [(int(begin), int(end) - 1) for begin, end in zip(edges[::2], edges[1::2], strict=True)]
