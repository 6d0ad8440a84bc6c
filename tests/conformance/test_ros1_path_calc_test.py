"""ROS 1 navfn's path tests (navfn/test/path_calc_test.cpp), on our global planner
(pytest_lasertest/nav/move_base/navfn.py: plan_path): a plan through a pinch point of the Willow
Garage costmap, and an easy one, must both be found.

Upstream copies the cost array of data/willow_costmap.pgm.gz (navfn/test/willow_costmap.pgm,
BSD, gzipped here) straight into NavFn: navfn's own costs, 50 for free space (COST_NEUTRAL), 253
for unknown space that may be crossed (COST_OBS - 1) and 254 for obstacles. The costmap that
NavfnROS::makePlan would turn into exactly those costs (NavFn::setCostmap with allow_unknown)
holds 0, 255 and 254, and that is what our planner is given. Upstream plans with no tolerance.

Each test's ASSERT_TRUE(nav != NULL), that the pgm file loaded, is not applicable: it checks the
test's own file reading, not the planner.
"""

from __future__ import annotations

import gzip
from pathlib import Path

import numpy as np
import pytest

from pytest_lasertest.nav.move_base.cost_values import FREE, LETHAL, UNKNOWN, Grid
from pytest_lasertest.nav.move_base.navfn import NavfnSettings, plan_path
from tests.helpers.upstream import NAVIGATION_NOETIC, Source

PATH_CALC = Source("ROS 1 NavFn", NAVIGATION_NOETIC, "navfn/test/path_calc_test.cpp")
WILLOW = Path(__file__).parent / "data" / "willow_costmap.pgm.gz"
# navfn's costs in the pgm, and the costmap costs NavFn::setCostmap turns into them.
NAVFN_FREE, NAVFN_UNKNOWN, NAVFN_OBSTACLE = 50, 253, 254
SETTINGS = NavfnSettings(allow_unknown=True, default_tolerance=0.0)
RESOLUTION = 0.05  # m per cell; with no tolerance it changes nothing


def read_pgm(data: bytes) -> np.ndarray:
    """A binary (P5) 8-bit pgm's grey levels, shape (rows, columns), its first row first."""
    magic, columns, rows, top = data.split(maxsplit=4)[:4]
    assert magic == b"P5"
    assert int(top) == 255
    # The pixels end the file; its header's last whitespace may look like a pixel.
    size = int(rows) * int(columns)
    return np.frombuffer(data[-size:], dtype=np.uint8).reshape(int(rows), int(columns))


@pytest.fixture(scope="module")
def willow() -> Grid:
    """The Willow Garage costmap's costs, indexed [y, x] as navfn indexes its array."""
    navfn = read_pgm(gzip.decompress(WILLOW.read_bytes()))
    assert set(np.unique(navfn).tolist()) == {NAVFN_FREE, NAVFN_UNKNOWN, NAVFN_OBSTACLE}
    costs: Grid = np.select(
        [navfn == NAVFN_FREE, navfn == NAVFN_UNKNOWN], [FREE, UNKNOWN], LETHAL
    ).astype(np.uint8)
    return costs


def plans(costs: Grid, start: tuple[int, int], goal: tuple[int, int]) -> bool:
    """calcNavFnDijkstra's success: a plan from the start cell that ends on the goal cell."""
    path = plan_path(costs, start, goal, SETTINGS, RESOLUTION)
    if path is None:
        return False
    return tuple(path[0].tolist()) == start and tuple(path[-1].tolist()) == goal


@PATH_CALC.test("PathCalc.oscillate_in_pinch_point", assertions=1)
def test_a_plan_through_a_pinch_point_is_found(willow: Grid) -> None:
    assert plans(willow, start=(428, 746), goal=(350, 450))


@PATH_CALC.test("PathCalc.easy_nav_should_always_work", assertions=1)
def test_an_easy_plan_is_found(willow: Grid) -> None:
    assert plans(willow, start=(350, 400), goal=(350, 450))
