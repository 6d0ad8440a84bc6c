"""DWB's test of getForwardPose (dwb_critics/test/alignment_util_test.cpp), rebuilt on our
PathAlign critic (`dwb_critics.path_align`), which computes the point forward_point_distance
ahead of a trajectory's last pose inline: the point is seen through the one thing the critic
tells of it, whether it lies on the grid, and a grid's lower-left corner is an exact bound
(worldToMap's `x >= origin`), so two grids cornered one float apart pin a coordinate exactly.

Not applicable: TestProjection's two assertions that the forward pose keeps the heading, as
our forward point is a position only and no critic reads a heading there."""

from __future__ import annotations

import math

import numpy as np

from pytest_lasertest.nav.nav2.dwb_critics import Frame, Rollouts, path_align
from pytest_lasertest.nav.nav2.mppi import CostGrid
from tests.helpers.upstream import NAVIGATION2_HUMBLE, Source

ALIGNMENT = Source(
    "Nav2 DWB: critics",
    NAVIGATION2_HUMBLE,
    "nav2_dwb_controller/dwb_critics/test/alignment_util_test.cpp",
)
# Cells of 1 m, 200 of them each way: from any corner below the point, the grid reaches it.
CELLS = 200
DISTANCE = 1.0  # m, the upstream forward distance
FAR = -100.0  # m, a corner coordinate well below any coordinate of the tests


def forward_point_at_least(pose: tuple[float, float, float], corner: tuple[float, float]) -> bool:
    """Whether PathAlign's forward point of a one-pose trajectory at `pose` lies at or beyond
    `corner` in both x and y: the grid from that corner holds it, and the critic finds it
    legal."""
    grid = CostGrid(np.zeros((CELLS, CELLS), dtype=np.uint8), corner, 1.0, False)
    rollouts = Rollouts(
        np.zeros(1),
        np.zeros(1),
        np.array([[pose[0]]]),
        np.array([[pose[1]]]),
        np.array([[pose[2]]]),
    )
    plan = np.array([[pose[0], pose[1]]])
    frame = Frame(pose, (pose[0], pose[1]), plan, grid, rollouts, (DISTANCE, DISTANCE))
    return bool(path_align(frame).legal[0])


def x_between(pose: tuple[float, float, float], low: float, high: float) -> bool:
    """low <= forward x < high, y left free."""
    return forward_point_at_least(pose, (low, FAR)) and not forward_point_at_least(
        pose, (high, FAR)
    )


def y_between(pose: tuple[float, float, float], low: float, high: float) -> bool:
    """low <= forward y < high, x left free."""
    return forward_point_at_least(pose, (FAR, low)) and not forward_point_at_least(
        pose, (FAR, high)
    )


@ALIGNMENT.test("AlignmentUtil.TestProjection", assertions=2)
def test_the_forward_point_of_a_pose_facing_along_x_is_exactly_one_metre_ahead() -> None:
    pose = (1.0, -1.0, 0.0)
    # [v, the next float above v): exactly v.
    assert x_between(pose, 2.0, math.nextafter(2.0, math.inf))
    assert y_between(pose, -1.0, math.nextafter(-1.0, math.inf))


@ALIGNMENT.test("AlignmentUtil.TestProjection", assertions=2)
def test_the_forward_point_follows_the_heading() -> None:
    pose = (2.0, -10.0, 0.54)
    tolerance = 0.01  # m
    assert x_between(pose, 2.8577 - tolerance, 2.8577 + tolerance)
    assert y_between(pose, -9.4858 - tolerance, -9.4858 + tolerance)
