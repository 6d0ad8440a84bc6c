"""laser_filters' ROS 2 shadow detector test (test/test_shadow_detector.cpp at ros2 905f5e9a):
our `ShadowDetector` against the test's isShadowPureImpl, the angle of the line between two
readings seen from the laser, over the test's grid of thresholds, ranges and angles, each
stepped in float as the test's loops step them."""

from __future__ import annotations

import math

import numpy as np

from pytest_lasertest.nav.laser_filters.scan_filters import ShadowDetector
from tests.helpers.laser_filters import RANGES, pure_shadow, stepped, thresholds
from tests.helpers.upstream import LASER_FILTERS_ROS2, Source

DETECTOR = Source(
    "laser_filters: shadow detector (ROS 2)", LASER_FILTERS_ROS2, "test/test_shadow_detector.cpp"
)


@DETECTOR.test("ScanShadowDetector.ShadowDetectionGeometry", assertions=1)
def test_the_detector_agrees_with_the_angle_of_the_line_between_two_readings() -> None:
    first, second = np.meshgrid(RANGES, RANGES, indexing="ij")
    disagreements = []
    for min_angle, max_angle in thresholds():
        detector = ShadowDetector(math.radians(min_angle), math.radians(max_angle))
        for angle in stepped(0.01, 0.1, 0.02):
            ours = detector.is_shadow_at(first, second, angle)
            theirs = pure_shadow(first, second, angle, min_angle, max_angle)
            disagreements.append(int(np.count_nonzero(ours != theirs)))
    assert sum(disagreements) == 0
