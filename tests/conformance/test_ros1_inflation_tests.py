"""ROS 1 costmap_2d's inflation layer tests (costmap_2d/test/inflation_tests.cpp), rebuilt on our
Costmap's inflation (pytest_lasertest/nav/move_base/costmap.py: InflationCost, costs) through
tests/helpers/ros1_costmap.py: single lethal points and TenByTen's walls inflated around a
rectangular footprint, cost_scaling_factor 1 as inflation_tests.launch sets it.

Every test of the file is ported. Where the robot stands at (0, 0), its footprint reaching off
the map, neither costmap frees a cell under it (Costmap2D::setConvexPolygonCost gives up as soon
as a corner lies off the map, costmap_2d/src/costmap_2d.cpp:324).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from pytest_lasertest.model.geometry import FloatArray
from pytest_lasertest.model.occupancy import OccupancyGrid
from pytest_lasertest.nav.move_base.cost_values import FREE, INSCRIBED, LETHAL, UNKNOWN, Grid
from pytest_lasertest.nav.move_base.costmap import CostmapSettings
from tests.helpers.ros1_costmap import Layers, count, rectangle, ten_by_ten
from tests.helpers.upstream import NAVIGATION_NOETIC, Source

INFLATION = Source(
    "ROS 1 costmap_2d: inflation", NAVIGATION_NOETIC, "costmap_2d/test/inflation_tests.cpp"
)
COST_SCALING_FACTOR = 1.0  # 1/m, inflation_tests.launch's inflation/cost_scaling_factor


def inflated(
    footprint: FloatArray,
    inflation_radius: float,
    cells: int = 10,
    grid: OccupancyGrid | None = None,
) -> Layers:
    """setRadii's LayeredCostmap: an obstacle layer (over a static one if given a map) and an
    inflation layer out to `inflation_radius` m, the footprint `footprint`, 1 m cells."""
    settings = CostmapSettings(
        inflation_radius=inflation_radius, cost_scaling_factor=COST_SCALING_FACTOR
    )
    return Layers.of(cells, footprint, grid, settings)


def compute_cost(distance: float, inscribed: float) -> int:
    """InflationLayer::computeCost for a distance in 1 m cells: the expected cost."""
    if distance == 0.0:
        return LETHAL
    if distance <= inscribed:
        return INSCRIBED
    return int((INSCRIBED - 1) * math.exp(-COST_SCALING_FACTOR * (distance - inscribed)))


@pytest.fixture(scope="module")
def ten(tmp_path_factory: pytest.TempPathFactory) -> OccupancyGrid:
    return ten_by_ten(tmp_path_factory.mktemp("ten_by_ten"))


def adjacent() -> Grid:
    """testAdjacentToObstacleCanStillMove's costs: inscribed radius 2.1 m, inflation radius
    4.1 m, one obstacle at (0, 0), the robot there too."""
    layers = inflated(rectangle(2.1, 2.3), 4.1)
    layers.observe(0.0, 0.0)
    layers.update_map()
    return layers.costs()


@INFLATION.test("costmap.testAdjacentToObstacleCanStillMove", assertions=4)
def test_an_obstacle_at_the_robot_stays_lethal_and_inflates_its_inscribed_neighbours() -> None:
    costs = adjacent()
    assert costs[0, 0] == LETHAL
    assert costs[0, 1] == INSCRIBED
    assert costs[0, 2] == INSCRIBED
    assert costs[1, 1] == INSCRIBED


@INFLATION.test("costmap.testAdjacentToObstacleCanStillMove", assertions=2)
def test_cells_beyond_the_inscribed_radius_of_an_adjacent_obstacle_cost_less_than_inscribed() -> (
    None
):
    costs = adjacent()
    assert costs[0, 3] < INSCRIBED
    assert costs[1, 2] < INSCRIBED


@INFLATION.test("costmap.testInflationShouldNotCreateUnknowns", assertions=1)
def test_inflation_creates_no_unknown_cell() -> None:
    assert count(adjacent(), UNKNOWN) == 0


@INFLATION.test("costmap.testCostFunctionCorrectness", assertions=9)
def test_costs_are_inscribed_within_the_inscribed_radius_and_fall_off_beyond() -> None:
    # 100 x 100 cells, inscribed radius 5 m, inflation radius 10.5 m, one obstacle at (50, 50).
    layers = inflated(rectangle(5.0, 6.25), 10.5, cells=100)
    layers.observe(50.0, 50.0)
    layers.update_map()
    costs = layers.costs()
    for i in range(math.ceil(5.0) + 1):
        assert costs[50, 50 + i] >= INSCRIBED  # right
        assert costs[50, 50 - i] >= INSCRIBED  # left
        assert costs[50 + i, 50] >= INSCRIBED  # down, upstream's y growing
        assert costs[50 - i, 50] >= INSCRIBED  # up
    # Out to the inflation radius rounded up to whole cells, 11.
    for i in range(math.ceil(5.0) + 1, math.ceil(10.5) + 1):
        assert costs[50, 50 + i] == compute_cost(float(i), 5.0)


@INFLATION.test("costmap.testInflationOrderCorrectness", assertions=1)
def test_every_cell_around_two_diagonal_obstacles_costs_at_least_its_distance_cost() -> None:
    inflation_radius = 4.1  # m
    layers = inflated(rectangle(2.1, 2.3), inflation_radius)
    layers.observe(4.0, 4.0)
    layers.observe(5.0, 5.0)
    layers.update_map()
    costs = layers.costs()
    for source in ((4, 4), (5, 5)):
        # validatePointInflation's walk: the cells within the inflation radius of the source,
        # and their 4-neighbours on the map, each checked against its distance to the source.
        for cell, distance in walked(source, inflation_radius, costs.shape[1]):
            assert costs[cell[1], cell[0]] >= compute_cost(distance, 2.1), cell


def walked(
    source: tuple[int, int], radius: float, cells: int
) -> list[tuple[tuple[int, int], float]]:
    """The cells (x, y) validatePointInflation visits from `source`, and their distances to it
    in cells."""
    x, y = np.meshgrid(np.arange(cells), np.arange(cells), indexing="xy")
    within = np.hypot(x - source[0], y - source[1]) <= radius
    visited = within.copy()
    visited[1:, :] |= within[:-1, :]
    visited[:-1, :] |= within[1:, :]
    visited[:, 1:] |= within[:, :-1]
    visited[:, :-1] |= within[:, 1:]
    rows, columns = np.nonzero(visited)
    return [
        ((int(c), int(r)), math.hypot(c - source[0], r - source[1]))
        for r, c in zip(rows, columns, strict=True)
    ]


def inflation_steps(ten: OccupancyGrid) -> list[Grid]:
    """testInflation's costs after each update: TenByTen's walls alone, then with obstacles at
    (0, 0), (2, 0), (1, 9) and (0, 9) added one by one; footprint +-1 m, inflation radius 1 m."""
    layers = inflated(rectangle(1.0, 1.0), 1.0, grid=ten)
    layers.update_map()
    steps = [layers.costs()]
    for x, y in ((0.0, 0.0), (2.0, 0.0), (1.0, 9.0), (0.0, 9.0)):
        layers.observe(x, y)
        layers.update_map()
        steps.append(layers.costs())
    return steps


def marked(costs: Grid) -> int:
    """How many cells are lethal or inscribed."""
    return count(costs, LETHAL) + count(costs, INSCRIBED)


@INFLATION.test("costmap.testInflation", assertions=2)
def test_the_maps_walls_alone_make_20_lethal_and_28_inscribed_cells(ten: OccupancyGrid) -> None:
    walls = inflation_steps(ten)[0]
    assert count(walls, LETHAL) == 20
    assert count(walls, INSCRIBED) == 28


@INFLATION.test("costmap.testInflation", assertions=2)
def test_obstacles_at_the_robot_and_two_cells_on_add_their_cells_and_neighbours(
    ten: OccupancyGrid,
) -> None:
    steps = inflation_steps(ten)
    assert marked(steps[1]) == 51  # (0, 0) and its 2 neighbours on the map
    assert marked(steps[2]) == 54  # (2, 0) and 2 neighbours not yet marked


@INFLATION.test("costmap.testInflation", assertions=4)
def test_an_obstacle_inflates_its_neighbours_and_an_obstacle_overwrites_inflation(
    ten: OccupancyGrid,
) -> None:
    steps = inflation_steps(ten)
    assert steps[3][9, 1] == LETHAL
    assert steps[3][9, 0] == INSCRIBED
    assert steps[3][9, 2] == INSCRIBED
    assert steps[4][9, 0] == LETHAL


@INFLATION.test("costmap.testInflation2", assertions=2)
def test_an_l_shaped_obstacle_inflates_without_making_inflated_cells_lethal(
    ten: OccupancyGrid,
) -> None:
    layers = inflated(rectangle(1.0, 1.0), 1.0, grid=ten)
    for x, y in ((1.0, 1.0), (2.0, 1.0), (2.0, 2.0)):
        layers.observe(x, y)
    layers.update_map()
    costs = layers.costs()
    assert costs[3, 2] == INSCRIBED
    assert costs[3, 3] == INSCRIBED


@INFLATION.test("costmap.testInflation3", assertions=8)
def test_one_obstacle_in_an_empty_map_inflates_29_cells_and_again_the_same() -> None:
    # Inscribed radius 1 m, inflation radius 3 m.
    layers = inflated(rectangle(1.0, 1.75), 3.0)
    empty = layers.costs()
    assert count(empty, LETHAL) == 0
    assert count(empty, INSCRIBED) == 0
    layers.observe(5.0, 5.0)
    for _ in range(2):  # updating again changes nothing
        layers.update_map()
        costs = layers.costs()
        assert int(np.count_nonzero(costs != FREE)) == 29
        assert count(costs, LETHAL) == 1
        assert count(costs, INSCRIBED) == 4
