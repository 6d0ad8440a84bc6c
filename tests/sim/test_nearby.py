"""Which obstacles the robot can come near: by footprint, not bounding circle, and found again as
it moves."""

from __future__ import annotations

import math

import pytest

from pytest_lasertest.model.obstacles import Box, Cylinder
from pytest_lasertest.sim.nearby import REFRESH, Footprint, Nearby


def test_a_turned_boxs_gap_is_to_its_rectangle_and_a_cylinders_to_its_circle() -> None:
    box = Footprint.of(Box(0.0, 0.0, math.pi / 2.0, 2.0, 1.0, 1.0))  # 2 m long along y
    assert box.gap(0.0, 2.0) == pytest.approx(1.0)
    assert box.gap(1.5, 0.0) == pytest.approx(1.0)
    assert box.gap(1.5, 2.0) == pytest.approx(math.sqrt(2.0))
    assert box.gap(0.2, 0.3) == 0.0
    assert Footprint.of(Cylinder(3.0, 0.0, 0.5, 1.0)).gap(0.0, 0.0) == pytest.approx(2.5)


def test_a_wall_beside_the_robot_is_near_and_one_far_off_is_found_once_the_robot_moves() -> None:
    wall, far = Box(6.0, 1.0, 0.0, 12.0, 0.1, 1.0), Box(6.0, 3.0, 0.0, 12.0, 0.1, 1.0)
    nearby = Nearby((7, 8), (wall, far), reach=0.6)
    assert nearby.bodies(0.0, 0.0, within=0.5) == (7,)
    assert nearby.bodies(0.0, REFRESH / 2.0, within=0.5) == (7,)
    assert nearby.bodies(0.0, 2.0, within=0.5) == (7, 8)  # between the walls
