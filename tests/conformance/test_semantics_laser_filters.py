"""Behaviour tests of the laser_filters filters no upstream unit test covers, from the upstream
code's semantics: ros-perception/laser_filters at ros2 905f5e9a and noetic-devel 75913d51
(range_filter.h, angular_bounds_filter.h, angular_bounds_filter_in_place.h, box_filter.h and
box_filter.cpp, footprint_filter.h, interpolation_filter.h, speckle_filter.h and
speckle_filter.cpp, array_filter.h), ros/filters at ros2 e33463ae and noetic-devel 310202ed
(mean.hpp, median.hpp, filter_base.hpp) and ros-perception/laser_geometry (the projection the
box and footprint filters use), on our filters (pytest_lasertest/nav/laser_filters/), read
from a params file by the pairs file's reader where the test is about what a left-out
parameter becomes.

These tests port no upstream assertion and carry no `upstream` mark.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from pytest_lasertest.model.geometry import Pose3D
from pytest_lasertest.nav.laser_filters.scan_filters import (
    AngularBoundsFilter,
    AngularBoundsFilterInPlace,
    BoxFilter,
    FootprintFilter,
    InterpolationFilter,
    RangeFilter,
    ScanRefused,
    SpeckleFilter,
)
from pytest_lasertest.nav.laser_filters.temporal import ArrayFilter, ChannelFilter, kth_smallest
from tests.helpers.laser_filters import assert_ranges, chain_of, filtered, message

NAN, INF = float("nan"), float("inf")


def range_chain(params: str, ros: str) -> str:
    """A params file of one LaserScanRangeFilter with `params` (a flow mapping), in `ros`."""
    entry = f"{{name: r, type: laser_filters/LaserScanRangeFilter, params: {params}}}"
    if ros == "ros1":
        return f"scan_filter_chain:\n- {entry}\n"
    return f"scan_to_scan_filter_chain:\n  ros__parameters:\n    filter1: {entry}\n"


def test_ros1s_range_filter_replaces_with_its_dynamic_reconfigure_defaults_0_and_100000(
    tmp_path: Path,
) -> None:
    # cfg/RangeFilter.cfg:49-53: the replacement values default to 0 and 100000, not NaN.
    chain = chain_of(tmp_path, range_chain("{lower_threshold: 0.3, upper_threshold: 5.0}", "ros1"))
    (out,) = filtered(chain, message([0.2, 0.3, 1.0, 5.0, INF, NAN], -0.5, 0.5, 0.1, 10.0))
    assert_ranges(out.ranges, [0.0, 0.0, 1.0, 100000.0, 100000.0, NAN])


def test_ros2s_range_filter_replaces_with_the_zero_its_getparam_declares_not_nan(
    tmp_path: Path,
) -> None:
    # range_filter.h:64-71 means NaN, but filter_base.hpp:181-184 declares a left-out double
    # 0.0 (laser_filters issue #172).
    chain = chain_of(tmp_path, range_chain("{lower_threshold: 0.3, upper_threshold: 5.0}", "ros2"))
    (out,) = filtered(chain, message([0.2, 1.0, INF, -INF], -0.5, 0.5, 0.1, 10.0))
    assert_ranges(out.ranges, [0.0, 1.0, 0.0, 0.0], tolerance=0.0)


def test_the_range_filter_can_take_the_scans_own_limits_and_meets_them_inclusively() -> None:
    # range_filter.h:88-107: <= range_min and >= range_max are replaced.
    limits = RangeFilter(0.0, 1.0, True, -INF, INF)
    out = limits.apply(message([0.1, 0.2, 9.9, 10.0], -0.5, 0.5, 0.1, 10.0))
    assert_ranges(out.ranges, [-INF, 0.2, 9.9, INF], tolerance=0.0)


def test_the_angular_bounds_filter_cuts_the_scan_and_says_where_it_now_begins_and_ends() -> None:
    # angular_bounds_filter.h:77-115: from the first beam at or above lower_angle to the first
    # whose next beam lies beyond upper_angle; the stamp moves a time_increment per beam cut.
    scan = message(list(np.arange(21.0)), -1.0, 1.0, 0.1, 100.0)
    out = AngularBoundsFilter(-0.25, 0.35).apply(scan)
    assert_ranges(out.ranges, [8.0, 9.0, 10.0, 11.0, 12.0, 13.0])
    assert out.meta.angle_min == pytest.approx(-0.2)
    assert out.meta.angle_max == pytest.approx(0.3)
    assert out.stamp == pytest.approx(8 * scan.meta.time_increment)


def test_a_cut_that_reaches_the_scans_end_says_it_ends_one_beam_past_its_last() -> None:
    # angular_bounds_filter.h:94-98: the loop ends without a break, current_angle one step on.
    out = AngularBoundsFilter(0.05, 2.0).apply(
        message(list(np.arange(21.0)), -1.0, 1.0, 0.1, 100.0)
    )
    assert len(out.ranges) == 10
    assert out.meta.angle_max == pytest.approx(1.1)


def test_the_in_place_filter_reads_range_max_plus_1_strictly_between_its_angles() -> None:
    # angular_bounds_filter_in_place.h:73-80.
    out = AngularBoundsFilterInPlace(-0.25, 0.25).apply(message([1.0] * 5, -0.5, 0.5, 0.1, 10.0))
    assert_ranges(out.ranges, [1.0, 1.0, 11.0, 1.0, 1.0])


LASER = Pose3D((0.5, 0.0, 0.4), (0.0, 0.0, 0.0))  # m: 0.5 m ahead of the base, 0.4 m up


def test_the_box_filter_removes_the_readings_inside_its_box_in_the_base_frame() -> None:
    # box_filter.h:189-207: strictly inside every side, in box_frame; the laser sits 0.5 m ahead.
    scan = message([0.4, 1.0, 2.0], 0.0, 0.0, 0.1, 10.0, angle_increment=0.0, mount=LASER)
    box = BoxFilter(0.0, 1.0, -1.0, 1.0, 0.0, 1.0, False)
    assert_ranges(box.apply(scan).ranges, [NAN, 1.0, 2.0])  # at x 0.9, 1.5 and 2.5 m


def test_a_box_below_the_scan_plane_removes_nothing_and_inverted_every_projected_reading() -> None:
    # The scan plane lies at the laser's 0.4 m; laser_geometry projects range_min <= r <
    # range_max alone (laser_geometry.cpp:183-191 at humble ba53212e), so 10 m stays.
    scan = message([0.4, 1.0, 10.0], 0.0, 0.0, 0.1, 10.0, angle_increment=0.0, mount=LASER)
    low = (0.0, 5.0, -1.0, 1.0, 0.0, 0.3)
    assert_ranges(BoxFilter(*low, False).apply(scan).ranges, [0.4, 1.0, 10.0])
    assert_ranges(BoxFilter(*low, True).apply(scan).ranges, [NAN, NAN, 10.0])


def test_the_footprint_filter_removes_a_square_edges_included_not_a_circle() -> None:
    # footprint_filter.h:137-142: |x| <= r and |y| <= r in base_link: the edge at 1 m ahead
    # and the corner 1.4 m away at 45 degrees go, 1.01 m to the left stays.
    ranges = [1.0, 0.99 * math.sqrt(2.0), 1.01]
    scan = message(ranges, 0.0, math.pi / 2, 0.1, 10.0)
    assert_ranges(FootprintFilter(1.0).apply(scan).ranges, [NAN, NAN, 1.01])


def test_a_trailing_run_is_interpolated_with_the_reading_after_the_run_before_it() -> None:
    # interpolation_filter.h:65-101: next_valid_range keeps the last value found.
    scan = message([INF, 1.0, 2.0, 0.0, 3.0, 4.0, INF], -0.5, 0.5, 0.1, 10.0)
    out = InterpolationFilter().apply(scan)
    assert_ranges(out.ranges, [(9.99 + 1.0) / 2, 1.0, 2.0, 2.5, 3.0, 4.0, (4.0 + 3.0) / 2])


def test_the_median_of_an_even_count_is_the_lower_one_and_each_run_starts_empty() -> None:
    # median.hpp:88-92: k = n/2 - 1 of an even n; RealtimeCircularBuffer keeps the last n.
    median = ArrayFilter((ChannelFilter("median", 4),))
    scans = [message([value], 0.0, 0.0, 0.1, 10.0, 0.0) for value in (4.0, 1.0, 3.0, 2.0, 9.0)]
    run = median.start()
    assert [float(run(scan).ranges[0]) for scan in scans] == [4.0, 1.0, 3.0, 2.0, 2.0]
    assert float(median.start()(scans[-1]).ranges[0]) == 9.0


def test_wirths_selection_of_a_median_among_nans_goes_by_its_exchanges() -> None:
    # median.hpp:64-86: no comparison with NaN holds, so the order decides: NaN first is
    # swapped up and 2 m lands at k; NaN in the middle is x itself and stays there.
    assert kth_smallest([NAN, 1.0, 2.0], 1) == 2.0
    assert math.isnan(kth_smallest([1.0, NAN, 2.0], 1))


def test_ros1s_speckle_filter_refuses_a_scan_its_window_does_not_fit() -> None:
    # speckle_filter.cpp:83-87 at noetic-devel: size <= filter_window + 1 fails the update.
    with pytest.raises(ScanRefused, match="refuses a scan of 5 readings"):
        SpeckleFilter("ros1", 0, 2.0, 0.1, 4).apply(message([1.0] * 5, -0.5, 0.5, 0.1, 10.0))


def test_a_radius_outlier_window_judged_by_its_first_reading_keeps_the_speckle_after_it() -> None:
    # speckle_filter.h:86-154, :228-243: a window is valid where filter_window readings within
    # filter_window beams lie within max_range_difference of its first, and a valid window
    # keeps all its readings: a speckle first in the scan goes, one after a wall reading stays.
    speckle = SpeckleFilter("ros2", 1, 2.0, 0.1, 2)
    first = speckle.apply(message([1.6] + [1.0] * 10, -0.05, 0.05, 0.1, 10.0))
    assert_ranges(first.ranges, [NAN] + [1.0] * 10)
    inside = speckle.apply(message([1.0] * 5 + [1.6] + [1.0] * 5, -0.05, 0.05, 0.1, 10.0))
    assert_ranges(inside.ranges, [1.0] * 5 + [1.6] + [1.0] * 5)
