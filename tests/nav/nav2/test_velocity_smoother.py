"""Nav2's velocity smoother: speeds ramp at max_accel, fall at max_decel, hold between ticks;
with scale_velocities, every axis keeps the command's direction."""

from __future__ import annotations

import pytest

from pytest_lasertest.nav.nav2.velocity_smoother import SmootherSettings, VelocitySmoother


def test_a_step_to_full_speed_ramps_at_2_5_m_per_s2_ticking_at_20_hz() -> None:
    smoother = VelocitySmoother()
    outputs = [smoother.step((1.0, 0.0), tick * 0.05)[0] for tick in range(6)]
    # Clamped to 0.5 m/s, reached by 0.125 m/s a tick.
    assert outputs == pytest.approx([0.125, 0.25, 0.375, 0.5, 0.5, 0.5])


def test_between_ticks_the_output_holds() -> None:
    smoother = VelocitySmoother()
    assert smoother.step((0.5, 1.0), 0.0) == pytest.approx((0.125, 0.16))
    assert smoother.step((0.0, 0.0), 0.02) == pytest.approx((0.125, 0.16))


def test_reversing_through_zero_brakes_at_max_decel() -> None:
    smoother = VelocitySmoother()
    smoother.last = (0.3, 0.0)
    assert smoother.step((-0.3, 0.0), 0.0)[0] == pytest.approx(0.175)


def test_with_scale_velocities_both_axes_change_by_the_most_limited_axis_s_factor() -> None:
    # From smootherTimer (velocity_smoother.cpp:365-390 at jazzy f4108e5b): x wants 0.5 m/s
    # more (0.125 a tick allowed: eta 0.25), the turn 0.1 rad/s more (0.16 allowed): both
    # changes are scaled by 0.25, and the command's direction is kept.
    scaled = VelocitySmoother(SmootherSettings(scale_velocities=True))
    assert scaled.step((0.5, 0.1), 0.0) == pytest.approx((0.125, 0.025))
    assert VelocitySmoother().step((0.5, 0.1), 0.0) == pytest.approx((0.125, 0.1))
