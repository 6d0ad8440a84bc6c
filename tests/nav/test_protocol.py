"""What a controller is given: a LaserScan's readings as points in the robot's base frame; and
what stands in front of a controller (`InFront`) changes nothing it does not mean to."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from pytest_lasertest.model.geometry import Point2D, Pose2D
from pytest_lasertest.model.robot import Robot
from pytest_lasertest.nav.move_base import MoveBase
from pytest_lasertest.nav.nav2.nav2 import Nav2
from pytest_lasertest.nav.protocol import ControllerFactory, InFront, LaserScan, Odometry
from pytest_lasertest.nav.reactive import ReactiveController
from pytest_lasertest.sim.scenario import Scenario, run_scenario
from tests.helpers.paper import PAPER

SIZE = next(pair for pair in PAPER.pairs if pair.name == "size")


def test_readings_nearer_than_range_min_become_points_at_range_min_only_when_asked() -> None:
    profile = SIZE.baseline.profile
    ranges = np.full(profile.beam_count, np.inf)
    ranges[profile.beam_count // 2] = -np.inf
    scan = LaserScan(0.0, ranges, profile.to_laserscan_meta(), profile.pose)
    assert len(scan.points_in_base()) == 0
    (point,) = scan.points_in_base(too_near=True)
    mount = np.array(profile.pose.xyz[:2])
    assert np.linalg.norm(point - mount) == pytest.approx(profile.range_min)


def _unchanged(scan: LaserScan, odometry: Odometry, time: float) -> LaserScan:
    return scan


@pytest.mark.parametrize(
    "stack", [MoveBase, Nav2, ReactiveController], ids=["move_base", "nav2", "reactive"]
)
def test_a_stack_with_nothing_in_front_of_it_drives_exactly_as_the_bare_stack(
    stack: ControllerFactory,
) -> None:
    # InFront hands the inner stack's optional attributes on: without them Nav2 would tick at
    # the scan rate and be judged stuck after 10 s, and the trajectories would part.
    def wrapped(robot: Robot, route: tuple[Point2D, ...]) -> InFront:
        return InFront(stack(robot, route), _unchanged)

    profile = SIZE.candidate.profile
    scenario = Scenario(
        PAPER.robot, profile, (), Pose2D(0.0, 0.0, 0.0), (Point2D(4.0, 1.0),), 30.0, seed=3
    )
    bare, behind = run_scenario(scenario, stack), run_scenario(scenario, wrapped)
    assert np.array_equal(bare.poses, behind.poses)
    assert np.array_equal(bare.commands, behind.commands)
    assert bare.verdicts == behind.verdicts


def test_each_scan_goes_through_what_stands_in_front_once_ticks_between_scans_included() -> None:
    seen: list[float] = []

    def counting(scan: LaserScan, odometry: Odometry, time: float) -> LaserScan:
        seen.append(time)
        return scan

    slow = dataclasses.replace(SIZE.candidate.profile, update_rate=10.0)  # Hz, Nav2 ticks 20
    scenario = Scenario(
        PAPER.robot,
        slow,
        (),
        Pose2D(0.0, 0.0, 0.0),
        (Point2D(3.0, 0.0),),
        5.0,
        seed=0,
    )
    nav2: list[Nav2] = []

    def make(robot: Robot, route: tuple[Point2D, ...]) -> InFront:
        nav2.append(Nav2(robot, route))
        return InFront(nav2[0], counting)

    run = run_scenario(scenario, make)
    assert nav2[0].control_frequency > slow.update_rate  # it ticks between scans
    assert len(seen) == run.scans
