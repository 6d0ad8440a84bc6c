"""Nav2's releases in a drive: `nav2_version` picks the obstacle layer's marking rule, and the
bugs navigation2 #6084 and #5476 come and go with the releases that had them, in costmaps fed
by the simulated scanner."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from pytest_lasertest.model.geometry import Point2D
from pytest_lasertest.model.obstacles import Cylinder
from pytest_lasertest.model.robot import Robot
from pytest_lasertest.nav.move_base.cost_values import LETHAL
from pytest_lasertest.nav.move_base.costmap import CostmapSettings
from pytest_lasertest.nav.nav2.costmap import Nav2Costmap
from pytest_lasertest.nav.nav2.nav2 import Nav2
from pytest_lasertest.nav.nav2.obstacle_layer import ObservationSource
from pytest_lasertest.nav.nav2.settings import marking_of
from pytest_lasertest.nav.protocol import LaserScan, Odometry
from pytest_lasertest.pairsfile import load_pairs_file
from pytest_lasertest.sim.lidar import FlatLidar
from pytest_lasertest.sim.scenario import Scenario, run_scenario
from tests.helpers import EXAMPLES

CROPPED = load_pairs_file(EXAMPLES / "nav2" / "cropped_range.lasertest.yaml")


class Watched:
    """Nav2 as the pairs file makes it, counting the lethal cells of its local costmap after
    each scan."""

    def __init__(self, robot: Robot, route: tuple[Point2D, ...]) -> None:
        self.nav2 = Nav2(robot, route)
        self.goal_tolerance = self.nav2.goal_tolerance
        self.lethal: list[int] = []

    def observe(self, scan: LaserScan, odometry: Odometry, time: float) -> tuple[float, float]:
        command = self.nav2.observe(scan, odometry, time)
        self.lethal.append(int((self.nav2.local.grid == LETHAL).sum()))
        return command


def phantom_cells(release: str) -> tuple[int, bool]:
    """The most lethal cells the candidate's local costmap held at once in its drive through an
    empty world under `release`, and whether the drive passed."""
    robot = dataclasses.replace(CROPPED.robot, nav2_release=release)
    world, profile = CROPPED.world, CROPPED.pairs[0].candidate.profile
    made: list[Watched] = []

    def make(robot: Robot, route: tuple[Point2D, ...]) -> Watched:
        made.append(Watched(robot, route))
        return made[-1]

    scenario = Scenario(robot, profile, (), world.start, world.route, world.time_limit, seed=1)
    run = run_scenario(scenario, make)
    return max(made[0].lethal), run.passed


def test_the_cropped_range_example_shows_6084s_phantom_cells_only_where_marking_is_by_cells() -> (
    None
):
    # Jazzy 1.3.11 (PR #5697 through #5775) and Humble's branch (#5891) mark by whole cells:
    # no-returns read as 0.7999 m make lethal cells in an empty world. 1.3.12's world
    # pre-filter (PR #6092) and Kilted's squared distance make none.
    assert CROPPED.robot.nav2_release == "1.3.11"
    found = {release: phantom_cells(release) for release in ("1.3.11", "humble", "jazzy", "kilted")}
    assert found["1.3.11"][0] > 0
    assert found["humble"][0] > 0
    assert found["jazzy"][0] == 0
    assert found["kilted"][0] == 0
    # Here they slow the Husky but do not stop it.
    assert all(passed for _, passed in found.values())


@pytest.mark.parametrize(
    ("release", "kept"), [("kilted", False), ("1.3.11", True), ("humble", True), ("jazzy", False)]
)
def test_a_pole_backed_away_from_past_obstacle_max_range_is_forgotten_as_5476_says(
    release: str, kept: bool
) -> None:
    # navigation2 #5476: marking and clearing reach alike (1.0 m), 0.05 m cells. The robot
    # faces a pole and backs away; once the pole reads just past 1.0 m, its ray still clears
    # its cell (ceil(1.0 / 0.05) = 20 cells along) while the world distance no longer marks
    # it, unless marking is by cells (1.3.11, Humble's branch). 1.3.12's pre-filter brings the
    # bug back, as its own test testPointBeyondObstacleMaxRangeNotMarkedWhenSameMapCell says.
    marking = marking_of(release)
    assert marking is not None
    source = ObservationSource(obstacle_max_range=1.0, raytrace_max_range=1.0)
    settings = CostmapSettings(size=4.0, resolution=0.05, inflation_radius=0.3)
    robot = CROPPED.robot
    costmap = Nav2Costmap(settings, robot.footprint_array(), source, marking)
    profile = CROPPED.pairs[0].baseline.profile
    # Read 0.95 m off at first: the laser sits 0.337 m ahead of the base.
    pole = Cylinder(1.337, 0.0, 0.05, 1.0)
    lidar, meta = FlatLidar(profile, (pole,)), profile.to_laserscan_meta()
    lethal = []
    for x in np.arange(0.0, -0.15, -0.005):  # backing up 5 mm a scan, to 1.10 m off
        pose = np.array([x, 0.0, 0.0])
        costmap.update(LaserScan(0.0, lidar.ranges(pose), meta, profile.pose), (x, 0.0, 0.0))
        lethal.append(int((costmap.grid == LETHAL).sum()))
    assert lethal[0] > 0
    assert (lethal[-1] == lethal[0]) is kept
