"""Nav2's collision monitor: the robot reaches what its scan reads no sooner than 1.2 s from now,
readings of exactly range_max count, and what stands in the footprint stops it."""

from __future__ import annotations

import numpy as np
import pytest

from pytest_lasertest.model.geometry import Pose3D
from pytest_lasertest.model.sensor import LaserScanMeta
from pytest_lasertest.nav.nav2.collision_monitor import (
    CollisionMonitorSettings,
    _process_approach,
    approach,
    scan_points,
)
from pytest_lasertest.nav.protocol import LaserScan

SETTINGS = CollisionMonitorSettings()
FOOTPRINT = np.array([[0.5, 0.35], [-0.5, 0.35], [-0.5, -0.35], [0.5, -0.35]])  # m


def wall(x: float) -> np.ndarray:
    """Points (20, 2) m across the robot's way, `x` m ahead of its centre."""
    return np.column_stack([np.full(20, x), np.linspace(-0.5, 0.5, 20)])


@pytest.mark.parametrize(
    ("ahead", "expected"),
    [
        (3.0, (0.5, 0.0)),  # 2.5 m off: not reached within 1.2 s at 0.5 m/s
        # Its front reaches it after 1.0 s; Nav2 returns the loop's time, one step behind the
        # pose it moved, so the time is 1.0 s while the pose is at 1.1 s.
        (1.0, (0.5 * 1.0 / 1.2, 0.0)),
        (0.3, (0.0, 0.0)),  # inside the footprint now
    ],
)
def test_a_wall_ahead_slows_the_robot_to_reach_it_no_sooner_than_1_2_s(
    ahead: float, expected: tuple[float, float]
) -> None:
    assert approach((0.5, 0.0), wall(ahead), FOOTPRINT, SETTINGS) == pytest.approx(expected)


def test_fewer_than_six_points_in_the_way_do_not_slow_the_robot() -> None:
    few = wall(1.0)[:5]
    assert approach((0.5, 0.0), few, FOOTPRINT, SETTINGS) == (0.5, 0.0)


def test_a_reading_of_exactly_range_max_counts_and_a_no_return_does_not() -> None:
    meta = LaserScanMeta(-0.1, 0.1, 0.1, 0.0, 0.0, 0.1, 5.0)
    mount = Pose3D((0.0, 0.0, 0.4), (0.0, 0.0, 0.0))
    scan = LaserScan(0.0, np.array([5.0, np.inf, 4.0]), meta, mount)
    assert len(scan_points(scan)) == 2


def test_a_scan_source_is_read_at_any_height_as_nav2s_scan_source_has_no_heights() -> None:
    meta = LaserScanMeta(-0.1, 0.1, 0.1, 0.0, 0.0, 0.1, 5.0)
    low = LaserScan(0.0, np.array([5.0, 4.0, 4.0]), meta, Pose3D((0.0, 0.0, 0.1), (0.0, 0.0, 0.0)))
    assert len(scan_points(low)) == 3  # 0.1 m up: a point cloud source's min_height, 0.05 m


@pytest.mark.parametrize("seed", range(30))
def test_testing_only_the_points_the_footprint_can_reach_changes_no_command(seed: int) -> None:
    rng = np.random.default_rng(seed)
    # A scan's worth of points, some about the robot and most metres away.
    points = np.vstack([rng.uniform(-4.0, 4.0, (300, 2)), rng.uniform(-1.6, 1.6, (30, 2))])
    command = (float(rng.uniform(-0.6, 0.6)), float(rng.uniform(-1.5, 1.5)))
    settings = CollisionMonitorSettings(
        float(rng.uniform(0.3, 2.0)), float(rng.choice([0.02, 0.05, 0.1])), int(rng.integers(1, 12))
    )
    # processApproach as Nav2 runs it: every point tested at every step.
    every_point = _process_approach(command, points, FOOTPRINT, settings)
    assert approach(command, points, FOOTPRINT, settings) == every_point
