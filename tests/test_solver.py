"""Z3 placements on the paper's pairs, each judged by the exact ray cast."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
import pytest

from pytest_lasertest.geometry import Box, Cylinder
from pytest_lasertest.path import nominal_path
from pytest_lasertest.placement import REQUIRED_MARGIN, Placement, Scene, readings, verify
from pytest_lasertest.solver.encoding import ObstacleShape
from pytest_lasertest.solver.plan import plan_direction
from pytest_lasertest.solver.search import Found, Query, SearchSettings
from pytest_lasertest.spec import load_pairs_file
from pytest_lasertest.spec.constraints import Constraint, parse_formula
from pytest_lasertest.spec.errors import Location
from tests.conftest import EXAMPLES

PAPER = load_pairs_file(EXAMPLES / "paper.lasertest.yaml")
SETTINGS = SearchSettings(witnesses=1, min_size=PAPER.settings.min_obstacle_size)


def scene(name: str) -> Scene:
    pair = next(pair for pair in PAPER.pairs if pair.name == name)
    robot, world = PAPER.robot, PAPER.world
    path = nominal_path(world.start, world.route, robot.nominal_speed, robot.nominal_turn_rate)
    return Scene(pair.baseline.profile, pair.candidate.profile, robot, path)


def test_the_sixteen_beam_scanner_misses_a_thin_obstacle_the_thirty_two_beam_one_reads() -> None:
    plan = plan_direction(scene("size"), "candidate-misses", SETTINGS)
    assert plan.status == "sat"
    (witness,) = plan.witnesses
    assert witness.verification.margin >= REQUIRED_MARGIN
    obstacle = witness.placement.obstacle
    pose = np.array([witness.pose])
    assert np.isfinite(readings(scene("size").baseline, pose, obstacle)).any()
    assert not np.isfinite(readings(scene("size").candidate, pose, obstacle)).any()


def test_the_five_metre_scanner_misses_an_obstacle_the_ten_metre_one_reads_at_the_start() -> None:
    plan = plan_direction(scene("distance"), "candidate-misses", SETTINGS)
    (witness,) = plan.witnesses
    assert witness.placement.anchor == 0.0
    obstacle = witness.placement.obstacle
    assert 5.0 < np.hypot(obstacle.x - 0.337, obstacle.y) < 10.0 + 0.337


def test_a_narrower_field_of_view_hides_nothing_in_the_way_ahead_at_the_start_pose() -> None:
    query = Query(scene("blind_spot"), "candidate-misses", 0.0, ObstacleShape("cylinder"), SETTINGS)
    answer = dataclasses.replace(query, beam_limit=None).run()
    assert not isinstance(answer, Found)
    assert answer.verdict == "unsat"
    assert {"detector", "path", "misser@0.000"} <= set(answer.core)


def test_the_same_query_gives_the_same_witness_every_time() -> None:
    query = Query(scene("size"), "baseline-misses", 1.0, ObstacleShape("box"), SETTINGS)
    first, second = query.run(), query.run()
    assert isinstance(first, Found)
    assert first == second


def test_witnesses_keep_to_the_users_constraints() -> None:
    beyond = Constraint("x > 4", Location(Path("gate.lasertest.yaml"), 9), parse_formula("x > 4"))
    settings = SearchSettings(witnesses=2, min_size=0.0507, constraints=(beyond,))
    plan = plan_direction(scene("size"), "candidate-misses", settings)
    assert len(plan.witnesses) == 2
    assert all(witness.placement.obstacle.x > 4 for witness in plan.witnesses)


def test_witnesses_of_one_direction_are_apart_from_each_other() -> None:
    settings = SearchSettings(witnesses=2, min_size=0.0507)
    plan = plan_direction(scene("size"), "candidate-misses", settings)
    assert len(plan.witnesses) == 2
    centres = [(w.placement.obstacle.x, w.placement.obstacle.y) for w in plan.witnesses]
    for index, (x, y) in enumerate(centres):
        for other_x, other_y in centres[:index]:
            assert max(abs(x - other_x), abs(y - other_y)) >= settings.diversity - 1e-9


def test_the_verifier_rejects_an_obstacle_both_scanners_read() -> None:
    straight_ahead = Cylinder(x=3.0, y=0.5, radius=0.2, height=1.0)
    verification = verify(scene("distance"), Placement(straight_ahead, "candidate-misses", 0.0))
    assert verification.detection >= REQUIRED_MARGIN
    assert verification.concealment < 0
    assert verification.seen_by_misser_at == (0.0,)
    assert not verification.holds()


def test_the_verifier_rejects_an_obstacle_the_robot_cannot_stop_for() -> None:
    at_the_bumper = Box(x=0.6, y=0.0, yaw=0.0, length=0.1, width=0.1, height=1.0)
    verification = verify(scene("size"), Placement(at_the_bumper, "candidate-misses", 0.0))
    assert verification.clearance < 0


def test_an_obstacle_lower_than_the_scan_plane_is_not_read() -> None:
    low = Cylinder(x=3.0, y=0.0, radius=0.2, height=0.2)
    pose = np.array([[0.0, 0.0, 0.0]])
    assert np.all(readings(scene("size").baseline, pose, low) == np.inf)


@pytest.mark.parametrize("shape", ["box", "cylinder"])
def test_a_witness_survives_the_required_margin_in_both_ray_casts(shape: str) -> None:
    obstacle_shape = ObstacleShape("box" if shape == "box" else "cylinder")
    query = Query(scene("size"), "candidate-misses", 0.0, obstacle_shape, SETTINGS)
    found = query.run()
    assert isinstance(found, Found)
    assert found.verification.holds()
