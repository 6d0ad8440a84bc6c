"""ROS 1 costmap_2d's footprint parameter tests (costmap_2d/test/footprint_tests.cpp with
footprint_tests.launch), on our reading of a robot file's `footprint` and `footprint_padding`
(pytest_lasertest/pairsfile/robot.py: load_robot_file; model/robot.py: pad_footprint), which a
move_base robot's costmaps take as costmap_2d takes its parameters.

Left out as not applicable: every EXPECT_EQ on a corner's z (geometry_msgs/Point's third
coordinate; our footprint is planar), and the tests radius_param and footprint_empty, which make
a 16-corner footprint from robot_radius (set, or its 0.46 m default): a robot file must give its
footprint and has no robot_radius.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from pytest_lasertest.inputs.errors import SpecError
from pytest_lasertest.model.robot import Robot
from pytest_lasertest.pairsfile.robot import load_robot_file
from tests.helpers.upstream import NAVIGATION_NOETIC, Source

FOOTPRINT = Source(
    "ROS 1 costmap_2d: footprint", NAVIGATION_NOETIC, "costmap_2d/test/footprint_tests.cpp"
)
# A robot file but for its footprint, which each test appends with footprint_tests.launch's text.
ROBOT_FILE = """\
name: footprint test
laser_mount: {xyz: [0.0, 0.0, 0.3], rpy: [0.0, 0.0, 0.0]}
max_linear_velocity: 0.8
max_linear_acceleration: 1.5
max_angular_velocity: 1.2
max_angular_acceleration: 3.0
body: {height: 0.3}
"""
TRIANGLE = "[[1, 1], [-1, 1], [-1, -1]]"  # unpadded/ and padded/footprint
REFUSED = (
    "costmap_2d accepts any three or more [x, y] pairs as a footprint "
    "(makeFootprintFromString, costmap_2d/src/footprint.cpp:170-208, and "
    "makeFootprintFromXMLRPC, :287-322, check nothing else); our robot file refuses a footprint "
    "that is not a convex polygon around the robot's origin, of which the simulation builds the "
    "robot's body (pytest_lasertest/pairsfile/robot.py:_footprint), and {which}"
)


def robot(tmp_path: Path, footprint: str, padding: str) -> Robot:
    """The robot of a robot file setting `footprint` and `footprint_padding` as written."""
    path = tmp_path / "robot.yaml"
    path.write_text(f"{ROBOT_FILE}footprint: {footprint}\nfootprint_padding: {padding}\n")
    return load_robot_file(path)


def same_corners(robot: Robot, expected: list[tuple[float, float]]) -> None:
    """The footprint's corners, in order, are `expected` (m): upstream compares them with float
    literals (1.0f, 0.1f), its corners having passed through parseVVF's floats."""
    assert len(robot.footprint) == len(expected)
    corners = np.array(robot.footprint, dtype=np.float32)
    for (x, y), (want_x, want_y) in zip(corners, expected, strict=True):
        assert x == np.float32(want_x)
        assert y == np.float32(want_y)


@FOOTPRINT.test("Costmap2DROS.unpadded_footprint_from_string_param", assertions=7)
def test_a_triangle_with_no_padding_keeps_its_corners(tmp_path: Path) -> None:
    same_corners(robot(tmp_path, TRIANGLE, "0"), [(1.0, 1.0), (-1.0, 1.0), (-1.0, -1.0)])


@FOOTPRINT.test("Costmap2DROS.padded_footprint_from_string_param", assertions=7)
def test_a_padded_triangle_moves_each_corner_out_by_the_padding(tmp_path: Path) -> None:
    same_corners(robot(tmp_path, TRIANGLE, ".5"), [(1.5, 1.5), (-1.5, 1.5), (-1.5, -1.5)])


@FOOTPRINT.test("Costmap2DROS.footprint_from_xmlrpc_param", assertions=9)
def test_a_square_given_as_a_list_keeps_its_four_corners_in_order(tmp_path: Path) -> None:
    square = robot(tmp_path, "[[0.1, 0.1], [-0.1, 0.1], [-0.1, -0.1], [0.1, -0.1]]", "0")
    same_corners(square, [(0.1, 0.1), (-0.1, 0.1), (-0.1, -0.1), (0.1, -0.1)])


@FOOTPRINT.test("Costmap2DROS.footprint_from_same_level_param", assertions=7)
@pytest.mark.xfail(
    strict=True,
    raises=SpecError,
    reason=REFUSED.format(which="these three corners lie on one line, off the origin"),
)
def test_a_footprint_read_from_its_own_namespace_keeps_its_corners(tmp_path: Path) -> None:
    collinear = robot(tmp_path, "[[1, 2], [3, 4], [5, 6]]", "0")
    same_corners(collinear, [(1.0, 2.0), (3.0, 4.0), (5.0, 6.0)])


@FOOTPRINT.test("Costmap2DROS.footprint_from_xmlrpc_param_failure", assertions=1)
def test_a_corner_of_three_numbers_is_refused(tmp_path: Path) -> None:
    with pytest.raises(SpecError, match="expected 2 numbers"):
        robot(tmp_path, "[[0.1, 0.1], [-0.1, 0.1, 77.0], [-0.1, -0.1], [0.1, -0.1]]", "0")
