"""A team's laser_filters chain, run in front of the stack on every scan of a drive.

The chain is read once, from the params file the pairs file names (pairsfile/scan_filters.py),
and started afresh for each run (`ScanFilterChain.start`), so that a filter with memory (the
median of the last scans) starts empty, as the chain's node does when the robot is launched.
The filters run in the file's order, each on the scan the one before it made, as
filters::FilterChain::update passes one filter's output to the next (filter_chain.hpp at
ros/filters noetic-devel 310202ed and ros2 e33463ae).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from pytest_lasertest.model.geometry import Point2D
from pytest_lasertest.model.robot import Robot
from pytest_lasertest.nav.laser_filters.filter_types import ScanFilter
from pytest_lasertest.nav.laser_filters.scan_filters import Ros
from pytest_lasertest.nav.laser_filters.temporal import ArrayFilter
from pytest_lasertest.nav.protocol import ControllerFactory, InFront, LaserScan, Odometry

Step = Callable[[LaserScan], LaserScan]
ROS_NAMES: dict[Ros, str] = {"ros1": "ROS 1", "ros2": "ROS 2"}


@dataclass(frozen=True)
class NamedFilter:
    """One filter of a chain: its name and type as the file gives them, and the filter."""

    name: str
    type: str  # e.g. laser_filters/LaserScanRangeFilter
    filter: ScanFilter


@dataclass(frozen=True)
class ScanFilterChain:
    """A laser_filters scan_to_scan_filter_chain as its params file configures it."""

    file: str  # the params file as the pairs file names it
    path: str  # the params file's resolved path: two files of one name are two chains
    ros: Ros  # the laser_filters whose reading and behaviour are imitated
    filters: tuple[NamedFilter, ...]

    def start(self) -> RunningChain:
        """The chain as its node starts: every filter with memory empty."""
        return RunningChain(tuple(_started(named.filter) for named in self.filters))

    def describe(self) -> str:
        """`scan filters: laser_filters.yaml (2 filters)`, for reports."""
        count = len(self.filters)
        return f"scan filters: {self.file} ({count} filter{'' if count == 1 else 's'})"


@dataclass(frozen=True)
class RunningChain:
    """A chain during one run: what `InFront` passes each scan through."""

    steps: tuple[Step, ...]

    def __call__(self, scan: LaserScan, odometry: Odometry, time: float) -> LaserScan:
        for step in self.steps:
            scan = step(scan)
        return scan


def _started(kind: ScanFilter) -> Step:
    return kind.start() if isinstance(kind, ArrayFilter) else kind.apply


@dataclass(frozen=True)
class Filtered:
    """A controller factory whose controllers see each scan through a fresh run of `chain`,
    everything else of the stack kept (`InFront`)."""

    inner: ControllerFactory
    chain: ScanFilterChain

    def __call__(self, robot: Robot, route: tuple[Point2D, ...]) -> InFront:
        return InFront(self.inner(robot, route), self.chain.start())
