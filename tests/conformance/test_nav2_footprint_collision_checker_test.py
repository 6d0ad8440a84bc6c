"""nav2_costmap_2d's footprint collision checker tests (test/unit/footprint_collision_checker_test
.cpp), rebuilt on what stands for FootprintCollisionChecker in our Nav2: the behaviours'
collision check (`Nav2._collides`, whether the footprint's outline at a pose, rasterised edge by
edge as footprintCost does, meets a cost of lethal or more in the local costmap), on a local
costmap of 100 x 100 cells of 0.1 m from (0, 0); and the footprint strings of the same file on
our reading of a params file's `footprint` (`costmap_params.footprint_from_string`).

Our check answers lethal or not, where footprintCostAtPose gives the highest cost on the
outline; on these costmaps, which hold only 0 and 254, the cost is 0 exactly where no lethal
cell is met and 254 where one is.

Not applicable: to_point_32 and to_polygon, conversions between ROS messages.
"""

from __future__ import annotations

import numpy as np
import pytest

from pytest_lasertest.model.geometry import Point2D
from pytest_lasertest.nav.move_base.cost_values import FREE, LETHAL
from pytest_lasertest.nav.move_base.costmap import CostmapSettings
from pytest_lasertest.nav.nav2.costmap_params import footprint_from_string
from pytest_lasertest.nav.nav2.nav2 import Nav2
from pytest_lasertest.nav.nav2.settings import CostmapConfig, Nav2Settings
from tests.helpers.paper import PAPER
from tests.helpers.upstream import NAVIGATION2_JAZZY, NotPorted, Source

PATH = "nav2_costmap_2d/test/unit/footprint_collision_checker_test.cpp"
CHECKER = Source("Nav2 costmap: collision checker", NAVIGATION2_JAZZY, PATH)
FOOTPRINT = Source("Nav2 costmap: footprint", NAVIGATION2_JAZZY, PATH)
NOT_PORTED = (
    NotPorted(
        FOOTPRINT,
        "collision_footprint.not_enough_points",
        2,
        "a footprint of two points cannot be set up: our params reader refuses a footprint of "
        "fewer than three points (costmap_params._polygon), and we compute no circumscribed "
        "radius (calculateMinAndMaxDistances' max)",
    ),
)
SQUARE = ((-1.0, 1.0), (1.0, 1.0), (1.0, -1.0), (-1.0, -1.0))  # m, 2 m a side
DIAMOND = ((-0.5, 0.0), (0.0, 0.5), (0.5, 0.0), (0.0, -0.5))  # m


def checker(footprint: tuple[tuple[float, float], ...], cost: int = FREE) -> Nav2:
    """Our Nav2 with `footprint` and a local costmap of 100 x 100 cells of 0.1 m from (0, 0),
    every cell `cost` (Costmap2D(100, 100, 0.1, 0, 0, cost)). No scan is given it, so the
    window stays where it was made."""
    local = CostmapConfig(CostmapSettings(size=10.0, resolution=0.1), footprint=footprint)
    nav2 = Nav2(PAPER.robot, (Point2D(5.0, 5.0),), Nav2Settings(local=local))
    nav2.local.grid[:] = cost
    return nav2


@CHECKER.test("collision_footprint.test_basic", assertions=1)
def test_a_footprint_on_free_cells_meets_nothing() -> None:
    assert not checker(DIAMOND)._collides((5.0, 5.0, 0.0))


@CHECKER.test("collision_footprint.test_point_cost", assertions=1)
def test_a_cell_of_a_fresh_costmap_costs_nothing() -> None:
    assert checker(DIAMOND).local.grid[50, 50] == FREE


@CHECKER.test("collision_footprint.test_world_to_map", assertions=2)
def test_a_point_reads_the_cost_of_the_cell_it_lies_in() -> None:
    nav2 = checker(DIAMOND)
    x, y, inside = nav2.local.cell_of(np.array([[1.0, 1.0]]))
    assert inside[0]
    assert nav2.local.grid[y[0], x[0]] == FREE
    nav2.local.grid[50, 50] = 200
    x, y, inside = nav2.local.cell_of(np.array([[5.0, 5.0]]))
    assert inside[0]
    assert nav2.local.grid[y[0], x[0]] == 200


@CHECKER.test("collision_footprint.test_footprint_at_pose_with_movement", assertions=3)
def test_a_footprint_that_leaves_a_free_square_meets_the_lethal_cells_round_it() -> None:
    nav2 = checker(SQUARE, LETHAL)
    nav2.local.grid[40:61, 40:61] = FREE  # cells 40 to 60 along x and y
    assert not nav2._collides((5.0, 5.0, 0.0))
    assert nav2._collides((5.0, 4.9, 0.0))
    assert nav2._collides((5.0, 5.2, 0.0))


def two_lethal_cells() -> Nav2:
    """test_point_and_line_cost's costmap: free but for cells (62, 50) and (39, 60)."""
    nav2 = checker(SQUARE)
    nav2.local.grid[50, 62] = LETHAL
    nav2.local.grid[60, 39] = LETHAL
    return nav2


@CHECKER.test("collision_footprint.test_point_and_line_cost", assertions=2)
def test_a_footprint_meets_a_lethal_cell_under_its_corner_and_not_one_outside() -> None:
    nav2 = two_lethal_cells()
    assert not nav2._collides((5.0, 5.0, 0.0))
    # Its top left corner, (3.9, 6.0) m, lies in cell (39, 60).
    assert nav2._collides((4.9, 5.0, 0.0))


@CHECKER.test("collision_footprint.test_point_and_line_cost", assertions=1)
def test_a_footprint_meets_a_lethal_cell_in_the_middle_of_its_edge() -> None:
    assert two_lethal_cells()._collides((5.2, 5.0, 0.0))


def footprint(text: str) -> tuple[tuple[float, float], ...]:
    """makeFootprintFromString's footprint (m) of `text`: our reader's of a params file's
    `footprint`, before the reach the gate allows a robot (which -4e4 m exceeds)."""
    return footprint_from_string(text)


@FOOTPRINT.test("collision_footprint.make_footprint_from_string", assertions=10)
def test_a_footprint_string_of_numbers_without_leading_zeros_is_read() -> None:
    points = footprint("[[1, 2.2], [.3, -4e4], [-.3, -4e4], [-1, 2.2]]")
    assert points is not None  # upstream: it parses
    assert len(points) == 4
    expected = ((1.0, 2.2), (0.3, -4e4), (-0.3, -4e4), (-1.0, 2.2))
    for point, (x, y) in zip(points, expected, strict=True):
        assert point[0] == pytest.approx(x, abs=1e-5)
        assert point[1] == pytest.approx(y, abs=1e-5)


@FOOTPRINT.test("collision_footprint.make_footprint_from_string_parse_error", assertions=1)
def test_a_footprint_string_that_is_not_a_list_is_refused() -> None:
    with pytest.raises(ValueError, match="cannot be read"):
        footprint("[[bad_string")


@FOOTPRINT.test("collision_footprint.make_footprint_from_string_two_points_error", assertions=1)
def test_a_footprint_string_of_two_points_is_refused() -> None:
    with pytest.raises(ValueError, match="cannot be read"):
        footprint("[[1, 2.2], [.3, -4e4]")
    with pytest.raises(ValueError, match="three or more"):
        footprint("[[1, 2.2], [.3, -4e4]]")


@FOOTPRINT.test("collision_footprint.make_footprint_from_string_not_pairs", assertions=1)
def test_a_footprint_string_with_a_point_of_three_numbers_is_refused() -> None:
    with pytest.raises(ValueError, match="three or more"):
        footprint("[[1, 2.2], [.3, -4e4], [-.3, -4e4], [-1, 2.2, 5.6]]")
