"""The simulated scanner publishes through its driver: the scans a controller is given carry the
driver's encodings, beam order and range_max, and arrive at the driver's stamp."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from pytest_lasertest.model.driver import Driver
from pytest_lasertest.model.geometry import Point2D, Pose2D
from pytest_lasertest.model.obstacles import Cylinder
from pytest_lasertest.model.robot import Robot
from pytest_lasertest.nav.protocol import LaserScan, Odometry
from pytest_lasertest.pairsfile import load_pairs_file
from pytest_lasertest.sim.scenario import Scenario, run_scenario
from tests.helpers import EXAMPLES
from tests.helpers.model import profile

PAPER = load_pairs_file(EXAMPLES / "paper.lasertest.yaml")
SCANNER = dataclasses.replace(PAPER.pairs[0].baseline.profile, update_rate=10.0)

POLE = Cylinder(1.5, 0.0, 0.1, 1.0)  # m


class Recorder:
    """Turns on the spot and keeps every scan it is given, with the time it was given."""

    def __init__(self) -> None:
        self.given: list[tuple[float, LaserScan]] = []

    def observe(self, scan: LaserScan, odometry: Odometry, time: float) -> tuple[float, float]:
        self.given.append((time, scan))
        return 0.0, 0.5


def given(driver: Driver, duration: float = 0.5) -> list[tuple[float, LaserScan]]:
    recorder = Recorder()

    def make(robot: Robot, route: tuple[Point2D, ...]) -> Recorder:
        return recorder

    scanner = dataclasses.replace(SCANNER, driver=driver)
    start, route = Pose2D(0.0, 0.0, 0.0), (Point2D(3.0, 0.0),)
    scenario = Scenario(PAPER.robot, scanner, (POLE,), start, route, duration, seed=0)
    run_scenario(scenario, make)
    return recorder.given


def test_a_late_stamp_delivers_each_scan_then_with_what_was_measured_before() -> None:
    prompt, late = given(Driver()), given(Driver(latency=0.06))
    # Given at the first physics step (20 ms) at or after the stamp.
    assert [round(time, 6) for time, _ in late] == [round(t + 0.06, 6) for t, _ in prompt[:5]]
    assert [round(scan.stamp, 6) for _, scan in late] == [round(t, 6) for t, _ in late]
    # Both first scans were measured at the start, before any command moved the robot.
    np.testing.assert_array_equal(prompt[0][1].ranges, late[0][1].ranges)


def test_a_driver_that_stamps_the_sweeps_end_delivers_a_sweep_later() -> None:
    prompt, ended = given(Driver()), given(Driver(stamp="end"))
    assert ended[0][0] - prompt[0][0] == pytest.approx(0.1)  # s, one sweep at 10 Hz


def test_a_clockwise_driver_gives_the_controller_the_ranges_reversed() -> None:
    prompt, reversed_ = given(Driver()), given(Driver(beam_order="clockwise"))
    for (_, scan), (_, turned) in zip(prompt, reversed_, strict=True):
        np.testing.assert_array_equal(turned.ranges, scan.ranges[::-1])
        assert turned.meta == scan.meta


def test_a_per_scan_range_max_is_in_each_scans_header() -> None:
    (_, scan), *_ = given(Driver(range_max="per_scan", no_return="nan"))
    finite = scan.ranges[np.isfinite(scan.ranges)]
    assert scan.meta.range_max == finite.max() < 10.0
    assert np.isnan(scan.ranges).sum() > 600


def test_a_run_without_a_driver_is_the_run_with_gazebos_driver() -> None:
    assert dataclasses.replace(profile(), driver=Driver()) == profile()
