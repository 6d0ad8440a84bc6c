"""What a controller is given: a LaserScan's readings as points in the robot's base frame."""

from __future__ import annotations

import numpy as np
import pytest

from pytest_lasertest.nav.protocol import LaserScan
from tests.helpers.paper import PAPER

SIZE = next(pair for pair in PAPER.pairs if pair.name == "size")


def test_readings_nearer_than_range_min_become_points_at_range_min_only_when_asked() -> None:
    profile = SIZE.baseline.profile
    ranges = np.full(profile.beam_count, np.inf)
    ranges[profile.beam_count // 2] = -np.inf
    scan = LaserScan(0.0, ranges, profile.to_laserscan_meta(), profile.pose)
    assert len(scan.points_in_base()) == 0
    (point,) = scan.points_in_base(too_near=True)
    mount = np.array(profile.pose.xyz[:2])
    assert np.linalg.norm(point - mount) == pytest.approx(profile.range_min)
