"""The Husky's move_base on the paper's pairs: its findings reappear, for the reasons ROS gives.

- distance: a 5 m scanner's no-return readings, read as range_max - 1e-4 with inf_is_valid, lie
  inside obstacle_range (5.5 m) and mark a phantom arc the robot never gets past;
- size: the 16-beam robot drives into the thin pole, the 32-beam robot stops short of it;
- a robot that stops too close to turn needs to reverse, which DWA's min_vel_x = 0 forbids and
  the optional back-up recovery allows;
- blind spot: straight ahead the narrower field of view changes nothing; on a route that turns
  through the lost wedge it does.
"""

from __future__ import annotations

import numpy as np
import pytest

from pytest_lasertest.model.geometry import Point2D, Pose2D
from pytest_lasertest.model.obstacles import Box, Cylinder, Obstacle
from pytest_lasertest.model.robot import Robot
from pytest_lasertest.model.sensor import LaserProfile
from pytest_lasertest.nav.move_base import MoveBase
from pytest_lasertest.nav.move_base.cost_values import LETHAL
from pytest_lasertest.nav.move_base.settings import NavigationSettings, Parameter
from pytest_lasertest.nav.protocol import LaserScan, Odometry
from pytest_lasertest.pairsfile import load_pairs_file
from pytest_lasertest.search.drives import drive
from pytest_lasertest.search.plans import plan_for
from pytest_lasertest.sim.oracles import Rules
from pytest_lasertest.sim.scenario import Run, Scenario, run_scenario
from tests.helpers import EXAMPLES

PAPER = load_pairs_file(EXAMPLES / "paper.lasertest.yaml")
TURNING = load_pairs_file(EXAMPLES / "turning.lasertest.yaml")
PAIRS = {pair.name: pair for pair in (*PAPER.pairs, *TURNING.pairs)}
FIVE_METRES = PAIRS["distance"].candidate.profile
TEN_METRES = PAIRS["distance"].baseline.profile


class Recorded:
    """A MoveBase factory that keeps the controllers it made."""

    def __init__(self, *parameters: Parameter) -> None:
        self.parameters = parameters
        self.made: list[MoveBase] = []

    def __call__(self, robot: Robot, route: tuple[Point2D, ...]) -> MoveBase:
        settings = NavigationSettings.from_parameters(robot.navigation + self.parameters)
        self.made.append(MoveBase(robot, route, settings))
        return self.made[-1]


def run(
    profile: LaserProfile,
    obstacles: tuple[Obstacle, ...] = (),
    controller: Recorded | None = None,
    route: tuple[Point2D, ...] = PAPER.world.route,
    rules: Rules | None = None,
) -> Run:
    """The Husky carrying `profile` from the origin along `route` for 60 s."""
    scenario = Scenario(
        PAPER.robot,
        profile,
        obstacles,
        Pose2D(0.0, 0.0, 0.0),
        route,
        60.0,
        seed=0,
        rules=rules or Rules(),
    )
    return run_scenario(scenario, controller or Recorded())


def first_scan_marks(profile: LaserProfile) -> np.ndarray:
    """The lethal cells' centres (N, 2) m after the Husky's costmap takes one scan of nothing."""
    controller = Recorded()(PAPER.robot, PAPER.world.route)
    nothing = np.full(profile.beam_count, np.inf)
    scan = LaserScan(0.0, nothing, profile.to_laserscan_meta(), profile.pose)
    controller.observe(scan, Odometry(0.0, 0.0, 0.0, 0.0, 0.0), 0.0)
    rows, columns = np.nonzero(controller.costmap.grid == LETHAL)
    return controller.costmap.centres(columns, rows)


def test_the_5_m_robot_marks_a_phantom_arc_5_m_ahead_across_its_field_of_view() -> None:
    marks = first_scan_marks(FIVE_METRES)
    laser = np.array(FIVE_METRES.pose.xyz[:2])
    reach = np.hypot(*(marks - laser).T)
    bearing = np.arctan2(marks[:, 1] - laser[1], marks[:, 0] - laser[0])
    assert len(marks) > 100
    assert reach.min() > 4.9
    assert reach.max() < 5.1
    assert bearing.min() < -1.5
    assert bearing.max() > 1.5
    assert len(first_scan_marks(TEN_METRES)) == 0


def test_the_5_m_robot_finds_no_plan_past_its_phantom_and_the_10_m_robot_reaches_the_goal() -> None:
    # Given two minutes, and a minute to make progress, it never leaves the start.
    controller = Recorded()
    patient = Rules(stuck_window=60.0)
    start, route = Pose2D(0.0, 0.0, 0.0), PAPER.world.route
    scenario = Scenario(PAPER.robot, FIVE_METRES, (), start, route, 120.0, 0, rules=patient)
    five = run_scenario(scenario, controller)
    assert not five.verdicts.goal.passed
    assert five.verdicts.goal.nearest > 9.9
    # navfn finds no way through the arc; each recovery in turn, the next scan marks it again.
    assert [name for _, name in controller.made[0].recovered] == [
        "conservative_reset",
        "rotate_recovery",
        "aggressive_reset",
        "rotate_recovery",
    ]
    assert run(TEN_METRES).passed


@pytest.mark.parametrize(
    "cure",
    [("costmap", "inf_is_valid", False), ("costmap", "obstacle_range", 4.9)],
    ids=["inf_is_valid false", "obstacle_range below the range"],
)
def test_the_phantom_disappears_without_inf_is_valid_or_with_obstacle_range_below_5_m(
    cure: Parameter,
) -> None:
    assert run(FIVE_METRES, controller=Recorded(cure)).passed


@pytest.mark.parametrize(("obstacle_range", "phantom"), [(4.99995, True), (4.99985, False)])
def test_the_phantom_appears_exactly_when_range_max_less_1e_4_is_inside_obstacle_range(
    obstacle_range: float, phantom: bool
) -> None:
    # No return reads 5.0 - 1e-4 = 4.9999 m: marked below 4.99995, not below 4.99985.
    controller = Recorded(("costmap", "obstacle_range", obstacle_range))
    assert run(FIVE_METRES, controller=controller).verdicts.goal.passed is not phantom


def test_the_10_m_robot_plans_around_a_block_and_reaches_the_goal() -> None:
    block = Box(4.5, 0.0, 0.0, 0.6, 1.5, 1.0)
    result = run(TEN_METRES, (block,))
    assert result.passed, result.verdicts.failures()
    # It drove past beside the block, its half width (0.34 m) clear of the block's side.
    beside = result.poses[np.abs(result.poses[:, 0] - 4.5) < 0.3]
    assert np.abs(beside[:, 1]).min() > 0.75 + 0.34


@pytest.fixture(scope="module")
def thin_pole() -> Cylinder:
    """The size pair's second pole the 16-beam scanner misses, as the gate places it on the
    path the 32-beam robot drives with move_base."""
    size = PAIRS["size"]
    control = drive(PAPER, size.baseline.profile, (), 0, Recorded())
    plan = plan_for(PAPER, size, control)
    pole = plan.direction("candidate-misses").witnesses[1].placement.obstacle
    assert isinstance(pole, Cylinder)
    return pole


def test_the_16_beam_robot_hits_the_thin_pole_and_the_32_beam_robot_stops_short_stuck(
    thin_pole: Cylinder,
) -> None:
    sparse = run(PAIRS["size"].candidate.profile, (thin_pole,))
    dense = run(PAIRS["size"].baseline.profile, (thin_pole,))
    assert not sparse.verdicts.collision.passed
    assert dense.verdicts.collision.passed
    assert 0.0 < dense.verdicts.collision.margin < 0.3
    assert not dense.verdicts.stuck.passed
    assert not dense.verdicts.goal.passed


# A wall 5 cm ahead of the Husky's front: too close to turn on the spot (its corners reach
# 0.61 m from its centre), and the goal lies behind it.
WALL = Box(0.51 + 0.05 + 0.15, 0.0, 0.0, 0.3, 2.0, 1.0)
BEHIND_THE_WALL = (Point2D(4.0, 0.0),)
# move_base waits its controller_patience (15 s) before it recovers: the oracle waits longer.
PATIENT = Rules(stuck_window=45.0)


def test_a_robot_too_close_to_turn_is_stuck_because_it_never_reverses() -> None:
    controller = Recorded()
    result = run(PAIRS["size"].baseline.profile, (WALL,), controller, BEHIND_THE_WALL, PATIENT)
    assert not result.verdicts.goal.passed
    assert result.verdicts.collision.passed
    # move_base's default recoveries, each in vain: rotating would sweep a corner into the wall.
    assert [name for _, name in controller.made[0].recovered] == [
        "conservative_reset",
        "rotate_recovery",
        "aggressive_reset",
        "rotate_recovery",
    ]
    assert float(np.abs(result.poses[:, :2]).max()) < 0.01


def test_the_back_up_recovery_frees_a_robot_too_close_to_turn_and_it_reaches_the_goal() -> None:
    controller = Recorded(("move_base", "back_up_recovery", True))
    result = run(PAIRS["size"].baseline.profile, (WALL,), controller, BEHIND_THE_WALL, PATIENT)
    assert result.passed, result.verdicts.failures()
    recovered = [name for _, name in controller.made[0].recovered]
    assert recovered == ["conservative_reset", "back_up_recovery"]
    assert float(result.poses[:, 0].min()) < -0.4  # it reversed half a metre


def test_straight_ahead_the_narrower_field_of_view_changes_nothing() -> None:
    blind_spot = PAIRS["blind_spot"]
    plan = plan_for(PAPER, blind_spot)
    assert not plan.direction("candidate-misses").witnesses
    assert not plan.direction("baseline-misses").witnesses
    wide, narrow = run(blind_spot.baseline.profile), run(blind_spot.candidate.profile)
    assert wide.passed
    assert narrow.passed
    assert wide.digest() == narrow.digest()


def test_on_a_route_turning_through_the_lost_wedge_the_narrower_field_of_view_differs() -> None:
    turning = PAIRS["blind_spot_turning"]
    world = TURNING.world
    plan = plan_for(TURNING, turning)
    witnesses = plan.direction("candidate-misses").witnesses
    assert witnesses
    obstacles = (witnesses[0].placement.obstacle,)
    wide = run(turning.baseline.profile, obstacles, route=world.route)
    narrow = run(turning.candidate.profile, obstacles, route=world.route)
    assert wide.digest() != narrow.digest()
    assert wide.verdicts.collision.margin != narrow.verdicts.collision.margin


def test_replanning_on_a_clock_takes_the_32_beam_robot_round_the_pole_it_was_stuck_at(
    thin_pole: Cylinder,
) -> None:
    # The Husky plans once (planner_frequency 0): its plan still runs through the pole.
    replanning = Recorded(("move_base", "planner_frequency", 1.0))
    result = run(PAIRS["size"].baseline.profile, (thin_pole,), replanning)
    assert result.passed, result.verdicts.failures()


def test_oscillation_timeout_starts_the_recoveries_of_a_robot_turning_on_the_spot(
    thin_pole: Cylinder,
) -> None:
    husky = Recorded()
    run(PAIRS["size"].baseline.profile, (thin_pole,), husky)
    assert husky.made[0].recovered == []  # oscillation_timeout 0: it turns there for ever
    watching = Recorded(("move_base", "oscillation_timeout", 5.0))
    result = run(PAIRS["size"].baseline.profile, (thin_pole,), watching)
    began, first = watching.made[0].recovered[0]
    assert first == "conservative_reset"
    # For the 5 s before, the robot stayed within oscillation_distance (0.5 m) of one spot.
    window = (result.times > began - 5.0) & (result.times <= began)
    positions = result.poses[window, :2]
    assert np.hypot(*(positions - positions[-1]).T).max() < 0.5
