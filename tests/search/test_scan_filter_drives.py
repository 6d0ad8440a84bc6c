"""A team's laser_filters chain in front of the stack (`navigation: {scan_filters: FILE}`):
each drive's controller sees each scan as the chain leaves it, the chain started afresh for
each run, and the report says it stands there."""

from __future__ import annotations

from pathlib import Path

from pytest_lasertest.model.geometry import Point2D, Pose2D
from pytest_lasertest.model.obstacles import Cylinder
from pytest_lasertest.model.robot import Robot
from pytest_lasertest.nav.protocol import InFront, LaserScan, Odometry
from pytest_lasertest.nav.reactive import ReactiveController
from pytest_lasertest.pairsfile.controller import ControllerChoice
from pytest_lasertest.pairsfile.scan_filters import with_scan_filters, without_scan_filters
from pytest_lasertest.reports.drive import controller_line
from pytest_lasertest.sim.scenario import Scenario, run_scenario
from tests.helpers.laser_filters import BLINDING, STANDING, chain_of, message
from tests.helpers.paper import PAPER

REACTIVE = ControllerChoice("reactive", "the default", ReactiveController)
MEDIAN = """\
scan_filter_chain:
- name: median
  type: laser_filters/LaserMedianFilter
  params:
    internal_filter:
    - {name: m, type: filters/MultiChannelMedianFilterFloat, params: {number_of_observations: 3}}
"""


def test_a_chain_that_drops_every_reading_drives_the_robot_into_a_pole_the_bare_stack_avoids(
    tmp_path: Path,
) -> None:
    # A 4 m run past a pole 2 m ahead: 3 s of driving at most before the pole or the goal.
    profile = next(pair for pair in PAPER.pairs if pair.name == "size").baseline.profile
    pole = Cylinder(2.0, 0.0, 0.15, 1.0)
    world = Scenario(
        PAPER.robot, profile, (pole,), Pose2D(0.0, 0.0, 0.0), (Point2D(4.0, 0.0),), 12.0, 0
    )
    blinded = with_scan_filters(REACTIVE, chain_of(tmp_path, BLINDING))
    bare, behind = run_scenario(world, REACTIVE.factory), run_scenario(world, blinded.factory)
    assert bare.passed, bare.verdicts.failures()
    assert not behind.passed
    assert not behind.verdicts.collision.passed


def test_the_stack_description_names_the_chain_and_its_filters(tmp_path: Path) -> None:
    nav2 = ControllerChoice("nav2", "the default", ReactiveController, "Nav2 jazzy: NavFn, MPPI")
    chosen = with_scan_filters(nav2, chain_of(tmp_path, BLINDING))
    assert controller_line(chosen) == (
        "  controller nav2 (the default): Nav2 jazzy: NavFn, MPPI, scan filters: filters.yaml "
        "(1 filter)"
    )
    # Taken out again, for the blame's drive without it: the stack alone.
    assert controller_line(without_scan_filters(chosen)) == controller_line(nav2)
    assert with_scan_filters(REACTIVE, None) is REACTIVE


class Recorder:
    """A stack that remembers the first reading of each scan it sees."""

    def __init__(self, robot: Robot, route: tuple[Point2D, ...]) -> None:
        self.seen: list[float] = []

    def observe(self, scan: LaserScan, odometry: Odometry, time: float) -> tuple[float, float]:
        self.seen.append(float(scan.ranges[0]))
        return 0.0, 0.0


def test_each_run_starts_the_chain_afresh_its_median_remembering_no_other_runs_scans(
    tmp_path: Path,
) -> None:
    factory = with_scan_filters(
        ControllerChoice("recorder", "here", Recorder), chain_of(tmp_path, MEDIAN)
    ).factory
    scans = [message([value], 0.0, 0.0, 0.1, 10.0, 0.0) for value in (5.0, 1.0, 3.0)]
    first, second = factory(PAPER.robot, ()), factory(PAPER.robot, ())
    assert isinstance(first, InFront)
    assert isinstance(second, InFront)
    for time, scan in enumerate(scans):
        first.observe(scan, STANDING, float(time))
    second.observe(scans[-1], STANDING, 0.0)
    assert isinstance(first.inner, Recorder)
    assert isinstance(second.inner, Recorder)
    # The lower median of the last scans: 5, then of (5, 1) 1, then of (5, 1, 3) 3.
    assert first.inner.seen == [5.0, 1.0, 3.0]
    assert second.inner.seen == [3.0]
