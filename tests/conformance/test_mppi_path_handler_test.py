"""nav2_mppi_controller's path handler tests (path_handler_test.cpp), rebuilt on what hands MPPI
its path here: `Nav2._pruned` (nav2.py), the plan from its point nearest the robot up to
prune_distance along it.

Not applicable: GetAndPrunePath's setPath and getPath checks (the plan's ROS message and frame),
TestTransforms (TF between frames: our plan, robot and costmaps share one frame) and
TestInversionToleranceChecks (enforce_path_inversion is not imitated).
"""

from __future__ import annotations

import numpy as np

from pytest_lasertest.model.geometry import Point2D
from pytest_lasertest.nav.nav2.nav2 import Nav2
from pytest_lasertest.pairsfile import load_pairs_file
from tests.helpers import EXAMPLES
from tests.helpers.upstream import NAVIGATION2_JAZZY, NotPorted, Source

PATH_HANDLER = Source(
    "Nav2 MPPI: path handler",
    NAVIGATION2_JAZZY,
    "nav2_mppi_controller/test/path_handler_test.cpp",
)
PERSISTENT_PRUNING = (
    "Nav2 erases the plan's poses before the one nearest the robot (prunePlan), so that the "
    "next search starts there: ours keeps the whole plan and searches all of it every cycle "
    "(nav2.py Nav2._pruned), so there is nothing erased to count"
)
NOT_PORTED: tuple[NotPorted, ...] = (
    NotPorted(PATH_HANDLER, "PathHandlerTests.GetAndPrunePath", 1, PERSISTENT_PRUNING),
    NotPorted(PATH_HANDLER, "PathHandlerTests.TestBounds", 1, PERSISTENT_PRUNING),
    NotPorted(
        PATH_HANDLER,
        "PathHandlerTests.TestBounds",
        1,
        "getMaxCostmapDist is half the costmap's larger side (2.5 m), the default "
        "max_robot_pose_search_dist that bounds the search for the nearest pose: ours has no "
        "such bound, it searches the whole plan",
    ),
)


@PATH_HANDLER.test("PathHandlerTests.TestBounds", assertions=1)
def test_the_path_starts_at_the_plans_point_nearest_the_robot() -> None:
    robot = load_pairs_file(EXAMPLES / "paper.lasertest.yaml").robot
    nav2 = Nav2(robot, (Point2D(99.0, 0.0),))
    nav2.plan = np.column_stack([np.arange(100.0), np.zeros(100)])  # a pose every metre along x
    path = nav2._pruned((25.0, 0.0, 0.0))  # the path handler's part of a controller cycle
    assert tuple(path[0]) == (25.0, 0.0)  # the test's closest pose, index 25
