"""Offsets from a witness, and the box within which a perturbed witness stays discriminating."""

from __future__ import annotations

import dataclasses
from functools import cache

import numpy as np
import pytest

from pytest_lasertest.model.obstacles import Box, Cylinder
from pytest_lasertest.model.plan import PairPlan, Witness
from pytest_lasertest.model.verify import Placement
from pytest_lasertest.pairsfile import load_pairs_file
from pytest_lasertest.search.offsets import (
    AXES,
    REACH,
    Offset,
    OffsetBox,
    discriminates,
    offset_box,
    perturbed,
)
from pytest_lasertest.search.plans import plan_for
from tests.helpers import EXAMPLES

SIZES = (0.0507, 1.0)  # m, the paper's pairs file's smallest and largest obstacle


@cache
def size_plan() -> PairPlan:
    spec = load_pairs_file(EXAMPLES / "paper.lasertest.yaml")
    (size,) = (pair for pair in spec.pairs if pair.name == "size")
    return plan_for(spec, size)


def witnesses() -> list[Witness]:
    return [witness for plan in size_plan().directions for witness in plan.witnesses]


def test_a_perturbed_box_is_moved_turned_resized_and_raised() -> None:
    box = Box(1.0, 2.0, 0.1, 0.4, 0.2, 0.5)
    placement = Placement(box, "candidate-misses", 1.0, 1.0)
    moved = perturbed(placement, Offset(0.1, -0.2, 0.3, 0.05, 0.25))
    assert dataclasses.astuple(moved.obstacle) == pytest.approx((1.1, 1.8, 0.4, 0.45, 0.25, 0.75))
    assert (moved.anchor, moved.until, moved.direction) == (1.0, 1.0, "candidate-misses")


def test_a_perturbed_cylinder_grows_by_its_diameter_and_ignores_yaw() -> None:
    cylinder = Cylinder(1.0, 2.0, 0.1, 0.5)
    moved = perturbed(Placement(cylinder, "baseline-misses", 0.0, 0.0), Offset(size=0.04, yaw=1.0))
    assert isinstance(moved.obstacle, Cylinder)
    assert dataclasses.astuple(moved.obstacle) == pytest.approx((1.0, 2.0, 0.12, 0.5))


def test_the_zero_offset_is_the_witness() -> None:
    witness = witnesses()[0]
    assert perturbed(witness.placement, Offset()) == witness.placement


def test_an_offset_describes_only_the_axes_it_changes() -> None:
    assert Offset().describe() == "none"
    assert Offset(x=0.012, yaw=-0.1).describe() == "x +0.012 m, yaw -0.100 rad"


@pytest.mark.parametrize("index", range(6))
def test_nearly_every_offset_in_a_witness_box_still_discriminates(index: int) -> None:
    scene, witness = size_plan().scene, witnesses()[index]
    box = offset_box(scene, witness.placement, SIZES, np.random.default_rng(0))
    rng = np.random.default_rng(123)
    held = [
        discriminates(scene, perturbed(witness.placement, _uniform(box, rng)), SIZES)
        for _ in range(100)
    ]
    assert sum(held) >= 90


@pytest.mark.parametrize("index", range(6))
def test_a_witness_box_holds_the_witness_and_stays_within_reach(index: int) -> None:
    scene, witness = size_plan().scene, witnesses()[index]
    box = offset_box(scene, witness.placement, SIZES, np.random.default_rng(0))
    for name in AXES:
        low, high = box.bounds(name)
        assert -REACH[name] <= low <= 0.0 <= high <= REACH[name]
    assert any(box.bounds(name) != (0.0, 0.0) for name in AXES)


def test_a_cylinder_witness_gets_no_yaw() -> None:
    scene = size_plan().scene
    witness = next(w for w in witnesses() if isinstance(w.placement.obstacle, Cylinder))
    box = offset_box(scene, witness.placement, SIZES, np.random.default_rng(0))
    assert box.bounds("yaw") == (0.0, 0.0)


def test_no_offset_may_shrink_an_obstacle_below_the_smallest_size() -> None:
    scene, witness = size_plan().scene, witnesses()[1]
    assert not discriminates(scene, perturbed(witness.placement, Offset(size=-0.01)), SIZES)
    box = offset_box(scene, witness.placement, SIZES, np.random.default_rng(0))
    obstacle = perturbed(witness.placement, box.low).obstacle
    side = obstacle.radius * 2 if isinstance(obstacle, Cylinder) else obstacle.width
    assert side >= SIZES[0] - 1e-9


def test_the_box_is_the_same_for_the_same_generator_seed() -> None:
    scene, witness = size_plan().scene, witnesses()[2]
    boxes = [
        offset_box(scene, witness.placement, SIZES, np.random.default_rng(5)) for _ in range(2)
    ]
    assert boxes[0] == boxes[1]


def test_a_placement_that_does_not_verify_gets_an_empty_box() -> None:
    scene, witness = size_plan().scene, witnesses()[0]
    lost = perturbed(witness.placement, Offset(y=5.0))
    assert offset_box(scene, lost, SIZES, np.random.default_rng(0)) == OffsetBox(Offset(), Offset())


def _uniform(box: OffsetBox, rng: np.random.Generator) -> Offset:
    values = {}
    for name in AXES:
        low, high = box.bounds(name)
        values[name] = float(rng.uniform(low, high)) if high > low else low
    return Offset(**values)
