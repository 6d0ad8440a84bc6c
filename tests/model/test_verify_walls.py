"""Walls in the verifier and the solver (issue 25): a scanner reads nothing behind a wall, so a
witness "read" through one is refused, no obstacle may stand in one, and the solver's witnesses
in the aisle world (examples/worlds/aisle.lasertest.yaml: two racks of shelving either side
of a 1.6 m aisle) are read past the racks, never through them."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from pytest_lasertest.model.obstacles import Cylinder
from pytest_lasertest.model.plan import PairPlan
from pytest_lasertest.model.verify import REQUIRED_MARGIN, Placement, Scene, readings, verify
from pytest_lasertest.model.walls import NO_WALLS
from pytest_lasertest.pairsfile import PairsFile, load_pairs_file
from pytest_lasertest.search.plans import pair_scene, plan_scene
from tests.helpers import WORLDS

# The aisle runs along y = 3 m between racks at y 1.4-2.2 m and 3.8-4.6 m, x 2-10 m; the robot
# starts at its mouth, (1, 3) m, facing along it.
BEHIND_THE_LOWER_RACK = Cylinder(x=6.0, y=0.8, radius=0.1, height=1.0)
IN_THE_AISLE = Cylinder(x=6.0, y=3.0, radius=0.1, height=1.0)
INSIDE_THE_LOWER_RACK = Cylinder(x=6.0, y=1.8, radius=0.1, height=1.0)


@pytest.fixture(scope="module")
def aisle() -> PairsFile:
    return load_pairs_file(WORLDS / "aisle.lasertest.yaml")


@pytest.fixture(scope="module")
def scene(aisle: PairsFile) -> Scene:
    """The RPLIDAR A1 (12 m) and the LDS-01 (3.5 m) on the burger, along the aisle."""
    return pair_scene(aisle, aisle.pairs[0])


@pytest.fixture(scope="module")
def plan(aisle: PairsFile, scene: Scene) -> PairPlan:
    return plan_scene(aisle, aisle.pairs[0], scene)


def read_from_the_start(obstacle: Cylinder) -> Placement:
    """The obstacle as the RPLIDAR A1 would have to read it at the start, the LDS-01 missing it."""
    return Placement(obstacle, "baseline-misses", 0.0, 0.0)


def test_an_obstacle_the_new_scanner_reads_in_an_empty_world_is_hidden_by_a_rack(
    scene: Scene,
) -> None:
    placement = read_from_the_start(BEHIND_THE_LOWER_RACK)
    without_walls = verify(dataclasses.replace(scene, walls=NO_WALLS), placement)
    assert without_walls.detection >= REQUIRED_MARGIN

    with_walls = verify(scene, placement)

    assert with_walls.detection < 0.0
    assert not with_walls.holds()


def test_the_same_obstacle_in_the_aisle_in_plain_view_is_read_with_the_racks_there(
    scene: Scene,
) -> None:
    verification = verify(scene, read_from_the_start(IN_THE_AISLE))
    assert verification.detection >= REQUIRED_MARGIN


def test_an_obstacle_standing_inside_a_rack_is_refused_by_its_wall_margin(scene: Scene) -> None:
    verification = verify(scene, read_from_the_start(INSIDE_THE_LOWER_RACK))
    assert verification.walls < 0.0
    assert not verification.holds()


def test_a_scan_reads_no_obstacle_behind_a_rack(scene: Scene) -> None:
    start = scene.path.poses_at(np.array([0.0]))
    scanner = scene.candidate

    hidden = readings(scanner, start, BEHIND_THE_LOWER_RACK, scene.walls)
    in_view = readings(scanner, start, IN_THE_AISLE, scene.walls)

    assert not np.isfinite(hidden).any()
    assert np.isfinite(in_view).any()


def test_the_solver_finds_a_witness_in_the_aisle_and_every_witness_verifies_among_the_racks(
    scene: Scene, plan: PairPlan
) -> None:
    witnesses = [witness for direction in plan.directions for witness in direction.witnesses]
    assert witnesses
    for witness in witnesses:
        verification = verify(scene, witness.placement)
        assert verification.holds()
        assert verification.walls >= REQUIRED_MARGIN


def test_each_aisle_witness_is_read_by_its_detector_at_its_anchor_with_no_rack_in_between(
    scene: Scene, plan: PairPlan
) -> None:
    for direction in plan.directions:
        for witness in direction.witnesses:
            placement = witness.placement
            detector = getattr(scene, placement.readers[0])
            anchor = scene.path.poses_at(np.array([placement.anchor]))
            read = readings(detector, anchor, placement.obstacle, scene.walls)
            assert np.isfinite(read).any(), f"{placement.obstacle} is read only through a rack"
