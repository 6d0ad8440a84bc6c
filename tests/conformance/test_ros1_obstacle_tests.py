"""ROS 1 costmap_2d's obstacle layer tests (costmap_2d/test/obstacle_tests.cpp), rebuilt on our
Costmap (pytest_lasertest/nav/move_base/costmap.py) through tests/helpers/ros1_costmap.py: single
points marked lethal and the rays to them cleared, over TenByTen's static layer or an empty map,
never clearing what the map marks.

Left out as not applicable: testZThreshold, which drops a point above max_obstacle_height; our
costmap is planar (a 2D scanner's plane is handled in the simulation, not by a height filter).
"""

from __future__ import annotations

import pytest

from pytest_lasertest.model.occupancy import OccupancyGrid
from pytest_lasertest.nav.move_base.cost_values import FREE, LETHAL, UNKNOWN
from pytest_lasertest.nav.move_base.costmap import CostmapSettings
from tests.helpers.ros1_costmap import Layers, count, ten_by_ten
from tests.helpers.upstream import NAVIGATION_NOETIC, Source

OBSTACLE = Source(
    "ROS 1 costmap_2d: obstacle layer", NAVIGATION_NOETIC, "costmap_2d/test/obstacle_tests.cpp"
)
MAP_LETHAL = 20  # TenByTen's occupied cells


@pytest.fixture(scope="module")
def ten(tmp_path_factory: pytest.TempPathFactory) -> OccupancyGrid:
    return ten_by_ten(tmp_path_factory.mktemp("ten_by_ten"))


def on_the_map(grid: OccupancyGrid) -> Layers:
    """The tests' LayeredCostmap("frame", false, false) with a static and an obstacle layer."""
    return Layers.of(10, grid=grid)


@OBSTACLE.test("costmap.testRaytracing", assertions=1)
def test_a_point_at_the_sensor_origin_adds_one_lethal_cell_to_the_map(ten: OccupancyGrid) -> None:
    layers = on_the_map(ten)
    layers.observe(0.0, 0.0)
    layers.update_map()
    assert count(layers.combined(), LETHAL) == MAP_LETHAL + 1


@OBSTACLE.test("costmap.testRaytracing2", assertions=4)
def test_a_ray_across_the_map_clears_the_obstacle_layer_but_never_the_static_one(
    ten: OccupancyGrid,
) -> None:
    layers = on_the_map(ten)
    layers.update_map()
    before = count(layers.combined(), LETHAL)
    assert before == MAP_LETHAL
    # The ray from (0.5, 0.5) to (9.5, 9.5) m crosses the static block at (7, 7).
    layers.observe(9.5, 9.5, origin=(0.5, 0.5))
    layers.update_map()
    after = count(layers.combined(), LETHAL)
    assert after == before + 1
    # The diagonal marked in the obstacle layer's own grid is cleared again by the same ray.
    for i in range(10):
        layers.costmap.grid[i, i] = LETHAL
    layers.update_map()
    combined = layers.combined()
    assert count(combined, LETHAL) == after
    assert count(combined, FREE) == 79


@OBSTACLE.test("costmap.testWaveInterference", assertions=3)
def test_three_points_on_a_diagonal_leave_the_rest_of_an_unknown_map_unknown() -> None:
    layers = Layers.of(10, settings=CostmapSettings(track_unknown_space=True))
    for corner in (3.0, 5.0, 7.0):
        layers.observe(corner, corner)
    layers.update_map()
    combined = layers.combined()
    assert count(combined, LETHAL) == 3
    assert count(combined, UNKNOWN) == 92
    assert count(combined, FREE) == 5


@OBSTACLE.test("costmap.testDynamicObstacles", assertions=2)
def test_the_same_point_observed_three_times_adds_one_lethal_cell(ten: OccupancyGrid) -> None:
    layers = on_the_map(ten)
    for _ in range(3):
        layers.observe(0.0, 0.0)
    layers.update_map()
    assert count(layers.combined(), LETHAL) == MAP_LETHAL + 1
    # Upstream counts again "repeating the call"; updating again must change nothing either.
    layers.update_map()
    assert count(layers.combined(), LETHAL) == MAP_LETHAL + 1


@OBSTACLE.test("costmap.testMultipleAdditions", assertions=1)
def test_a_point_on_a_static_obstacle_adds_no_lethal_cell(ten: OccupancyGrid) -> None:
    layers = on_the_map(ten)
    layers.observe(9.5, 0.0)
    layers.update_map()
    assert count(layers.combined(), LETHAL) == MAP_LETHAL
