"""The exact ray-cast verifier every solver witness faces (`model/verify.py`): a placement's four
margins, the misser's miss margins, the readings a scan gives, and the robot's last chance to
stop."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from pytest_lasertest.model.geometry import Point2D, Pose2D
from pytest_lasertest.model.obstacles import Box, Cylinder, segment_clearances
from pytest_lasertest.model.plan import Witness
from pytest_lasertest.model.route import nominal_path
from pytest_lasertest.model.verify import (
    EXACT_WITHIN,
    REQUIRED_MARGIN,
    Placement,
    Verification,
    last_chance,
    miss_margins,
    readings,
    stopping_clearance,
    verify,
)
from pytest_lasertest.solver.plan import plan_direction
from tests.helpers.paper import SETTINGS, scene


def test_the_verifier_rejects_an_obstacle_both_scanners_read() -> None:
    straight_ahead = Cylinder(x=3.0, y=0.5, radius=0.2, height=1.0)
    placement = Placement(straight_ahead, "candidate-misses", 0.0, 0.0)
    verification = verify(scene("distance"), placement)
    assert verification.detection >= REQUIRED_MARGIN
    assert verification.concealment < 0
    assert verification.seen_by_misser_at == (0.0,)
    assert not verification.holds()


def test_the_verifier_rejects_an_obstacle_the_robot_cannot_stop_for() -> None:
    at_the_bumper = Box(x=0.6, y=0.0, yaw=0.0, length=0.1, width=0.1, height=1.0)
    verification = verify(scene("size"), Placement(at_the_bumper, "candidate-misses", 0.0, 0.0))
    assert verification.clearance < 0


def test_a_scans_miss_margin_is_its_nearest_beams_clearance_up_to_the_exact_limit() -> None:
    rng = np.random.default_rng(5)
    scanner = scene("size").baseline
    poses = np.column_stack([rng.uniform(0, 4, 30), rng.uniform(-1, 1, 30), rng.uniform(-1, 1, 30)])
    for obstacle in (
        Cylinder(x=3.0, y=0.3, radius=0.12, height=1.0),
        Box(x=2.5, y=-0.4, yaw=0.6, length=0.3, width=0.1, height=1.0),
    ):
        origins, directions = scanner.rays(poses)
        count = origins.shape[0] * origins.shape[1]
        every_beam = segment_clearances(
            origins.reshape(-1, 2),
            directions.reshape(-1, 2),
            np.full(count, scanner.range_min),
            np.full(count, scanner.range_max),
            obstacle,
        ).reshape(origins.shape[:2])

        margins = miss_margins(scanner, poses, obstacle)

        np.testing.assert_allclose(
            margins, np.minimum(every_beam.min(axis=1), EXACT_WITHIN), rtol=0, atol=1e-12
        )


@pytest.mark.parametrize("route", [[(10.0, 0.0)], [(2.0, 0.0), (2.0, 6.0)]])
def test_the_last_chance_is_the_latest_instant_braking_still_stops_clear(
    route: list[tuple[float, float]],
) -> None:
    path = nominal_path(Pose2D(0.0, 0.0, 0.0), tuple(Point2D(*p) for p in route), 0.5, 1.0)
    size = dataclasses.replace(scene("size"), path=path)
    rng = np.random.default_rng(7)
    in_the_way = 0
    for _ in range(40):
        x, y, _ = path.poses_at(rng.uniform(0.0, path.duration, 1))[0] + rng.uniform(-0.7, 0.7, 3)
        obstacle = Box(float(x), float(y), float(rng.uniform(0, 1.5)), 0.2, 0.1, 1.0)

        last = last_chance(size, obstacle)

        if 0.0 < last < path.duration:
            in_the_way += 1
            assert stopping_clearance(size, obstacle, last) > 0.0
            assert stopping_clearance(size, obstacle, last + 1e-4) <= 0.0
    assert in_the_way >= 20


def test_an_obstacle_lower_than_the_scan_plane_is_not_read() -> None:
    low = Cylinder(x=3.0, y=0.0, radius=0.2, height=0.2)
    pose = np.array([[0.0, 0.0, 0.0]])
    assert np.all(readings(scene("size").baseline, pose, low) == np.inf)


MARGINS = ("detection", "concealment", "clearance", "obstruction")


@pytest.fixture(scope="module")
def size_witness() -> Witness:
    """The solver's witness that the size pair's 16-beam candidate misses what its 32-beam
    baseline reads."""
    (witness,) = plan_direction(scene("size"), "candidate-misses", SETTINGS).witnesses
    return witness


def test_a_witness_the_solver_returned_verifies_with_every_margin_at_least_the_required_one(
    size_witness: Witness,
) -> None:
    verification = verify(scene("size"), size_witness.placement)
    assert all(getattr(verification, margin) >= REQUIRED_MARGIN for margin in MARGINS)
    assert verification.holds()
    assert verification.seen_by_misser_at == ()
    assert verification == size_witness.verification


def test_moving_the_obstacle_into_the_missers_beams_makes_concealment_negative(
    size_witness: Witness,
) -> None:
    size = scene("size")
    misser = size.misser("candidate-misses")
    # Centred on the misser's middle beam of its first scan, at the start, 3 m out.
    origins, directions = misser.rays(size.path.poses_at(np.array([0.0])))
    beam = misser.beam_count // 2
    x, y = origins[0, beam] + 3.0 * directions[0, beam]
    moved = dataclasses.replace(size_witness.placement.obstacle, x=float(x), y=float(y))
    assert moved.height > misser.scan_height

    verification = verify(size, dataclasses.replace(size_witness.placement, obstacle=moved))

    assert verification.concealment < 0.0
    assert verification.seen_by_misser_at[0] == 0.0
    assert not verification.holds()


def test_lowering_the_obstacle_under_the_detectors_scan_plane_makes_detection_negative(
    size_witness: Witness,
) -> None:
    size = scene("size")
    detector = size.detector("candidate-misses")
    obstacle = size_witness.placement.obstacle
    lowered = dataclasses.replace(obstacle, height=detector.scan_height - 0.05)

    verification = verify(size, dataclasses.replace(size_witness.placement, obstacle=lowered))

    assert verification.detection < 0.0
    assert verification.detection <= lowered.height - detector.scan_height
    assert not verification.holds()


@pytest.mark.parametrize("smallest", MARGINS)
def test_the_margin_of_a_verification_is_the_smallest_of_its_four_margins(smallest: str) -> None:
    margins = dict(zip(MARGINS, (0.04, 0.03, 0.02, 0.01), strict=True))
    margins[smallest] = 0.003
    verification = Verification(**margins, seen_by_misser_at=(), lead=0.0, late=False)
    assert verification.margin == 0.003
    assert not verification.holds()
    assert verification.holds(required=0.003)


def test_being_read_too_near_obstructs_a_placement_both_read_as_standing_in_the_way_does() -> None:
    margins = dict(zip(MARGINS, (0.04, 0.03, 0.02, -0.5), strict=True))
    apart = Verification(**margins, seen_by_misser_at=(), lead=0.0, late=False)
    assert not apart.holds()
    assert dataclasses.replace(apart, too_near=0.01).margin == 0.01
    assert dataclasses.replace(apart, too_near=0.1).margin == 0.02


def test_a_placement_both_read_holds_beside_the_path_only_if_the_candidate_reads_it_too_near() -> (
    None
):
    # Beside the straight route, 0.36 m clear of the Husky's side, 0.7 m from its scanner.
    beside = Placement(Cylinder(x=4.0, y=0.9, radius=0.2, height=1.0), None, 4.0, 4.0)
    same = scene("size")
    hidden = dataclasses.replace(same, candidate=dataclasses.replace(same.candidate, range_min=0.9))

    assert verify(same, beside).too_near == -np.inf
    assert not verify(same, beside).holds()
    assert verify(hidden, beside).too_near >= REQUIRED_MARGIN
    assert verify(hidden, beside).holds()
