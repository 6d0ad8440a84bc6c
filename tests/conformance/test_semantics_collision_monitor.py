"""Behaviour tests of Nav2's collision monitor approach polygon, from the upstream code's
semantics where no upstream unit test pins them: ros-navigation/navigation2 at jazzy f4108e5b,
nav2_collision_monitor/src/polygon.cpp (getCollisionTime, isPointInside),
src/kinematics.cpp (projectState, transformPoints), src/collision_monitor_node.cpp
(processApproach) and include/nav2_collision_monitor/types.hpp (Velocity), src/scan.cpp
(getData), with nav2_params.yaml's FootprintApproach (time_before_collision 1.2 s,
simulation_time_step 0.1 s, min_points 6).

On our `approach` and `scan_points` (pytest_lasertest/nav/nav2/collision_monitor.py), with a
footprint of 1 m x 0.6 m about the base. Each expected command is worked out by hand from the
upstream loop:

    for (time = 0.0; time <= time_before_collision; time += simulation_time_step) {
      projectState(simulation_time_step, pose, vel);   // the pose moves first
      if (getPointsInside(points seen from pose) >= min_points) return time;
    }

so the k-th simulated step (the robot moved k x 0.1 s) returns (k - 1) x 0.1 s, and
processApproach scales the whole command by that time over 1.2 s.

These tests port no upstream assertion and carry no `upstream` mark.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from pytest_lasertest.model.geometry import FloatArray, Pose3D
from pytest_lasertest.model.sensor import LaserScanMeta
from pytest_lasertest.nav.nav2.collision_monitor import (
    CollisionMonitorSettings,
    approach,
    scan_points,
)
from pytest_lasertest.nav.protocol import LaserScan

MONITOR = CollisionMonitorSettings()  # nav2_params.yaml's FootprintApproach
HALF_LENGTH, HALF_WIDTH = 0.5, 0.3  # m
FOOTPRINT = np.array(
    [
        [HALF_LENGTH, HALF_WIDTH],
        [-HALF_LENGTH, HALF_WIDTH],
        [-HALF_LENGTH, -HALF_WIDTH],
        [HALF_LENGTH, -HALF_WIDTH],
    ]
)
TIGHT = 1e-12  # what floating-point rounding leaves of a command, m/s or rad/s
ACROSS = (-0.25, -0.15, -0.05, 0.05, 0.15, 0.25)  # m, six points across the footprint's width


def wall(x: float, count: int = 6) -> FloatArray:
    """`count` points across the robot's way at `x` m from its centre, shape (count, 2) m."""
    return np.column_stack([np.full(count, x), np.array(ACROSS[:count])])


def allowed(command: tuple[float, float], points: FloatArray) -> tuple[float, float]:
    return approach(command, points, FOOTPRINT, MONITOR)


@pytest.mark.parametrize(
    ("beyond", "expected"),
    [
        # 0.05 m beyond the front: the first step (0.1 m) takes it in, at loop time 0: stop.
        pytest.param(0.05, 0.0, id="taken-in-by-the-first-step-stops"),
        # 0.35 m: the fourth step (0.4 m) takes it in; loop time 0.1 + 0.1 + 0.1: 0.3 / 1.2.
        pytest.param(0.35, 0.25, id="taken-in-by-the-fourth-step"),
        # 1.15 m: the twelfth step (1.2 m); loop time eleven 0.1 s added: 1.1 / 1.2.
        pytest.param(1.15, 1.1 / 1.2, id="taken-in-by-the-twelfth-and-last-step"),
        # 1.25 m: would need a thirteenth step, but the time added up twelve times is
        # 1.2000000000000002 s > 1.2 s: the loop has ended, no collision, the command passes.
        pytest.param(1.25, 1.0, id="beyond-the-last-step"),
    ],
)
def test_driving_at_a_wall_scales_the_speed_by_the_loop_time_of_the_step_that_takes_it_in(
    beyond: float, expected: float
) -> None:
    # polygon.cpp:283-295 and collision_monitor_node.cpp:594-605: at 1 m/s each step moves
    # the footprint 0.1 m; the speed becomes 1 m/s x time / time_before_collision.
    command = allowed((1.0, 0.0), wall(HALF_LENGTH + beyond))
    assert command[0] == pytest.approx(expected, abs=TIGHT)
    assert command[1] == 0.0


def test_backing_towards_points_behind_slows_the_reverse_alike() -> None:
    # kinematics.cpp:44-57 moves the pose by velocity x dt whatever its sign: at -0.5 m/s the
    # rear edge reaches points 0.12 m behind it at the third step (0.15 m), loop time 0.2 s.
    command = allowed((-0.5, 0.0), wall(-HALF_LENGTH - 0.12))
    assert command[0] == pytest.approx(-0.5 * 0.2 / 1.2, abs=TIGHT)
    assert command[1] == 0.0


def test_five_points_in_the_way_do_not_slow_the_robot_and_six_do() -> None:
    # polygon.cpp:292: getPointsInside(...) >= min_points, 6.
    assert allowed((1.0, 0.0), wall(0.85, count=5)) == (1.0, 0.0)
    assert allowed((1.0, 0.0), wall(0.85, count=6))[0] == pytest.approx(0.25, abs=TIGHT)


def test_six_points_inside_the_footprint_now_stop_the_robot() -> None:
    # polygon.cpp:277-280: the static check returns 0.0 s, so the ratio and the command are 0.
    assert allowed((1.0, 0.5), wall(0.3)) == (0.0, 0.0)


def test_points_inside_now_count_together_with_a_point_the_motion_takes_in() -> None:
    # Five points inside (0.45 m ahead) are fewer than min_points, so the robot moves; they
    # stay inside while it moves 0.3 m, and the third step (0.3 m) takes in the sixth, 0.72 m
    # ahead: six points at loop time 0.2 s, 0.2 / 1.2.
    points = np.vstack([wall(0.45, count=5), [[0.72, 0.0]]])
    command = allowed((1.0, 0.0), points)
    assert command[0] == pytest.approx(0.2 / 1.2, abs=TIGHT)


def cluster(x: float, y: float) -> FloatArray:
    """Six points within 1 cm of (x, y) m, shape (6, 2)."""
    return np.array([[x + dx, y + dy] for dx in (-0.01, 0.0, 0.01) for dy in (-0.01, 0.01)])


def test_turning_while_driving_follows_the_velocity_turned_each_step_and_scales_both_speeds() -> (
    None
):
    # kinematics.cpp:44-68: each step moves the pose by the velocity, then turns the pose and
    # the velocity by w dt. At 0.5 m/s and 1 rad/s the k-th pose is 0.05 m x
    # sum_{j<k} (cos 0.1 j, sin 0.1 j) at heading 0.1 k rad: the sixth (0.2865, 0.0731) m,
    # 0.6 rad leaves the cluster at (0.69, 0.40) m 3.7 mm outside; the seventh
    # (0.3277, 0.1014) m, 0.7 rad, holds it by 16 mm or more. Loop time 0.6 s: both speeds
    # scaled by 0.6 / 1.2 (types.hpp:38-41, Velocity * ratio).
    points = cluster(0.69, 0.40)
    command = allowed((0.5, 1.0), points)
    assert command[0] == pytest.approx(0.25, abs=TIGHT)
    assert command[1] == pytest.approx(0.5, abs=TIGHT)
    # Straight on, the footprint sweeps |y| < 0.3 m only; turning right it sweeps away from
    # the cluster: neither takes it in, and the command passes.
    assert allowed((0.5, 0.0), points) == (0.5, 0.0)
    assert allowed((0.5, -1.0), points) == (0.5, -1.0)


def test_a_point_on_the_rear_edge_is_inside_the_footprint_and_one_on_the_front_edge_is_not() -> (
    None
):
    # polygon.cpp:615-623: a ray along +x from the point toggles on each edge it crosses with
    # x_inter > point.x, strictly. On the rear edge it crosses the front edge only (inside);
    # on the front edge it crosses none (outside).
    on_rear, on_front = wall(-HALF_LENGTH), wall(HALF_LENGTH)
    assert allowed((0.5, 0.0), on_rear) == (0.0, 0.0)  # inside now, although driving away
    assert allowed((-0.5, 0.0), on_front) == (-0.5, 0.0)  # outside, and backing away


def test_a_scan_becomes_points_in_the_base_frame_through_an_upside_down_mount() -> None:
    # scan.cpp:88-100: readings with range_min <= r <= range_max, each (r cos a, r sin a, 0)
    # transformed from the laser frame to the base frame; the Husky's laser sits 0.337 m ahead
    # with roll pi, which maps (x, y) to (0.337 + x, -y).
    meta = LaserScanMeta(-0.5, 0.5, 0.25, 0.0, 0.1, 0.1, 5.0)
    mount = Pose3D((0.337, 0.0, 0.44), (math.pi, 0.0, 0.0))
    # Beams at -0.5, -0.25, 0, 0.25, 0.5 rad: 2 m; below range_min; exactly range_min;
    # no return; exactly range_max.
    ranges = np.array([2.0, 0.09, 0.1, np.inf, 5.0])
    points = scan_points(LaserScan(0.0, ranges, meta, mount))
    expected = [
        (0.337 + 2.0 * math.cos(-0.5), 2.0 * math.sin(0.5)),
        (0.337 + 0.1, 0.0),
        (0.337 + 5.0 * math.cos(0.5), -5.0 * math.sin(0.5)),
    ]
    # Upstream steps the angle in single precision (float angle += angle_increment).
    np.testing.assert_allclose(points, expected, rtol=0.0, atol=1e-6)
