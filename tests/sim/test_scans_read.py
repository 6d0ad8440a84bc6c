"""Scans are cast when something reads them, and what a run does does not depend on which."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from pytest_lasertest.model.geometry import Point2D, Pose2D
from pytest_lasertest.model.obstacles import Box, Cylinder
from pytest_lasertest.model.robot import Robot
from pytest_lasertest.nav.protocol import LaserScan, Odometry
from pytest_lasertest.pairsfile import load_pairs_file
from pytest_lasertest.sim.scenario import Caster, Scenario, run_scenario
from tests.helpers import EXAMPLES

PAPER = load_pairs_file(EXAMPLES / "paper.lasertest.yaml")
# The distance pair's candidate has range noise: each reading it publishes is drawn.
NOISY = next(pair for pair in PAPER.pairs if pair.name == "distance").candidate.profile
OBSTACLES = (Cylinder(2.0, 0.6, 0.1, 1.0), Box(3.5, -0.8, 0.4, 0.6, 0.3, 1.0))


def noisy_scenario(caster: Caster = "flat") -> Scenario:
    start, goal = Pose2D(0.0, 0.0, 0.0), (Point2D(4.0, 0.0),)
    return Scenario(PAPER.robot, NOISY, OBSTACLES, start, goal, 3.0, seed=5, caster=caster)


class Reader:
    """Drives straight on, reading the ranges of the scans `reads` picks by their index."""

    def __init__(self, reads: range) -> None:
        self.reads, self.index = reads, 0
        self.ranges: dict[int, np.ndarray] = {}

    def observe(self, scan: LaserScan, odometry: Odometry, time: float) -> tuple[float, float]:
        if self.index in self.reads:
            self.ranges[self.index] = scan.ranges
        self.index += 1
        return 0.3, 0.0


def readings(reads: range, caster: Caster = "flat") -> dict[int, np.ndarray]:
    readers: list[Reader] = []

    def make(robot: Robot, route: tuple[Point2D, ...]) -> Reader:
        readers.append(Reader(reads))
        return readers[-1]

    run_scenario(noisy_scenario(caster), make)
    return readers[0].ranges


@pytest.mark.parametrize("caster", ["flat", "pybullet"])
def test_a_scan_reads_the_same_whichever_scans_were_read_before_it(caster: Caster) -> None:
    every = readings(range(150), caster)
    some = readings(range(0, 150, 7), caster)
    assert NOISY.noise is not None
    assert NOISY.noise.stddev > 0.0
    assert len(every) == 150
    assert set(some) == set(range(0, 150, 7))
    for index, ranges in some.items():
        np.testing.assert_array_equal(ranges, every[index])
    # Not one scan served twice: 20 ms on, the next reads differently.
    assert not np.array_equal(every[0], every[1])


def test_a_scan_kept_and_read_after_the_run_reads_what_it_would_have_read_when_taken() -> None:
    kept: list[LaserScan] = []

    class Keeper:
        def observe(self, scan: LaserScan, odometry: Odometry, time: float) -> tuple[float, float]:
            kept.append(scan)
            return 0.3, 0.0  # as Reader drives: the same poses, scan by scan

    run_scenario(noisy_scenario(), lambda robot, route: Keeper())
    at_once = readings(range(len(kept)))
    assert len(kept) == len(at_once) == 150
    for index, scan in enumerate(kept):
        np.testing.assert_array_equal(scan.ranges, at_once[index])
    assert not np.array_equal(kept[0].ranges, kept[-1].ranges)  # the robot moved


def test_a_scan_replaced_with_new_ranges_keeps_them() -> None:
    scans: list[LaserScan] = []

    class Filter:
        def observe(self, scan: LaserScan, odometry: Odometry, time: float) -> tuple[float, float]:
            scans.append(dataclasses.replace(scan, ranges=np.zeros(3)))
            return 0.0, 0.0

    run_scenario(dataclasses.replace(noisy_scenario(), time_limit=0.1), lambda r, p: Filter())
    assert all(np.array_equal(scan.ranges, np.zeros(3)) for scan in scans)
    assert [scan.stamp for scan in scans] == pytest.approx([0.0, 0.02, 0.04, 0.06, 0.08])
