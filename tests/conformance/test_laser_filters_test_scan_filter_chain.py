"""laser_filters' ROS 2 filter chain tests (test/test_scan_filter_chain.cpp at ros2 905f5e9a),
each chain read by our reader from the node's section of test/test_scan_filter_chain.yaml and
run on gen_msg's scan: ten readings from -0.5 to 0.5 rad, 0.1 rad apart, range_min 0.5 m,
range_max 1.5 m. A test's EXPECT_TRUE(configure) is our reader making the chain without an
error, its EXPECT_TRUE(update) the chain filtering the scan without refusing it, and
expect_ranges_eq's two statements count once per call.

Not applicable: BadConfiguration (its one assertion, EXPECT_FALSE(false) in the catch of a
failed plugin load, holds whatever the chain does), IntensityFilter (the gate refuses
LaserScanIntensityFilter: the simulated scanner publishes no intensities), MaskFilter
(LaserScanMaskFilter is not imitated), and ArrayFilter's check of the filtered intensities
(there are none).
"""

from __future__ import annotations

from pathlib import Path

from pytest_lasertest.nav.protocol import LaserScan
from tests.helpers.laser_filters import assert_ranges, chain_of, filtered, message
from tests.helpers.upstream import LASER_FILTERS_ROS2, Source

CHAIN = Source(
    "laser_filters: scan filter chain (ROS 2)",
    LASER_FILTERS_ROS2,
    "test/test_scan_filter_chain.cpp",
)
GEN = [1.0, 0.1, 1.0, 1.0, 1.0, 9.0, 1.0, 1.0, 1.0, 2.3]  # m, gen_msg's ranges
NAN = float("nan")

INTERPOLATION = """\
interp_filter_chain:
  ros__parameters:
    filter1:
      name: interpolation
      type: laser_filters/InterpolationFilter
"""
SHADOWS = """\
shadow_filter_chain:
  ros__parameters:
    filter1:
      name: shadows
      type: laser_filters/ScanShadowsFilter
      params:
        min_angle: 80.
        max_angle: 100.
        neighbors: 1
        window: 1
"""
ARRAY = """\
array_filter_chain:
  ros__parameters:
    filter1:
      type: laser_filters/LaserArrayFilter
      name: laser_mean_filter
      params:
        range_filter_chain:
          filter1:
            name: mean_2
            type: filters/MultiChannelMeanFilterFloat
            params:
              number_of_observations: 3
        intensity_filter_chain:
          filter1:
            name: mean_2
            type: filters/MultiChannelMeanFilterFloat
            params:
              number_of_observations: 3
"""


def gen_msg(ranges: list[float] = GEN) -> LaserScan:
    return message(ranges, -0.5, 0.5, 0.5, 1.5, angle_increment=0.1)


@CHAIN.test("ScanToScanFilterChain.InterpFilter", assertions=3)
def test_interpolation_fills_each_reading_out_of_range_with_its_neighbours_mean(
    tmp_path: Path,
) -> None:
    chain = chain_of(tmp_path, INTERPOLATION)
    (out,) = filtered(chain, gen_msg())
    assert_ranges(out.ranges, [1.0] * 10)


@CHAIN.test("ScanToScanFilterChain.ShadowFilter", assertions=4)
def test_shadows_seen_beyond_80_to_100_degrees_delete_their_farther_neighbours(
    tmp_path: Path,
) -> None:
    chain = chain_of(tmp_path, SHADOWS)
    (out,) = filtered(chain, gen_msg())
    assert_ranges(out.ranges, [NAN, 0.1, NAN, 1.0, 1.0, NAN, 1.0, 1.0, 1.0, NAN])


@CHAIN.test("ScanToScanFilterChain.ArrayFilter", assertions=5)
def test_the_mean_of_the_last_three_scans_is_each_readings_mean(tmp_path: Path) -> None:
    chain = chain_of(tmp_path, ARRAY)
    scans = (gen_msg(), gen_msg([1.0] * 10), gen_msg())
    *_, out = filtered(chain, *scans)
    assert_ranges(out.ranges, [1.0, 0.4, 1.0, 1.0, 1.0, 6.3333, 1.0, 1.0, 1.0, 1.8667], 1e-3)
