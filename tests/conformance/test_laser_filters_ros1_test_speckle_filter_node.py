"""laser_filters' ROS 1 speckle filter node test (test/test_speckle_filter, a rostest run by
test/test_speckle_filter.launch at noetic-devel 75913d51): two scan_to_scan_filter_chain nodes,
one loading test/test_speckle_filter_distance.yaml (filter_type 0), one
test/test_speckle_filter_euclidean.yaml (filter_type 1), each read here by our reader, filter
one scan of eleven readings over π rad (range_max 100 m). Both remove the one speckle: ROS 1's
filter picks its validator before it reads filter_type from its params
(speckle_filter.cpp:63-69), so the euclidean file runs the distance validator too; the radius
outlier validator would find no reading 0.1 m from its neighbours π/10 rad away and remove
them all.

Not applicable: the test's assertion that both messages arrive within 10 s (no topics here).
"""

from __future__ import annotations

import math
from pathlib import Path

from tests.helpers.laser_filters import assert_ranges, chain_of, filtered, message
from tests.helpers.upstream import LASER_FILTERS_NOETIC, Source

NODE = Source(
    "laser_filters: speckle filter node (ROS 1)", LASER_FILTERS_NOETIC, "test/test_speckle_filter"
)
NAN = float("nan")
CHAIN = """\
scan_filter_chain:
- name: speckle_filter
  type: laser_filters/LaserScanSpeckleFilter
  params:
    filter_type: {kind}
    max_range: 2.0
    max_range_difference: 0.1
    filter_window: 2
"""


@NODE.test("TestSpeckleFilter.test_speckle_filter", assertions=4)
def test_the_distance_and_the_euclidean_chain_both_remove_the_one_speckle(
    tmp_path: Path,
) -> None:
    scan = message([1, 1, 1, 1, 0.5, 1, 1, 1, 1, 1, 1], -math.pi / 2, math.pi / 2, 0.0, 100.0)
    expected = [1, 1, 1, 1, NAN, 1, 1, 1, 1, 1, 1]
    for kind in (0, 1):
        (out,) = filtered(chain_of(tmp_path, CHAIN.format(kind=kind)), scan)
        assert_ranges(out.ranges, expected, tolerance=0.0)
