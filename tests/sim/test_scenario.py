"""Scenario runs: the reference controller on the paper's pairs, determinism, the oracles'
verdicts, and a process that runs many of them."""

from __future__ import annotations

import itertools
from pathlib import Path

import numpy as np
import pytest

from pytest_lasertest.model.geometry import Point2D, Pose2D
from pytest_lasertest.model.obstacles import Box, Cylinder, Obstacle
from pytest_lasertest.nav.reactive import ReactiveController
from pytest_lasertest.pairsfile import load_pairs_file
from pytest_lasertest.search.drives import drive
from pytest_lasertest.search.plans import plan_for
from pytest_lasertest.sim.client import PhysicsClient, connected_clients
from pytest_lasertest.sim.scenario import Caster, Scenario, run_scenario
from tests.helpers import EXAMPLES
from tests.helpers.texts import SIZE_PAIR

PAPER = load_pairs_file(EXAMPLES / "paper.lasertest.yaml")
SIZE = next(pair for pair in PAPER.pairs if pair.name == "size")
START = Pose2D(0.0, 0.0, 0.0)
GOAL = (Point2D(10.0, 0.0),)


def scenario(
    side: str,
    obstacles: tuple[Obstacle, ...],
    seed: int = 0,
    time_limit: float = 40.0,
    caster: Caster = "flat",
) -> Scenario:
    """The size pair's baseline or candidate robot driving 10 m straight ahead."""
    profile = getattr(SIZE, side).profile
    return Scenario(PAPER.robot, profile, obstacles, START, GOAL, time_limit, seed, caster=caster)


@pytest.fixture(scope="module")
def thin_pole() -> Cylinder:
    """The size pair's thin pole: the witness the 32-beam scanner reads and the 16-beam one
    misses for the longest."""
    plan = plan_for(PAPER, SIZE)
    poles = [
        witness.placement.obstacle
        for witness in plan.direction("candidate-misses").witnesses
        if isinstance(witness.placement.obstacle, Cylinder)
    ]
    assert poles, "the size pair's plan has no pole"
    return poles[0]


def test_the_16_beam_robot_hits_the_thin_pole_and_the_32_beam_robot_reaches_the_goal(
    thin_pole: Cylinder,
) -> None:
    for seed in range(3):
        sparse = run_scenario(scenario("candidate", (thin_pole,), seed), ReactiveController)
        dense = run_scenario(scenario("baseline", (thin_pole,), seed), ReactiveController)

        assert not sparse.verdicts.collision.passed
        assert sparse.verdicts.collision.margin <= 0.0
        assert dense.passed, dense.verdicts.failures()
        assert dense.verdicts.collision.margin > 0.0


def test_a_scenario_run_five_times_gives_one_trajectory_bit_for_bit(thin_pole: Cylinder) -> None:
    box = Box(5.0, -1.0, 0.4, 0.8, 0.3, 1.0)
    runs = [
        run_scenario(scenario("baseline", (thin_pole, box), seed=7), ReactiveController)
        for _ in range(5)
    ]
    assert len({run.digest() for run in runs}) == 1
    assert runs[0].scans > 100


def test_a_client_reset_for_each_world_drives_the_runs_of_fresh_clients_bit_for_bit(
    thin_pole: Cylinder,
) -> None:
    box = Box(3.0, -0.4, 0.5, 0.4, 0.3, 1.0)
    scenarios = [scenario("baseline", (thin_pole, box), seed=3), scenario("candidate", ())]
    fresh = [run_scenario(each, ReactiveController).digest() for each in scenarios]
    with PhysicsClient() as client:
        reused = [run_scenario(each, ReactiveController, client).digest() for each in scenarios * 2]
    assert reused == fresh * 2
    assert connected_clients() == 0


def test_in_the_empty_world_the_robot_keeps_to_the_nominal_path_round_its_corners() -> None:
    # The turning example's route: 2 m ahead, a quarter turn, 6 m to the goal.
    route = (Point2D(2.0, 0.0), Point2D(2.0, 6.0))
    profile = SIZE.baseline.profile
    run = run_scenario(
        Scenario(PAPER.robot, profile, (), START, route, 40.0, seed=0), ReactiveController
    )
    assert run.passed, run.verdicts.failures()
    corners = [(START.x, START.y), *((point.x, point.y) for point in route)]
    off_path = [
        min(_to_segment(pose, a, b) for a, b in itertools.pairwise(corners))
        for pose in run.poses[:, :2]
    ]
    assert max(off_path) < 0.1


def _to_segment(point: np.ndarray, start: tuple[float, float], end: tuple[float, float]) -> float:
    """The distance from a point to a line segment (m)."""
    a, b = np.array(start), np.array(end)
    share = np.clip(np.dot(point - a, b - a) / np.dot(b - a, b - a), 0.0, 1.0)
    return float(np.linalg.norm(point - (a + share * (b - a))))


def test_a_candidate_in_the_empty_world_reaches_the_goal_in_the_nominal_time() -> None:
    run = run_scenario(scenario("candidate", ()), ReactiveController)
    assert run.passed
    goal = run.verdicts.goal
    # 10 m at the Husky's nominal 0.5 m/s, less the 0.2 m tolerance, plus speeding up.
    assert goal.time == pytest.approx(9.8 / 0.5, abs=0.5)
    assert run.poses[-1, 0] == pytest.approx(9.8, abs=0.05)


@pytest.mark.parametrize("caster", ["flat", "pybullet"])
def test_both_ray_casters_drive_the_same_run(caster: Caster) -> None:
    wall = Box(4.0, 0.0, 0.0, 0.3, 6.0, 1.0)  # across the route: the robot stops before it
    run = run_scenario(scenario("baseline", (wall,), caster=caster), ReactiveController)
    flat = run_scenario(scenario("baseline", (wall,)), ReactiveController)
    for oracle in ("collision", "stuck", "goal"):
        mine, theirs = getattr(run.verdicts, oracle), getattr(flat.verdicts, oracle)
        assert mine.time == theirs.time
        # PyBullet reads up to a few mm off the exact shapes (tests/sim/test_lidar.py), and the runs
        # part by that much.
        assert mine.margin == pytest.approx(theirs.margin, abs=0.005)
    np.testing.assert_allclose(run.poses[-1], flat.poses[-1], atol=0.02)


def test_a_run_collides_only_where_its_clearance_reaches_zero(tmp_path: Path) -> None:
    # The first witness of tests/helpers/texts.py's size pair reaches 4 cm into the 16-beam robot's
    # path: the robot scrapes past it by a millimetre or two, within the distance at which
    # PyBullet already keeps contact points.
    pairs = tmp_path / "size.lasertest.yaml"
    pairs.write_text(SIZE_PAIR)
    spec = load_pairs_file(pairs)
    box = Box(4.530794013521309, -0.31299598647869104, 0.0, 0.0507, 0.0507, 0.45961598647869104)
    margins = []
    for seed in range(4):
        run = drive(spec, spec.pairs[0].candidate.profile, (box,), seed, ReactiveController)
        collision = run.verdicts.collision
        assert collision.passed == (collision.margin > 0.0), collision
        margins.append(collision.margin)
    assert min(abs(margin) for margin in margins) < 0.005


def test_a_robot_facing_a_wall_across_its_route_stops_and_is_stuck_not_crashed() -> None:
    wall = Box(4.0, 0.0, 0.0, 0.3, 6.0, 1.0)
    run = run_scenario(scenario("baseline", (wall,)), ReactiveController)
    verdicts = run.verdicts
    assert verdicts.collision.passed
    assert not verdicts.stuck.passed
    assert not verdicts.goal.passed
    assert 0.0 < verdicts.collision.margin < 0.3
    assert verdicts.stuck.time == pytest.approx(run.times[-1])


def _resident_bytes() -> int:
    return int(Path("/proc/self/statm").read_text().split()[1]) * 4096


def test_many_runs_in_one_process_leak_no_client_and_little_memory(thin_pole: Cylinder) -> None:
    # As the plugin runs them: one client, reset for each world. (PyBullet leaks about 0.3 MB
    # for each client connected and disconnected while another stays connected.)
    short = scenario("baseline", (thin_pole,), time_limit=0.5)
    with PhysicsClient() as client:
        for _ in range(10):
            run_scenario(short, ReactiveController, client)
        before = _resident_bytes()
        for _ in range(100):
            run_scenario(short, ReactiveController, client)
        grown = _resident_bytes() - before
    assert connected_clients() == 0
    assert grown < 5 * 2**20
