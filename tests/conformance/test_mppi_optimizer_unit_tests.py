"""nav2_mppi_controller's optimizer tests (optimizer_unit_tests.cpp), rebuilt on our `Optimizer`
(mppi.py) made from the test's parameters as a params file sets them (params.py), and on its
steps: `_reset`, `_shift`, `_constrain` (applyControlSequenceConstraints), `motion_model.predict`
(updateStateVelocities) and `motion_model.integrate` (integrateStateVelocities).

Not applicable: the Omni and Ackermann parts of every test (setMotionModel("Omni"/"Ackermann"),
getOptimizedTrajectory of an omni robot, vy everywhere, Omni_openLoopMppiTest; neither model
nor open_loop is imitated), isHolonomic, the motion model pointer checks, critics_data_'s goal
checker, and setSpeedLimit (speed limit zones are not imitated).
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np
import pytest

from pytest_lasertest.model.robot import ParameterValue
from pytest_lasertest.nav.nav2.motion_model import changes, integrate, predict
from pytest_lasertest.nav.nav2.mppi import F32, CriticData, Optimizer
from pytest_lasertest.nav.nav2.node_parameters import ParameterProblem
from tests.helpers.mppi import nav2_settings, optimizer, path_along_x
from tests.helpers.upstream import NAVIGATION2_JAZZY, NotPorted, Source

OPTIMIZER = Source(
    "Nav2 MPPI: optimizer",
    NAVIGATION2_JAZZY,
    "nav2_mppi_controller/test/optimizer_unit_tests.cpp",
)
NOT_PORTED: tuple[NotPorted, ...] = (
    NotPorted(
        OPTIMIZER,
        "OptimizerTests.BasicInitializedFunctions",
        1,
        "the generated trajectories are zeros before any cycle: ours keeps no trajectories "
        "between cycles, each cycle makes its own",
    ),
    NotPorted(
        OPTIMIZER,
        "OptimizerTests.resetTests",
        3,
        "reset zeroes the state's speeds, the costs and the generated trajectories: ours keeps "
        "none of them between cycles, each cycle makes them afresh",
    ),
)
# The parameters most of the tests set: mppic.batch_size, mppic.time_steps and the
# controller_frequency.
COMMON: Mapping[str, ParameterValue] = {
    "controller_frequency": 30.0,
    "FollowPath.batch_size": 1000,
    "FollowPath.time_steps": 50,
}
NO_CRITICS: Mapping[str, ParameterValue] = {"FollowPath.critics": ()}
# Sampling that leaves the sequence as it is (no noise to speak of, no control cost), for tests of
# what the optimizer does with its sequence around the sampling.
NO_SAMPLING: Mapping[str, ParameterValue] = {
    "FollowPath.vx_std": 1e-9,
    "FollowPath.wz_std": 1e-9,
    "FollowPath.gamma": 0.0,
    **NO_CRITICS,
}
POSE = (0.0, 0.0, 0.0)  # m, m, rad
PATH = path_along_x([0.0, 5.0])
GOAL = (5.0, 0.0)  # m


def built(parameters: Mapping[str, ParameterValue]) -> Optimizer:
    return optimizer({**COMMON, **NO_CRITICS, **parameters})


# BasicInitializedFunctions


@OPTIMIZER.test("OptimizerTests.BasicInitializedFunctions", assertions=1)
def test_a_positive_ax_min_is_read_as_a_deceleration() -> None:
    settings = nav2_settings({**COMMON, "FollowPath.ax_min": 3.0, "FollowPath.ay_min": 3.0})
    assert settings.mppi.ax_min == -3.0


@OPTIMIZER.test("OptimizerTests.BasicInitializedFunctions", assertions=2)
def test_the_trajectories_are_batch_size_by_time_steps() -> None:
    mppi = built({"FollowPath.ax_min": 3.0, "FollowPath.ay_min": 3.0})
    data = cycle_data(mppi)
    assert data.x.shape[0] == 1000
    assert data.x.shape[1] == 50


def cycle_data(mppi: Optimizer) -> CriticData:
    """What the critics are given in one cycle, the robot standing at the path's start."""
    recorder = Recorder()
    mppi.critics = (recorder,)
    mppi.command(POSE, (0.0, 0.0), PATH, GOAL)
    return recorder.last


class Recorder:
    """A critic that keeps what it is given, on entry, and leaves it used: the path's furthest
    point and validity found, the costs raised."""

    def __init__(self) -> None:
        self.seen: list[tuple[float, bool, int | None, bool, tuple[float, float, float], int]] = []

    def __call__(self, data: CriticData) -> None:
        self.last = data
        entry = (float(data.costs.sum()), data.fail, data.furthest, data.path_valid is None)
        self.seen.append((*entry, data.pose, len(data.path)))
        data.furthest_reached()
        data.path_points_valid()
        data.costs += 1.0


# TestOptimizerMotionModels


@OPTIMIZER.test("OptimizerTests.TestOptimizerMotionModels", assertions=1)
def test_the_differential_drive_model_is_accepted() -> None:
    assert isinstance(built({"FollowPath.motion_model": "DiffDrive"}), Optimizer)


@OPTIMIZER.test("OptimizerTests.TestOptimizerMotionModels", assertions=1)
def test_an_unknown_motion_model_is_refused() -> None:
    with pytest.raises(ParameterProblem, match="motion_model"):
        built({"FollowPath.motion_model": "Random"})


# setOffsetTests: model_dt 0.1 s. A ramp of speeds as the sequence, kept as it is by the
# sampling and too short (19 steps after the first) to be smoothed, shows which element is
# commanded and whether the sequence moves on.

RAMP = np.arange(20, dtype=np.float32) * np.float32(0.01)  # m/s


def offset(controller_frequency: float) -> Optimizer:
    return built(
        {
            "controller_frequency": controller_frequency,
            "FollowPath.model_dt": 0.1,
            "FollowPath.time_steps": 20,
            **NO_SAMPLING,
        }
    )


def ramp_cycle(mppi: Optimizer) -> tuple[float, F32]:
    """The speed commanded from the ramp, and the sequence after the cycle."""
    mppi.vx[:], mppi.wz[:] = RAMP, 0.0
    command = mppi.command(POSE, (0.0, 0.0), PATH, GOAL)
    assert command is not None
    return command[0], mppi.vx


@OPTIMIZER.test("OptimizerTests.setOffsetTests", assertions=1)
def test_a_controller_period_longer_than_model_dt_is_refused() -> None:
    with pytest.raises(ParameterProblem):
        offset(1.0)


@OPTIMIZER.test("OptimizerTests.setOffsetTests", assertions=1)
def test_a_controller_period_shorter_than_model_dt_is_accepted() -> None:
    assert isinstance(offset(30.0), Optimizer)


@OPTIMIZER.test("OptimizerTests.setOffsetTests", assertions=1)
def test_a_controller_period_shorter_than_model_dt_does_not_shift_the_sequence() -> None:
    command, sequence = ramp_cycle(offset(30.0))
    assert command == pytest.approx(RAMP[0], abs=1e-6)
    assert sequence == pytest.approx(RAMP, abs=1e-6)


@OPTIMIZER.test("OptimizerTests.setOffsetTests", assertions=2)
def test_a_controller_period_equal_to_model_dt_shifts_the_sequence() -> None:
    mppi = offset(10.0)  # accepted
    command, sequence = ramp_cycle(mppi)
    assert command == pytest.approx(RAMP[1], abs=1e-6)
    assert sequence[:-1] == pytest.approx(RAMP[1:], abs=1e-6)


# resetTests


@OPTIMIZER.test("OptimizerTests.resetTests", assertions=2)
def test_reset_zeroes_the_sequence_and_the_command_history() -> None:
    mppi = built({})
    # Garbage of the sequence's own length: ours is sized once, by time_steps.
    mppi.vx[:] = 342.0
    mppi.history[0] = (43.0, 32432.0)  # vx, wz
    mppi.reset()
    assert np.array_equal(mppi.vx, np.zeros(50, dtype=np.float32))
    assert mppi.history[0, 0] == 0.0


# FallbackTests: retry_attempt_limit 2.


class FailingFirst:
    """A critic that finds no valid sample in its first `failures` calls."""

    def __init__(self, failures: int) -> None:
        self.failures, self.calls = failures, 0

    def __call__(self, data: CriticData) -> None:
        self.calls += 1
        data.fail = self.calls <= self.failures


def fallback(failures: int) -> tuple[tuple[float, float] | None, int]:
    """The command of a cycle whose first `failures` attempts fail, and the attempts made."""
    mppi = built({"FollowPath.retry_attempt_limit": 2})
    critic = FailingFirst(failures)
    mppi.critics = (critic,)
    return mppi.command(POSE, (0.0, 0.0), PATH, GOAL), critic.calls


@OPTIMIZER.test("OptimizerTests.FallbackTests", assertions=1)
def test_a_cycle_that_does_not_fail_is_not_retried() -> None:
    command, attempts = fallback(0)
    assert command is not None
    assert attempts == 1


@OPTIMIZER.test("OptimizerTests.FallbackTests", assertions=2)
def test_a_failing_cycle_is_retried_retry_attempt_limit_times() -> None:
    command, attempts = fallback(2)
    assert command is not None
    assert attempts == 3


@OPTIMIZER.test("OptimizerTests.FallbackTests", assertions=1)
def test_failing_past_retry_attempt_limit_gives_no_command() -> None:
    command, _ = fallback(3)
    assert command is None


# PrepareTests: the robot at (999, 0), a path of 17 poses.


@OPTIMIZER.test("OptimizerTests.PrepareTests", assertions=6)
def test_each_cycle_starts_from_the_robots_pose_and_path_with_its_findings_reset() -> None:
    mppi = built({"FollowPath.retry_attempt_limit": 2})
    recorder = Recorder()
    mppi.critics = (recorder,)
    path = np.zeros((17, 2), dtype=np.float32)
    for _ in range(2):  # the second cycle after a first that left its data used
        mppi.command((999.0, 0.0, 0.0), (0.0, 0.0), path, (0.0, 0.0))
    costs, fail, furthest, validity_unknown, pose, points = recorder.seen[-1]
    assert costs == pytest.approx(0.0, abs=1e-6)
    assert not fail
    assert furthest is None
    assert validity_unknown
    assert pose[0] == 999.0
    assert points == 17


# shiftControlSequenceTests


@OPTIMIZER.test("OptimizerTests.shiftControlSequenceTests", assertions=6)
def test_shifting_moves_the_sequence_one_step_on() -> None:
    mppi = built({"FollowPath.retry_attempt_limit": 2})
    mppi.vx, mppi.wz = (np.zeros(100, dtype=np.float32) for _ in range(2))
    for sequence in (mppi.vx, mppi.wz):
        sequence[:3] = (9999.0, 6.0, 888.0)
    mppi._shift()  # shiftControlSequence, which a cycle ends with
    for sequence in (mppi.vx, mppi.wz):
        assert sequence[0] == 6.0
        assert sequence[1] == 888.0
        assert sequence[2] == 0.0


# SpeedLimitTests


@OPTIMIZER.test("OptimizerTests.SpeedLimitTests", assertions=2)
def test_the_speed_limits_default_to_0_5_and_minus_0_35() -> None:
    settings = nav2_settings({**COMMON, "FollowPath.retry_attempt_limit": 2}).mppi
    assert np.float32(settings.vx_max) == np.float32(0.5)
    assert np.float32(settings.vx_min) == np.float32(-0.35)


# applyControlSequenceConstraintsTests: vx from -1 to 1 m/s, wz up to 2 rad/s either way.


def constrained(vx: float, wz: float) -> tuple[F32, F32]:
    mppi = built(
        {
            "FollowPath.vx_max": 1.0,
            "FollowPath.vx_min": -1.0,
            "FollowPath.vy_max": 0.75,
            "FollowPath.wz_max": 2.0,
        }
    )
    mppi.vx[:], mppi.wz[:] = vx, wz
    mppi._constrain()  # applyControlSequenceConstraints, which each update ends with
    return mppi.vx, mppi.wz


@OPTIMIZER.test("OptimizerTests.applyControlSequenceConstraintsTests", assertions=6)
def test_the_sequence_is_clipped_to_the_speed_limits() -> None:
    # At the limits, beyond them, and beyond them the other way.
    for asked, limits in (
        ((1.0, 2.0), (1.0, 2.0)),
        ((5.0, 5.0), (1.0, 2.0)),
        ((-5.0, -5.0), (-1.0, -2.0)),
    ):
        vx, wz = constrained(*asked)
        assert np.array_equal(vx, np.full(50, limits[0], dtype=np.float32))
        assert np.array_equal(wz, np.full(50, limits[1], dtype=np.float32))


# updateStateVelocitiesTests: accelerations 3 m/s^2 and 3.5 rad/s^2, model_dt 0.05 s.

ACCELERATIONS: Mapping[str, ParameterValue] = {
    "FollowPath.vx_max": 1.0,
    "FollowPath.vx_min": -1.0,
    "FollowPath.vy_max": 0.60,
    "FollowPath.wz_max": 2.0,
    "FollowPath.ax_max": 3.0,
    "FollowPath.ax_min": -3.0,
    "FollowPath.ay_max": 3.0,
    "FollowPath.ay_min": -3.0,
    "FollowPath.az_max": 3.5,
}


class Predicted:
    """Each sample's speeds from the robot's speed (vx, wz) on, under constant controls."""

    def __init__(self, speed: tuple[float, float], controls: tuple[float, float]) -> None:
        s = nav2_settings({**COMMON, **ACCELERATIONS}).mppi
        shape = (s.time_steps, s.batch_size)  # time first
        cvx = np.full(shape, controls[0], dtype=np.float32)
        cwz = np.full(shape, controls[1], dtype=np.float32)
        change = changes(s.model_dt, s.ax_max, s.ax_min, s.az_max)
        self.vx, self.wz = predict(cvx, cwz, speed, change)
        # The largest changes a step, in float as the test works them out.
        step = np.float32(s.model_dt)
        self.vx_up, self.vx_down = np.float32(s.ax_max) * step, np.float32(s.ax_min) * step
        self.wz_change = np.float32(s.az_max) * step


@OPTIMIZER.test("OptimizerTests.updateStateVelocitiesTests", assertions=6)
def test_each_samples_first_speeds_are_the_robots() -> None:
    # The test reads them after updateInitialStateVelocities and again after the propagation;
    # ours does both in one step (motion_model.predict), so that each check here stands for both.
    forward = Predicted((5.0, 6.0), (0.75, 0.1))
    assert forward.vx[0, 0] == pytest.approx(5.0, abs=1e-6)
    assert forward.wz[0, 0] == pytest.approx(6.0, abs=1e-6)
    reverse = Predicted((-5.0, -6.0), (-0.75, -0.1))
    assert reverse.vx[0, 0] == pytest.approx(-5.0, abs=1e-6)
    assert reverse.wz[0, 0] == pytest.approx(-6.0, abs=1e-6)


@OPTIMIZER.test("OptimizerTests.updateStateVelocitiesTests", assertions=4)
def test_each_next_speed_is_the_control_bounded_by_the_accelerations() -> None:
    forward = Predicted((5.0, 6.0), (0.75, 0.1))
    high = min(max(0.75, 5.0 + forward.vx_down), 5.0 + forward.vx_up)
    assert forward.vx[1, 0] == pytest.approx(high, abs=1e-6)
    turn = min(max(0.1, 6.0 - forward.wz_change), 6.0 + forward.wz_change)
    assert forward.wz[1, 0] == pytest.approx(turn, abs=1e-6)
    reverse = Predicted((-5.0, -6.0), (-0.75, -0.1))
    low = min(max(-0.75, -5.0 + reverse.vx_down), -5.0 + reverse.vx_up)
    assert reverse.vx[1, 0] == pytest.approx(low, abs=1e-6)
    turn = min(max(-0.1, -6.0 - reverse.wz_change), -6.0 + reverse.wz_change)
    assert reverse.wz[1, 0] == pytest.approx(turn, abs=1e-6)


# getControlFromSequenceAsTwistTests: a constant sequence of 10 steps (the test's own length).


@OPTIMIZER.test("OptimizerTests.getControlFromSequenceAsTwistTests", assertions=2)
def test_the_command_is_read_from_the_sequence() -> None:
    mppi = built(
        {
            "FollowPath.time_steps": 10,
            "FollowPath.vx_max": 1.0,
            "FollowPath.vx_min": -1.0,
            "FollowPath.vy_max": 0.60,
            "FollowPath.wz_max": 2.0,
            **NO_SAMPLING,
        }
    )
    mppi.vx[:], mppi.wz[:] = 0.25, 0.1
    # The robot already at those speeds, so that no acceleration limit moves them.
    command = mppi.command(POSE, (0.25, 0.1), PATH, GOAL)
    assert command is not None
    assert command[0] == pytest.approx(0.25, abs=1e-6)
    assert command[1] == pytest.approx(0.1, abs=1e-6)


# integrateStateVelocitiesTests: model_dt 0.1 s, from (0, 0) heading along x; every sample
# drives at 0.1 m/s after its first step, and turns at 0.2 rad/s after it in the last part.


def integrated(wz: float) -> tuple[F32, F32, F32]:
    s = nav2_settings({**COMMON, "FollowPath.model_dt": 0.1}).mppi
    vx = np.full((s.time_steps, s.batch_size), 0.1, dtype=np.float32)  # time first
    turns = np.full_like(vx, wz)
    vx[0] = turns[0] = 0.0
    return integrate(vx, turns, POSE, s.model_dt)


@OPTIMIZER.test("OptimizerTests.integrateStateVelocitiesTests", assertions=3)
def test_driving_straight_moves_along_x_only() -> None:
    x, y, yaw = integrated(0.0)
    assert not y.any()
    assert not yaw.any()
    for step in range(50):  # sample 1, as the test reads traj.x(1, i)
        assert x[step, 1] == pytest.approx(step * 0.1 * 0.1, abs=1e-3)


@OPTIMIZER.test("OptimizerTests.integrateStateVelocitiesTests", assertions=2)
def test_each_step_moves_along_the_heading_of_the_step_before() -> None:
    x, y, _ = integrated(0.2)
    expected_x = expected_y = 0.0
    for step in range(1, 50):
        heading = 0.2 * 0.1 * (step - 1)  # rad
        expected_x += 0.1 * np.cos(heading) * 0.1
        expected_y += 0.1 * np.sin(heading) * 0.1
        assert x[step, 1] == pytest.approx(expected_x, abs=1e-6)
        assert y[step, 1] == pytest.approx(expected_y, abs=1e-6)
