"""Faults in the software that reads the scanner, for the mutation analysis of fault_finding.py.

Each fault is a bug class that real ROS systems have had where the scan enters the navigation
stack, written as a team would have it: a filter or a setting tuned for the scanner the robot had
(the baseline), which does no harm with it and can do harm with the new one. A fault is put into
the default controller, move_base, through the public controller interface: `faulty(mutant,
baseline)` makes a controller factory that changes each scan (or the command) on its way in, as
the team's filter node or misconfigured costmap would. Each names the source it imitates; the
code is ours.

`nan_guard` is the equivalent mutant: it replaces NaN readings by +inf (REP 117's "no return"),
and the simulated scanner publishes no NaN, so it must never be killed.
"""

from __future__ import annotations

import dataclasses
import math
from collections import deque
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from pytest_lasertest.model.geometry import FloatArray, Point2D, Pose3D
from pytest_lasertest.model.robot import Robot
from pytest_lasertest.model.sensor import LaserProfile
from pytest_lasertest.nav.move_base import MoveBase
from pytest_lasertest.nav.protocol import Controller, ControllerFactory, LaserScan, Odometry

Command = tuple[float, float]  # m/s, rad/s


class Fault:
    """What the faulty code does to a scan on its way to move_base, and to the command back.
    One instance serves one run: a fault with memory (a median over scans) starts empty."""

    def scan(self, scan: LaserScan, odometry: Odometry) -> LaserScan:
        return scan

    def command(self, command: Command, scan: LaserScan) -> Command:
        return command


@dataclass(frozen=True)
class Mutant:
    """A fault class, where it comes from, and how to make it for a baseline scanner."""

    name: str
    bug: str  # what the code does wrong
    source: str  # the real case or the real code it imitates
    make: Callable[[LaserProfile], Fault]  # the fault, tuned for the baseline scanner
    equivalent: bool = False  # changes nothing the simulator can publish


@dataclass
class FaultyController:
    """move_base behind a faulty filter."""

    inner: Controller
    fault: Fault

    def observe(self, scan: LaserScan, odometry: Odometry, time: float) -> Command:
        command = self.inner.observe(self.fault.scan(scan, odometry), odometry, time)
        return self.fault.command(command, scan)


def faulty(mutant: Mutant | None, baseline: LaserProfile) -> ControllerFactory:
    """move_base, with the mutant's fault tuned for `baseline` if one is given."""

    def make(robot: Robot, route: tuple[Point2D, ...]) -> Controller:
        if mutant is None:
            return MoveBase(robot, route)
        return FaultyController(MoveBase(robot, route), mutant.make(baseline))

    return make


def _with_ranges(scan: LaserScan, ranges: FloatArray, **meta: float) -> LaserScan:
    return LaserScan(scan.stamp, ranges, dataclasses.replace(scan.meta, **meta), scan.mount)


class Speckle(Fault):
    """laser_filters' LaserScanSpeckleFilter, distance type: a reading nearer than `max_range`
    is kept only if, in some window of `window` consecutive beams holding it, every reading is
    within `difference` of the window's first; the rest become NaN. Tuned so that the dense
    baseline keeps every obstacle the robot meets; a sparse scanner reads a thin pole with one
    beam, and loses it."""

    def __init__(self, window: int = 2, difference: float = 0.1, max_range: float = 10.0) -> None:
        self.window, self.difference, self.max_range = window, difference, max_range

    def scan(self, scan: LaserScan, odometry: Odometry) -> LaserScan:
        ranges = scan.ranges
        if len(ranges) < self.window:
            return scan
        windows = np.lib.stride_tricks.sliding_window_view(ranges, self.window)  # (W, window)
        with np.errstate(invalid="ignore"):
            # inf - inf is NaN, which the filter's `>` lets pass: two infinities agree.
            apart = np.abs(windows[:, 1:] - windows[:, :1]) > self.difference
        agree = ~np.isnan(windows).any(axis=1) & ~apart.any(axis=1)
        valid = ranges > self.max_range  # beyond max_range: left alone
        for offset in range(self.window):
            valid[offset : offset + len(agree)] |= agree
        return _with_ranges(scan, np.where(valid, ranges, np.nan))


class Stride(Fault):
    """A throttle that keeps every `step`-th beam (as slam_gmapping's `lskip` and amcl's
    `laser_max_beams` thin a scan for their own use), sized so that the baseline's beams still
    number `keep`: a scanner with fewer beams keeps too few."""

    def __init__(self, baseline: LaserProfile, keep: int = 180) -> None:
        self.step = max(1, round(baseline.beam_count / keep))

    def scan(self, scan: LaserScan, odometry: Odometry) -> LaserScan:
        ranges = scan.ranges[:: self.step]
        increment = scan.meta.angle_increment * self.step
        last = scan.meta.angle_min + (len(ranges) - 1) * increment
        return _with_ranges(scan, ranges, angle_increment=increment, angle_max=last)


class TemporalMedian(Fault):
    """laser_filters' LaserArrayFilter with filters/MultiChannelMedianFilterFloat and
    `number_of_observations: 5`: each beam reads the median of its last five readings (the upper
    one of an even count, as nth_element picks it). At 50 Hz an obstacle shows 60 ms late; at a
    few Hz, half a second."""

    def __init__(self, observations: int = 5) -> None:
        self.history: deque[FloatArray] = deque(maxlen=observations)

    def scan(self, scan: LaserScan, odometry: Odometry) -> LaserScan:
        self.history.append(scan.ranges)
        ordered = np.sort(np.stack(self.history), axis=0)
        return _with_ranges(scan, ordered[len(self.history) // 2])


class NearAsFar(Fault):
    """laser_filters' LaserScanRangeFilter with `lower_threshold` the baseline's range_min and
    `lower_replacement_value: .inf`: every reading at or below the threshold becomes +inf, REP
    117's -inf ("too near") among them. With inf_is_valid the costmap then clears through an
    obstacle nearer than the new scanner's minimum range."""

    def __init__(self, baseline: LaserProfile) -> None:
        self.threshold = baseline.range_min

    def scan(self, scan: LaserScan, odometry: Odometry) -> LaserScan:
        return _with_ranges(scan, np.where(scan.ranges <= self.threshold, np.inf, scan.ranges))


class AngleTable(Fault):
    """Beam angles from the old scanner's configuration instead of the message (a driver or
    republisher whose angle_min and angle_increment are launch parameters of the old model; a
    wrong angle_min published by ouster-ros, issue 340): a scanner with other angles has its
    readings drawn at the wrong bearings."""

    def __init__(self, baseline: LaserProfile) -> None:
        meta = baseline.to_laserscan_meta()
        self.angle_min, self.increment = meta.angle_min, meta.angle_increment

    def scan(self, scan: LaserScan, odometry: Odometry) -> LaserScan:
        last = self.angle_min + (len(scan.ranges) - 1) * self.increment
        return _with_ranges(
            scan,
            scan.ranges,
            angle_min=self.angle_min,
            angle_increment=self.increment,
            angle_max=last,
        )


class IndexMask(Fault):
    """laser_filters' LaserScanMaskFilter, which masks beams by index: the `edge` outermost beams
    at each end of the baseline's scan, where the robot's own frame shows, become NaN. The same
    indices of a scanner with fewer beams mask a far wider arc."""

    def __init__(self, baseline: LaserProfile, edge: float = 0.25) -> None:
        count = round(edge / baseline.angle_increment) if baseline.beam_count > 1 else 0
        self.masked = np.r_[0:count, baseline.beam_count - count : baseline.beam_count]

    def scan(self, scan: LaserScan, odometry: Odometry) -> LaserScan:
        ranges = scan.ranges.copy()
        ranges[self.masked[self.masked < len(ranges)]] = np.nan
        return _with_ranges(scan, ranges)


class SweepSkew(Fault):
    """The scan stamped at the end of its sweep and placed with the pose of that instant
    (ros-navigation/navigation2 issue 3352): the readings are moved by what the robot drives and
    turns in one scan period. At 50 Hz that is a centimetre; at 10 Hz while turning, a tenth of a
    radian."""

    def scan(self, scan: LaserScan, odometry: Odometry) -> LaserScan:
        period = scan.meta.scan_time  # s
        turn, ahead = odometry.angular * period, odometry.linear * period  # rad, m
        cos, sin = math.cos(turn), math.sin(turn)
        x, y, z = scan.mount.xyz
        roll, pitch, yaw = scan.mount.rpy
        mount = Pose3D((ahead + cos * x - sin * y, sin * x + cos * y, z), (roll, pitch, yaw + turn))
        return LaserScan(scan.stamp, scan.ranges, scan.meta, mount)


class StaleSweep(Fault):
    """A driver that double-buffers its sweeps and publishes the previous one: every reading is
    one scan period old (20 ms at 50 Hz; 180 ms at 5.5 Hz)."""

    def __init__(self) -> None:
        self.previous: FloatArray | None = None

    def scan(self, scan: LaserScan, odometry: Odometry) -> LaserScan:
        previous, self.previous = self.previous, scan.ranges
        if previous is None or len(previous) != len(scan.ranges):
            return scan
        return _with_ranges(scan, previous)


class ExpectedRate(Fault):
    """costmap_2d's observation source `expected_update_rate`, set to 0.05 s for the 50 Hz
    baseline: when scans come further apart the costmap is not current, and move_base commands
    zero velocity ("Sensor data is out of date, we're not going to allow commanding of the base
    for safety", move_base.cpp)."""

    def __init__(self, expected: float = 0.05) -> None:
        self.expected = expected  # s
        self.last: float | None = None

    def command(self, command: Command, scan: LaserScan) -> Command:
        last, self.last = self.last, scan.stamp
        if last is not None and scan.stamp - last > self.expected:
            return 0.0, 0.0
        return command


class StaleMount(Fault):
    """The laser frame from the old mount (a static_transform_publisher in the team's launch
    file, not the robot description): a scanner re-mounted upright is still taken to hang
    upside down, and its scan is mirrored (the reversed readings of Slamtec/rplidar_ros
    issue 55)."""

    def __init__(self, baseline: LaserProfile) -> None:
        self.mount = baseline.pose

    def scan(self, scan: LaserScan, odometry: Odometry) -> LaserScan:
        return LaserScan(scan.stamp, scan.ranges, scan.meta, self.mount)


class NanGuard(Fault):
    """NaN readings as +inf, REP 117's no return. The simulated scanner publishes none."""

    def scan(self, scan: LaserScan, odometry: Odometry) -> LaserScan:
        return _with_ranges(scan, np.where(np.isnan(scan.ranges), np.inf, scan.ranges))


MUTANTS = (
    Mutant(
        "speckle",
        "a speckle filter drops a reading no neighbouring beam confirms",
        "ros-perception/laser_filters speckle_filter.h, 905f5e9",
        lambda baseline: Speckle(),
    ),
    Mutant(
        "stride",
        "a throttle keeps every 4th beam, sized for the baseline's beam count",
        "slam_gmapping lskip; amcl laser_max_beams",
        lambda baseline: Stride(baseline),
    ),
    Mutant(
        "median",
        "a median over the last 5 scans of each beam delays what appears",
        "ros-perception/laser_filters median_filter_example.yaml, 905f5e9",
        lambda baseline: TemporalMedian(),
    ),
    Mutant(
        "near_as_far",
        "readings below the old range_min, -inf among them, become +inf and clear",
        "ros-perception/laser_filters range_filter.h, 905f5e9",
        NearAsFar,
    ),
    Mutant(
        "angle_table",
        "beam angles from the old scanner's configuration, not the message",
        "ouster-lidar/ouster-ros issue 340",
        AngleTable,
    ),
    Mutant(
        "index_mask",
        "a mask of beam indices chosen for the old scanner",
        "ros-perception/laser_filters scan_mask_filter.h, 905f5e9",
        IndexMask,
    ),
    Mutant(
        "sweep_skew",
        "the scan placed with the pose at the end of its sweep",
        "ros-navigation/navigation2 issue 3352",
        lambda baseline: SweepSkew(),
    ),
    Mutant(
        "stale_sweep",
        "the driver publishes the previous sweep",
        "double-buffered sweeps; mrpt-ros-pkg/mvsim_nav2_demos issue 2",
        lambda baseline: StaleSweep(),
    ),
    Mutant(
        "expected_rate",
        "the costmap's expected_update_rate set for 50 Hz stops the robot between slower scans",
        "ros-planning/navigation costmap_2d observation_buffer.cpp isCurrent; move_base.cpp",
        lambda baseline: ExpectedRate(),
    ),
    Mutant(
        "stale_mount",
        "the laser frame from the old mount, not the robot description",
        "Slamtec/rplidar_ros issue 55",
        StaleMount,
    ),
    Mutant(
        "nan_guard",
        "NaN readings become +inf (equivalent: the simulator publishes no NaN)",
        "REP 117",
        lambda baseline: NanGuard(),
        equivalent=True,
    ),
)
