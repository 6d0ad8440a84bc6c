"""Nav2's velocity smoother: speeds ramp at max_accel, fall at max_decel, hold between ticks."""

from __future__ import annotations

import pytest

from pytest_lasertest.nav.nav2.velocity_smoother import VelocitySmoother


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
