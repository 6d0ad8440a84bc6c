"""nav_2d_utils' tests of adjustPlanResolution (nav_2d_utils/test/path_ops_test.cpp), rebuilt on
our `dwb_critics.adjust_plan_resolution`, which the MapGrid critics run on the plan with the
costmap's resolution: the upstream resolution argument is a grid of that cell size."""

from __future__ import annotations

import math

import numpy as np

from pytest_lasertest.nav.nav2.dwb_critics import adjust_plan_resolution
from pytest_lasertest.nav.nav2.mppi import CostGrid
from tests.helpers.upstream import NAVIGATION2_HUMBLE, Source

PATH_OPS = Source(
    "Nav2 DWB: path utilities",
    NAVIGATION2_HUMBLE,
    "nav2_dwb_controller/nav_2d_utils/test/path_ops_test.cpp",
)


def cells_of(resolution: float) -> CostGrid:
    """A grid whose cells are `resolution` wide (m); only their size is read."""
    return CostGrid(np.zeros((1, 1), dtype=np.uint8), (0.0, 0.0), resolution, False)


@PATH_OPS.test("path_ops_test.AdjustResolutionEmpty", assertions=1)
def test_an_empty_plan_stays_empty() -> None:
    assert len(adjust_plan_resolution(np.zeros((0, 2)), cells_of(2.0))) == 0


@PATH_OPS.test("path_ops_test.AdjustResolutionSimple", assertions=2)
def test_a_long_gap_is_filled_with_evenly_spaced_points() -> None:
    resolution = 20.0  # m
    plan = adjust_plan_resolution(np.array([[0.0, 0.0], [100.0, 0.0]]), cells_of(resolution))
    length = 100.0  # m
    points = math.ceil(length / (2 * resolution))
    assert len(plan) == points
    gaps = np.hypot(*np.diff(plan, axis=0).T)  # m
    assert (gaps <= length / (points - 1)).all()
