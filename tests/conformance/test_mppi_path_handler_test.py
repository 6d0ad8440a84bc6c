"""nav2_mppi_controller's path handler tests (path_handler_test.cpp), rebuilt on our path
handler (pytest_lasertest/nav/nav2/path_handler.py: `transform_path`, which searches, cuts and
prunes in one call, and `max_costmap_dist`), and on what hands MPPI its path in our Nav2.

Not applicable: GetAndPrunePath's frame_id check (the plan's ROS message), TestTransforms (TF
between frames: our plan, robot and costmaps share one frame) and
TestInversionToleranceChecks (enforce_path_inversion is not imitated).
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from pytest_lasertest.model.geometry import FloatArray, Point2D
from pytest_lasertest.nav.nav2.nav2 import Nav2
from pytest_lasertest.nav.nav2.path_handler import max_costmap_dist, transform_path
from pytest_lasertest.pairsfile import load_pairs_file
from tests.helpers import EXAMPLES
from tests.helpers.costmap import scan
from tests.helpers.upstream import NAVIGATION2_JAZZY, Source

PATH_HANDLER = Source(
    "Nav2 MPPI: path handler",
    NAVIGATION2_JAZZY,
    "nav2_mppi_controller/test/path_handler_test.cpp",
)


def along_x(count: int) -> FloatArray:
    """A plan of `count` poses a metre apart along x from the origin."""
    return np.column_stack([np.arange(float(count)), np.zeros(count)])


def everywhere(points: FloatArray) -> npt.NDArray[np.bool_]:
    """A costmap that holds every point."""
    return np.ones(len(points), dtype=bool)


@PATH_HANDLER.test("PathHandlerTests.GetAndPrunePath", assertions=2)
def test_pruning_at_the_sixth_of_eleven_poses_keeps_six() -> None:
    handled = transform_path(along_x(11), (5.0, 0.0, 0.0), 99999.9, 1.5, everywhere)
    assert len(along_x(11)) == 11  # setPath keeps the plan whole until a cycle prunes it
    assert len(handled.plan) == 6


@PATH_HANDLER.test("PathHandlerTests.TestBounds", assertions=1)
def test_the_search_is_bounded_by_half_the_default_costmap() -> None:
    # Costmap2DROS's defaults: width 5 m at 0.1 m a cell (costmap_2d_ros.cpp).
    assert max_costmap_dist(50, 0.1) == 2.5


@PATH_HANDLER.test("PathHandlerTests.TestBounds", assertions=2)
def test_a_robot_at_25_m_finds_pose_25_and_prunes_the_25_before_it() -> None:
    plan = along_x(100)
    handled = transform_path(plan, (25.0, 0.0, 0.0), 99999.9, 1.5, everywhere)
    assert tuple(handled.path[0]) == tuple(plan[25])
    assert len(handled.plan) == 75


def test_our_nav2_hands_mppi_the_plan_from_its_pose_nearest_the_robot() -> None:
    robot = load_pairs_file(EXAMPLES / "paper.lasertest.yaml").robot
    nav2 = Nav2(robot, (Point2D(99.0, 0.0),))
    nav2.plan = nav2._handled = along_x(100)
    for x, first in ((0.3, 0.0), (1.2, 1.0), (2.6, 3.0)):  # m; each cycle searches on from the last
        nav2.local.update(scan(np.inf), (x, 0.0, 0.0))  # the window rolls round the robot
        path = nav2._path((x, 0.0, 0.0))
        assert tuple(path[0]) == (first, 0.0)
        # Up to prune_distance along it (the paper's Husky's Clearpath parameters: 2.0 m), on
        # its 5 m window.
        assert tuple(path[-1]) == (first + 2.0, 0.0)
        assert len(nav2._handled) == 100 - first


def test_a_robot_further_along_the_plan_than_the_search_reaches_gets_no_path() -> None:
    # The search stops 2.5 m along the plan (half the Husky's 5 m local costmap): pose 2 is
    # the nearest it finds, off the window round a robot at 25 m; Nav2 fails the cycle
    # (InvalidPath).
    robot = load_pairs_file(EXAMPLES / "paper.lasertest.yaml").robot
    nav2 = Nav2(robot, (Point2D(99.0, 0.0),))
    nav2.plan = nav2._handled = along_x(100)
    nav2.local.update(scan(np.inf), (25.0, 0.0, 0.0))
    assert len(nav2._path((25.0, 0.0, 0.0))) == 0


def test_the_search_for_the_nearest_pose_stops_at_its_bound() -> None:
    # A plan that comes back past the robot: the nearer pose lies 6 m along it, beyond 2.5 m.
    plan = np.array([[0.0, 1.0], [1.0, 1.0], [2.0, 1.0], [2.0, 3.0], [0.0, 3.0], [0.0, 0.1]])
    handled = transform_path(plan, (0.0, 0.0, 0.0), 2.5, 1.5, everywhere)
    assert tuple(handled.path[0]) == (0.0, 1.0)


def test_the_path_ends_before_its_first_pose_off_the_costmap() -> None:
    def before_1_5_m(points: FloatArray) -> npt.NDArray[np.bool_]:
        return np.asarray(points[:, 0] < 1.5)

    handled = transform_path(along_x(10), (0.0, 0.0, 0.0), 99999.9, 5.0, before_1_5_m)
    assert len(handled.path) == 2
