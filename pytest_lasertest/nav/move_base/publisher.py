"""A costmap as costmap_2d's Costmap2DPublisher sends it: nav_msgs/OccupancyGrid, each cost
translated to 0-100 as RViz and Foxglove colour it.

ros-planning/navigation noetic-devel 9ad644198e132d0e950579a3bc72c29da46e60b0,
costmap_2d/src/costmap_2d_publisher.cpp: the cost translation table (0 free, 253 inscribed to
99, 254 lethal to 100, 255 unknown to -1, 1-252 scaled to 1-98 with integer division) and
prepareGrid, whose origin is the lower left corner of cell (0, 0). ros-navigation/navigation2
0285d20e10ffaa6630ced4f8574902a97e17d84a, nav2_costmap_2d/src/costmap_2d_publisher.cpp, keeps the
same table and origin.
"""

from __future__ import annotations

import numpy as np

from pytest_lasertest.model.occupancy import OccupancyGrid
from pytest_lasertest.nav.move_base.cost_values import FREE, INSCRIBED, LETHAL, UNKNOWN
from pytest_lasertest.nav.move_base.costmap import Costmap


def _translation() -> np.ndarray:
    """The table (256,) int8 from a cost to the grid value it is published as."""
    table = np.zeros(256, dtype=np.int8)
    regular = np.arange(1, INSCRIBED)
    table[regular] = 1 + (97 * (regular - 1)) // 251
    table[FREE], table[INSCRIBED], table[LETHAL], table[UNKNOWN] = 0, 99, 100, -1
    return table


COST_TRANSLATION = _translation()


def published(costmap: Costmap) -> OccupancyGrid:
    """The costmap's inflated costs over its whole window, as its publisher sends them."""
    return OccupancyGrid(
        costmap.settings.resolution, costmap.origin, COST_TRANSLATION[costmap.costs()]
    )
