"""nav2_mppi_controller's critic tests (critics_tests.cpp), rebuilt on our critics
(pytest_lasertest/nav/nav2/critics.py) as a params file that lists the critic builds it: its
parameters the test leaves out take Nav2's code defaults there too.

Not applicable: the getName checks (plugin names), the Ackermann half of ConstraintsCritic,
PathAngleCritic's mode 2 and modeToStr (only modes 0 and 1 are imitated), the ObstaclesCritic,
GoalAngleCritic, TwirlingCritic and VelocityDeadbandCritic tests (critics we do not imitate) and
CostCritic's consider_footprint checks (footprint collision checking is not imitated).
"""

from __future__ import annotations

import numpy as np
import pytest

from pytest_lasertest.nav.move_base.cost_values import LETHAL
from pytest_lasertest.nav.nav2.critics import ConstraintCritic
from pytest_lasertest.nav.nav2.mppi import CriticData
from tests.helpers.mppi import critic, critic_data, dummy_costmap, path_along_x
from tests.helpers.upstream import NAVIGATION2_JAZZY, NotPorted, Source

CRITICS = Source(
    "Nav2 MPPI: critics", NAVIGATION2_JAZZY, "nav2_mppi_controller/test/critics_tests.cpp"
)
NOT_PORTED: tuple[NotPorted, ...] = ()
# The critic tests' batch: 1000 trajectories of 30 steps of 0.1 s.
BATCH, STEPS = 1000, 30


# ConstraintsCritic: vx_max and vx_min are left at their defaults (0.5, -0.35 m/s, ours the
# same); so is vy_max, which the critic counts in even for a differential drive. The test builds
# the critic alone, where its own default for vy_max, 0.0, holds (constraint_critic.cpp:33); in
# the controller the optimizer has declared vy_max first with 0.5 (optimizer.cpp:78, before
# critic_manager_.on_configure at :50), which the critic then reads, as ours does. So the
# critic alone is the one of a params file setting vy_max 0.0.
ALONE = {"FollowPath.vy_max": 0.0}


def constraint_data() -> CriticData:
    data = critic_data(BATCH, STEPS)
    data.vx[:], data.wz[:] = 0.40, 1.0  # m/s, rad/s
    return data


@CRITICS.test("CriticTests.ConstraintsCritic", assertions=2)
def test_the_critic_alone_allows_vx_min_to_vx_max() -> None:
    made = critic("ConstraintCritic", ALONE)
    assert isinstance(made, ConstraintCritic)
    assert made.max_vel_constraint > 0.0
    assert made.min_vel_constraint < 0.0


@CRITICS.test("CriticTests.ConstraintsCritic", assertions=1)
def test_speeds_within_the_limits_cost_nothing() -> None:
    data = constraint_data()
    critic("ConstraintCritic", ALONE)(data)
    assert data.costs.sum() == pytest.approx(0.0, abs=1e-6)


@CRITICS.test("CriticTests.ConstraintsCritic", assertions=2)
def test_a_trajectory_above_vx_max_costs_weight_x_dt_x_excess_per_step() -> None:
    data = constraint_data()
    data.vx[-1] = 0.60  # m/s
    critic("ConstraintCritic", ALONE)(data)
    assert data.costs.sum() > 0.0
    # 4.0 (weight) x 0.1 s x 0.1 m/s over x 30 steps
    assert data.costs[-1] == pytest.approx(1.2, abs=0.01)


@CRITICS.test("CriticTests.ConstraintsCritic", assertions=2)
def test_a_trajectory_below_vx_min_costs_weight_x_dt_x_excess_per_step() -> None:
    data = constraint_data()
    data.vx[-1] = 0.60  # m/s: still there upstream when the minimum is tried
    data.vx[1] = -0.45  # m/s
    critic("ConstraintCritic", ALONE)(data)
    assert data.costs.sum() > 0.0
    assert data.costs[1] == pytest.approx(1.2, abs=0.01)


# GoalCritic: every trajectory stays at (0, 0), the robot at (1, 0).


def goal_data(goal_x: float) -> CriticData:
    path = path_along_x([0.0] * 9 + [goal_x])
    return critic_data(BATCH, STEPS, pose=(1.0, 0.0, 0.0), goal=(goal_x, 0.0), path=path)


@CRITICS.test("CriticTests.GoalCritic", assertions=2)
def test_the_goal_critic_ignores_a_goal_beyond_its_threshold() -> None:
    data = goal_data(10.0)
    critic("GoalCritic")(data)
    assert data.costs[2] == pytest.approx(0.0, abs=1e-6)
    assert data.costs.sum() == pytest.approx(0.0, abs=1e-6)


@CRITICS.test("CriticTests.GoalCritic", assertions=2)
def test_near_the_goal_each_trajectory_costs_its_mean_distance_to_it_x_weight() -> None:
    data = goal_data(0.5)
    critic("GoalCritic")(data)
    assert data.costs[2] == pytest.approx(2.5, abs=1e-6)  # 0.5 m x 5.0
    assert data.costs.sum() == pytest.approx(2500.0, abs=1e-6)


# PathAngleCritic: the robot at (0, 0) heading along x, the goal 0.95 m ahead, the samples
# reaching path point 2, so that the critic aims at point 2 + offset_from_furthest 4 = 6.


def aiming_at(point: tuple[float, float]) -> CriticData:
    path = path_along_x([0.0] * 9 + [0.95])
    path[6] = point
    data = critic_data(BATCH, STEPS, goal=(0.95, 0.0), path=path)
    data.furthest = 2
    return data


def path_angle(mode: int) -> CriticData:
    """The costs of the point (-1, 4) m, 1.82 rad off the heading (1.33 rad off reversing)."""
    data = aiming_at((-1.0, 4.0))
    critic("PathAngleCritic", {"FollowPath.PathAngleCritic.mode": mode})(data)
    return data


@CRITICS.test("CriticTests.PathAngleCritic", assertions=2)
def test_the_path_angle_critic_ignores_a_near_goal_and_a_point_straight_ahead() -> None:
    near = critic_data(BATCH, STEPS, goal=(0.15, 0.0), path=path_along_x([0.0] * 9 + [0.15]))
    critic("PathAngleCritic")(near)
    assert near.costs.sum() == pytest.approx(0.0, abs=1e-6)
    ahead = aiming_at((1.0, 0.0))
    critic("PathAngleCritic")(ahead)
    assert ahead.costs.sum() == pytest.approx(0.0, abs=1e-6)


@CRITICS.test("CriticTests.PathAngleCritic", assertions=1)
def test_a_point_far_off_the_heading_costs_something() -> None:
    assert path_angle(mode=0).costs.sum() > 0.0


@CRITICS.test("CriticTests.PathAngleCritic", assertions=1)
def test_a_point_far_off_the_heading_costs_the_angle_x_weight() -> None:
    assert path_angle(mode=0).costs[0] == pytest.approx(3.9947, abs=1e-2)


@CRITICS.test("CriticTests.PathAngleCritic", assertions=2)
def test_without_direction_preference_a_point_ahead_or_behind_costs_nothing() -> None:
    either_way = {"FollowPath.PathAngleCritic.mode": 1}
    for point in ((1.0, 0.0), (-1.0, 0.0)):
        data = aiming_at(point)
        critic("PathAngleCritic", either_way)(data)
        assert data.costs.sum() == pytest.approx(0.0, abs=1e-6)


@CRITICS.test("CriticTests.PathAngleCritic", assertions=1)
def test_without_direction_preference_a_point_far_off_both_ways_costs_something() -> None:
    assert path_angle(mode=1).costs.sum() > 0.0


@CRITICS.test("CriticTests.PathAngleCritic", assertions=1)
def test_without_direction_preference_the_cost_is_the_angle_off_reversing_x_weight() -> None:
    assert path_angle(mode=1).costs[0] == pytest.approx(2.9167, abs=1e-2)


# PreferForwardCritic: the robot at (1, 0).


def prefer_forward(goal_x: float, vx: float) -> CriticData:
    path = path_along_x([0.0] * 9 + [goal_x])
    data = critic_data(BATCH, STEPS, pose=(1.0, 0.0, 0.0), goal=(goal_x, 0.0), path=path)
    data.vx[:] = vx  # m/s
    critic("PreferForwardCritic")(data)
    return data


@CRITICS.test("CriticTests.PreferForwardCritic", assertions=2)
def test_standing_or_driving_forward_costs_nothing() -> None:
    assert prefer_forward(10.0, 0.0).costs.sum() == pytest.approx(0.0, abs=1e-6)
    assert prefer_forward(0.15, 1.0).costs.sum() == pytest.approx(0.0, abs=1e-6)


@CRITICS.test("CriticTests.PreferForwardCritic", assertions=2)
def test_reversing_costs_weight_x_the_distance_reversed() -> None:
    data = prefer_forward(0.15, -1.0)
    assert data.costs.sum() > 0.0
    assert data.costs[0] == pytest.approx(15.0, abs=1e-3)  # 1 m/s x 0.1 s x 5.0 x 30 steps


# PathFollowCritic: a path of six points; offset_from_furthest (Nav2's 6, ours 5) runs past its
# end either way, so the critic aims at its last point.


def path_follow(pose_x: float, end_x: float) -> CriticData:
    path = path_along_x([0.0] * 5 + [end_x])
    data = critic_data(
        BATCH, STEPS, pose=(pose_x, 0.0, 0.0), goal=(end_x, 0.0), path=path, costmap=dummy_costmap()
    )
    critic("PathFollowCritic")(data)
    return data


@CRITICS.test("CriticTests.PathFollowCritic", assertions=1)
def test_the_path_follow_critic_ignores_a_near_goal() -> None:
    assert path_follow(2.0, 1.8).costs.sum() == pytest.approx(0.0, abs=1e-6)


@CRITICS.test("CriticTests.PathFollowCritic", assertions=1)
def test_each_trajectory_costs_its_end_distance_to_the_point_ahead_x_weight() -> None:
    # 0.15 m x 5.0 x 1000 trajectories
    assert path_follow(2.0, 0.15).costs.sum() == pytest.approx(750.0, abs=1e-2)


# PathAlignCritic: the robot at (1, 0), then at (0, 0) on a path along x.


def path_align(data: CriticData) -> float:
    critic("PathAlignCritic")(data)
    return float(data.costs.sum())


@CRITICS.test("CriticTests.PathAlignCritic", assertions=3)
def test_the_path_align_critic_waits_for_the_goal_far_and_the_samples_far_along() -> None:
    def robot_at_1(goal_x: float) -> CriticData:
        path = path_along_x([0.0] * 9 + [goal_x])
        costmap = dummy_costmap()
        return critic_data(
            BATCH, STEPS, pose=(1.0, 0.0, 0.0), goal=(goal_x, 0.0), path=path, costmap=costmap
        )

    assert path_align(robot_at_1(0.85)) == pytest.approx(0.0, abs=1e-6)  # the goal is near
    # The samples, all at (0, 0), reach point 0, short of offset_from_furthest (20).
    assert path_align(robot_at_1(0.15)) == pytest.approx(0.0, abs=1e-6)
    # Past it, trajectories at the path's own points cost nothing.
    reached = robot_at_1(0.15)
    reached.furthest = 21
    assert path_align(reached) == pytest.approx(0.0, abs=1e-6)


def aligned_22_points() -> CriticData:
    """The robot at (0, 0) on a path of 22 points from x = 0 to 0.9 m, the samples reaching
    point 21, every trajectory standing at (0.66, 0)."""
    path = path_along_x([0.1 * i for i in range(10)] + [0.9] * 12)
    data = critic_data(BATCH, STEPS, goal=(0.9, 0.0), path=path, costmap=dummy_costmap())
    data.furthest = 21
    data.x[:] = 0.66  # m
    return data


@CRITICS.test("CriticTests.PathAlignCritic", assertions=1)
def test_each_trajectory_costs_its_mean_distance_to_the_path_x_weight() -> None:
    assert path_align(aligned_22_points()) == pytest.approx(6600.0, abs=1e-2)


@CRITICS.test("CriticTests.PathAlignCritic", assertions=1)
def test_a_path_blocked_by_lethal_cells_is_not_aligned_to() -> None:
    data = aligned_22_points()
    data.costmap = dummy_costmap()
    data.costmap.costs[11:31, 11:31] = LETHAL  # an island from 1.1 to 3.0 m
    data.path = np.full((22, 2), 1.5, dtype=np.float32)  # every point on it
    data.goal = (1.5, 0.0)
    assert path_align(data) == pytest.approx(0.0, abs=1e-6)
