"""The DWA local planner: dwa_local_planner's samples, rollouts, critics and oscillation flags."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import numpy.typing as npt
import pytest

from pytest_lasertest.model.geometry import FloatArray
from pytest_lasertest.nav.move_base.costmap import InflationCost
from pytest_lasertest.nav.move_base.dwa import (
    DwaSettings,
    LocalPlanner,
    Oscillation,
    Rollouts,
    Surroundings,
    roll_out_in_numpy,
    time_steps,
    velocity_samples,
)

# The Husky's footprint without padding, counter-clockwise: 1 m long, 0.66 m wide.
HALF_LENGTH, HALF_WIDTH = 0.5, 0.33
FOOTPRINT = np.array(
    [
        [-HALF_LENGTH, -HALF_WIDTH],
        [HALF_LENGTH, -HALF_WIDTH],
        [HALF_LENGTH, HALF_WIDTH],
        [-HALF_LENGTH, HALF_WIDTH],
    ]
)
CORNER_RADIUS = math.hypot(HALF_LENGTH, HALF_WIDTH)  # m, what turning on the spot sweeps
RESOLUTION = 0.05  # m
COST = InflationCost(inscribed=HALF_WIDTH, inflation_radius=1.0, cost_scaling_factor=10.0)
# The Husky's DWA: 0.5 m/s at most, 6 forward speeds; min_rot_vel is DWA's default 0.4 rad/s.
SETTINGS = DwaSettings(max_vel_x=0.5, max_trans_vel=0.5, vx_samples=6)
HUSKY_PERIOD = 0.2  # s, move_base's controller_frequency 5 Hz
WINDOW = 200  # cells: the Husky's 10 m local window at 5 cm
STANDING = (0.0, 0.0)
ORIGIN = (0.0, 0.0, 0.0)
NOTHING = np.zeros((0, 2))
# A plan straight ahead along x to 4 m, a point every 5 cm.
AHEAD = np.column_stack([np.linspace(0.0, 4.0, 81), np.zeros(81)])


def planner(settings: DwaSettings = SETTINGS, period: float = HUSKY_PERIOD) -> LocalPlanner:
    return LocalPlanner(settings, FOOTPRINT, COST, period, RESOLUTION, WINDOW)


def straight_to(goal: tuple[float, float], lethal: FloatArray = NOTHING) -> Surroundings:
    """A plan straight from the origin to `goal`, which ends it."""
    length = math.hypot(*goal)
    count = round(length / 0.05) + 1
    plan = np.column_stack([np.linspace(0.0, goal[0], count), np.linspace(0.0, goal[1], count)])
    return Surroundings(plan, goal, lethal)


def ros_steps(settings: DwaSettings, v: float, w: float) -> int:
    """SimpleTrajectoryGenerator's number of steps of a sample."""
    return math.ceil(
        max(
            settings.sim_time * abs(v) / settings.sim_granularity,
            settings.sim_time * abs(w) / settings.angular_sim_granularity,
        )
    )


def euler(
    pose: tuple[float, float, float], v: float, w: float, steps: int, dt: float
) -> FloatArray:
    """SimpleTrajectoryGenerator's points: the pose, then computeNewPositions steps_-1 times."""
    x, y, yaw = pose
    points = [(x, y, yaw)]
    for _ in range(steps - 1):
        x, y, yaw = x + v * math.cos(yaw) * dt, y + v * math.sin(yaw) * dt, yaw + w * dt
        points.append((x, y, yaw))
    return np.array(points)


def covers(
    poses: FloatArray, point: tuple[float, float], grow: float = 0.0
) -> npt.NDArray[np.bool_]:
    """Whether the footprint, each edge moved out by `grow` m, covers `point` at each pose."""
    dx, dy = point[0] - poses[:, 0], point[1] - poses[:, 1]
    cos, sin = np.cos(poses[:, 2]), np.sin(poses[:, 2])
    forward, left = dx * cos + dy * sin, dy * cos - dx * sin
    inside: npt.NDArray[np.bool_] = (np.abs(forward) <= HALF_LENGTH + grow) & (
        np.abs(left) <= HALF_WIDTH + grow
    )
    return inside


def sample_index(rollouts: Rollouts, v: float, w: float) -> int:
    found = np.flatnonzero(np.isclose(rollouts.linear, v) & np.isclose(rollouts.angular, w))
    assert len(found) == 1, (v, w)
    return int(found[0])


# --- velocity_samples: base_local_planner's VelocityIterator ---


@pytest.mark.parametrize(
    ("low", "high", "count", "expected"),
    [
        (0.0, 0.5, 6, [0.0, 0.1, 0.2, 0.3, 0.4, 0.5]),
        (-0.5, -0.1, 3, [-0.5, -0.3, -0.1]),
        (-0.3, 0.3, 3, [-0.3, 0.0, 0.3]),  # 0 is already a sample: no second one
        (-0.3, 0.5, 3, [-0.3, 0.0, 0.1, 0.5]),
        (0.2, 0.6, 1, [0.2, 0.6]),  # VelocityIterator samples at least both ends
        (0.25, 0.25, 6, [0.25]),
        (0.0, 0.0, 20, [0.0]),
    ],
)
def test_velocity_samples_span_low_to_high_with_zero_inserted_where_they_cross_it(
    low: float, high: float, count: int, expected: list[float]
) -> None:
    np.testing.assert_allclose(velocity_samples(low, high, count), expected, atol=1e-12)


def test_an_even_number_of_turn_rates_around_zero_gets_zero_added_between_the_middle_two() -> None:
    samples = velocity_samples(-0.64, 0.64, 20)
    assert len(samples) == 21
    assert samples[10] == 0.0
    assert samples[9] < 0.0 < samples[11]
    np.testing.assert_allclose(np.delete(samples, 10), np.linspace(-0.64, 0.64, 20))


# --- the dynamic window ---


def test_from_standstill_a_husky_control_cycle_reaches_every_forward_speed() -> None:
    rollouts = planner().rollouts(ORIGIN, STANDING)
    # acc_lim_x 2.5 m/s^2 for 0.2 s reaches 0.5 m/s: the whole range.
    np.testing.assert_allclose(np.unique(rollouts.linear), [0.0, 0.1, 0.2, 0.3, 0.4, 0.5])
    # acc_lim_theta 3.2 rad/s^2 for 0.2 s reaches 0.64 rad/s either way.
    assert rollouts.angular.min() == pytest.approx(-0.64)
    assert rollouts.angular.max() == pytest.approx(0.64)


def test_at_speed_a_20_hz_cycle_only_reaches_speeds_within_one_period_of_braking() -> None:
    rollouts = planner(period=0.05).rollouts(ORIGIN, (0.5, 0.0))
    speeds = np.unique(rollouts.linear)
    # 2.5 m/s^2 for 0.05 s: 0.125 m/s slower at most, and no faster than max_vel_x.
    assert speeds.min() == pytest.approx(0.375)
    assert speeds.max() == pytest.approx(0.5)
    assert len(speeds) == SETTINGS.vx_samples
    assert rollouts.angular.min() == pytest.approx(-0.16)  # 3.2 rad/s^2 for 0.05 s
    assert rollouts.angular.max() == pytest.approx(0.16)


def test_samples_too_slow_both_to_drive_and_to_turn_are_dropped() -> None:
    rollouts = planner().rollouts(ORIGIN, STANDING)
    slow = (np.abs(rollouts.linear) + 1e-4 < SETTINGS.min_trans_vel) & (
        np.abs(rollouts.angular) + 1e-4 < SETTINGS.min_rot_vel
    )
    assert not slow.any()
    # Each on its own is fine: standing and turning fast, or driving min_trans_vel straight.
    sample_index(rollouts, 0.0, 0.64)
    sample_index(rollouts, 0.1, 0.0)
    # 6 speeds x 21 turn rates, less standing with the 13 turn rates below 0.4 rad/s.
    assert len(rollouts.linear) == 6 * 21 - 13


def test_no_sample_is_faster_than_max_trans_vel_even_if_max_vel_x_allows_it() -> None:
    settings = dataclasses.replace(SETTINGS, max_vel_x=0.6, max_trans_vel=0.45)
    rollouts = planner(settings).rollouts(ORIGIN, (0.3, 0.0))
    assert np.abs(rollouts.linear).max() <= 0.45
    np.testing.assert_allclose(np.unique(rollouts.linear), [0.0, 0.12, 0.24, 0.36])


# --- rollouts ---

START = (1.0, -2.0, 0.7)  # a pose away from the origin, turned


def test_a_straight_rollout_ends_v_times_steps_less_one_times_dt_ahead() -> None:
    rollouts = planner().rollouts(START, STANDING)
    for v in (0.1, 0.2, 0.3, 0.4, 0.5):
        i = sample_index(rollouts, v, 0.0)
        steps = ros_steps(SETTINGS, v, 0.0)
        dt = SETTINGS.sim_time / steps
        ahead = v * (steps - 1) * dt
        expected = (START[0] + ahead * math.cos(0.7), START[1] + ahead * math.sin(0.7), 0.7)
        np.testing.assert_allclose(rollouts.ends[i], expected, atol=1e-9)
        # Exactly `steps` points: each one step on from the last, then the last repeated.
        moves = np.hypot(*np.diff(rollouts.poses[i, :, :2], axis=0).T)
        np.testing.assert_allclose(moves[: steps - 1], v * dt)
        assert not moves[steps - 1 :].any()
        np.testing.assert_allclose(rollouts.poses[i, 0], START)


def test_an_arc_ends_where_the_unicycle_arc_ends_within_the_euler_error() -> None:
    rollouts = planner().rollouts(START, STANDING)
    arcs = np.flatnonzero((rollouts.linear > 0.0) & (rollouts.angular != 0.0))
    assert len(arcs) > 50
    for i in arcs:
        v, w = float(rollouts.linear[i]), float(rollouts.angular[i])
        steps = ros_steps(SETTINGS, v, w)
        dt = SETTINGS.sim_time / steps
        # base_local_planner's own integration, step by step.
        np.testing.assert_allclose(rollouts.ends[i], euler(START, v, w, steps, dt)[-1], atol=1e-9)
        # The closed-form arc driven for the same time; Euler drifts at most v w dt t / 2.
        t = (steps - 1) * dt
        turned = START[2] + w * t
        x = START[0] + v / w * (math.sin(turned) - math.sin(START[2]))
        y = START[1] - v / w * (math.cos(turned) - math.cos(START[2]))
        error = math.dist((x, y), rollouts.ends[i, :2])
        assert error <= v * abs(w) * dt * t / 2.0 + 1e-9
        assert error < 0.015
        assert rollouts.ends[i, 2] == pytest.approx(turned)


def test_a_turn_on_the_spot_stays_in_place_and_turns_w_times_steps_less_one_times_dt() -> None:
    rollouts = planner().rollouts(START, STANDING)
    spins = np.flatnonzero(rollouts.linear == 0.0)
    assert len(spins) == 8  # the turn rates of 0.4 rad/s or more, either way
    for i in spins:
        w = float(rollouts.angular[i])
        steps = ros_steps(SETTINGS, 0.0, w)
        dt = SETTINGS.sim_time / steps
        np.testing.assert_allclose(
            rollouts.poses[i, :, :2], np.tile(START[:2], (rollouts.poses.shape[1], 1))
        )
        assert rollouts.ends[i, 2] == pytest.approx(START[2] + w * (steps - 1) * dt)


# --- obstacles ---

AHEAD_OF_FRONT = (HALF_LENGTH + 0.3, 0.0)  # a lethal cell centre 0.3 m ahead of the front edge
BESIDE = (0.0, HALF_WIDTH + 0.07)  # beside the middle of the left side: within the corner radius


def test_every_forward_sample_that_reaches_a_lethal_cell_ahead_is_rejected() -> None:
    local = planner()
    rollouts = local.rollouts(ORIGIN, STANDING)
    scores = local.scores(rollouts, ORIGIN, straight_to((4.0, 0.0), np.array([AHEAD_OF_FRONT])))
    reaching = np.array([covers(poses, AHEAD_OF_FRONT).any() for poses in rollouts.poses])
    assert reaching.sum() >= 20  # the faster ones, straight or nearly
    assert np.isinf(scores[reaching]).all()
    assert np.isinf(scores[sample_index(rollouts, 0.5, 0.0)])


def test_turning_on_the_spot_is_allowed_when_the_lethal_cell_ahead_is_beyond_the_corners() -> None:
    assert math.hypot(*AHEAD_OF_FRONT) > CORNER_RADIUS + RESOLUTION
    local = planner()
    rollouts = local.rollouts(ORIGIN, STANDING)
    scores = local.scores(rollouts, ORIGIN, straight_to((4.0, 0.0), np.array([AHEAD_OF_FRONT])))
    spins = rollouts.linear == 0.0
    assert spins.sum() == 8
    assert np.isfinite(scores[spins]).all()


def test_turning_on_the_spot_is_rejected_when_a_corner_would_sweep_a_lethal_cell() -> None:
    assert math.hypot(*BESIDE) < CORNER_RADIUS
    local = planner()
    rollouts = local.rollouts(ORIGIN, STANDING)
    spins = rollouts.linear == 0.0
    # Every turn on the spot, either way, brings the footprint over the cell.
    assert all(covers(poses, BESIDE).any() for poses in rollouts.poses[spins])
    clear = local.scores(rollouts, ORIGIN, straight_to((4.0, 0.0)))
    beside = local.scores(rollouts, ORIGIN, straight_to((4.0, 0.0), np.array([BESIDE])))
    assert np.isfinite(clear[spins]).all()
    assert np.isinf(beside[spins]).all()
    # Driving straight on passes it: the side stays 7 cm away.
    assert np.isfinite(beside[sample_index(rollouts, 0.3, 0.0)])


def test_command_is_none_when_every_sample_would_drive_or_turn_into_a_lethal_cell() -> None:
    # A cell 0.1 m ahead of the front edge and one beside each side.
    lethal = np.array([(HALF_LENGTH + 0.1, 0.0), BESIDE, (0.0, -BESIDE[1])])
    local = planner()
    rollouts = local.rollouts(ORIGIN, STANDING)
    assert all(
        any(covers(poses, (float(x), float(y))).any() for x, y in lethal)
        for poses in rollouts.poses
    )
    assert local.command(ORIGIN, STANDING, straight_to((4.0, 0.0), lethal)) is None
    # Without the cell ahead it would drive on: the cells beside only stop the turns.
    assert local.command(ORIGIN, STANDING, straight_to((4.0, 0.0), lethal[1:])) is not None


def test_with_nothing_near_it_drives_straight_at_a_goal_ahead_at_max_vel_x() -> None:
    assert planner().command(ORIGIN, STANDING, straight_to((4.0, 0.0))) == (0.5, 0.0)


def test_a_turned_robot_turns_toward_a_goal_behind_its_left_shoulder() -> None:
    command = planner().command((0.0, 0.0, -1.0), STANDING, straight_to((0.0, 3.0)))
    assert command is not None
    assert command[1] > 0.0


# --- the footprint grows with speed ---

# Just outside the unscaled footprint's left side as it drives straight on, 5 cm from it.
SIDE_CELL = (0.3, HALF_WIDTH + 0.05)


@pytest.mark.parametrize(("max_scaling_factor", "rejected"), [(0.2, (0.4, 0.5)), (0.0, ())])
def test_a_lethal_cell_just_beside_the_path_rejects_only_samples_fast_enough_to_grow_over_it(
    max_scaling_factor: float, rejected: tuple[float, ...]
) -> None:
    # scaling_speed 0.25 m/s, max_trans_vel 0.5 m/s: a 0.2 factor grows the half width 0.33 m
    # by 1.3 cm at 0.3 m/s, 4 cm at 0.4 m/s and 6.6 cm at 0.5 m/s.
    settings = dataclasses.replace(SETTINGS, max_scaling_factor=max_scaling_factor)
    local = planner(settings)
    rollouts = local.rollouts(ORIGIN, STANDING)
    scores = local.scores(rollouts, ORIGIN, straight_to((4.0, 0.0), np.array([SIDE_CELL])))
    for v in (0.1, 0.2, 0.3, 0.4, 0.5):
        score = scores[sample_index(rollouts, v, 0.0)]
        assert np.isinf(score) == (v in rejected), v


# --- scoring ---


@pytest.mark.parametrize("side", [1.0, -1.0], ids=["left", "right"])
def test_with_a_plan_that_bends_one_way_the_chosen_command_turns_that_way(side: float) -> None:
    # A quarter-ish circle of 1 m radius, starting straight ahead.
    t = np.linspace(0.0, 1.5, 31)
    plan = np.column_stack([np.sin(t), side * (1.0 - np.cos(t))])
    goal = (float(plan[-1, 0]), float(plan[-1, 1]))
    command = planner().command(ORIGIN, STANDING, Surroundings(plan, goal, NOTHING))
    assert command is not None
    assert command[0] > 0.0
    assert np.sign(command[1]) == side


def _nearest(points: FloatArray, plan: FloatArray) -> FloatArray:
    gaps: FloatArray = np.hypot(
        points[:, np.newaxis, 0] - plan[np.newaxis, :, 0],
        points[:, np.newaxis, 1] - plan[np.newaxis, :, 1],
    ).min(axis=1)
    return gaps


@pytest.mark.parametrize(("goal_distance", "aligning"), [(0.3, False), (1.0, True)])
def test_the_alignment_critic_is_off_once_the_goal_is_nearer_than_forward_point_distance(
    goal_distance: float, aligning: bool
) -> None:
    """path_distance_bias weighs the end's distance to the plan, and, unless the goal is within
    forward_point_distance (0.325 m), the distance of the point that far ahead of the end."""
    around = straight_to((goal_distance, 0.0))
    scores = []
    for bias in (32.0, 40.0):
        local = planner(dataclasses.replace(SETTINGS, path_distance_bias=bias))
        rollouts = local.rollouts(ORIGIN, STANDING)
        scores.append(local.scores(rollouts, ORIGIN, around))
    per_bias = (scores[1] - scores[0]) / 8.0
    ends = rollouts.ends
    ahead = ends[:, :2] + 0.325 * np.column_stack([np.cos(ends[:, 2]), np.sin(ends[:, 2])])
    expected = _nearest(ends[:, :2], around.plan)
    if aligning:
        expected = expected + _nearest(ahead, around.plan)
    np.testing.assert_allclose(per_bias, expected, atol=1e-9)


# --- oscillation ---

SPIN_LEFT, SPIN_RIGHT = (0.0, 0.5), (0.0, -0.5)
# Standing, left and right; driving fast, left and right.
LINEAR = np.array([0.0, 0.0, 0.4, 0.4])
ANGULAR = np.array([0.5, -0.5, 0.5, -0.5])


def oscillating() -> Oscillation:
    """Flags after turning left on the spot and then right: only right is allowed."""
    flags = Oscillation(SETTINGS.oscillation_reset_dist, SETTINGS.oscillation_reset_angle)
    flags.record((0.0, 0.0, 0.0), SPIN_LEFT, SETTINGS.min_trans_vel)
    flags.record((0.0, 0.0, 0.05), SPIN_RIGHT, SETTINGS.min_trans_vel)
    return flags


def test_turning_back_the_other_way_on_the_spot_allows_only_the_latter_way() -> None:
    flags = Oscillation(SETTINGS.oscillation_reset_dist, SETTINGS.oscillation_reset_angle)
    flags.record((0.0, 0.0, 0.0), SPIN_LEFT, SETTINGS.min_trans_vel)
    assert flags.allowed(LINEAR, ANGULAR).all()  # one way alone restricts nothing
    flags.record((0.0, 0.0, 0.05), SPIN_RIGHT, SETTINGS.min_trans_vel)
    assert flags.allowed(LINEAR, ANGULAR).tolist() == [False, True, False, True]


def test_turning_while_driving_faster_than_min_trans_vel_is_no_oscillation() -> None:
    flags = Oscillation(SETTINGS.oscillation_reset_dist, SETTINGS.oscillation_reset_angle)
    flags.record((0.0, 0.0, 0.0), (0.3, 0.5), SETTINGS.min_trans_vel)
    flags.record((0.0, 0.0, 0.05), (0.3, -0.5), SETTINGS.min_trans_vel)
    assert flags.allowed(LINEAR, ANGULAR).all()


@pytest.mark.parametrize(
    ("pose", "lifted"),
    [
        ((0.0, 0.0, 0.05 - 0.19), False),  # turned 0.19 rad since the restriction began
        ((0.0, 0.0, 0.05 - 0.21), True),  # more than oscillation_reset_angle 0.2 rad
        ((0.0, 0.0, 0.05 + 0.21), True),  # either way
        ((0.03, 0.03, 0.05), False),  # moved 4.2 cm
        ((0.04, 0.04, 0.05), True),  # more than oscillation_reset_dist 5 cm
    ],
    ids=["turned 0.19", "turned 0.21", "turned back 0.21", "moved 4.2 cm", "moved 5.7 cm"],
)
def test_the_restriction_lasts_until_the_robot_has_turned_or_moved_far_enough(
    pose: tuple[float, float, float], lifted: bool
) -> None:
    flags = oscillating()
    flags.record(pose, SPIN_RIGHT, SETTINGS.min_trans_vel)
    assert bool(flags.allowed(LINEAR, ANGULAR)[0]) is lifted


def test_reset_lifts_the_restriction() -> None:
    flags = oscillating()
    flags.reset()
    assert flags.allowed(LINEAR, ANGULAR).all()


def test_reversing_the_way_of_driving_allows_only_the_new_way() -> None:
    flags = Oscillation(SETTINGS.oscillation_reset_dist, SETTINGS.oscillation_reset_angle)
    flags.record((0.0, 0.0, 0.0), (0.2, 0.0), SETTINGS.min_trans_vel)
    flags.record((0.01, 0.0, 0.0), (-0.2, 0.0), SETTINGS.min_trans_vel)
    allowed = flags.allowed(np.array([0.2, -0.2, 0.0]), np.zeros(3))
    assert allowed.tolist() == [False, True, True]


def test_the_planner_does_not_turn_back_the_way_an_oscillation_forbids() -> None:
    # A goal behind the left shoulder: free to choose, the robot turns left on the spot.
    behind_left = straight_to((-1.0, 2.0))
    free = planner().command(ORIGIN, STANDING, behind_left)
    assert free is not None
    assert free[1] > 0.0
    local = planner()
    local.oscillation = oscillating()
    command = local.command(ORIGIN, STANDING, behind_left)
    assert command is not None
    assert command[1] < 0.0


# --- where the planner once differed from dwa_local_planner ---


def test_a_sample_is_not_rejected_only_because_its_forward_point_nears_a_lethal_cell() -> None:
    lethal = (HALF_LENGTH + 0.25, 0.0)  # 0.25 m ahead of the front edge
    local = planner()
    rollouts = local.rollouts(ORIGIN, STANDING)
    slow = sample_index(rollouts, 0.1, 0.0)
    # Its footprint stays 8 cm short of the cell and its end 0.6 m from it; only the point
    # 0.325 m ahead of its end comes within the inscribed radius.
    assert not covers(rollouts.poses[slow], lethal, grow=0.05).any()
    scores = local.scores(rollouts, ORIGIN, straight_to((4.0, 0.0), np.array([lethal])))
    assert np.isfinite(scores[slow])


def test_the_scores_depend_on_the_local_plan_not_on_where_the_global_goal_lies_beyond_it() -> None:
    # The plan leaves the local window 4 m ahead; the goal lies far to the left beyond it.
    local = planner()
    rollouts = local.rollouts(ORIGIN, STANDING)
    beyond = local.scores(rollouts, ORIGIN, Surroundings(AHEAD, (4.0, 20.0), NOTHING))
    ahead = local.scores(rollouts, ORIGIN, Surroundings(AHEAD, (4.0, 0.0), NOTHING))
    np.testing.assert_allclose(beyond, ahead)


def test_no_footprint_grows_when_scaling_speed_is_above_every_sampled_speed() -> None:
    # A slow robot: 0.2 m/s at most, below the default scaling_speed 0.25 m/s.
    settings = dataclasses.replace(SETTINGS, max_vel_x=0.2, max_trans_vel=0.2, vx_samples=3)
    local = planner(settings)
    rollouts = local.rollouts(ORIGIN, STANDING)
    scores = local.scores(rollouts, ORIGIN, straight_to((4.0, 0.0), np.array([SIDE_CELL])))
    assert np.isfinite(scores[sample_index(rollouts, 0.2, 0.0)])


@pytest.mark.filterwarnings("ignore::RuntimeWarning")
def test_a_lethal_cell_in_the_way_still_rejects_when_scaling_speed_equals_max_trans_vel() -> None:
    # 0.2 m ahead of the front edge and 1 cm inside the left side: only the footprint meets it
    # (the end and the point ahead of it stay beyond the inscribed radius).
    lethal = (HALF_LENGTH + 0.2, HALF_WIDTH - 0.01)
    settings = dataclasses.replace(SETTINGS, scaling_speed=0.5)
    local = planner(settings)
    rollouts = local.rollouts(ORIGIN, STANDING)
    fast = sample_index(rollouts, 0.5, 0.0)
    assert covers(rollouts.poses[fast], lethal).any()
    scores = local.scores(rollouts, ORIGIN, straight_to((4.0, 0.0), np.array([lethal])))
    assert np.isinf(scores[fast])


@pytest.mark.parametrize("lift", ["reset", "turned"])
def test_after_the_restriction_is_lifted_one_turn_back_the_other_way_restricts_nothing(
    lift: str,
) -> None:
    flags = oscillating()  # left, then right: only right allowed
    if lift == "reset":
        flags.reset()  # as for a new plan
    else:
        flags.record((0.0, 0.0, -0.3), SPIN_RIGHT, SETTINGS.min_trans_vel)
    assert flags.allowed(LINEAR, ANGULAR).all()
    flags.record((0.0, 0.0, -0.3), SPIN_LEFT, SETTINGS.min_trans_vel)
    assert flags.allowed(LINEAR, ANGULAR).all()


@pytest.mark.parametrize("seed", range(5))
def test_the_compiled_rollouts_are_the_numpy_rollouts_to_the_bit(seed: int) -> None:
    rng = np.random.default_rng(seed)
    settings = dataclasses.replace(SETTINGS, vx_samples=int(rng.integers(3, 12)), min_vel_x=-0.2)
    planner = LocalPlanner(settings, FOOTPRINT, COST, HUSKY_PERIOD, RESOLUTION, WINDOW)
    for _ in range(10):
        pose = (float(rng.uniform(-5, 5)), float(rng.uniform(-5, 5)), float(rng.uniform(-4, 4)))
        speed = (float(rng.uniform(-0.2, 0.5)), float(rng.uniform(-1.0, 1.0)))
        rollouts = planner.rollouts(pose, speed)
        steps, dt = time_steps(planner.settings, rollouts.linear, rollouts.angular)
        expected = roll_out_in_numpy(pose, rollouts.linear, rollouts.angular, steps, dt)
        for ours, theirs in zip((rollouts.x, rollouts.y, rollouts.yaw), expected, strict=True):
            assert np.array_equal(ours.view(np.uint64), theirs.view(np.uint64))
