"""laser_filters' ROS 1 shadow detector test (test/test_shadow_detector.cpp at noetic-devel
75913d51): our `ShadowDetector` against the test's isShadowPureImpl over its grid, the angle
between the readings 1 to 5 beams of 0.02 rad either way, given as the angle and as its sine
and cosine (the form ROS 1's ScanShadowsFilter calls with its precomputed tables)."""

from __future__ import annotations

import math

import numpy as np

from pytest_lasertest.nav.laser_filters.scan_filters import ShadowDetector
from tests.helpers.laser_filters import RANGES, pure_shadow, thresholds
from tests.helpers.upstream import LASER_FILTERS_NOETIC, Source

DETECTOR = Source(
    "laser_filters: shadow detector (ROS 1)",
    LASER_FILTERS_NOETIC,
    "test/test_shadow_detector.cpp",
)
WINDOW = 5  # beams either way
INCREMENT = float(np.float32(0.02))  # rad


@DETECTOR.test("ScanShadowDetector.ShadowDetectionGeometry", assertions=2)
def test_the_detector_agrees_with_the_line_angle_given_the_angle_or_its_sine_and_cosine() -> None:
    first, second = np.meshgrid(RANGES, RANGES, indexing="ij")
    by_angle, by_sine = 0, 0
    for min_angle, max_angle in thresholds():
        detector = ShadowDetector(math.radians(min_angle), math.radians(max_angle))
        for beams in (b for b in range(-WINDOW, WINDOW + 1) if b != 0):
            angle = float(np.float32(beams * np.float32(INCREMENT)))
            theirs = pure_shadow(first, second, angle, min_angle, max_angle)
            ours = detector.is_shadow_at(first, second, angle)
            sine, cosine = float(np.sin(np.float32(angle))), float(np.cos(np.float32(angle)))
            by_angle += int(np.count_nonzero(ours != theirs))
            by_sine += int(
                np.count_nonzero(detector.is_shadow(first, second, sine, cosine) != theirs)
            )
    assert by_angle == 0
    assert by_sine == 0
