"""laser_filters in front of the stack: a team's scan_to_scan_filter_chain, its filters
imitated from ros-perception/laser_filters (ROS 1 noetic-devel 75913d51, ROS 2 ros2 905f5e9a)
and run on each scan before the controller sees it.

`scan_filters.py` holds the filters of one scan, `temporal.py` those over several scans,
`params.py` what each reads from its params file in each ROS, and `chain.py` the chain and the
controller factory it stands in front of.
"""

from __future__ import annotations

from pytest_lasertest.nav.laser_filters.chain import Filtered, NamedFilter, ScanFilterChain

__all__ = ["Filtered", "NamedFilter", "ScanFilterChain"]
