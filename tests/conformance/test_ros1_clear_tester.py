"""ROS 1 clear_costmap_recovery's tests (clear_costmap_recovery/test/clear_tester.cpp with
params.yaml), on our recovery (pytest_lasertest/nav/move_base/recovery.py: ClearCostmap) over
our Costmap through tests/helpers/ros1_costmap.py: a global costmap of TenByTen's static layer,
an obstacle layer tracking unknown space with two points 5 m from the robot, and inflation
around a 0.5 m robot_radius; a local costmap with nothing in it. The recovery forgets the
obstacle layer's cells outside a square of reset_distance around the robot at (0, 0).

Left out as not applicable: clearNoLayersTest, clearBothTest and clearBothTest2, which choose the
layers to clear (layer_names: none, or the static layer too); ours clears the obstacle layer
alone, as layer_names' default ["obstacles"] does, and has no choice of layers.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from pytest_lasertest.model.geometry import FloatArray
from pytest_lasertest.model.occupancy import OccupancyGrid
from pytest_lasertest.nav.move_base.cost_values import LETHAL
from pytest_lasertest.nav.move_base.costmap import Costmap, CostmapSettings
from pytest_lasertest.nav.move_base.recovery import ClearCostmap
from tests.helpers.ros1_costmap import Layers, count, ten_by_ten
from tests.helpers.upstream import NAVIGATION_NOETIC, Source

CLEAR = Source(
    "ROS 1 clear_costmap_recovery",
    NAVIGATION_NOETIC,
    "clear_costmap_recovery/test/clear_tester.cpp",
)
ROBOT = (0.0, 0.0, 0.0)  # the static transform map -> base_link of clear_tests.launch


def radius_footprint(radius: float) -> FloatArray:
    """costmap_2d's makeFootprintFromRadius: 16 corners `radius` m from the origin.

    params.yaml sets no footprint_padding. costmap_2d's default pads by 0.01 m
    (cfg/Costmap2D.cfg:21); a robot file that omits it is not padded (pairsfile/robot.py:172),
    and that is what our costmap gets. No count here depends on it: the footprint only
    inflates, and frees no lethal cell."""
    angles = np.arange(16) * 2.0 * math.pi / 16
    corners = [(radius * math.cos(a), radius * math.sin(a)) for a in angles]
    return np.array(corners)


@pytest.fixture(scope="module")
def ten(tmp_path_factory: pytest.TempPathFactory) -> OccupancyGrid:
    return ten_by_ten(tmp_path_factory.mktemp("ten_by_ten"))


def lethal_after_clearing(ten: OccupancyGrid, reset_distance: float) -> tuple[int, int]:
    """testCountLethal with the obstacle layer cleared: the lethal cells of the global and of
    the local costmap after the recovery (m) and an update."""
    footprint = radius_footprint(0.5)
    # params.yaml: obstacles.track_unknown_space true; inflation keeps its defaults.
    tracking = CostmapSettings(track_unknown_space=True)
    global_layers = Layers.of(10, footprint, ten, tracking)
    global_layers.observe(5.0, 0.0)
    global_layers.observe(0.0, 5.0)
    global_layers.update_map(ROBOT)
    local = Costmap(CostmapSettings(), footprint)  # `plugins: []`: it never holds anything
    global_layers.observations.clear()  # clearStaticObservations
    for costmap in (global_layers.costmap, local):  # affected_maps' default: both
        assert ClearCostmap("clear", costmap, reset_distance).step(ROBOT, 0.0) is None
    global_layers.update_map(ROBOT)
    return count(global_layers.costs(), LETHAL), count(local.costs(), LETHAL)


@CLEAR.test("ClearTester.basicTest", assertions=2)
def test_clearing_beyond_3_m_forgets_the_points_5_m_away_and_keeps_the_map(
    ten: OccupancyGrid,
) -> None:
    global_lethal, local_lethal = lethal_after_clearing(ten, 3.0)
    assert global_lethal == 20
    assert local_lethal == 0


@CLEAR.test("ClearTester.bigRadiusTest", assertions=2)
def test_clearing_beyond_20_m_keeps_the_points_5_m_away(ten: OccupancyGrid) -> None:
    global_lethal, local_lethal = lethal_after_clearing(ten, 20.0)
    assert global_lethal == 22
    assert local_lethal == 0
