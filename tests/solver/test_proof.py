"""Proofs at an anchor the robot reaches after standing still: the misser's scans before the
anchor, from where the robot stood, must miss a witness too, and a proof asks them."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np

from pytest_lasertest.model.route import nominal_path, scan_times
from pytest_lasertest.model.verify import REQUIRED_MARGIN, Scene, miss_margins
from pytest_lasertest.pairsfile import load_pairs_file
from pytest_lasertest.solver.plan import plan_direction
from pytest_lasertest.solver.proof import prove
from pytest_lasertest.solver.search import SearchSettings, shapes_for
from tests.helpers.texts import write

# The strict upgrade of tests/data/harmless/move_base.lasertest.yaml: more beams, a wider field
# and a longer range on the same mount. Only at the start is the route's far end (6.9 m) far
# enough from the scanner for a 0.05 m pole to fit between two of the baseline's beams, 0.5 deg
# apart, with the required margin on either side: with about 0.2 mm to spare.
STRICT_UPGRADE = """\
robot: husky
world:
  start: {x: 0.0, y: 0.0, yaw: 0.0}
  route:
    - {x: 6.0, y: 0.0}
    - {x: 6.0, y: 4.0}
  time_limit: 40.0
pairs:
  strict_upgrade:
    baseline:  {model: sick_lms111}
    candidate:
      model: sick_lms111
      samples: 1201
      min_angle: -2.61799388
      max_angle: 2.61799388
      range: {max: 30.0}
"""
# s: move_base's obstacle-free run set off this late, so the first anchor (0.10 s, the first scan
# on a leg) comes after five scans from the start pose, and 4.9 mm along.
SETS_OFF = 0.09
FIRST_ANCHOR = 0.1


def _scene(directory: Path) -> Scene:
    """The pair on the route, the robot setting off SETS_OFF s after the start."""
    spec = load_pairs_file(write(directory, STRICT_UPGRADE))
    (pair,) = spec.pairs
    robot, world = spec.robot, spec.world
    path = nominal_path(world.start, world.route, robot.nominal_speed, robot.nominal_turn_rate)
    late = tuple(
        dataclasses.replace(segment, begins=segment.begins + SETS_OFF) for segment in path.segments
    )
    path = dataclasses.replace(path, segments=late)
    return Scene(pair.baseline.profile, pair.candidate.profile, robot, path)


def test_a_pole_that_fits_between_the_beams_only_at_the_start_is_proven_not_to_discriminate(
    tmp_path: Path,
) -> None:
    # The proof's model fit between the baseline's beams at 0.10 s, and the scans the baseline
    # took standing at the start read it: the direction was left undecided, and the gate red.
    settings = SearchSettings(min_size=0.05)
    plan = plan_direction(_scene(tmp_path), "baseline-misses", settings)
    assert plan.status == "unsat"
    assert "between two of its beams (0.500 deg apart), ruled out by" in plan.explanation
    assert "its earlier scan at t = 0.00 s, from where the robot was then" in plan.explanation


def test_a_thinner_pole_that_the_baseline_misses_from_the_start_pose_too_is_a_witness(
    tmp_path: Path,
) -> None:
    scene = _scene(tmp_path)
    settings = SearchSettings(min_size=0.047)
    shapes = tuple(shapes_for(0, 0.0))
    proof = prove(scene, "baseline-misses", FIRST_ANCHOR, settings, shapes)
    assert proof.verdict == "sat"
    assert proof.witness is not None
    assert proof.witness.verification.holds()
    obstacle = proof.witness.placement.obstacle
    times = scan_times(scene.baseline.update_rate, FIRST_ANCHOR)
    start = scene.path.poses_at(np.array([0.0]))
    assert np.array_equal(scene.path.poses_at(times[:-1]), np.repeat(start, len(times) - 1, 0))
    assert miss_margins(scene.baseline, scene.path.poses_at(times), obstacle).min() >= (
        REQUIRED_MARGIN
    )
