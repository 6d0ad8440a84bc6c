"""The setups of nav2_costmap_2d's layer tests (test/testing_helper.hpp at jazzy f4108e5b)
built on our Nav2 costmap: a fixed costmap of whole cells from (0, 0), observations of single
points added to its obstacle layer, the layer's update with them, the inflation layer's cost
function as upstream computes the costs it expects, and counts of the costs read back.

The conformance modules of the costmap's inflation and obstacle layers share it.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from pytest_lasertest.model.geometry import IntArray
from pytest_lasertest.nav.move_base.cost_values import FREE, INSCRIBED, LETHAL, Grid
from pytest_lasertest.nav.move_base.costmap import CostmapSettings
from pytest_lasertest.nav.nav2.costmap import Nav2Costmap
from pytest_lasertest.nav.nav2.obstacle_layer import ObservationSource, Window, cleared, marked
from pytest_lasertest.nav.nav2.settings import Nav2Settings

# The footprint of a layered costmap no test sets: unused where no inflation layer reads it.
ANY_FOOTPRINT = ((0.1, 0.1), (-0.1, 0.1), (-0.1, -0.1), (0.1, -0.1))  # m


@dataclass(frozen=True)
class Observation:
    """One point seen from a sensor, as testing_helper.hpp's addObservation adds it to an
    obstacle layer (addStaticObservation): marking and clearing, and its ranges (m) with the
    helper's defaults, 100 m out and none in. Its height is left out: every upstream point
    this ports lies between the layer's min and max obstacle height (0 and 2 m)."""

    x: float  # m
    y: float  # m
    origin: tuple[float, float] = (0.0, 0.0)  # m, the sensor
    marking: bool = True
    clearing: bool = True
    raytrace_max_range: float = 100.0  # m
    raytrace_min_range: float = 0.0  # m
    obstacle_max_range: float = 100.0  # m
    obstacle_min_range: float = 0.0  # m

    def source(self) -> ObservationSource:
        """Our observation source with this observation's ranges."""
        return ObservationSource(
            obstacle_max_range=self.obstacle_max_range,
            obstacle_min_range=self.obstacle_min_range,
            raytrace_max_range=self.raytrace_max_range,
            raytrace_min_range=self.raytrace_min_range,
            marking=self.marking,
            clearing=self.clearing,
        )


def costmap(
    cells: int,
    resolution: float,
    footprint: tuple[tuple[float, float], ...] = ANY_FOOTPRINT,
    inflation_radius: float = 0.0,
    cost_scaling_factor: float = 0.0,
    track_unknown_space: bool = False,
) -> Nav2Costmap:
    """LayeredCostmap::resizeMap(cells, cells, resolution, 0, 0) with `footprint` (m), marking
    as Jazzy's obstacle layer does. No scan is given it, so its window stays where it was
    made: cell (0, 0)'s corner at the origin, as upstream's fixed (not rolling) costmaps."""
    settings = CostmapSettings(
        size=cells * resolution,
        resolution=resolution,
        inflation_radius=inflation_radius,
        cost_scaling_factor=cost_scaling_factor,
        track_unknown_space=track_unknown_space,
    )
    return Nav2Costmap(
        settings, np.array(footprint), ObservationSource(), Nav2Settings(release="jazzy").marking
    )


def window(costmap: Nav2Costmap) -> Window:
    """Where the costmap's cells lie, as the obstacle layer's functions take it."""
    cells, resolution = costmap.settings.cells, costmap.settings.resolution
    return Window(costmap.origin[0], costmap.origin[1], resolution, cells, cells)


def update(costmap: Nav2Costmap, observations: Sequence[Observation]) -> None:
    """ObstacleLayer::updateBounds with its static observations (each update takes them all
    again): every clearing observation's ray frees its cells, then every marking observation's
    point marks its cell, on the layer's own grid (`grid`). Footprint clearing is left out: the
    robot stands at (0, 0) in every test, where its footprint reaches below the map's origin, and
    setConvexPolygonCost then clears nothing (src/costmap_2d.cpp:399-411)."""
    area = window(costmap)
    for seen in observations:
        freed = cleared(area, seen.origin, np.array([[seen.x, seen.y]]), seen.source())
        _write(costmap, freed, FREE)
    for seen in observations:
        point = np.array([[seen.x, seen.y]])
        lethal = marked(area, seen.origin, point, seen.source(), costmap.marking)
        _write(costmap, lethal, LETHAL)


def _write(costmap: Nav2Costmap, cells: IntArray, cost: int) -> None:
    """Set the cells with flat indices x + y * size_x to `cost`, as Nav2Costmap does."""
    size = costmap.settings.cells
    costmap.grid[cells // size, cells % size] = cost


def compute_cost(
    distance: float, resolution: float, inscribed_radius: float, cost_scaling_factor: float
) -> int:
    """InflationLayer::computeCost (include/nav2_costmap_2d/inflation_layer.hpp at f4108e5b),
    the cost upstream's tests expect at `distance` cells from an obstacle."""
    if distance == 0.0:
        return LETHAL
    if distance * resolution <= inscribed_radius:
        return INSCRIBED
    factor = math.exp(-cost_scaling_factor * (distance * resolution - inscribed_radius))
    return int((INSCRIBED - 1) * factor)


def rectangle(length: float, width: float) -> tuple[tuple[float, float], ...]:
    """inflation_tests.cpp's setRadii: a footprint `width` m either side along x and `length` m
    either side along y, so its inscribed radius is the smaller."""
    return ((width, length), (width, -length), (-width, -length), (-width, length))


def count(grid: Grid, cost: int) -> int:
    """How many cells hold `cost` (testing_helper.hpp's countValues)."""
    return int(np.count_nonzero(grid == cost))
