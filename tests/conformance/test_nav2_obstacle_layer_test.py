"""nav2_costmap_2d's obstacle layer unit tests (test/unit/obstacle_layer_test.cpp), rebuilt on
our Nav2 costmap's obstacle layer (`cleared`, `marked`, with Jazzy's marking rule): one point
seen from a sensor in a fixed 20 x 20 costmap of 0.1 m cells (0.05 m in the fine one), the
layer's own grid read back after its update (updateBounds, which clears, then marks).
"""

from __future__ import annotations

import numpy as np

from pytest_lasertest.nav.move_base.cost_values import FREE, LETHAL
from pytest_lasertest.nav.nav2.costmap import Nav2Costmap
from tests.helpers.nav2_costmap import Observation, costmap, count, update, window
from tests.helpers.upstream import NAVIGATION2_JAZZY, Source

OBSTACLE = Source(
    "Nav2 costmap: obstacle layer",
    NAVIGATION2_JAZZY,
    "nav2_costmap_2d/test/unit/obstacle_layer_test.cpp",
)


def layer(resolution: float = 0.1) -> Nav2Costmap:
    """ObstacleLayerTest's layered costmap: 20 x 20 cells from (0, 0)."""
    return costmap(20, resolution)


def cost_at(layers: Nav2Costmap, x: float, y: float) -> int:
    """The layer's cost of the cell holding (x, y) m (Costmap2D::worldToMap, then getCost)."""
    cell_x, cell_y, inside = window(layers).cells_of(np.array([x]), np.array([y]))
    assert inside[0]
    return int(layers.grid[cell_y[0], cell_x[0]])


def seen_alone(seen: Observation, resolution: float = 0.1) -> Nav2Costmap:
    """A fresh layer after one update with `seen`."""
    layers = layer(resolution)
    update(layers, [seen])
    return layers


@OBSTACLE.test("ObstacleLayerTest.testPointWithinCellMaxRange", assertions=1)
def test_a_point_within_the_obstacle_max_range_marks_its_cell() -> None:
    layers = seen_alone(Observation(0.55, 0.0, obstacle_max_range=1.0))
    assert cost_at(layers, 0.55, 0.0) == LETHAL


@OBSTACLE.test("ObstacleLayerTest.testPointBeyondCellMaxRange", assertions=1)
def test_a_point_beyond_the_obstacle_max_range_does_not_mark() -> None:
    layers = seen_alone(Observation(1.55, 0.0, obstacle_max_range=1.0))
    assert cost_at(layers, 1.55, 0.0) != LETHAL


@OBSTACLE.test("ObstacleLayerTest.testPointWithinCellMinRange", assertions=1)
def test_a_point_nearer_than_the_obstacle_min_range_does_not_mark() -> None:
    seen = Observation(0.35, 0.0, obstacle_max_range=10.0, obstacle_min_range=0.5)
    assert cost_at(seen_alone(seen), 0.35, 0.0) != LETHAL


@OBSTACLE.test("ObstacleLayerTest.testDiagonalDistanceWithinRange", assertions=1)
def test_a_diagonal_point_within_the_obstacle_max_range_marks_its_cell() -> None:
    # 0.991 m away; its cell (7, 7) is 9.9 cells from the sensor's, within 10.
    layers = seen_alone(Observation(0.701, 0.701, obstacle_max_range=1.0))
    assert cost_at(layers, 0.701, 0.701) == LETHAL


@OBSTACLE.test(
    "ObstacleLayerTest.testPointBeyondObstacleMaxRangeNotMarkedWhenSameMapCell", assertions=1
)
def test_a_point_beyond_the_max_range_in_the_cell_of_one_within_it_does_not_mark() -> None:
    # 0.79 m and 0.72 m both lie in cell 7; the world distance decides.
    layers = seen_alone(Observation(0.79, 0.0, obstacle_max_range=0.72))
    assert cost_at(layers, 0.79, 0.0) != LETHAL


@OBSTACLE.test("ObstacleLayerTest.testDiagonalDistanceBeyondRange", assertions=1)
def test_a_diagonal_point_beyond_the_obstacle_max_range_does_not_mark() -> None:
    # 1.41 m away, 14 cells against 12.
    layers = seen_alone(Observation(1.0, 1.0, obstacle_max_range=1.2))
    assert cost_at(layers, 1.0, 1.0) != LETHAL


@OBSTACLE.test("ObstacleLayerTest.testPointAtCellMaxRangeBoundary", assertions=1)
def test_a_point_exactly_at_the_obstacle_max_range_marks_its_cell() -> None:
    layers = seen_alone(Observation(1.0, 0.0, obstacle_max_range=1.0))
    assert cost_at(layers, 1.0, 0.0) == LETHAL


@OBSTACLE.test("ObstacleLayerTest.testPointAtCellMinRangeBoundary", assertions=1)
def test_a_point_exactly_at_the_obstacle_min_range_marks_its_cell() -> None:
    seen = Observation(0.5, 0.0, obstacle_max_range=10.0, obstacle_min_range=0.5)
    assert cost_at(seen_alone(seen), 0.5, 0.0) == LETHAL


@OBSTACLE.test("ObstacleLayerFineResolutionTest.testDifferentResolution", assertions=1)
def test_a_point_marks_its_cell_of_a_finer_grid() -> None:
    layers = seen_alone(Observation(0.52, 0.28, obstacle_max_range=1.0), resolution=0.05)
    assert layers.grid[5, 10] == LETHAL  # cell (10, 5)


@OBSTACLE.test("ObstacleLayerTest.testOriginOffset", assertions=1)
def test_a_point_seen_from_a_sensor_off_the_origin_marks_its_cell() -> None:
    seen = Observation(1.75, 1.85, origin=(0.5, 1.5), obstacle_max_range=2.0)
    assert cost_at(seen_alone(seen), 1.75, 1.85) == LETHAL


@OBSTACLE.test("ObstacleLayerTest.testRaytraceClearsPathAndMarksEndpoint", assertions=2)
def test_a_ray_frees_the_cells_before_its_point_and_the_point_marks_its_own() -> None:
    layers = layer()
    layers.grid[0, 0:4] = LETHAL
    update(layers, [Observation(0.85, 0.0, raytrace_max_range=2.0, obstacle_max_range=2.0)])
    assert (layers.grid[0, 0:8] == FREE).all()  # cells 0 to 7, before the point's cell 8
    assert cost_at(layers, 0.85, 0.0) == LETHAL


@OBSTACLE.test("ObstacleLayerTest.testDiagonalRaytraceDoesNotClearEndpoint", assertions=2)
def test_a_diagonal_ray_frees_the_cells_on_it_and_its_point_stays_lethal() -> None:
    layers = layer()
    layers.grid[7, 7] = LETHAL  # the cell of (0.75, 0.75)
    layers.grid[4, 4] = LETHAL  # the cell of (0.45, 0.45), on the ray
    update(layers, [Observation(0.75, 0.75, raytrace_max_range=2.0)])
    assert cost_at(layers, 0.75, 0.75) == LETHAL
    assert cost_at(layers, 0.45, 0.45) == FREE


@OBSTACLE.test("ObstacleLayerTest.testClearDiagonalDistance", assertions=3)
def test_a_diagonal_ray_frees_cells_only_up_to_the_raytrace_max_range() -> None:
    layers = layer()
    layers.grid[:] = LETHAL
    # To (1.55, 1.55) m, cleared to 1 m: the diagonal's cells (0, 0) to (7, 7).
    update(layers, [Observation(1.55, 1.55, raytrace_max_range=1.0)])
    diagonal = np.arange(8)
    assert (layers.grid[diagonal, diagonal] == FREE).all()
    assert count(layers.grid, FREE) == 8
    assert count(layers.grid, LETHAL) == 20 * 20 - 8
