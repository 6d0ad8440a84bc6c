"""DWB's tests of BaseObstacleCritic (dwb_critics/test/base_obstacle_test.cpp), rebuilt on our
`dwb_critics.base_obstacle`, which scores whole trajectories: each upstream scorePose is a
trajectory of that one pose, whose cost is the score and whose legality is whether scorePose
would not throw. The grid is the one the upstream Costmap2DROS makes with no parameters
(costmap_2d_ros.cpp: 5 m x 5 m, 0.1 m cells, origin (0, 0)), built directly: the critic reads
whatever grid it is given.

Not applicable: CriticVisualization (the point cloud of costs, which we do not publish)."""

from __future__ import annotations

import math

import numpy as np

from pytest_lasertest.nav.move_base.cost_values import INSCRIBED, LETHAL, UNKNOWN
from pytest_lasertest.nav.nav2.dwb_critics import Frame, Rollouts, Scored, base_obstacle
from pytest_lasertest.nav.nav2.mppi import CostGrid
from tests.helpers.upstream import NAVIGATION2_HUMBLE, Source

BASE_OBSTACLE = Source(
    "Nav2 DWB: critics",
    NAVIGATION2_HUMBLE,
    "nav2_dwb_controller/dwb_critics/test/base_obstacle_test.cpp",
)
RESOLUTION = 0.1  # m
SIZE = 5.0  # m, each way
SOME_OTHER_COST = 128


def score_poses(grid: CostGrid, poses: list[tuple[float, float, float]]) -> Scored:
    """The critic on one trajectory per pose, each of that pose alone."""
    x, y, yaw = (np.array([[pose[i]] for pose in poses]) for i in range(3))
    rollouts = Rollouts(np.zeros(len(poses)), np.zeros(len(poses)), x, y, yaw)
    frame = Frame(poses[0], (0.0, 0.0), np.zeros((1, 2)), grid, rollouts, (0.0, 0.0))
    return base_obstacle(frame)


def free_grid() -> CostGrid:
    """The costmap's geometry, all free."""
    cells = round(SIZE / RESOLUTION)
    return CostGrid(np.zeros((cells, cells), dtype=np.uint8), (0.0, 0.0), RESOLUTION, False)


def upstream_grid() -> CostGrid:
    """The test's costmap: free, with cells (0, 0) lethal, (0, 1) unknown and (0, 2) 128."""
    grid = free_grid()
    grid.costs[0, 0], grid.costs[1, 0], grid.costs[2, 0] = LETHAL, UNKNOWN, SOME_OTHER_COST
    return grid


@BASE_OBSTACLE.test("BaseObstacle.IsValidCost", assertions=2)
def test_only_lethal_inscribed_and_unknown_costs_are_illegal() -> None:
    # One row of 256 cells of 1 m, cell i of cost i, a pose at the centre of each.
    grid = CostGrid(np.arange(256, dtype=np.uint8)[np.newaxis, :], (0.0, 0.0), 1.0, False)
    poses = [(i + 0.5, 0.5, 0.0) for i in range(256)]
    legal = score_poses(grid, poses).legal
    invalid = {LETHAL, INSCRIBED, UNKNOWN}
    assert [i for i in range(256) if not legal[i]] == sorted(invalid)
    assert all(legal[i] for i in range(256) if i not in invalid)


@BASE_OBSTACLE.test("BaseObstacle.ScorePose", assertions=2)
def test_poses_on_lethal_or_unknown_cells_are_illegal() -> None:
    scored = score_poses(upstream_grid(), [(0.0, 0.0, 0.0), (0.0, 0.15, 0.0)])
    assert not scored.legal[0]  # cell (0, 0), lethal
    assert not scored.legal[1]  # cell (0, 1), no information


@BASE_OBSTACLE.test("BaseObstacle.ScorePose", assertions=2)
def test_a_pose_scores_its_cells_cost_whatever_its_heading() -> None:
    headings = [i * math.pi / 50.0 for i in range(-50, 150)]  # rad
    poses = [(0.05, 0.25, 0.0)] + [(0.05, 0.25, yaw) for yaw in headings]
    scored = score_poses(upstream_grid(), poses)
    assert scored.legal.all()
    assert scored.raw[0] == SOME_OTHER_COST
    assert (scored.raw[1:] == SOME_OTHER_COST).all()


@BASE_OBSTACLE.test("BaseObstacle.ScorePose", assertions=4)
def test_poses_off_the_grid_are_illegal() -> None:
    poses = [(1.0, -0.1, 0.0), (SIZE + 0.1, 1.0, 0.0), (1.0, SIZE + 0.1, 0.0), (-0.1, 1.0, 0.0)]
    # On a free grid: the upstream one's lethal cell (0, 0) is where our worldToMap parks
    # points off the grid, which would make them illegal even if the edge were not checked.
    assert not score_poses(free_grid(), poses).legal.any()
