"""Scans fed to a costmap, and the costs read back."""

from __future__ import annotations

import math

import numpy as np

from pytest_lasertest.model.sensor import LaserProfile
from pytest_lasertest.nav.move_base.costmap import Costmap
from pytest_lasertest.nav.protocol import LaserScan
from tests.helpers.model import profile

# Three beams: -90, 0 and +90 degrees, from a laser at the base origin.
THREE_BEAMS = profile(samples=3, min_angle=-math.pi / 2, max_angle=math.pi / 2, range_max=5.0)


def scan(ahead: float, scanner: LaserProfile = THREE_BEAMS) -> LaserScan:
    """A scan reading `ahead` m straight ahead and nothing either side."""
    ranges = np.full(scanner.beam_count, np.inf)
    ranges[scanner.beam_count // 2] = ahead
    return LaserScan(0.0, ranges, scanner.to_laserscan_meta(), scanner.pose)


def cost_at(costmap: Costmap, x: float, y: float, grid: np.ndarray | None = None) -> int:
    """The cost of the cell at (x, y) m, in the costmap's grid or in `grid`."""
    cell_x, cell_y, inside = costmap.cell_of(np.array([[x, y]]))
    assert inside[0]
    grid = costmap.grid if grid is None else grid
    return int(grid[cell_y[0], cell_x[0]])
