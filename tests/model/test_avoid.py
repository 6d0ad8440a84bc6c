"""Placements both scanners read that the robot must act on (`model/avoid.py`)."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from pytest_lasertest.model.avoid import LOOKAHEAD, SEEDS, avoid_witnesses
from pytest_lasertest.model.geometry import Point2D, Pose2D
from pytest_lasertest.model.obstacles import Cylinder
from pytest_lasertest.model.route import nominal_path, scan_times
from pytest_lasertest.model.verify import (
    REQUIRED_MARGIN,
    Scene,
    hit_margins,
    readings,
    verify,
)
from tests.helpers.paper import PAPER, scene

SIZES = (0.05, 1.0)  # m


def turning(name: str) -> Scene:
    """The paper's pair `name` on a route 4 m ahead, then 4 m to the left."""
    robot = PAPER.robot
    route = (Point2D(4.0, 0.0), Point2D(4.0, 4.0))
    path = nominal_path(Pose2D(0.0, 0.0, 0.0), route, robot.nominal_speed, robot.nominal_turn_rate)
    return dataclasses.replace(scene(name), path=path)


@pytest.mark.parametrize("name", ["size", "distance", "blind_spot"])
def test_every_placement_to_steer_round_is_read_by_both_scanners_and_in_the_way(name: str) -> None:
    here = turning(name)
    witnesses = avoid_witnesses(here, SIZES)
    assert witnesses
    for witness in witnesses:
        placement = witness.placement
        pose = here.path.poses_at(np.array([placement.anchor]))
        for profile in (here.baseline, here.candidate):
            assert np.max(hit_margins(profile, pose, placement.obstacle)) >= REQUIRED_MARGIN
        verification = verify(here, placement)
        assert verification.obstruction >= REQUIRED_MARGIN
        assert verification.clearance >= REQUIRED_MARGIN
        assert verification.concealment == math.inf
        assert witness.verification == verification


def test_a_placement_to_steer_round_stands_beside_the_path_not_on_it() -> None:
    here = turning("size")
    for witness in avoid_witnesses(here, SIZES):
        obstacle = witness.placement.obstacle
        assert isinstance(obstacle, Cylinder)
        beside = min(abs(obstacle.y), abs(obstacle.x - 4.0))  # m off the nearer leg's centre line
        assert beside >= 0.1 - 1e-9


def test_the_anchor_is_lookahead_before_the_obstacle_or_the_start() -> None:
    here = turning("size")
    for witness in avoid_witnesses(here, SIZES):
        placement = witness.placement
        obstacle = placement.obstacle
        pose = here.path.poses_at(np.array([placement.anchor]))[0]
        ahead = math.hypot(obstacle.x - pose[0], obstacle.y - pose[1])
        assert placement.anchor == 0.0 or ahead <= LOOKAHEAD + 0.5


def test_placements_to_steer_round_are_numbered_in_order_and_named_avoid() -> None:
    witnesses = avoid_witnesses(turning("size"), SIZES)
    assert [witness.index for witness in witnesses] == list(range(len(witnesses)))
    assert [witness.id for witness in witnesses][:2] == ["avoid-0", "avoid-1"]
    assert all(witness.placement.direction is None for witness in witnesses)
    assert all(witness.placement.read_by() == "baseline and candidate" for witness in witnesses)


def test_the_same_scene_gives_the_same_placements() -> None:
    assert avoid_witnesses(turning("size"), SIZES) == avoid_witnesses(turning("size"), SIZES)


def test_thin_seeds_take_the_smallest_size_and_wide_ones_stay_within_the_largest() -> None:
    witnesses = avoid_witnesses(turning("distance"), (0.08, 0.3))
    radii = {round(witness.placement.obstacle.bounding_radius, 6) for witness in witnesses}
    assert radii <= {0.04, 0.15}
    assert 0.04 in radii


def test_a_seed_no_scanner_can_read_at_its_anchor_is_passed_over() -> None:
    # A scanner looking backwards reads nothing ahead of the robot: no seed verifies.
    here = turning("size")
    backwards = dataclasses.replace(here.candidate, min_angle=2.5, max_angle=3.0)
    assert avoid_witnesses(dataclasses.replace(here, candidate=backwards), SIZES) == ()
    assert len(SEEDS) >= 3


def near_field(range_min: float = 0.6) -> Scene:
    """The turning route, the candidate the baseline with its range_min raised to hide the
    chassis."""
    here = turning("size")
    candidate = dataclasses.replace(here.baseline, range_min=range_min)
    return dataclasses.replace(here, candidate=candidate)


def test_a_larger_range_min_puts_placements_read_too_near_first() -> None:
    here = near_field()
    witnesses = avoid_witnesses(here, SIZES)
    first = witnesses[0].verification
    assert first.too_near >= REQUIRED_MARGIN
    assert first.obstruction < 0.0  # clear of what the robot sweeps: it drives past untouched
    assert first.clearance >= REQUIRED_MARGIN
    assert first.holds()


def test_the_candidate_reads_a_placement_too_near_where_the_baseline_reads_it_in_range() -> None:
    here = near_field()
    placement = avoid_witnesses(here, SIZES)[0].placement
    times = scan_times(here.candidate.update_rate, here.path.duration)
    poses = here.path.poses_at(times)
    candidate = readings(here.candidate, poses, placement.obstacle)  # (T, N) m
    baseline = readings(here.baseline, poses, placement.obstacle)
    too_near = np.isneginf(candidate) & np.isfinite(baseline)
    assert too_near.any()
    assert np.all(baseline[too_near] >= here.baseline.range_min)


def test_the_robot_stops_short_of_the_placement_beyond_the_turn_and_turns_away() -> None:
    here = near_field()
    obstacle = avoid_witnesses(here, SIZES)[0].placement.obstacle
    assert isinstance(obstacle, Cylinder)
    assert obstacle.x > 4.0 + 0.6  # straight on beyond the corner at (4, 0), past the turning disc
    assert obstacle.y == pytest.approx(0.0)


@pytest.mark.parametrize("range_min", [0.1, 0.05])
def test_no_placement_is_read_too_near_unless_the_candidate_range_min_is_larger(
    range_min: float,
) -> None:
    for witness in avoid_witnesses(near_field(range_min), SIZES):
        assert witness.verification.too_near == -math.inf
        assert witness.verification.obstruction >= REQUIRED_MARGIN
