"""Nav2, as far as it is built: the Husky drives its route round an obstacle to the goal, and a
robot that does not move for the progress checker's allowance stops."""

from __future__ import annotations

import math
from importlib.metadata import entry_points

import numpy as np
import pytest

from pytest_lasertest.model.geometry import Point2D, Pose2D
from pytest_lasertest.model.obstacles import Cylinder
from pytest_lasertest.nav.nav2.behaviors import BehaviorSettings, Spin
from pytest_lasertest.nav.nav2.mppi import Optimizer
from pytest_lasertest.nav.nav2.nav2 import Nav2
from pytest_lasertest.nav.nav2.settings import Nav2Settings
from pytest_lasertest.nav.protocol import LaserScan, Odometry
from pytest_lasertest.pairsfile import load_pairs_file
from pytest_lasertest.sim.scenario import Scenario, run_scenario
from tests.helpers import EXAMPLES

PAPER = load_pairs_file(EXAMPLES / "paper.lasertest.yaml")
SCANNER = next(pair for pair in PAPER.pairs if pair.name == "distance").baseline.profile
TURN = (Point2D(4.0, 0.0), Point2D(4.0, 4.0))


def test_the_husky_drives_round_a_pole_on_its_route_to_the_goal() -> None:
    pole = Cylinder(2.0, 0.1, 0.2, 1.0)
    # The goal checker's 0.25 m is what the oracle judges by (Nav2's goal_tolerance).
    scenario = Scenario(PAPER.robot, SCANNER, (pole,), Pose2D(0.0, 0.0, 0.0), TURN, 45.0, seed=0)
    run = run_scenario(scenario, Nav2)
    assert run.passed, run.verdicts.failures()
    assert run.verdicts.collision.clearance > 0.05  # m


def test_a_robot_that_never_moves_goes_through_the_default_trees_recoveries_in_order() -> None:
    nav2 = Nav2(PAPER.robot, TURN)
    meta = SCANNER.to_laserscan_meta()
    standing = Odometry(0.0, 0.0, 0.0, 0.0, 0.0)  # whatever it commands
    for step in range(int(80.0 / 0.02)):
        time = step * 0.02
        scan = LaserScan(time, np.full(SCANNER.beam_count, np.inf), meta, SCANNER.pose)
        nav2.observe(scan, standing, time)
    names = [name for _, name in nav2.activity]
    assert names[:6] == [
        # The progress checker's 10 s: FollowPath's own recovery, then the tree's.
        "ClearLocalCostmap-Context",
        "ClearingActions",
        "ClearLocalCostmap-Context",
        # A spin that never turns runs out of its 10 s and fails: the round robin goes on.
        "Spin",
        "Wait",
        "ClearLocalCostmap-Context",
    ]
    times = [round(time) for time, _ in nav2.activity[:4]]
    assert times == [10, 20, 30, 40]


def test_a_followpath_that_fails_resets_mppi_as_the_controller_server_does() -> None:
    nav2 = Nav2(PAPER.robot, TURN, Nav2Settings())  # Jazzy's MPPI
    assert isinstance(nav2.controller, Optimizer)
    meta = SCANNER.to_laserscan_meta()
    standing = Odometry(0.0, 0.0, 0.0, 0.0, 0.0)  # whatever it commands
    sequences = []
    for step in range(int(11.0 / 0.02)):
        time = step * 0.02
        scan = LaserScan(time, np.full(SCANNER.beam_count, np.inf), meta, SCANNER.pose)
        nav2.observe(scan, standing, time)
        sequences.append(nav2.controller.vx.copy())
        if nav2.activity:
            break
    # The progress checker failed FollowPath at 10 s: its action ended, and the controller
    # server reset MPPI, whose sequence had been driving the robot forward.
    assert nav2.activity == [(pytest.approx(10.0, abs=0.05), "ClearLocalCostmap-Context")]
    assert sequences[-2].max() > 0.1  # m/s
    assert not sequences[-1].any()


def test_a_pairs_file_names_nav2_as_a_registered_controller() -> None:
    (nav2,) = [
        point for point in entry_points(group="lasertest.controllers") if point.name == "nav2"
    ]
    assert nav2.load() is Nav2


def test_spin_slows_into_its_last_radians_as_the_behaviour_servers_parameters_say() -> None:
    # Clearpath's A200: rotational_acc_lim 0.5, min_rotational_vel 0.2; Jazzy's: 3.2 and 0.4.
    a200 = BehaviorSettings(min_rotational_vel=0.2, rotational_acc_lim=0.5)
    commands = {}
    for name, settings in (("a200", a200), ("jazzy", BehaviorSettings())):
        spin = Spin(1.57, lambda pose: False, settings)
        spin.step((0.0, 0.0, 0.0), 0.0)
        commands[name] = spin.step((0.0, 0.0, 1.50), 1.0)  # 0.07 rad left
    assert commands["a200"] == (0.0, pytest.approx(math.sqrt(2.0 * 0.5 * 0.07)))
    assert commands["jazzy"] == (0.0, pytest.approx(math.sqrt(2.0 * 3.2 * 0.07)))
