"""Obstacles as drives place them (`obstacles.placed`): to a micrometre, the numbers a pinned
replay writes, so that the replay drives the very obstacle the failure drove."""

from __future__ import annotations

import numpy as np

from pytest_lasertest.model.obstacles import Box, Cylinder, placed


def test_each_number_is_rounded_to_a_micrometre_and_minus_zero_is_zero() -> None:
    box = Box(3.5999999999999996, 0.1 + 0.2, -1e-12, 1.0 / 30.0, 0.05, 0.323)
    assert placed(box) == Box(3.6, 0.3, 0.0, 0.033333, 0.05, 0.323)
    assert str(placed(box).yaw) == "0.0"


def test_a_size_that_would_round_to_nothing_is_kept_in_full() -> None:
    assert placed(Cylinder(5.0, 0.0, 4e-7, 0.5)) == Cylinder(5.0, 0.0, 4e-7, 0.5)


def test_solver_output_in_numpy_floats_is_placed_as_plain_floats() -> None:
    cylinder = placed(Cylinder(np.float64(1.23456789), 0.0, 0.1, 0.5))  # type: ignore[arg-type]
    assert type(cylinder.x) is float
    assert cylinder.x == 1.234568
