"""DWB's tests of the StandardTrajectoryGenerator (dwb_plugins/test/twist_gen.cpp): its twists
(getTwists, XYThetaIterator) on our `dwb_trajectories.sample_twists`, and its trajectories
(generateTrajectory) on our `dwb_trajectories.roll_out`, with `DwbSettings` read from a params file
that sets what the upstream test node sets (`params.configure`, FollowPath as DWB), so that whatever
the test leaves at its code default takes ours; those it reads agree (sim_time 1.7 s, vx_samples and
vtheta_samples 20, angular_granularity 0.025 rad). The assertions of checkLimits, matchPose and
matchTwist count once per call.

The imitation is a differential drive: the upstream test node's y limits are left out (y is 0
alone), so each twist set here is the upstream one's y = 0 part, and the limits on x and theta
(and the greatest speed, where no twist with y reaches it) stay those upstream asserts. Where a
test turns a speed limit off with -1, the params file sets -1, which Nav2 reads as "no limit"
(xy_theta_iterator.cpp:99-104). Upstream's time_granularity steps are made with a
linear_granularity giving the same steps.

Not applicable: the assertions on y and on speeds that include y (each test's min_y and max_y;
max_xy's, no_limits' and no_limits_samples' greatest speed hypot(0.55, 0.1)), each matchTwist's
y, the holonomic and twisty trajectories (lateral commands), every time_offsets assertion (our
trajectories hold poses, no time offsets, which only RotateToGoal's projectPose reads, not
imitated), and the LimitedAccelGenerator's tests (dwa_gen*, nonzero, dwa: not imitated)."""

from __future__ import annotations

import dataclasses
import struct

import numpy as np

from pytest_lasertest.model.robot import ParameterValue
from pytest_lasertest.nav.nav2.dwb_critics import F64
from pytest_lasertest.nav.nav2.dwb_settings import DwbSettings
from pytest_lasertest.nav.nav2.dwb_trajectories import roll_out, sample_twists
from tests.helpers.dwb import dwb_settings
from tests.helpers.upstream import NAVIGATION2_HUMBLE, NotPorted, Source

PATH = "nav2_dwb_controller/dwb_plugins/test/twist_gen.cpp"
TWISTS = Source("Nav2 DWB: velocity iterator", NAVIGATION2_HUMBLE, PATH)
TRAJECTORIES = Source("Nav2 DWB: trajectory generator", NAVIGATION2_HUMBLE, PATH)

_HOLONOMIC_COUNT = (
    "counts the twists over vy_samples (5) y velocities from -0.1 to 0.1 m/s; the imitation is "
    "a differential drive (y is 0 alone), and upstream gives no count of the y = 0 part"
)
NOT_PORTED = (
    NotPorted(TWISTS, "VelocityIterator.standard_gen", 1, _HOLONOMIC_COUNT + " (1926)"),
    NotPorted(TWISTS, "VelocityIterator.max_xy", 1, _HOLONOMIC_COUNT + " (2010)"),
    NotPorted(TWISTS, "VelocityIterator.min_xy", 1, _HOLONOMIC_COUNT + " (2015)"),
    NotPorted(TWISTS, "VelocityIterator.min_theta", 1, _HOLONOMIC_COUNT + " (2015)"),
)

# getDefaultKinematicParameters, less the y limits.
KINEMATICS: dict[str, ParameterValue] = {
    "min_vel_x": 0.0,  # m/s
    "max_vel_x": 0.55,  # m/s
    "max_vel_theta": 1.0,  # rad/s
    "acc_lim_x": 2.5,  # m/s^2
    "acc_lim_theta": 3.2,  # rad/s^2
    "decel_lim_x": -2.5,  # m/s^2
    "decel_lim_theta": -3.2,  # rad/s^2
    "min_speed_xy": 0.1,  # m/s
    "max_speed_xy": 0.55,  # m/s
    "min_speed_theta": 0.4,  # rad/s
}
SIM_TIME = 1.7  # s, upstream's DEFAULT_SIM_TIME
FORWARD = 0.3  # m/s, upstream's `forward`
NO_LIMIT = -1.0


def follow_path(**overrides: ParameterValue) -> DwbSettings:
    """DWB's settings from a params file setting the upstream test node's parameters."""
    return dwb_settings(KINEMATICS | overrides)


def double_eq(a: float, b: float) -> bool:
    """gtest's EXPECT_DOUBLE_EQ: at most 4 units in the last place apart."""
    return abs(_biased(a) - _biased(b)) <= 4


def _biased(value: float) -> int:
    """The float's bits as gtest orders them: negative below positive, -0 equal to 0."""
    bits: int = struct.unpack("<Q", struct.pack("<d", value))[0]
    magnitude = bits & ((1 << 63) - 1)
    return (1 << 63) - magnitude if bits >> 63 else (1 << 63) + magnitude


# The twists (getTwists from standstill).


@dataclasses.dataclass(frozen=True)
class Twists:
    vx: F64  # (K,) m/s
    theta: F64  # (K,) rad/s


def twists(settings: DwbSettings) -> Twists:
    vx, theta = sample_twists(settings, (0.0, 0.0))
    return Twists(vx, theta)


def check_limits(found: Twists, max_x: float = 0.55) -> None:
    """checkLimits' assertions on x and theta: some twist, x from 0 to 0.55 m/s, theta from
    -1 to 1 rad/s."""
    assert len(found.vx) > 0
    assert double_eq(float(found.vx.min()), 0.0)
    assert double_eq(float(found.vx.max()), max_x)
    assert double_eq(float(found.theta.min()), -1.0)
    assert double_eq(float(found.theta.max()), 1.0)


def slow_twists_turn(found: Twists, min_xy: float, min_theta: float) -> bool:
    """checkLimits' check that no twist is below both minimum speeds."""
    return bool(((np.abs(found.theta) >= min_theta) | (np.abs(found.vx) >= min_xy)).all())


@TWISTS.test("VelocityIterator.standard_gen", assertions=7)
def test_the_twists_span_the_limits_and_none_is_below_both_minimum_speeds() -> None:
    found = twists(follow_path())
    check_limits(found)
    assert slow_twists_turn(found, 0.1, 0.4)
    assert double_eq(float(np.abs(found.vx).max()), 0.55)  # the greatest speed


@TWISTS.test("VelocityIterator.max_xy", assertions=5)
def test_a_speed_limit_beyond_the_velocities_limits_nothing() -> None:
    check_limits(twists(follow_path(max_speed_xy=1.0)))


@TWISTS.test("VelocityIterator.min_xy", assertions=5)
def test_without_a_least_speed_the_twists_still_span_the_limits() -> None:
    check_limits(twists(follow_path(min_speed_xy=NO_LIMIT)))


@TWISTS.test("VelocityIterator.min_theta", assertions=5)
def test_without_a_least_turn_the_twists_still_span_the_limits() -> None:
    check_limits(twists(follow_path(min_speed_theta=NO_LIMIT)))


# The three speed limits off, as the upstream tests turn them off.
UNLIMITED = dict.fromkeys(("max_speed_xy", "min_speed_xy", "min_speed_theta"), NO_LIMIT)


@TWISTS.test("VelocityIterator.no_limits", assertions=7)
def test_without_speed_limits_every_sample_is_a_twist_but_standing_still() -> None:
    found = twists(follow_path(**UNLIMITED))
    vx_samples, vtheta_samples, vy_samples = 20, 20, 1  # upstream's defaults; one y here
    # Upstream's count: every combination, a zero theta put in for each (x, y) (20 samples
    # from -1 to 1 rad/s miss 0), less (0, 0, 0).
    assert len(found.vx) == vx_samples * vtheta_samples * vy_samples + vx_samples * vy_samples - 1
    check_limits(found)
    assert slow_twists_turn(found, 0.0, 0.0)


@TWISTS.test("VelocityIterator.no_limits_samples", assertions=7)
def test_without_speed_limits_the_twists_are_the_samples_combined() -> None:
    x_samples, theta_samples, y_samples = 10, 5, 1  # upstream's 3 y samples: one here
    found = twists(follow_path(vx_samples=x_samples, vtheta_samples=theta_samples, **UNLIMITED))
    # 5 samples from -1 to 1 rad/s hit 0: nothing is put in.
    assert len(found.vx) == x_samples * y_samples * theta_samples - 1
    check_limits(found)
    assert slow_twists_turn(found, 0.0, 0.0)


# The trajectories (generateTrajectory from the origin).


@dataclasses.dataclass(frozen=True)
class Trajectory:
    vx: float  # m/s, the command it is scored for
    theta: float  # rad/s
    poses: list[tuple[float, float, float]]  # (x m, y m, yaw rad), the start first


def trajectory(settings: DwbSettings, start: float, command: float) -> Trajectory:
    """One trajectory from the origin at `start` m/s toward `command` m/s, no turn."""
    rollouts = roll_out(settings, (0.0, 0.0, 0.0), (start, 0.0), np.array([command]), np.zeros(1))
    poses = list(
        zip(rollouts.x[0].tolist(), rollouts.y[0].tolist(), rollouts.yaw[0].tolist(), strict=True)
    )
    return Trajectory(float(rollouts.vx[0]), float(rollouts.wz[0]), poses)


def at(pose: tuple[float, float, float], x: float, y: float, yaw: float) -> bool:
    """matchPose: each of x, y and yaw DOUBLE_EQ."""
    return double_eq(pose[0], x) and double_eq(pose[1], y) and double_eq(pose[2], yaw)


def is_for(found: Trajectory, vx: float, theta: float) -> bool:
    """matchTwist's x and theta: the trajectory is scored for the command it was made for."""
    return double_eq(found.vx, vx) and double_eq(found.theta, theta)


@TRAJECTORIES.test("TrajectoryGenerator.basic", assertions=9)
def test_a_trajectory_at_constant_speed_ends_sim_time_times_the_speed_ahead() -> None:
    found = trajectory(follow_path(linear_granularity=0.5), FORWARD, FORWARD)
    assert is_for(found, FORWARD, 0.0)
    assert len(found.poses) > 0
    assert at(found.poses[0], 0.0, 0.0, 0.0)
    # poses[n - 1], the repeat of the last step's pose.
    assert at(found.poses[-1], SIM_TIME * FORWARD, 0.0, 0.0)


@TRAJECTORIES.test("TrajectoryGenerator.basic", assertions=1)
def test_a_trajectory_of_two_steps_has_four_poses() -> None:
    # 0.51 m at most 0.5 m a step: 2 steps.
    assert len(trajectory(follow_path(linear_granularity=0.5), FORWARD, FORWARD).poses) == 4


@TRAJECTORIES.test("TrajectoryGenerator.basic_no_last_point", assertions=10)
def test_without_the_repeated_last_pose_a_trajectory_of_two_steps_has_three_poses() -> None:
    found = trajectory(
        follow_path(linear_granularity=0.5, include_last_point=False), FORWARD, FORWARD
    )
    assert is_for(found, FORWARD, 0.0)
    assert len(found.poses) == 3
    assert len(found.poses) > 0
    assert at(found.poses[0], 0.0, 0.0, 0.0)
    assert at(found.poses[-2], 0.255, 0.0, 0.0)  # halfway, after the first step


@TRAJECTORIES.test("TrajectoryGenerator.too_slow", assertions=6)
def test_a_trajectory_shorter_than_a_step_starts_at_the_start() -> None:
    found = trajectory(follow_path(linear_granularity=0.5), 0.2, 0.2)
    assert is_for(found, 0.2, 0.0)
    assert len(found.poses) > 0
    assert at(found.poses[0], 0.0, 0.0, 0.0)


@TRAJECTORIES.test("TrajectoryGenerator.too_slow", assertions=1)
def test_a_trajectory_shorter_than_a_step_has_three_poses() -> None:
    # 0.34 m, under the 0.5 m of a step: one step.
    assert len(trajectory(follow_path(linear_granularity=0.5), 0.2, 0.2).poses) == 3


@TRAJECTORIES.test("TrajectoryGenerator.sim_time", assertions=9)
def test_a_longer_sim_time_makes_a_longer_trajectory() -> None:
    sim_time = 2.5  # s
    found = trajectory(follow_path(sim_time=sim_time, linear_granularity=0.5), FORWARD, FORWARD)
    assert is_for(found, FORWARD, 0.0)
    assert len(found.poses) > 0
    assert at(found.poses[0], 0.0, 0.0, 0.0)
    # poses[n - 2], n = 4: the last step's pose.
    assert at(found.poses[2], sim_time * FORWARD, 0.0, 0.0)


@TRAJECTORIES.test("TrajectoryGenerator.sim_time", assertions=1)
def test_a_trajectory_of_two_longer_steps_has_four_poses() -> None:
    settings = follow_path(sim_time=2.5, linear_granularity=0.5)
    assert len(trajectory(settings, FORWARD, FORWARD).poses) == 4


def accelerating() -> DwbSettings:
    """Upstream's accel node: 5 s in steps of 1 s (discretize_by_time, time_granularity 1),
    which ceil(0.3 m/s x 5 s / 0.31 m) = 5 steps by distance make here; x accelerates at
    0.1 m/s^2. Its min_speed_xy of -1 only matters to the twists."""
    return follow_path(sim_time=5.0, linear_granularity=0.31, acc_lim_x=0.1)


@TRAJECTORIES.test("TrajectoryGenerator.accel", assertions=20)
def test_a_trajectory_from_standstill_accelerates_at_the_limit() -> None:
    found = trajectory(accelerating(), 0.0, FORWARD)
    assert is_for(found, FORWARD, 0.0)
    # 0.1, 0.2, then 0.3 m/s for 1 s each.
    expected = [0.0, 0.1, 0.3, 0.6, 0.9, 1.2]
    assert all(at(found.poses[i], x, 0.0, 0.0) for i, x in enumerate(expected))


@TRAJECTORIES.test("TrajectoryGenerator.accel", assertions=1)
def test_a_trajectory_of_five_steps_has_seven_poses() -> None:
    assert len(trajectory(accelerating(), 0.0, FORWARD).poses) == 7
