"""laser_filters' ROS 1 ScanShadowsFilter tests (test/test_scan_shadows_filter.cpp at
noetic-devel 75913d51) on our `ShadowsFilter`, configured as each test's
ScanShadowsFilterConfig sets it, on create_message's scan: the readings spread from -π/12 to
π/12 rad, both ends sampled, range_min 0.1 m, range_max 10 m. expect_ranges_equal's
statements count once per call: its size check, its NaN check where the expected readings
hold a NaN, and its EXPECT_NEAR.

Not applicable: Performance, compiled only with CATKIN_ENABLE_PERFORMANCE_TESTING (a timing
run of 10,000 updates).
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Sequence

from pytest_lasertest.nav.laser_filters.scan_filters import ShadowDetector, ShadowsFilter
from pytest_lasertest.nav.protocol import LaserScan
from tests.helpers.laser_filters import assert_ranges, message
from tests.helpers.upstream import LASER_FILTERS_NOETIC, Source

SHADOWS = Source(
    "laser_filters: ScanShadowsFilter (ROS 1)",
    LASER_FILTERS_NOETIC,
    "test/test_scan_shadows_filter.cpp",
)
NAN = float("nan")
# The range-5 points stand for a nearby object, the range-9 points for a wall.
OBJECT_THEN_WALL = [5.0, 5.0, 5.0, 5.0, 5.0, 9.0, 9.0, 9.0, 9.0, 9.0]


def shadows(
    min_angle: float, max_angle: float, neighbors: int, window: int, remove: bool
) -> ShadowsFilter:
    """The filter as reconfigureCB sets it from a ScanShadowsFilterConfig (degrees)."""
    detector = ShadowDetector(math.radians(min_angle), math.radians(max_angle))
    return ShadowsFilter(detector, window, neighbors, remove)


def create_message(ranges: Sequence[float]) -> LaserScan:
    return message(ranges, -math.pi / 12, math.pi / 12, 0.1, 10.0)


@SHADOWS.test("ScanShadowsFilter.NoShadows", assertions=2)
def test_a_flat_wall_casts_no_shadow() -> None:
    out = shadows(15.0, 165.0, 1, 1, True).apply(create_message([9] * 10))
    assert_ranges(out.ranges, [9] * 10)


@SHADOWS.test("ScanShadowsFilter.DistanceDeltaWithoutShadow", assertions=3)
def test_the_step_from_an_object_to_a_wall_loses_both_its_edges_at_15_to_165_degrees() -> None:
    out = shadows(15.0, 165.0, 0, 1, True).apply(create_message(OBJECT_THEN_WALL))
    assert_ranges(out.ranges, [5, 5, 5, 5, NAN, NAN, 9, 9, 9, 9])


@SHADOWS.test("ScanShadowsFilter.DistanceDeltaWithoutShadow_Angles_8_172", assertions=3)
def test_the_step_loses_both_its_edges_at_8_to_172_degrees() -> None:
    out = shadows(8.0, 172.0, 0, 1, True).apply(create_message(OBJECT_THEN_WALL))
    assert_ranges(out.ranges, [5, 5, 5, 5, NAN, NAN, 9, 9, 9, 9])


@SHADOWS.test("ScanShadowsFilter.DistanceDeltaWithoutShadow_Angles_5_175", assertions=3)
def test_the_step_loses_only_its_far_edge_at_5_to_175_degrees() -> None:
    out = shadows(5.0, 175.0, 0, 1, True).apply(create_message(OBJECT_THEN_WALL))
    assert_ranges(out.ranges, [5, 5, 5, 5, 5, NAN, 9, 9, 9, 9])


@SHADOWS.test("ScanShadowsFilter.DistanceDeltaWithoutShadowFlipped_Angles_5_175", assertions=3)
def test_the_step_seen_the_other_way_round_loses_its_far_edge_at_5_to_175_degrees() -> None:
    out = shadows(5.0, 175.0, 0, 1, True).apply(create_message(OBJECT_THEN_WALL[::-1]))
    assert_ranges(out.ranges, [9, 9, 9, 9, NAN, 5, 5, 5, 5, 5])


@SHADOWS.test("ScanShadowsFilter.DistanceDeltaWithoutShadow_Angles_3_177", assertions=2)
def test_the_step_loses_nothing_at_3_to_177_degrees() -> None:
    out = shadows(3.0, 177.0, 0, 1, True).apply(create_message(OBJECT_THEN_WALL))
    assert_ranges(out.ranges, OBJECT_THEN_WALL)


@SHADOWS.test("ScanShadowsFilter.SingleBackwardShadow_NoNeighbours", assertions=3)
def test_a_shadow_behind_the_object_is_removed_with_the_points_around_it() -> None:
    out = shadows(15.0, 165.0, 0, 1, True).apply(create_message([5, 5, 5, 5, 5, 9, 7, 9, 9, 9]))
    assert_ranges(out.ranges, [5, 5, 5, 5, NAN, NAN, NAN, NAN, 9, 9])


@SHADOWS.test("ScanShadowsFilter.SingleBackwardShadow_OneNeighbour", assertions=3)
def test_one_neighbour_without_the_start_point_keeps_the_shadow_behind_the_object() -> None:
    out = shadows(15.0, 165.0, 1, 1, False).apply(create_message([5, 5, 5, 5, 5, 9, 7, 9, 9, 9]))
    assert_ranges(out.ranges, [5, 5, 5, 5, 5, NAN, 7, NAN, 9, 9])


@SHADOWS.test("ScanShadowsFilter.SingleForwardShadow_NoNeighbours", assertions=3)
def test_a_shadow_before_the_wall_is_removed_with_the_points_around_it() -> None:
    out = shadows(15.0, 165.0, 0, 1, True).apply(create_message([5, 5, 5, 5, 5, 9, 3, 9, 9, 9]))
    assert_ranges(out.ranges, [5, 5, 5, 5, NAN, NAN, NAN, NAN, 9, 9])


@SHADOWS.test("ScanShadowsFilter.SingleForwardShadow_OneNeighbour", assertions=3)
def test_one_neighbour_without_the_start_point_keeps_the_shadow_before_the_wall() -> None:
    out = shadows(15.0, 165.0, 1, 1, False).apply(create_message([5, 5, 5, 5, 5, 9, 3, 9, 9, 9]))
    assert_ranges(out.ranges, [5, 5, 5, 5, 5, NAN, 3, NAN, 9, 9])


@SHADOWS.test("ScanShadowsFilter.SingleForwardShadow_AngleIncrementChanged", assertions=5)
def test_halving_the_angle_increment_makes_the_step_steep_enough_to_be_a_shadow() -> None:
    step = create_message([5, 5, 5, 5, 5, 4, 4, 4, 4, 4])
    shadow = shadows(15.0, 165.0, 1, 1, False)
    assert_ranges(shadow.apply(step).ranges, [5, 5, 5, 5, 5, 4, 4, 4, 4, 4])
    halved = dataclasses.replace(step.meta, angle_increment=step.meta.angle_increment / 2)
    out = shadow.apply(dataclasses.replace(step, meta=halved))
    assert_ranges(out.ranges, [5, 5, 5, 5, NAN, 4, 4, 4, 4, 4])
