"""nav2_costmap_2d's inflation layer tests (test/integration/inflation_tests.cpp), rebuilt on our
Nav2 costmap (`Nav2Costmap`): points observed by its obstacle layer (`cleared`, `marked`), the
TenByTen map under it as a static layer, and `costs()` inflating them around the footprint.

Not applicable: testDynParamsSet, which sets the layer's parameters through the parameter
service, something we do not imitate.
"""

from __future__ import annotations

import numpy as np

from pytest_lasertest.model.occupancy import FREE as MAP_FREE
from pytest_lasertest.model.occupancy import OCCUPIED, UNKNOWN, OccupancyGrid
from pytest_lasertest.nav.move_base.cost_values import FREE, INSCRIBED, LETHAL
from pytest_lasertest.nav.move_base.static_layer import StaticLayerSettings
from pytest_lasertest.nav.nav2.costmap import Nav2Costmap
from tests.helpers.nav2_costmap import (
    Observation,
    compute_cost,
    costmap,
    count,
    rectangle,
    update,
)
from tests.helpers.upstream import NAVIGATION2_JAZZY, NotPorted, Source

INFLATION = Source(
    "Nav2 costmap: inflation layer",
    NAVIGATION2_JAZZY,
    "nav2_costmap_2d/test/integration/inflation_tests.cpp",
)
NOT_PORTED = (
    NotPorted(
        INFLATION,
        "TestNode.testInflationInUnkown",
        1,
        "inflate_unknown is not imitated: our inflation writes over an unknown cell only from "
        "the inscribed cost up, as with Nav2's default false (costmap_params.py reads "
        "inflation_radius and cost_scaling_factor only)",
    ),
    NotPorted(
        INFLATION,
        "TestNode.testInflationAroundUnkown",
        1,
        "inflate_around_unknown is not imitated: our inflation starts from lethal cells only, "
        "as with Nav2's default false",
    ),
)
# The footprint most tests set (setRadii(2.1, 2.3)): inscribed radius 2.1 m.
NARROW = rectangle(2.1, 2.3)
# test/map/TenByTen.pgm as map_server publishes it (trinary, occupied_thresh 0.65,
# free_thresh 0.196), its top row first; '?' is unknown.
TEN_BY_TEN = (
    "..........",
    "..........",
    ".......###",
    "....#..###",
    "....#..###",
    "??........",
    "..........",
    "...###....",
    ".......###",
    ".......###",
)


def ten_by_ten() -> OccupancyGrid:
    """The TenByTen map: 1 m cells from (0, 0), its bottom row (the image's last) row 0."""
    values = {".": MAP_FREE, "#": OCCUPIED, "?": UNKNOWN}
    data = np.array([[values[c] for c in row] for row in reversed(TEN_BY_TEN)], dtype=np.int8)
    return OccupancyGrid(1.0, (0.0, 0.0), data)


def with_map(inflation_radius: float) -> Nav2Costmap:
    """testInflation's layers: the static layer's TenByTen map (which sizes the costmap), the
    obstacle layer, and inflation with cost_scaling_factor 1 around a 2 m square footprint."""
    layers = costmap(10, 1.0, rectangle(1.0, 1.0), inflation_radius, 1.0)
    # The test node declares track_unknown_space false: the map's unknown cells are free.
    layers.receive_map(ten_by_ten(), StaticLayerSettings.nav2(track_unknown_space=False))
    return layers


def inflated_or_lethal(layers: Nav2Costmap) -> int:
    """How many cells are lethal or inscribed once inflated."""
    costs = layers.costs()
    return count(costs, LETHAL) + count(costs, INSCRIBED)


@INFLATION.test("TestNode.testAdjacentToObstacleCanStillMove", assertions=6)
def test_a_cell_beyond_the_inscribed_radius_of_an_obstacle_costs_less_than_inscribed() -> None:
    layers = costmap(10, 1.0, NARROW, inflation_radius=4.1, cost_scaling_factor=1.0)
    update(layers, [Observation(0.0, 0.0)])
    costs = layers.costs()  # [y, x]
    assert costs[0, 0] == LETHAL
    assert costs[0, 1] == INSCRIBED
    assert costs[0, 2] == INSCRIBED
    assert costs[0, 3] < INSCRIBED  # 3 m > 2.1 m
    assert costs[1, 2] < INSCRIBED  # sqrt(5) m > 2.1 m
    assert costs[1, 1] == INSCRIBED


@INFLATION.test("TestNode.testInflationShouldNotCreateUnknowns", assertions=1)
def test_inflation_makes_no_cell_unknown() -> None:
    layers = costmap(10, 1.0, NARROW, inflation_radius=4.1, cost_scaling_factor=1.0)
    update(layers, [Observation(0.0, 0.0)])
    assert count(layers.costs(), 255) == 0


@INFLATION.test("TestNode.testCostFunctionCorrectness", assertions=9)
def test_costs_fall_off_by_the_cost_function_out_to_the_inflation_radius() -> None:
    # Inscribed radius 5 m (setRadii(5.0, 6.25)), inflation radius 10.5 m, 1 m cells.
    layers = costmap(100, 1.0, rectangle(5.0, 6.25), inflation_radius=10.5, cost_scaling_factor=1.0)
    update(layers, [Observation(50.0, 50.0)])
    costs = layers.costs()  # [y, x]
    for i in range(6):
        # Upstream's eight statements check each direction twice over.
        assert costs[50, 50 + i] >= INSCRIBED
        assert costs[50, 50 - i] >= INSCRIBED
        assert costs[50 + i, 50] >= INSCRIBED
        assert costs[50 - i, 50] >= INSCRIBED
    for i in range(6, 12):
        assert costs[50, 50 + i] == compute_cost(i, 1.0, 5.0, 1.0)


@INFLATION.test("TestNode.testInflationOrderCorrectness", assertions=1)
def test_two_diagonal_obstacles_each_inflate_their_cells_at_least_by_the_cost_function() -> None:
    layers = costmap(10, 1.0, NARROW, inflation_radius=4.1, cost_scaling_factor=1.0)
    update(layers, [Observation(4.0, 4.0), Observation(5.0, 5.0)])
    costs = layers.costs()
    for source in ((4, 4), (5, 5)):
        for x, y in visited(source, 4.1, 10):
            distance = float(np.hypot(x - source[0], y - source[1]))
            assert costs[y, x] >= compute_cost(distance, 1.0, 2.1, 1.0), (source, x, y)


def visited(source: tuple[int, int], radius: float, cells: int) -> set[tuple[int, int]]:
    """The cells validatePointInflation checks from `source`: its walk from cell to
    neighbouring cell goes on from each cell within `radius` cells of the source, so it checks
    those and their four neighbours on the map (the cells within the radius are connected: each
    has a neighbour nearer the source)."""
    sx, sy = source
    near = [
        (x, y)
        for x in range(cells)
        for y in range(cells)
        if (x - sx) ** 2 + (y - sy) ** 2 <= radius**2
    ]
    steps = ((0, 0), (1, 0), (-1, 0), (0, 1), (0, -1))
    return {
        (x + dx, y + dy)
        for x, y in near
        for dx, dy in steps
        if 0 <= x + dx < cells and 0 <= y + dy < cells
    }


@INFLATION.test("TestNode.testInflation", assertions=8)
def test_map_and_observed_obstacles_inflate_their_neighbours_to_inscribed() -> None:
    layers = with_map(inflation_radius=1.0)
    costs = layers.costs()
    assert count(costs, LETHAL) == 20
    assert count(costs, INSCRIBED) == 28
    seen = [Observation(0.0, 0.0)]
    update(layers, seen)
    # It and its two neighbours on the map.
    assert inflated_or_lethal(layers) == 51
    seen.append(Observation(2.0, 0.0))
    update(layers, seen)
    # It and two more neighbours: the ray to it frees (0, 0), which the first one marks again.
    assert inflated_or_lethal(layers) == 54
    seen.append(Observation(1.0, 9.0))
    update(layers, seen)
    costs = layers.costs()  # [y, x]
    assert costs[9, 1] == LETHAL
    assert costs[9, 0] == INSCRIBED
    assert costs[9, 2] == INSCRIBED
    seen.append(Observation(0.0, 9.0))
    update(layers, seen)
    assert layers.costs()[9, 0] == LETHAL


@INFLATION.test("TestNode.testInflation2", assertions=2)
def test_an_l_shaped_obstacle_and_the_map_inflate_the_cells_beside_them() -> None:
    layers = with_map(inflation_radius=1.0)
    update(layers, [Observation(1.0, 1.0), Observation(2.0, 1.0), Observation(2.0, 2.0)])
    costs = layers.costs()  # [y, x]
    assert costs[3, 2] == INSCRIBED
    assert costs[3, 3] == INSCRIBED


@INFLATION.test("TestNode.testInflation3", assertions=8)
def test_one_obstacle_in_an_empty_map_raises_the_29_cells_within_the_radius() -> None:
    # Inscribed radius 1 m (setRadii(1, 1.75)), inflation radius 3 m.
    layers = costmap(10, 1.0, rectangle(1.0, 1.75), inflation_radius=3.0, cost_scaling_factor=1.0)
    costs = layers.costs()
    assert count(costs, LETHAL) == 0
    assert count(costs, INSCRIBED) == 0
    seen = [Observation(5.0, 5.0)]
    for _ in range(2):  # a second update changes nothing
        update(layers, seen)
        costs = layers.costs()
        assert costs.size - count(costs, FREE) == 29
        assert count(costs, LETHAL) == 1
        assert count(costs, INSCRIBED) == 4
