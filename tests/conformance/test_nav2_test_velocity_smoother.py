"""nav2_velocity_smoother's unit tests (test/test_velocity_smoother.cpp), rebuilt on our
`VelocitySmoother` made from a params file by `params.configure`: a tick's step toward the
command, bounded by the acceleration or the deceleration limit over 20 Hz, the velocity limit,
and the parameters configure refuses.

Not applicable: approxClosedLoopTestTimer and testClosedLoopSub (CLOSED_LOOP feedback), the
message counts and the final stop of openLoopTestTimer (a wall timer spun for 1.5 s, and the
stop of a command stream that timed out: the stacks here command every cycle, and params.py
refuses a velocity_timeout they could outlast), testCommandCallback and testDynamicParameter
(topics and parameter services).
"""

from __future__ import annotations

import math

import pytest

from pytest_lasertest.model.robot import ParameterValue
from pytest_lasertest.nav.nav2.node_parameters import ParameterProblem
from pytest_lasertest.nav.nav2.velocity_smoother import (
    VelocitySmoother,
    apply_constraints,
    eta_constraint,
)
from tests.helpers.nav2_params import nav2_settings
from tests.helpers.upstream import NAVIGATION2_JAZZY, Source

SMOOTHER = Source(
    "Nav2 velocity smoother",
    NAVIGATION2_JAZZY,
    "nav2_velocity_smoother/test/test_velocity_smoother.cpp",
)
# The upstream tests' limits: slow to speed up, ten times faster to slow down.
ACCEL = 0.1  # m/s^2
DECEL = -1.0  # m/s^2
FREQUENCY = 20.0  # Hz, smoothing_frequency's default, which the upstream tests rely on
DV_ACCEL = ACCEL / FREQUENCY  # m/s per tick
DV_DECEL = -DECEL / FREQUENCY  # m/s per tick


def smoother(**parameters: ParameterValue) -> VelocitySmoother:
    """Our smoother as a params file setting only `parameters` for velocity_smoother makes it."""
    settings = nav2_settings({"velocity_smoother": parameters})
    return VelocitySmoother(settings.smoother)


def limited(accel: float, decel: float) -> VelocitySmoother:
    """A smoother with these limits on x, as applyConstraints takes them. The upstream tests call
    applyConstraints directly, past the clamp to max_velocity, so the velocity limits are set
    out of their way (up to 2 m/s)."""
    return smoother(
        max_accel=(accel, 0.0, accel),
        max_decel=(decel, 0.0, decel),
        max_velocity=(10.0, 0.0, 10.0),
        min_velocity=(-10.0, 0.0, -10.0),
    )


def ticks(smoothing: VelocitySmoother, start: float, target: float, count: int) -> list[float]:
    """The forward speed (m/s) after each of `count` ticks from `start` toward `target`. Each call
    is one tick: the clock moves a whole second, past the 20 Hz timer's next tick, and a tick's
    change is the limit over smoothing_frequency whatever the time between ticks."""
    smoothing.last = (start, 0.0)
    return [smoothing.step((target, 0.0), float(tick))[0] for tick in range(1, count + 1)]


def applied(start: float, target: float, accel: float, decel: float) -> float:
    """applyConstraints(start, target, accel, decel, eta = 1): one tick's output (m/s)."""
    return ticks(limited(accel, decel), start, target, 1)[0]


@SMOOTHER.test("VelocitySmootherTest.testapplyConstraints", assertions=4)
def test_a_command_within_a_tick_s_change_is_output_and_one_beyond_it_is_limited() -> None:
    assert applied(1.0, 1.0, 1.5, -2.0) == 1.0
    assert applied(0.5, 0.55, 1.5, -2.0) == 0.55
    assert applied(0.5, 0.45, 1.5, -2.0) == 0.45
    assert applied(1.0, 2.0, 1.5, -2.0) == pytest.approx(1.075, abs=0.01)  # 1.5 / 20 Hz more


def _steps(distance: float, per_tick: float) -> int:
    """How many whole ticks cover `distance` (m/s), as the upstream tests count them (uint)."""
    return int(distance / per_tick)


@pytest.mark.parametrize(
    ("start", "target"),
    [
        pytest.param(
            1.0,
            2.0,
            marks=SMOOTHER.test(
                "VelocitySmootherTest.testapplyConstraintsPositiveToPositiveAccel", assertions=3
            ),
        ),
        pytest.param(
            0.0,
            2.0,
            marks=SMOOTHER.test(
                "VelocitySmootherTest.testapplyConstraintsZeroToPositiveAccel", assertions=3
            ),
        ),
        pytest.param(
            -1.0,
            -2.0,
            marks=SMOOTHER.test(
                "VelocitySmootherTest.testapplyConstraintsNegativeToNegativeAccel", assertions=3
            ),
        ),
        pytest.param(
            0.0,
            -2.0,
            marks=SMOOTHER.test(
                "VelocitySmootherTest.testapplyConstraintsZeroToNegativeAccel", assertions=3
            ),
        ),
        pytest.param(
            2.0,
            1.0,
            marks=SMOOTHER.test(
                "VelocitySmootherTest.testapplyConstraintsPositiveToPositiveDecel", assertions=3
            ),
        ),
        pytest.param(
            2.0,
            0.0,
            marks=SMOOTHER.test(
                "VelocitySmootherTest.testapplyConstraintsPositiveToZeroDecel", assertions=3
            ),
        ),
        pytest.param(
            -2.0,
            -1.0,
            marks=SMOOTHER.test(
                "VelocitySmootherTest.testapplyConstraintsNegativeToNegativeDecel", assertions=3
            ),
        ),
        pytest.param(
            -2.0,
            0.0,
            marks=SMOOTHER.test(
                "VelocitySmootherTest.testapplyConstraintsNegativeToZeroDecel", assertions=3
            ),
        ),
    ],
)
def test_a_command_on_the_same_side_of_zero_is_reached_a_limit_s_step_per_tick(
    start: float, target: float
) -> None:
    # Speeding up (a larger magnitude, same sign) takes max_accel's steps, slowing max_decel's.
    per_tick = DV_ACCEL if abs(target) >= abs(start) else DV_DECEL
    direction = math.copysign(1.0, target - start)
    count = _steps(abs(target - start), per_tick)
    speeds = ticks(limited(ACCEL, DECEL), start, target, count + 1)
    for tick, speed in enumerate(speeds[:count], start=1):
        assert speed == pytest.approx(start + direction * tick * per_tick, abs=0.001)
    assert speeds[count - 1] == pytest.approx(target, abs=0.001)
    assert speeds[count] == pytest.approx(target, abs=0.001)  # and holds there


@pytest.mark.parametrize(
    "start",
    [
        pytest.param(
            -1.0,
            marks=SMOOTHER.test(
                "VelocitySmootherTest.testapplyConstraintsNegativeToPositiveDecelAccel",
                assertions=4,
            ),
        ),
        pytest.param(
            1.0,
            marks=SMOOTHER.test(
                "VelocitySmootherTest.testapplyConstraintsPositiveToNegativeDecelAccel",
                assertions=4,
            ),
        ),
    ],
)
def test_a_command_across_zero_slows_by_the_deceleration_then_speeds_up_by_the_acceleration(
    start: float,
) -> None:
    target = -2.0 * start  # 2 m/s the other way
    direction = math.copysign(1.0, target)
    to_zero = _steps(abs(start), DV_DECEL)
    from_zero = _steps(abs(target), DV_ACCEL)
    speeds = ticks(limited(ACCEL, DECEL), start, target, to_zero + from_zero + 1)
    for tick, speed in enumerate(speeds[: to_zero + from_zero], start=1):
        if speed * direction > 0.0:  # past zero, speeding up toward the command
            assert speed == pytest.approx(direction * (tick - to_zero) * DV_ACCEL, abs=0.001)
        else:  # still slowing down toward zero
            assert speed == pytest.approx(start + direction * tick * DV_DECEL, abs=0.001)
    assert speeds[-2] == pytest.approx(target, abs=0.001)
    assert speeds[-1] == pytest.approx(target, abs=0.001)


@SMOOTHER.test("VelocitySmootherTest.openLoopTestTimer", assertions=2)
def test_no_output_is_above_max_velocity_nor_within_the_deadband() -> None:
    # max_velocity is left out: Nav2's default 0.5 m/s (velocity_smoother.cpp:65) is ours too.
    smoothing = smoother(scale_velocities=True, deadband_velocity=(0.2, 0.0, 0.0))
    outputs = []
    for millisecond in range(1500):  # spun for 1.5 s, the 20 Hz timer ticking as it comes due
        time = millisecond / 1000.0  # s
        if smoothing.due(time):
            outputs.append(smoothing.step((1.0, 0.0), time)[0])
    # The first output that is not 0 is above the deadband: the ramp's 0.125 m/s a tick is
    # published as 0, and the next tick starts from 0.125 m/s all the same.
    assert next(speed for speed in outputs if speed != 0.0) > 0.2
    assert max(outputs) <= 0.5


# findEtaConstraint(v_curr, v_cmd) with accel 0.1 and decel -1.0 m/s^2 at 20 Hz (dv 0.005 and
# 0.05 m/s a tick): -1 within a tick's change, else the factor that brings the change to it.
ETA = SMOOTHER.test("VelocitySmootherTest.testfindEtaConstraint", assertions=1)
ETA_CASES = [
    # In range: constant, speeding up and slowing down on either side of 0, through 0.
    *[
        (current, wanted, -1.0)
        for current, wanted in [
            (1.0, 1.0), (-1.0, -1.0), (0.5, 0.504), (0.5, 0.46), (0.0, 0.004), (0.04, 0.0),
            (-0.5, -0.504), (-0.5, -0.46), (0.0, -0.004), (-0.04, 0.0), (-0.02, 0.02),
            (0.02, -0.02),
        ]
    ],
    # Faster than a tick allows.
    (0.5, 1.5, 0.005), (1.5, 0.5, 0.05), (0.0, 1.0, 0.005), (1.0, 0.0, 0.05),
    (-0.5, -1.5, 0.005), (-1.5, -0.5, 0.05), (0.0, -1.0, 0.005), (-1.0, 0.0, 0.05),
    (-0.2, 0.8, 0.05), (0.2, -0.8, 0.05),
]  # fmt: skip


@pytest.mark.parametrize(
    ("current", "wanted", "eta"), [pytest.param(*case, marks=ETA) for case in ETA_CASES]
)
def test_the_factor_on_a_change_beyond_a_tick_s_limit_brings_it_to_the_limit(
    current: float, wanted: float, eta: float
) -> None:
    assert eta_constraint(current, wanted, (ACCEL, DECEL), FREQUENCY) == eta


@SMOOTHER.test("VelocitySmootherTest.testapplyConstraints", assertions=3)
def test_a_change_scaled_by_eta_is_output_within_the_tick_s_limit() -> None:
    # accel 1.5 and decel -2.0 m/s^2 at 20 Hz: 0.075 m/s a tick speeding up.
    assert apply_constraints(1.0, 2.0, (1.5, -2.0), FREQUENCY, 0.075) == pytest.approx(
        1.075, abs=0.01
    )
    assert apply_constraints(0.5, 0.55, (1.5, -2.0), FREQUENCY, 0.075) == pytest.approx(
        0.503, abs=0.01
    )
    assert apply_constraints(0.8, 1.0, (3.2, -3.2), FREQUENCY, 0.75) == pytest.approx(
        1.075, abs=0.95
    )


INVALID = SMOOTHER.test("VelocitySmootherTest.testInvalidParams", assertions=1)


@pytest.mark.parametrize(
    "parameters",
    [
        # Two numbers where x, y and theta are three.
        pytest.param({"max_velocity": (0.0, 0.0)}, marks=INVALID),
        # Upstream's second configure keeps the short max_velocity too; alone, the feedback
        # type is refused as well (velocity_smoother.cpp:143), so it is tested alone.
        pytest.param({"feedback": "LAWLS"}, marks=INVALID),
    ],
)
def test_a_limit_of_two_numbers_or_an_unknown_feedback_type_is_refused(
    parameters: dict[str, ParameterValue],
) -> None:
    with pytest.raises(ParameterProblem) as refused:
        smoother(**parameters)
    assert refused.value.name in parameters  # refused for that, not another


@SMOOTHER.test("VelocitySmootherTest.testInvalidParamsAccelDecel", assertions=1)
def test_a_negative_max_velocity_and_a_positive_min_velocity_are_refused() -> None:
    with pytest.raises(ParameterProblem):
        smoother(max_velocity=(-10.0, -10.0, -10.0), min_velocity=(10.0, 10.0, 10.0))


@SMOOTHER.test("VelocitySmootherTest.testInvalidParamsAccelDecel", assertions=1)
def test_a_negative_max_accel_is_refused() -> None:
    # Upstream sets it on top of the bad velocities; alone it is refused too (line 85).
    with pytest.raises(ParameterProblem):
        smoother(max_accel=(-10.0, -10.0, -10.0))


@SMOOTHER.test("VelocitySmootherTest.testInvalidParamsAccelDecel", assertions=1)
def test_a_positive_max_decel_is_refused() -> None:
    # Upstream sets it on top of the bad velocities; alone it is refused too (line 78).
    with pytest.raises(ParameterProblem):
        smoother(max_decel=(10.0, 10.0, 10.0))
