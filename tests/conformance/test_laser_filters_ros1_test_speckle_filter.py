"""laser_filters' ROS 1 LaserScanSpeckleFilter tests (test/test_speckle_filter.cpp at
noetic-devel 75913d51) on our `SpeckleFilter` with the distance validator, configured as each
test's SpeckleFilterConfig sets it (max_range 2 m, max_range_difference 0.1 m), on
create_message's scan: eleven readings from -0.5 to 0.5 rad, range_min 0.5 m, range_max
1.5 m. expect_ranges_equal's statements count once per call: its size check, its NaN check
where the expected readings hold a NaN, and its EXPECT_NEAR.

Not applicable: Performance, compiled only with CATKIN_ENABLE_PERFORMANCE_TESTING (a timing
run of 10,000 updates).
"""

from __future__ import annotations

import pytest

from pytest_lasertest.nav.laser_filters.scan_filters import SpeckleFilter
from tests.helpers.laser_filters import assert_ranges, message
from tests.helpers.upstream import LASER_FILTERS_NOETIC, Source

SPECKLE = Source(
    "laser_filters: speckle filter (ROS 1)", LASER_FILTERS_NOETIC, "test/test_speckle_filter.cpp"
)
NAN = float("nan")
PLATEAUS = [1, 1, 1.2, 1.2, 1.2, 0.7, 0.7, 0.9, 0.9, 0.9, 0.9]


def upstream(
    name: str, assertions: int, window: int, ranges: list[float], expected: list[float]
) -> object:
    """One upstream test: filter_window, the readings, what the filter leaves of them."""
    mark = SPECKLE.test(f"SpeckleFilter_Distance.{name}", assertions)
    return pytest.param(window, ranges, expected, id=name, marks=mark)


# fmt: off
CASES = [
    upstream("SingleSpeckle", 3, 2,
             [1, 1, 1, 1, 0.5, 1, 1, 1, 1, 1, 1], [1, 1, 1, 1, NAN, 1, 1, 1, 1, 1, 1]),
    upstream("TwoDistantSpeckles", 3, 2,
             [1, 1, 1, 1, 0.5, 1, 1, 1, 0.5, 1, 1], [1, 1, 1, 1, NAN, 1, 1, 1, NAN, 1, 1]),
    upstream("TwoNearSpeckles", 3, 2,
             [1, 1, 1, 1, 0.5, 1, 0.5, 1, 1, 1, 1], [1, 1, 1, 1, NAN, NAN, NAN, 1, 1, 1, 1]),
    upstream("TwoSpecklesAtEdge", 3, 2,
             [1.2, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1.2], [NAN, 1, 1, 1, 1, 1, 1, 1, 1, 1, NAN]),
    upstream("SinglePeak", 2, 2,
             [1, 1, 1, 1, 3, 1, 1, 1, 1, 1, 1], [1, 1, 1, 1, 3, 1, 1, 1, 1, 1, 1]),
    upstream("TwoFarPeaks", 2, 2,
             [1, 1, 1, 1, 3, 1, 1, 1, 3, 1, 1], [1, 1, 1, 1, 3, 1, 1, 1, 3, 1, 1]),
    upstream("TwoNearPeaks", 3, 2,
             [1, 1, 1, 1, 3, 1, 3, 1, 1, 1, 1], [1, 1, 1, 1, 3, NAN, 3, 1, 1, 1, 1]),
    upstream("TwoPeaksAtEdge", 2, 2,
             [3, 1, 1, 1, 1, 1, 1, 1, 1, 1, 3], [3, 1, 1, 1, 1, 1, 1, 1, 1, 1, 3]),
    upstream("MultiplePlateausNoSpeckles", 2, 2, PLATEAUS, PLATEAUS),
    upstream("MultiplePlateausBiggerWindow", 3, 3,
             PLATEAUS, [NAN, NAN, 1.2, 1.2, 1.2, NAN, NAN, 0.9, 0.9, 0.9, 0.9]),
]
# fmt: on


@pytest.mark.parametrize(("window", "ranges", "expected"), CASES)
def test_a_reading_stays_only_in_a_window_of_readings_that_agree_or_beyond_max_range(
    window: int, ranges: list[float], expected: list[float]
) -> None:
    speckle = SpeckleFilter("ros1", 0, 2.0, 0.1, window)
    out = speckle.apply(message(ranges, -0.5, 0.5, 0.5, 1.5))
    assert_ranges(out.ranges, expected)
