"""nav2_collision_monitor's kinematics tests (test/kinematics_test.cpp), rebuilt on the two
functions our collision monitor moves the robot and the scan's points with
(`collision_monitor.transform_points` and `project_state`)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from pytest_lasertest.nav.nav2.collision_monitor import project_state, transform_points
from tests.helpers.upstream import NAVIGATION2_JAZZY, Source

KINEMATICS = Source(
    "Nav2 collision monitor", NAVIGATION2_JAZZY, "nav2_collision_monitor/test/kinematics_test.cpp"
)
EPSILON = float(np.finfo(np.float32).eps)  # std::numeric_limits<float>::epsilon()


@KINEMATICS.test("KinematicsTest.testTransformPoints", assertions=4)
def test_points_are_seen_from_a_frame_moved_to_2_1_and_turned_30_degrees() -> None:
    moved = transform_points((2.0, 1.0, math.pi / 6.0), np.array([[3.0, 2.0], [0.0, 0.0]]))
    # (3, 2) lies sqrt(2) away at 45 degrees of the moved frame, less its turn.
    distance, angle = math.sqrt(2.0), math.pi / 4.0 - math.pi / 6.0
    assert moved[0, 0] == pytest.approx(distance * math.cos(angle), abs=EPSILON)
    assert moved[0, 1] == pytest.approx(distance * math.sin(angle), abs=EPSILON)
    distance, angle = math.sqrt(5.0), math.pi + math.atan(0.5) - math.pi / 6.0
    assert moved[1, 0] == pytest.approx(distance * math.cos(angle), abs=EPSILON)
    assert moved[1, 1] == pytest.approx(distance * math.sin(angle), abs=EPSILON)


@KINEMATICS.test("KinematicsTest.testProjectState", assertions=6)
def test_a_state_projected_one_second_moves_by_the_velocity_and_turns_it() -> None:
    pose, velocity = project_state(1.0, (2.0, 1.0, math.pi / 4.0), (0.0, 1.0, math.pi / 4.0))
    assert pose[0] == pytest.approx(2.0, abs=EPSILON)
    assert pose[1] == pytest.approx(2.0, abs=EPSILON)
    assert pose[2] == pytest.approx(math.pi / 2.0, abs=EPSILON)
    # The velocity, along y at first, turned by pi/4 with the robot; its turn rate kept.
    turned = math.pi / 2.0 + math.pi / 4.0
    assert velocity[0] == pytest.approx(math.cos(turned), abs=EPSILON)
    assert velocity[1] == pytest.approx(math.sin(turned), abs=EPSILON)
    assert velocity[2] == pytest.approx(math.pi / 4.0, abs=EPSILON)
