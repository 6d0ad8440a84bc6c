"""costmap_2d's static layer: the world's map under a costmap's obstacle layer.

The layers are combined in the order costmap_2d's LayeredCostmap::updateMap runs its plugins:
static, obstacle, inflation. Each layer keeps a grid of its own; the costmap combines them
afresh at each read, so the obstacle layer's clearing never frees a cell the map marks lethal,
and a wall is inflated as any lethal cell is, seen or not. As read in ros-planning/navigation
noetic-devel 9ad64419 (costmap_2d/plugins/static_layer.cpp: interpretValue, updateCosts;
src/costmap_layer.cpp: updateWithTrueOverwrite, updateWithMax; src/layered_costmap.cpp:
updateMap) and in ros-navigation/navigation2 a3a97043 (the same files under nav2_costmap_2d),
our own code:

- the layer turns each map value into a cost once (interpretValue: the unknown value to 255 with
  its track_unknown_space, else free; from lethal_cost_threshold up lethal; the rest free with
  trinary_costmap, else scaled by 254 / lethal_cost_threshold);
- in a rolling window the layer writes each window cell with the map cell under the cell's
  centre (worldToMap truncates), overwriting the master (updateWithTrueOverwrite's rule, unless
  use_maximum); a window cell off the map it does not write, and the master keeps what
  resetMap left there: 255 with the costmap's track_unknown_space, else free;
- the obstacle layer then raises each cell with updateWithMax: its unknown cells leave the
  master as it is, its other cells overwrite an unknown master cell and raise any other.

The window's static cells are read from the map once each time the window moves (by whole
cells), not at each update.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from pytest_lasertest.model.geometry import IntArray
from pytest_lasertest.model.occupancy import OccupancyGrid
from pytest_lasertest.nav.move_base.cost_values import FREE, LETHAL, UNKNOWN, Grid


@dataclass(frozen=True)
class StaticLayerSettings:
    """A static layer's parameters, with costmap_2d's names; the defaults are ROS 1's
    (StaticLayer::onInitialize), `nav2()` Nav2's."""

    # ROS 1: the layer's own, true unless set, the costmap's copied onto it where the costmap
    # sets one (Costmap2DROS::copyParentParameters). Nav2: the costmap's.
    track_unknown_space: bool = True
    lethal_cost_threshold: int = 100  # a map value from this up is lethal (cut to 0 .. 100)
    unknown_cost_value: int = -1  # the map value that means unknown, read as a byte: 255
    trinary_costmap: bool = True  # values below the threshold free, else scaled
    use_maximum: bool = False  # write with the larger cost, not overwrite

    @classmethod
    def nav2(cls, track_unknown_space: bool) -> StaticLayerSettings:
        """Nav2's defaults (Costmap2DROS's constructor declares them: unknown_cost_value 0xff)
        with the costmap's track_unknown_space. inscribed_obstacle_cost_value came after the
        releases imitated (costmap_2d_ros.cpp at a3a97043 declares it; kilted 71a1d84f, jazzy
        f4108e5b and humble 3c3db59d do not): a map's 99 is below the lethal threshold."""
        return cls(track_unknown_space, unknown_cost_value=0xFF)

    def costs(self) -> Grid:
        """interpretValue as a table: the cost (256,) of each map value read as a byte, as the
        layer's incomingMap reads the map's int8 data into unsigned chars."""
        value = np.arange(256)
        threshold = min(max(self.lethal_cost_threshold, 0), 100)
        below = FREE if self.trinary_costmap else LETHAL * value / max(threshold, 1)
        # A double converted to unsigned char truncates.
        costs = np.where(value >= threshold, LETHAL, below).astype(np.uint8)
        # Checked first: the unknown value is unknown (or free) whatever the thresholds say.
        costs[self.unknown_cost_value & 0xFF] = UNKNOWN if self.track_unknown_space else FREE
        return costs


class StaticLayer:
    """costmap_2d's StaticLayer holding one map, read through a rolling window."""

    def __init__(self, grid: OccupancyGrid, settings: StaticLayerSettings, unseen: int) -> None:
        self.map, self.settings = grid, settings
        costs = settings.costs()[grid.data.view(np.uint8)]
        if settings.use_maximum:
            # The larger of the map's cost and what resetMap left in the master cell.
            costs = np.maximum(costs, np.uint8(unseen))
        # Row and column 0 stand for off the map, where the layer writes nothing and the master
        # keeps what resetMap left there.
        self._cells: Grid = np.pad(costs, ((1, 0), (1, 0)), constant_values=unseen)

    def block(
        self, origin: tuple[float, float], resolution: float, columns: range, rows: range
    ) -> Grid:
        """What the layer writes into the `columns` and `rows` of a window of `resolution` m
        cells from `origin` (m, its lower left corner), indexed [y, x]: each cell's the map cell
        under its centre, or the master's reset value off the map. Only the block is read: the
        window rolls with the robot, and a 100 m one holds four million cells."""
        x = self._under(origin[0], resolution, columns, self.map.origin[0], self.map.width)
        y = self._under(origin[1], resolution, rows, self.map.origin[1], self.map.height)
        block: Grid = self._cells[np.ix_(y, x)]
        return block

    def _under(
        self, low: float, resolution: float, cells: range, map_low: float, map_cells: int
    ) -> IntArray:
        """Along one axis: the index into `_cells` of the map cell under the centre of each of
        the window's `cells` (Costmap2D::mapToWorld), 0 off the map; the map's worldToMap
        refuses a point below its origin and truncates the rest."""
        centres = low + (np.arange(cells.start, cells.stop) + 0.5) * resolution
        index = ((centres - map_low) / self.map.resolution).astype(np.int64)
        on = (centres >= map_low) & (index < map_cells)
        under: IntArray = np.where(on, index + 1, 0)
        return under


def with_max(master: Grid, layer: Grid) -> Grid:
    """CostmapLayer::updateWithMax of `layer` onto `master`, same shape: where the layer is
    unknown the master stays; elsewhere the layer's cost overwrites an unknown master cell and
    raises any other."""
    raised = np.where(master == UNKNOWN, layer, np.maximum(master, layer))
    combined: Grid = np.where(layer == UNKNOWN, master, raised).astype(np.uint8)
    return combined
