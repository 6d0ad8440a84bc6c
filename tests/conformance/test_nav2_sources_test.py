"""nav2_collision_monitor's source tests (test/sources_test.cpp), the scan source's part, rebuilt
on our `scan_points`: the points Scan::getData makes of a LaserScan in the base frame.

Not applicable: the point cloud, range and polygon sources (our monitor reads a scan), and
testGetOutdatedData, testIncorrectFrameData and testIgnoreTimeShift (source_timeout, tf and
base_shift_correction, none imitated: our monitor reads the latest scan, its mount fixed).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from pytest_lasertest.model.geometry import Pose3D
from pytest_lasertest.model.sensor import LaserScanMeta
from pytest_lasertest.nav.nav2.collision_monitor import scan_points
from pytest_lasertest.nav.protocol import LaserScan
from tests.helpers.upstream import NAVIGATION2_JAZZY, Source

SOURCES = Source(
    "Nav2 collision monitor", NAVIGATION2_JAZZY, "nav2_collision_monitor/test/sources_test.cpp"
)
EPSILON = float(np.finfo(np.float32).eps)  # upstream's tolerance
# The upstream scan: four beams a quarter turn apart from 0 rad, readings from 0.1 m to 1.1 m,
# from a laser 0.1 m ahead of and 0.1 m left of the base, level with it.
META = LaserScanMeta(
    angle_min=0.0,
    angle_max=2.0 * math.pi,
    angle_increment=math.pi / 2.0,
    time_increment=0.0,
    scan_time=0.0,
    range_min=0.1,
    range_max=1.1,
)
MOUNT = Pose3D((0.1, 0.1, 0.0))


def scan(reading: float) -> LaserScan:
    """The upstream scan with every beam reading `reading` m, as sensor_msgs' float32."""
    return LaserScan(0.0, np.full(4, reading, dtype=np.float32), META, MOUNT)


@SOURCES.test("Tester.testGetData", assertions=9)
def test_each_reading_becomes_a_point_in_the_base_frame_in_beam_order() -> None:
    seen = scan_points(scan(1.0))
    assert len(seen) == 4
    expected = [(1.1, 0.1), (0.1, 1.1), (-0.9, 0.1), (0.1, -0.9)]  # m, 1 m along each beam
    for point, (x, y) in zip(seen, expected, strict=True):
        assert point[0] == pytest.approx(x, abs=EPSILON)
        assert point[1] == pytest.approx(y, abs=EPSILON)


@SOURCES.test("Tester.testIncorrectData", assertions=1)
def test_readings_beyond_range_max_make_no_points() -> None:
    assert len(scan_points(scan(2.0))) == 0  # 2 m, past range_max 1.1 m
