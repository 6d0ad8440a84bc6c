"""A Nav2 costmap: the rolling window of move_base's costmap_2d (nav2_costmap_2d is its port)
with Nav2's obstacle layer for the laser (`obstacle_layer.py`): marking by release, clearing
from raytrace_min_range to raytrace_max_range. The inflation layer's cost is the same function
(nav2_costmap_2d/plugins/inflation_layer.cpp computeCost at jazzy f4108e5b).
"""

from __future__ import annotations

import numpy as np

from pytest_lasertest.model.geometry import FloatArray
from pytest_lasertest.nav.move_base.cost_values import FREE, LETHAL
from pytest_lasertest.nav.move_base.costmap import Costmap, CostmapSettings
from pytest_lasertest.nav.nav2.mppi import CostGrid
from pytest_lasertest.nav.nav2.obstacle_layer import (
    Marking,
    ObservationSource,
    Window,
    cleared,
    marked,
)
from pytest_lasertest.nav.protocol import LaserScan
from pytest_lasertest.nav.raytrace import bresenham


class Nav2Costmap(Costmap):
    """A rolling costmap whose laser source marks and clears as Nav2's ObstacleLayer does."""

    def __init__(
        self,
        settings: CostmapSettings,
        footprint: FloatArray,
        source: ObservationSource,
        marking: Marking,
    ) -> None:
        super().__init__(settings, footprint)
        self.source, self.marking = source, marking
        self._height = 0.0  # m, the latest scan's plane above the ground

    def update(self, scan: LaserScan, robot: tuple[float, float, float]) -> None:
        """One scan's update; a scan outside the source's heights neither marks nor clears,
        and one outside the layer's clears only."""
        self._height = scan.mount.xyz[2]
        super().update(scan, robot)

    def cost_grid(self) -> CostGrid:
        """The inflated costs as MPPI's critics read them."""
        resolution = self.settings.resolution
        return CostGrid(self.costs(), self.origin, resolution, self.settings.track_unknown_space)

    def footprint_cost(self, outline: FloatArray) -> int:
        """FootprintCollisionChecker::footprintCost of a footprint placed in the world (V, 2) m:
        the highest cost of the cells each edge runs through, cell by cell as lineCost's
        LineIterator steps (Bresenham's, as raytracing's), before inflation, which never
        raises a cell to lethal; lethal if a corner lies off the window
        (nav2_costmap_2d/src/footprint_collision_checker.cpp:48-104 at jazzy f4108e5b)."""
        x, y, inside = self.cell_of(outline)
        if not inside.all():
            return LETHAL
        end_x, end_y = np.roll(x, -1), np.roll(y, -1)
        steps = np.maximum(np.abs(end_x - x), np.abs(end_y - y))
        cells = self.settings.cells
        visited = bresenham(x, y, end_x, end_y, steps, cells)
        return int(self.combined()[visited // cells, visited % cells].max())

    def _geometry(self) -> Window:
        cells = self.settings.cells
        return Window(self.origin[0], self.origin[1], self.settings.resolution, cells, cells)

    def _clear(self, laser: tuple[float, float], points: FloatArray) -> None:
        if not self.source.sees(self._height):
            return
        freed = cleared(self._geometry(), laser, points, self.source)
        cells = self.settings.cells
        self.grid[freed // cells, freed % cells] = FREE

    def _mark(self, laser: tuple[float, float], points: FloatArray) -> None:
        if not self.source.marks_at(self._height):
            return
        lethal = marked(self._geometry(), laser, points, self.source, self.marking)
        cells = self.settings.cells
        self.grid[lethal // cells, lethal % cells] = LETHAL
