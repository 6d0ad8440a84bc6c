"""ROS 1 costmap_2d's coordinate tests (costmap_2d/test/coordinates_test.cpp), on our Costmap's
conversions (pytest_lasertest/nav/move_base/costmap.py): `centres` as Costmap2D::mapToWorld (a
cell's centre), `cell_of` as worldToMap (its cell, and whether it lies on the map) and
worldToMapNoBounds (its cell wherever it lies).

Upstream's costmaps are 2 x 3 cells; our window is square, so these tests use 3 x 3: every cell
upstream's tests find on the map is on it, and only the two assertions that x = 2 m lies off the
map cannot be set up (NOT_PORTED). Left out as not applicable: the worldToMapEnforceBounds
assertions (four in easy_coordinates_test, two in hard_coordinates_test); our costmap has no
conversion that clamps a point onto the map.
"""

from __future__ import annotations

import numpy as np
import pytest

from pytest_lasertest.nav.move_base.costmap import Costmap, CostmapSettings
from tests.helpers.ros1_costmap import NO_FOOTPRINT
from tests.helpers.upstream import NAVIGATION_NOETIC, NotPorted, Source

COORDINATES = Source(
    "ROS 1 costmap_2d: coordinates", NAVIGATION_NOETIC, "costmap_2d/test/coordinates_test.cpp"
)
NOT_PORTED = (
    NotPorted(
        COORDINATES,
        "CostmapCoordinates.easy_coordinates_test",
        2,
        "EXPECT_FALSE(worldToMap) at x = 2.5 and 2.0 m needs a map 2 cells wide and 3 high; our "
        "costmap's window is square, and one 3 cells high also holds x = 2",
    ),
)


def costmap(resolution: float, origin: tuple[float, float]) -> Costmap:
    """A 3 x 3 cell costmap from `origin` (m): upstream's Costmap2D(2, 3, resolution, ...)
    widened to a square."""
    settings = CostmapSettings(size=3 * resolution, resolution=resolution)
    costmap = Costmap(settings, NO_FOOTPRINT)
    assert costmap.settings.cells == 3
    costmap.origin = origin
    return costmap


def double_eq(value: float, expected: float) -> bool:
    """gtest's EXPECT_DOUBLE_EQ: equal within 4 units in the last place."""
    return bool(abs(value - expected) <= 4 * np.spacing(abs(expected)))


def centre(costmap: Costmap, x: int, y: int) -> tuple[float, float]:
    """mapToWorld: the centre (m) of cell (x, y)."""
    wx, wy = costmap.centres(np.array([x]), np.array([y]))[0]
    return float(wx), float(wy)


def cell(costmap: Costmap, wx: float, wy: float) -> tuple[int, int, bool]:
    """worldToMap and worldToMapNoBounds: the cell (x, y) of the point (m), and whether it lies
    on the map."""
    x, y, inside = costmap.cell_of(np.array([[wx, wy]]))
    return int(x[0]), int(y[0]), bool(inside[0])


@COORDINATES.test("CostmapCoordinates.easy_coordinates_test", assertions=4)
def test_a_cells_world_position_is_its_centre() -> None:
    unit = costmap(1.0, (0.0, 0.0))
    wx, wy = centre(unit, 0, 0)
    assert double_eq(wx, 0.5)
    assert double_eq(wy, 0.5)
    wx, wy = centre(unit, 1, 2)
    assert double_eq(wx, 1.5)
    assert double_eq(wy, 2.5)


@COORDINATES.test("CostmapCoordinates.easy_coordinates_test", assertions=7)
def test_a_cells_centre_lies_in_that_cell_and_a_point_beyond_in_the_cell_beyond() -> None:
    unit = costmap(1.0, (0.0, 0.0))
    x, y, inside = cell(unit, 1.5, 2.5)
    assert inside
    # worldToMap's cell and worldToMapNoBounds' (two EXPECT_EQ each): cell_of is both.
    assert (x, y) == (1, 2)
    x, y, _ = cell(unit, 2.5, 2.5)
    assert (x, y) == (2, 2)  # worldToMapNoBounds off upstream's map: two EXPECT_EQ


# Eight border cases of two assertions each (EXPECT_TRUE and EXPECT_EQ).
@COORDINATES.test("CostmapCoordinates.easy_coordinates_test", assertions=2)
@pytest.mark.parametrize(
    ("wx", "expected"),
    [(0.0, 0), (0.25, 0), (0.75, 0), (0.9999, 0), (1.0, 1), (1.25, 1), (1.75, 1), (1.9999, 1)],
)
def test_a_point_on_a_cells_low_edge_or_inside_it_is_in_that_cell(wx: float, expected: int) -> None:
    x, _, inside = cell(costmap(1.0, (0.0, 0.0)), wx, 2.5)
    assert inside
    assert x == expected


@COORDINATES.test("CostmapCoordinates.hard_coordinates_test", assertions=4)
def test_a_cells_centre_counts_from_a_negative_origin_in_tenth_metre_cells() -> None:
    fine = costmap(0.1, (-0.2, 0.2))
    wx, wy = centre(fine, 0, 0)
    assert double_eq(wx, -0.15)
    assert double_eq(wy, 0.25)
    wx, wy = centre(fine, 1, 2)
    assert double_eq(wx, -0.05)
    assert double_eq(wy, 0.45)


@COORDINATES.test("CostmapCoordinates.hard_coordinates_test", assertions=8)
def test_a_fine_cells_centre_lies_in_it_and_a_far_point_far_off_the_map() -> None:
    fine = costmap(0.1, (-0.2, 0.2))
    wx, wy = centre(fine, 1, 2)
    x, y, inside = cell(fine, wx, wy)
    assert inside
    # worldToMap's cell and worldToMapNoBounds' (two EXPECT_EQ each): cell_of is both.
    assert (x, y) == (1, 2)
    x, y, inside = cell(fine, 2.5, wy)
    assert not inside
    assert (x, y) == (27, 2)  # worldToMapNoBounds: two EXPECT_EQ
