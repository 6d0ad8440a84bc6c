"""nav2_costmap_2d's footprint tests (test/integration/footprint_tests.cpp), rebuilt on our
reading of a costmap's footprint from a params file (`configure`: `footprint`, `robot_radius`,
`footprint_padding` of local_costmap), which Costmap2DROS's parameters mirror.

Not applicable: the assertions on each point's z, which a geometry_msgs Point has and our
planar footprint's points do not.
"""

from __future__ import annotations

import pytest

from pytest_lasertest.model.robot import ParameterValue
from tests.helpers.nav2_params import local_footprint
from tests.helpers.upstream import NAVIGATION2_JAZZY, Source

FOOTPRINT = Source(
    "Nav2 costmap: footprint",
    NAVIGATION2_JAZZY,
    "nav2_costmap_2d/test/integration/footprint_tests.cpp",
)
TRIANGLE = "[[1, 1], [-1, 1], [-1, -1]]"


def footprint(**parameters: ParameterValue) -> tuple[tuple[float, float], ...]:
    """The local costmap's footprint (m) a params file setting `parameters` of it makes."""
    return local_footprint(parameters)


@FOOTPRINT.test("TestNode.footprint_empty", assertions=1)
def test_a_costmap_given_neither_footprint_nor_radius_is_a_circle_of_16_points() -> None:
    points = footprint(resolution=0.05)  # the file sets the costmap, not its footprint
    assert points is not None
    assert len(points) == 16


@FOOTPRINT.test("TestNode.footprint_empty", assertions=1)
def test_the_default_radius_circle_is_padded_to_0_11_m() -> None:
    points = footprint(resolution=0.05)
    assert points is not None
    assert points[0][0] == pytest.approx(0.11, abs=0.0001)


@FOOTPRINT.test("TestNode.footprint_empty", assertions=1)
def test_the_default_radius_circle_starts_on_the_x_axis() -> None:
    points = footprint(resolution=0.05)
    assert points is not None
    assert points[0][1] == pytest.approx(0.0, abs=0.0001)


@FOOTPRINT.test("TestNode.unpadded_footprint_from_string_param", assertions=7)
def test_a_footprint_string_without_padding_keeps_its_points() -> None:
    points = footprint(footprint=TRIANGLE, footprint_padding=0.0)
    assert points is not None
    assert len(points) == 3
    assert points[0] == (1.0, 1.0)
    assert points[1] == (-1.0, 1.0)
    assert points[2] == (-1.0, -1.0)


@FOOTPRINT.test("TestNode.padded_footprint_from_string_param", assertions=7)
def test_a_footprint_string_is_padded_away_from_the_origin_along_x_and_y() -> None:
    points = footprint(footprint=TRIANGLE, footprint_padding=0.5)
    assert points is not None
    assert len(points) == 3
    assert points[0] == (1.5, 1.5)
    assert points[1] == (-1.5, 1.5)
    assert points[2] == (-1.5, -1.5)


@FOOTPRINT.test("TestNode.radius_param", assertions=5)
def test_a_robot_radius_makes_a_circle_of_16_points() -> None:
    points = footprint(robot_radius=10.0, footprint_padding=0.0)
    assert points is not None
    assert len(points) == 16
    assert points[0] == (10.0, 0.0)
    # The 4th point (counting from 0), a quarter turn round.
    assert points[4][0] == pytest.approx(0.0, abs=0.0001)
    assert points[4][1] == pytest.approx(10.0, abs=0.0001)


@FOOTPRINT.test("TestNode.footprint_from_same_level_param", assertions=7)
def test_a_footprint_string_of_points_on_one_line_keeps_its_points() -> None:
    points = footprint(footprint="[[1, 2], [3, 4], [5, 6]]", footprint_padding=0.0)
    assert points is not None
    assert len(points) == 3
    assert points[0] == (1.0, 2.0)
    assert points[1] == (3.0, 4.0)
    assert points[2] == (5.0, 6.0)
