"""Faults put into Nav2, the default stack, for the mutation analysis of fault_finding.py.

Nav2 is built as the plugin builds it for the robot (the Husky's: Clearpath's a200 nav2.yaml,
DWB, a voxel layer in the local costmap, inf_is_valid unset), and each fault goes in as
mutation.py puts one in: a filter, driver or relay in front of it (`Clocked`, an `InFront`), or the
parameters a team's params file would hold, tuned for the old scanner (the baseline).

Four are real. The costmaps' layer height just above the old scan plane (`marking_height`) and a
local voxel grid that ends there (`voxel_top`) are exposed by a scanner mounted higher; the
collision monitor's source_timeout sized for 50 Hz (`source_timeout`) by a slower one;
inf_is_valid carried over from the Husky's ROS 1 costmap (`inf_is_valid`) by a sparser scanner
that publishes +inf.

Four are equivalent and must never be killed. With inf_is_valid unset, the Husky's costmaps
project only readings from range_min to below range_max (laser_geometry's rule), and its collision
monitor counts readings from range_min to range_max, within about 1.2 m of the robot: no way of
saying "no reading" (+inf, -inf, NaN, 0.0, or range_max for a scanner that reaches 12 m or more)
reaches either. `zero_replacement` and `no_return_at_range_max` change the scans so, and nothing
Nav2 does with them; `ccw_only` and `time_increment_crash` act only on scans the simulator never
publishes (a clockwise one, a malformed time_increment) and pass the simulator's as they are.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
from mutation import Command, Fault, Mutant, with_ranges

from pytest_lasertest.model.sensor import LaserProfile
from pytest_lasertest.nav.nav2.settings import CostmapConfig, Nav2Settings
from pytest_lasertest.nav.protocol import LaserScan, Odometry

# The Husky's velocity smoother publishes at 20 Hz (smoothing_frequency in its nav2.yaml), and
# the collision monitor acts on each command it publishes.
MONITOR_RATE = 20.0  # Hz


class SourceTimeout(Fault):
    """Nav2's collision monitor with `source_timeout` at two periods of the old scanner, 0.04 s
    for 50 Hz, a watchdog that lets no scan be missed twice. CollisionMonitor::process
    (collision_monitor_node.cpp, f4108e5b) runs on each command the velocity smoother publishes;
    a scan source whose latest scan is older than source_timeout is invalid
    (Source::sourceValid, source.cpp), and an invalid source stops the robot (navigation2 PR
    3880). With a 10 Hz scanner (`slower`) it stops the robot at about every other command,
    with the 5.5 Hz RPLIDAR A1 at about three of four: a scanner slower than the expected rate,
    as costmaps report it (paulbovbel/frontier_exploration issue 22)."""

    def __init__(self, baseline: LaserProfile, rate: float = MONITOR_RATE) -> None:
        self.timeout = 2.0 / baseline.update_rate  # s
        self.period = 1.0 / rate  # s
        self.now = 0.0  # s
        self.next = -math.inf  # s, when the monitor next acts, as the smoother's timer runs
        self.stopped = False

    def tick(self, time: float) -> None:
        self.now = time

    def command(self, command: Command, scan: LaserScan) -> Command:
        if self.now >= self.next:
            self.next = self.now + self.period
            self.stopped = self.now - scan.stamp > self.timeout
        return (0.0, 0.0) if self.stopped else command


class ZeroReplacement(Fault):
    """laser_filters' LaserScanRangeFilter as ROS 2 runs it (range_filter.h, 905f5e9), the team
    setting upper_threshold to the old scanner's range_max and leaving the rest: lower_threshold
    0.0, and replacement values 0.0 rather than NaN (ros-perception/laser_filters issue 172). A
    reading at or below 0.0 (-inf, a driver's 0.0) or at or above the old range_max (+inf) reads
    0.0, below every range_min: where inf_is_valid is set, no-return beams stop clearing.
    Equivalent with the Husky's Nav2 and the benchmark's pairs, whose new scanners reach no
    further than the old: it reads neither 0.0 nor what is replaced (the module's docstring)."""

    def __init__(self, baseline: LaserProfile) -> None:
        self.lower, self.upper = 0.0, baseline.range_max  # m

    def scan(self, scan: LaserScan, odometry: Odometry) -> LaserScan:
        ranges = scan.ranges
        replaced = (ranges <= self.lower) | (ranges >= self.upper)  # NaN is neither
        return with_ranges(scan, np.where(replaced, 0.0, ranges))


class NoReturnAtRangeMax(Fault):
    """No return published as the scan's range_max, as the LMS1xx driver and gazebo_ros_laser did
    (ros-perception/laser_geometry PR 9). Nav2's collision monitor counts readings up to
    range_max inclusive (Scan::getSourceData, nav2_collision_monitor scan.cpp, a3a97043) where
    the costmaps stop below it: every no-return beam puts a point at range_max, and a short-range
    source (a 1.5 m ultrasonic scan, navigation2 issue 5718) stops or slows the robot in open
    space. Equivalent here: the benchmark's scanners reach 12 m or more, far beyond the points
    the Husky's monitor reads (the module's docstring)."""

    def scan(self, scan: LaserScan, odometry: Odometry) -> LaserScan:
        ranges = scan.ranges
        return with_ranges(scan, np.where(ranges == np.inf, scan.meta.range_max, ranges))


class CounterClockwiseOnly(Fault):
    """A relay in front of the stack that takes every scan to turn counter-clockwise, reading
    beam i at angle_min + i |angle_increment|: a consumer that assumes a positive increment, as
    wg-perception/people's did until PR 26. A clockwise scan (the SICK NAV310's, SICKAG/sick_scan
    issue 110, or the driver's of an upside-down scanner) comes out mirrored about its first
    beam. Equivalent here: every simulated driver publishes counter-clockwise angles (a
    clockwise beam order reverses the readings, not the angles: model/driver.py), and the relay
    passes each scan as it is."""

    def scan(self, scan: LaserScan, odometry: Odometry) -> LaserScan:
        meta = scan.meta
        if meta.angle_increment >= 0.0:
            return scan
        increment = -meta.angle_increment  # rad
        last = meta.angle_min + (len(scan.ranges) - 1) * increment
        return with_ranges(scan, scan.ranges, angle_increment=increment, angle_max=last)


class TimeIncrementCrash(Fault):
    """Nav2's obstacle layer before navigation2 PR 2511 (1261768d, issue 2506): projecting a scan
    builds its sweep's end time, stamp + (N - 1) time_increment, and one that is negative or past
    a 32-bit count of seconds throws an exception nothing catches, which ends the controller
    server: no command again, and the base stops. Equivalent here: the simulated drivers stamp
    a whole scan at one instant (time_increment 0, as Gazebo's plugin), and no end time is out
    of range."""

    def __init__(self) -> None:
        self.crashed = False

    def scan(self, scan: LaserScan, odometry: Odometry) -> LaserScan:
        end = scan.stamp + (len(scan.ranges) - 1) * scan.meta.time_increment  # s
        self.crashed |= not 0.0 <= end < 2.0**31
        return scan

    def command(self, command: Command, scan: LaserScan) -> Command:
        return (0.0, 0.0) if self.crashed else command


def plane_top(baseline: LaserProfile) -> float:
    """The decimetre above the old scanner's plane (m), where a team puts a height limit."""
    return math.ceil(baseline.scan_height * 10.0) / 10.0


def _marking_height(settings: Nav2Settings, baseline: LaserProfile) -> Nav2Settings:
    """Both costmaps' obstacle layers with `max_obstacle_height` (the layer's, not the
    source's) at the decimetre above the old scan plane, 0.5 m over the Husky's 0.44 m laser:
    the robot's height, so that nothing it passes under is kept. A scanner re-mounted above the
    limit gives points it drops (turtlebot/turtlebot_apps PR 157). Nav2's layer heights
    (ObstacleLayer::updateBounds, obstacle_layer.cpp, f4108e5b; the lower one added by
    navigation2 PR 3211 so that the ground can still clear) gate marking alone: the raised
    scanner (`upright`, 0.54 m) marks nothing in either costmap and still clears, and the
    collision monitor, which reads no heights from a scan, still sees it. move_base's
    `max_height` is the source's limit, which neither marks nor clears."""
    top = plane_top(baseline)

    def capped(config: CostmapConfig) -> CostmapConfig:
        source = config.source
        limit = min(source.layer_max_obstacle_height, top)
        return dataclasses.replace(
            config, source=dataclasses.replace(source, layer_max_obstacle_height=limit)
        )

    return dataclasses.replace(
        settings, local=capped(settings.local), global_=capped(settings.global_)
    )


def _voxel_top(settings: Nav2Settings, baseline: LaserProfile) -> Nav2Settings:
    """The local costmap's VoxelLayer with a grid that ends at the decimetre above the old scan
    plane (z_voxels 10 of 0.05 m, not the a200 file's 16: a column no higher than the plane it
    holds). Nav2's VoxelLayer (voxel_layer.cpp, f4108e5b) marks only points inside its grid and
    raytraces nothing from a sensor above it ("Sensor origin ... is out of map bounds ... The
    costmap cannot raytrace for it"; its rays were cut at max_obstacle_height, not at the
    grid's top, until navigation2 885477b9, ros-planning/navigation issue 662): the raised
    scanner (`upright`) neither marks nor clears the local costmap, which DWB and the behaviours
    read, while the global costmap (an ObstacleLayer) still takes it. The imitation's params
    reader takes the grid's top as a marking limit alone; for a level scan above it Nav2 does
    what a source whose height window ends there does, so that is what the fault sets."""
    top = plane_top(baseline)
    source = settings.local.source
    windowed = dataclasses.replace(
        source,
        max_obstacle_height=min(source.max_obstacle_height, top),
        layer_max_obstacle_height=min(source.layer_max_obstacle_height, top),
    )
    return dataclasses.replace(settings, local=dataclasses.replace(settings.local, source=windowed))


def _inf_is_valid(settings: Nav2Settings, baseline: LaserProfile) -> Nav2Settings:
    """Both costmaps' laser sources with inf_is_valid, carried over from the Husky's ROS 1
    costmap (husky_navigation's costmap_common.yaml sets it; ros-planning/navigation issue 808:
    "this will also shoot a ray if there is no reflection"). Nav2's laserScanValidInfCallback
    (obstacle_layer.cpp, a3a97043) reads +inf as range_max - 1e-4: a ring of lethal cells where
    that lies within obstacle_max_range (2.5 m here: a short-range scanner, or one whose driver
    lowers range_max scan by scan, SICKAG/sick_scan_xd issue 509), else a clearing ray along
    each beam that returns nothing, out to
    raytrace_max_range. Each update clears before it marks: the 720-beam scanner reads a thin
    pole with some beam in every scan and marks it again; a sparser one that publishes +inf
    (`fewer_beams`, the RPLIDAR A1 of `lms111_to_rplidar_a1`) misses it in some scans while a
    beam beside it crosses its cell and returns nothing, and the pole is gone until it is read
    again. The a200 file's Nav2 clears along no beam that returns nothing; the LMS111 publishes
    0.0 for no return, which the setting leaves alone."""

    def valid(config: CostmapConfig) -> CostmapConfig:
        costmap = dataclasses.replace(config.costmap, inf_is_valid=True)
        return dataclasses.replace(config, costmap=costmap)

    return dataclasses.replace(
        settings, local=valid(settings.local), global_=valid(settings.global_)
    )


def _unchanged(baseline: LaserProfile) -> Fault:
    return Fault()  # the fault is a setting


NAV2_MUTANTS = (
    Mutant(
        "marking_height",
        "the costmaps' layer max_obstacle_height just above the old scan plane: a raised scan "
        "clears and never marks",
        "turtlebot/turtlebot_apps PR 157; ros-navigation/navigation2 obstacle_layer.cpp "
        "updateBounds, f4108e5b, and PR 3211",
        _unchanged,
        stack="nav2",
        nav2=_marking_height,
    ),
    Mutant(
        "voxel_top",
        "the local voxel grid ends just above the old scan plane: a raised scan neither marks "
        "nor clears it",
        "ros-navigation/navigation2 voxel_layer.cpp raytraceFreespace, f4108e5b, and 885477b9; "
        "ros-planning/navigation issue 662",
        _unchanged,
        stack="nav2",
        nav2=_voxel_top,
    ),
    Mutant(
        "source_timeout",
        "the collision monitor's source_timeout at two 50 Hz periods stops the robot between "
        "slower scans",
        "analogue of paulbovbel/frontier_exploration issue 22 in the collision monitor: "
        "ros-navigation/navigation2 PR 3880, 0f72da26",
        SourceTimeout,
        stack="nav2",
    ),
    Mutant(
        "inf_is_valid",
        "inf_is_valid carried over from ROS 1: no-return beams clear a thin obstacle a sparse "
        "scanner misses",
        "ros-navigation/navigation2 obstacle_layer.cpp laserScanValidInfCallback, a3a97043; "
        "SICKAG/sick_scan_xd issue 509; ros-planning/navigation issue 808",
        _unchanged,
        stack="nav2",
        nav2=_inf_is_valid,
    ),
    Mutant(
        "zero_replacement",
        "a ROS 2 range filter replaces out-of-window readings by 0.0 (equivalent: Nav2 reads "
        "none of them)",
        "ros-perception/laser_filters issue 172; range_filter.h, 905f5e9",
        ZeroReplacement,
        equivalent=True,
        stack="nav2",
    ),
    Mutant(
        "no_return_at_range_max",
        "no return published as range_max, which the collision monitor counts (equivalent: "
        "range_max is 12 m or more)",
        "ros-navigation/navigation2 nav2_collision_monitor scan.cpp, a3a97043; "
        "ros-perception/laser_geometry PR 9",
        lambda baseline: NoReturnAtRangeMax(),
        equivalent=True,
        stack="nav2",
    ),
    Mutant(
        "ccw_only",
        "a relay reads every scan as counter-clockwise (equivalent: the simulator's all are)",
        "wg-perception/people PR 26; SICKAG/sick_scan issue 110",
        lambda baseline: CounterClockwiseOnly(),
        equivalent=True,
        stack="nav2",
    ),
    Mutant(
        "time_increment_crash",
        "a malformed time_increment ends the controller server (equivalent: the simulator's is 0)",
        "ros-navigation/navigation2 issue 2506, PR 2511, 1261768d",
        lambda baseline: TimeIncrementCrash(),
        equivalent=True,
        stack="nav2",
    ),
)
