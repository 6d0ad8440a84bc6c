"""ROS 1 costmap_2d's test harness rebuilt on our costmap, for the ROS 1 conformance tests.

costmap_2d's tests (ros-planning/navigation 9ad64419, costmap_2d/include/costmap_2d/
testing_helper.h) build a LayeredCostmap of a few layers, feed its ObstacleLayer single points
with addStaticObservation (each seen from an origin, obstacle and raytrace range 100 m) and call
updateMap at a robot pose; most of them lie on TenByTen, the 10 x 10 map of 1 m cells that
map_server serves them (costmap_2d/test/TenByTen.pgm and .yaml). `Layers` does the same with our
Costmap: it never rolls (updateMap with a fixed window), and each update runs the obstacle
layer's steps in updateBounds' order: every observation's ray cleared, then every point marked,
then the footprint freed.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from pytest_lasertest.inputs.errors import Location
from pytest_lasertest.inputs.node import SpecNode
from pytest_lasertest.model.geometry import FloatArray
from pytest_lasertest.model.occupancy import OccupancyGrid
from pytest_lasertest.nav.move_base.cost_values import Grid
from pytest_lasertest.nav.move_base.costmap import Costmap, CostmapSettings
from pytest_lasertest.nav.move_base.static_layer import StaticLayerSettings
from pytest_lasertest.pairsfile.maps import read_map

# TenByTen.pgm's grey levels, its top row first: 0x1a, 0x33 and 0x00 are occupied (20 cells),
# 0xb3 lies between the thresholds (2 unknown cells), 0xff is free.
TEN_BY_TEN_PIXELS = (
    "ff ff ff ff ff ff ff ff ff ff",
    "ff ff ff ff ff ff ff ff ff ff",
    "ff ff ff ff ff ff ff 1a 1a 1a",
    "ff ff ff ff 33 ff ff 1a 1a 1a",
    "ff ff ff ff 33 ff ff 1a 1a 1a",
    "b3 b3 ff ff ff ff ff ff ff ff",
    "ff ff ff ff ff ff ff ff ff ff",
    "ff ff ff 1a 1a 1a ff ff ff ff",
    "ff ff ff ff ff ff ff 00 00 00",
    "ff ff ff ff ff ff ff 00 00 00",
)
TEN_BY_TEN_YAML = """\
image: TenByTen.pgm
resolution: 1.0
origin: [0,0,0]
negate: 0
occupied_thresh: 0.65
free_thresh: 0.196
"""
# addObservation's ranges: "obstacle range = raytrace range = 100.0".
OBSERVATION_RANGE = 100.0  # m


def ten_by_ten(directory: Path) -> OccupancyGrid:
    """TenByTen as map_server publishes it, read by our map reader from `directory`."""
    pixels = bytes.fromhex(" ".join(TEN_BY_TEN_PIXELS))
    (directory / "TenByTen.pgm").write_bytes(b"P5\n10 10\n255\n" + pixels)
    (directory / "TenByTen.yaml").write_text(TEN_BY_TEN_YAML)
    return read_map(SpecNode("TenByTen.yaml", Location(directory / "world.yaml", 1), "map"))


def rectangle(length: float, width: float) -> FloatArray:
    """inflation_tests' setRadii footprint: x within +-width, y within +-length (m),
    counter-clockwise (setRadii lists it clockwise; only the polygon matters)."""
    return np.array([[width, -length], [width, length], [-width, length], [-width, -length]])


# A footprint for the tests whose LayeredCostmap has none: its clearing is turned off instead,
# as an empty footprint frees no cell (convexFillCells needs three corners).
NO_FOOTPRINT = rectangle(0.1, 0.1)


@dataclass
class Layers:
    """A LayeredCostmap of a fixed window from (0, 0): a static layer if given a map, our
    obstacle layer fed static observations, and inflation (read it through `costs`)."""

    costmap: Costmap
    # (point, origin), each (x, y) m: addStaticObservation keeps them for every update.
    observations: list[tuple[tuple[float, float], tuple[float, float]]] = field(
        default_factory=list
    )

    @classmethod
    def of(
        cls,
        cells: int,
        footprint: FloatArray | None = None,
        grid: OccupancyGrid | None = None,
        settings: CostmapSettings | None = None,
    ) -> Layers:
        """`cells` x `cells` cells of 1 m from (0, 0), with `footprint` (none: no footprint
        clearing), the map `grid` under a static layer with ROS 1's defaults, and the rest of
        `settings` (our defaults if none): inflation and track_unknown_space."""
        costmap_settings = dataclasses.replace(
            settings or CostmapSettings(),
            size=float(cells),
            resolution=1.0,
            obstacle_range=OBSERVATION_RANGE,
            raytrace_range=OBSERVATION_RANGE,
            footprint_clearing=footprint is not None,
        )
        costmap = Costmap(costmap_settings, NO_FOOTPRINT if footprint is None else footprint)
        if grid is not None:
            costmap.receive_map(grid, StaticLayerSettings())
        return cls(costmap)

    def observe(self, x: float, y: float, origin: tuple[float, float] = (0.0, 0.0)) -> None:
        """addObservation: one point seen from `origin` (m), marked and cleared."""
        self.observations.append(((x, y), origin))

    def update_map(self, robot: tuple[float, float, float] = (0.0, 0.0, 0.0)) -> None:
        """updateMap at the robot pose [x, y, yaw] (m, m, rad): the window stays put."""
        costmap = self.costmap
        for point, origin in self.observations:
            costmap._clear(origin, np.array([point]))
        for point, origin in self.observations:
            costmap._mark(origin, np.array([point]))
        if costmap.settings.footprint_clearing:
            costmap._free_footprint(robot)

    def costs(self) -> Grid:
        """The master grid: the layers combined and inflated, indexed [y, x]."""
        return self.costmap.costs()

    def combined(self) -> Grid:
        """The master grid of a LayeredCostmap without an inflation layer."""
        return self.costmap.combined()


def count(grid: Grid, value: int) -> int:
    """testing_helper's countValues: how many cells hold `value`."""
    return int(np.count_nonzero(grid == value))
