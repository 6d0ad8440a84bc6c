"""DWB's tests of OneDVelocityIterator (dwb_plugins/test/velocity_iterator_test.cpp), rebuilt on our
`dwb_trajectories.velocity_samples`, which returns the iterator's whole run as a list: the upstream
constructor's arguments (current, min, max, acceleration, deceleration, time, samples) are its
arguments in that order, getVelocity after k increments is the list's item k, and isFinished after k
increments is the list having k items; where upstream stops before the end, only the values it reads
are compared. Its reset, which XYThetaIterator uses to run the theta samples again for each x, is
seen in `dwb_trajectories.sample_twists`."""

from __future__ import annotations

import pytest

from pytest_lasertest.nav.nav2.dwb_settings import DwbSettings
from pytest_lasertest.nav.nav2.dwb_trajectories import sample_twists, velocity_samples
from tests.helpers.upstream import NAVIGATION2_HUMBLE, Source

ITERATOR = Source(
    "Nav2 DWB: velocity iterator",
    NAVIGATION2_HUMBLE,
    "nav2_dwb_controller/dwb_plugins/test/velocity_iterator_test.cpp",
)
EPSILON = 1e-3  # the upstream tolerance


def near(*values: float) -> list[object]:
    """The expected run, each value within the upstream tolerance."""
    return [pytest.approx(value, abs=EPSILON) for value in values]


@ITERATOR.test("VelocityIterator.basics", assertions=7)
def test_two_samples_are_the_ends_of_the_reachable_window() -> None:
    # From 2 m/s at 1 m/s^2 for 1 s: 1 to 3 m/s.
    run = velocity_samples(2.0, 0.0, 5.0, 1.0, -1.0, 1.0, 2)
    # Not finished at the start nor after the first increment (4 assertions), finished after
    # the second (1): exactly two values.
    assert len(run) == 2
    assert run == near(1.0, 3.0)


@ITERATOR.test("VelocityIterator.basics", assertions=2)
def test_after_a_reset_the_samples_start_again_from_the_first() -> None:
    # The same iterator as theta's in XYThetaIterator (theta from -5 to 5 rad/s reaches only
    # 1 to 3 within 1 s at 1 rad/s^2): reset after each x, so every x's thetas run again.
    settings = DwbSettings(
        min_vel_x=0.0,
        max_vel_x=1.0,
        max_vel_theta=5.0,
        max_speed_xy=10.0,
        acc_lim_x=10.0,
        decel_lim_x=-10.0,
        acc_lim_theta=1.0,
        decel_lim_theta=-1.0,
        vx_samples=3,
        vtheta_samples=2,
        sim_time=1.0,
    )
    vx, theta = sample_twists(settings, (0.0, 2.0))
    speeds = sorted(set(vx.tolist()))
    runs = [theta[vx == x].tolist() for x in speeds]
    assert speeds == [0.0, 0.5, 1.0]
    assert all(len(run) == 2 for run in runs)  # not finished after the reset: both again
    assert all(run[0] == pytest.approx(1.0, abs=EPSILON) for run in runs)


@ITERATOR.test("VelocityIterator.limits", assertions=2)
def test_the_window_is_clipped_to_the_limits() -> None:
    assert velocity_samples(2.0, 1.5, 2.5, 1.0, -1.0, 1.0, 2)[:2] == near(1.5, 2.5)


@ITERATOR.test("VelocityIterator.acceleration", assertions=2)
def test_the_window_narrows_with_the_acceleration() -> None:
    assert velocity_samples(2.0, 0.0, 5.0, 0.5, -0.5, 1.0, 2)[:2] == near(1.5, 2.5)


@ITERATOR.test("VelocityIterator.time", assertions=2)
def test_the_window_narrows_with_the_time() -> None:
    assert velocity_samples(2.0, 0.0, 5.0, 1.0, -1.0, 0.5, 2)[:2] == near(1.5, 2.5)


@ITERATOR.test("VelocityIterator.samples", assertions=4)
def test_three_samples_split_the_window_in_two() -> None:
    assert velocity_samples(2.0, 0.0, 5.0, 1.0, -1.0, 1.0, 3) == near(1.0, 2.0, 3.0)


@ITERATOR.test("VelocityIterator.samples2", assertions=6)
def test_five_samples_split_the_window_in_four() -> None:
    run = velocity_samples(2.0, 0.0, 5.0, 1.0, -1.0, 1.0, 5)
    assert run == near(1.0, 1.5, 2.0, 2.5, 3.0)


@ITERATOR.test("VelocityIterator.around_zero", assertions=3)
def test_zero_is_put_in_where_the_samples_cross_it() -> None:
    # Upstream increments once more after 1.0 and asserts nothing there.
    run = velocity_samples(0.0, -5.0, 5.0, 1.0, -1.0, 1.0, 2)
    assert run[:3] == near(-1.0, 0.0, 1.0)


@ITERATOR.test("VelocityIterator.around_zero2", assertions=5)
def test_zero_is_put_in_between_two_thirds() -> None:
    run = velocity_samples(0.0, -5.0, 5.0, 1.0, -1.0, 1.0, 4)
    assert run[:5] == near(-1.0, -0.3333, 0.0, 0.3333, 1.0)
