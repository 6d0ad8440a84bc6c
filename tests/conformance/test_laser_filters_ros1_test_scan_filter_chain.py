"""laser_filters' ROS 1 filter chain tests (test/test_scan_filter_chain.cpp at noetic-devel
75913d51): those of the ROS 2 file (test_laser_filters_test_scan_filter_chain.py), each chain
read from test/test_scan_filter_chain.yaml's ROS 1 list, whose shadow angles are integers,
which ROS 1 reads as doubles. A test's EXPECT_TRUE(configure) is our reader making the chain
without an error, its EXPECT_TRUE(update) the chain filtering the scan without refusing it, and
expect_ranges_eq's two statements count once per call.

Not applicable, as in ROS 2's: BadConfiguration (EXPECT_FALSE(false) holds whatever the chain
does), IntensityFilter (refused: no intensities), MaskFilter (not imitated), and ArrayFilter's
check of the filtered intensities.
"""

from __future__ import annotations

from pathlib import Path

from pytest_lasertest.nav.protocol import LaserScan
from tests.helpers.laser_filters import assert_ranges, chain_of, filtered, message
from tests.helpers.upstream import LASER_FILTERS_NOETIC, Source

CHAIN = Source(
    "laser_filters: scan filter chain (ROS 1)",
    LASER_FILTERS_NOETIC,
    "test/test_scan_filter_chain.cpp",
)
GEN = [1.0, 0.1, 1.0, 1.0, 1.0, 9.0, 1.0, 1.0, 1.0, 2.3]  # m, gen_msg's ranges
NAN = float("nan")

INTERPOLATION = """\
scan_filter_chain:
- name: interpolation
  type: laser_filters/InterpolationFilter
"""
SHADOWS = """\
scan_filter_chain:
- name: shadows
  type: laser_filters/ScanShadowsFilter
  params:
    min_angle: 80
    max_angle: 100
    neighbors: 1
    window: 1
"""
ARRAY = """\
scan_filter_chain:
  - type: laser_filters/LaserArrayFilter
    name: laser_median_filter
    params:
      range_filter_chain:
        - name: median_2
          type: filters/MultiChannelMeanFilterFloat
          params:
            number_of_observations: 3
      intensity_filter_chain:
        - name: median_2
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
    (out,) = filtered(chain_of(tmp_path, INTERPOLATION), gen_msg())
    assert_ranges(out.ranges, [1.0] * 10)


@CHAIN.test("ScanToScanFilterChain.ShadowFilter", assertions=4)
def test_shadows_seen_beyond_80_to_100_degrees_delete_their_farther_neighbours(
    tmp_path: Path,
) -> None:
    (out,) = filtered(chain_of(tmp_path, SHADOWS), gen_msg())
    assert_ranges(out.ranges, [NAN, 0.1, NAN, 1.0, 1.0, NAN, 1.0, 1.0, 1.0, NAN])


@CHAIN.test("ScanToScanFilterChain.ArrayFilter", assertions=5)
def test_the_mean_of_the_last_three_scans_is_each_readings_mean(tmp_path: Path) -> None:
    scans = (gen_msg(), gen_msg([1.0] * 10), gen_msg())
    *_, out = filtered(chain_of(tmp_path, ARRAY), *scans)
    assert_ranges(out.ranges, [1.0, 0.4, 1.0, 1.0, 1.0, 6.3333, 1.0, 1.0, 1.0, 1.8667], 1e-3)
