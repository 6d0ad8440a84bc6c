"""The faults of the mutation analysis (fault_finding.py): `MUTANTS`, those put into move_base
(here) and those put into Nav2 (nav2_faults.py). mutation.py says how a fault goes in.

Each fault is a bug class that real ROS systems have had where the scan enters the navigation
stack, written as a team would have it: a filter or a setting tuned for the scanner the robot had
(the baseline), which does no harm with it and can do harm with the new one. It changes each scan
(or the command) on its way in, as the team's filter node or misconfigured costmap would, or sets
the stack's parameters where the fault is a setting (a costmap's update rate, the planner's
unknown space). Each names the source it imitates; the code is ours.

A costmap fault is written as what the misconfigured costmap does with the scan, where a scan
can say it exactly (an observation source that drops every point of a raised scanner is a scan
of no readings), else as the parameter itself.

`nan_guard` is move_base's equivalent mutant: it replaces NaN readings by +inf (REP 117's "no
return"), and the simulated scanner publishes no NaN, so it must never be killed. Nav2's are in
nav2_faults.py.
"""

from __future__ import annotations

import dataclasses
import math
from collections import deque

import numpy as np
from mutation import Command, Fault, Mutant, with_ranges
from nav2_faults import NAV2_MUTANTS

from pytest_lasertest.model.geometry import FloatArray, Pose3D
from pytest_lasertest.model.sensor import LaserProfile
from pytest_lasertest.nav.move_base.settings import NavigationSettings
from pytest_lasertest.nav.protocol import LaserScan, Odometry


def _planar(x: float, y: float, yaw: float) -> Pose3D:
    """A pose in the ground plane: `x`, `y` m and `yaw` rad, as odometry or a move in it."""
    return Pose3D((x, y, 0.0), (0.0, 0.0, yaw))


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
            valid[offset : offset + len(windows)] |= agree
        return with_ranges(scan, np.where(valid, ranges, np.nan))


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
        return with_ranges(scan, ranges, angle_increment=increment, angle_max=last)


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
        return with_ranges(scan, ordered[len(self.history) // 2])


class NearAsFar(Fault):
    """laser_filters' LaserScanRangeFilter with `lower_threshold` the baseline's range_min and
    `lower_replacement_value: .inf`: every reading at or below the threshold becomes +inf, REP
    117's -inf ("too near") among them. With inf_is_valid the costmap then clears through an
    obstacle nearer than the new scanner's minimum range."""

    def __init__(self, baseline: LaserProfile) -> None:
        self.threshold = baseline.range_min

    def scan(self, scan: LaserScan, odometry: Odometry) -> LaserScan:
        return with_ranges(scan, np.where(scan.ranges <= self.threshold, np.inf, scan.ranges))


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
        return with_ranges(
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
        return with_ranges(scan, ranges)


class SweepSkew(Fault):
    """The scan stamped at the end of its sweep and placed with the pose of that instant
    (ros-navigation/navigation2 issue 3352): the readings are moved by what the robot drives and
    turns in one scan period. At 50 Hz that is a centimetre; at 10 Hz while turning, a tenth of a
    radian."""

    def scan(self, scan: LaserScan, odometry: Odometry) -> LaserScan:
        period = scan.meta.scan_time  # s
        moved = _planar(odometry.linear * period, 0.0, odometry.angular * period)
        return LaserScan(scan.stamp, scan.ranges, scan.meta, moved.then(scan.mount))


class StaleSweep(Fault):
    """A driver that double-buffers its sweeps and publishes the previous one: every reading is
    one scan period old (20 ms at 50 Hz; 180 ms at 5.5 Hz)."""

    def __init__(self) -> None:
        self.previous: FloatArray | None = None

    def scan(self, scan: LaserScan, odometry: Odometry) -> LaserScan:
        previous, self.previous = self.previous, scan.ranges
        if previous is None or len(previous) != len(scan.ranges):
            return scan
        return with_ranges(scan, previous)


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
        return with_ranges(scan, np.where(np.isnan(scan.ranges), np.inf, scan.ranges))


class ObstacleHeight(Fault):
    """costmap_2d's observation source `max_obstacle_height`, set to the decimetre above the old
    scan plane: 0.5 m over the Husky's 0.44 m laser, the value of the lidar source in
    ros-planning/navigation issue 485 (where it is suspected of "chopping off" the laser), as the
    TurtleBot's scan source kept 0.25-0.35 m until a laser mounted higher was lost to it
    (turtlebot/turtlebot_apps PR 157). ObservationBuffer::bufferCloud (costmap_2d
    observation_buffer.cpp, 9ad64419) keeps only the points from min_obstacle_height to
    max_obstacle_height in the global frame, and a level scan's points all lie at the laser's
    height: the old scanner's all stay; a scanner mounted above the limit gives observations
    with no points, which neither mark nor clear, exactly as a scan with every reading NaN.
    Exposed by `upright` (0.54 m): the costmap is blind to everything."""

    def __init__(self, baseline: LaserProfile) -> None:
        self.max_height = math.ceil(baseline.scan_height * 10.0) / 10.0  # m

    def scan(self, scan: LaserScan, odometry: Odometry) -> LaserScan:
        if scan.mount.xyz[2] <= self.max_height:
            return scan
        return with_ranges(scan, np.full(len(scan.ranges), np.nan))


class DropScans(Fault):
    """topic_tools' `drop scan X Y` between the driver and move_base (ros/ros_comm
    tools/topic_tools/src/drop.cpp, 845f7460: X of every Y messages dropped, the Y-th
    forwarded), the "downsampling the inputs to costmaps" of ros-planning/navigation issue 1196,
    sized so that the old scanner still feeds move_base at `rate` Hz: drop 4 of 5 at 50 Hz. The
    same counts feed the costmap at 2 Hz from a 10 Hz scanner and at 1.1 Hz from a 5.5 Hz one
    (`slower`, `lms111_to_rplidar_a1`), so that whatever a turn or a passed obstacle reveals
    reaches the costmap up to 0.4 or 0.7 s late. The costmap keeps its newest observation where
    it was taken (observation_persistence 0), so between forwarded scans move_base is given the
    last one again, placed where the robot was when it was measured; before the first, a scan
    of no readings (an empty observation buffer)."""

    def __init__(self, baseline: LaserProfile, rate: float = 10.0) -> None:
        self.every = max(1, round(baseline.update_rate / rate))  # Y; X = Y - 1
        self.count = 0
        self.kept: tuple[LaserScan, Odometry] | None = None

    def scan(self, scan: LaserScan, odometry: Odometry) -> LaserScan:
        self.count += 1
        if self.count % self.every == 0:
            self.kept = (scan, odometry)
            return scan
        if self.kept is None:
            return with_ranges(scan, np.full(len(scan.ranges), np.nan))
        kept, then = self.kept
        # The base frame the scan was taken in, seen from the current one.
        taken = (
            _planar(odometry.x, odometry.y, odometry.yaw)
            .inverse()
            .then(_planar(then.x, then.y, then.yaw))
        )
        return LaserScan(kept.stamp, kept.ranges, kept.meta, taken.then(kept.mount))


class TooNearStops(Fault):
    """A safety relay between move_base and the base, as ROBOTIS-GIT/turtlebot3's
    turtlebot3_obstacle_detection.py (da785b72) is one: while the least reading of the front half
    of the scan is below `stop_distance`, forward speed is zeroed and the turn passed on. Its
    min() takes REP 117's -inf ("nearer than range_min") for the least of all. The team set it
    0.25 m from the laser (the Husky's bumper is 0.16 m ahead of it) and skipped 0.0
    (sick_scan_xd's "no echo"). With the old range_min of 0.1 m, -inf only ever meant a contact;
    with `min_range`'s 0.6 m it stops the robot for anything within 0.6 m ahead, which it may
    pass or turn past. NaN is no reading."""

    def __init__(self, stop_distance: float = 0.25) -> None:
        self.stop_distance = stop_distance  # m

    def command(self, command: Command, scan: LaserScan) -> Command:
        meta, ranges = scan.meta, scan.ranges
        angles = meta.angle_min + np.arange(len(ranges)) * meta.angle_increment
        rotation = scan.mount.rotation()[:2, :2]
        ahead = (rotation @ np.stack([np.cos(angles), np.sin(angles)]))[0] > 0.0
        readings = ranges[ahead & ~np.isnan(ranges) & (ranges != 0.0)]
        if len(readings) and float(readings.min()) < self.stop_distance:
            return 0.0, command[1]
        return command


class ScanToBaseFrame(Fault):
    """The scan taken through a point cloud into the robot's base frame and back, as teams do to
    merge or self-filter scans: ros-perception/pointcloud_to_laserscan (d71ed2ea) projects it
    with laser_geometry (laserscan_to_pointcloud_node.cpp) and bins the points by their bearing
    from the base (pointcloud_to_laserscan_node.cpp: the nearest point of each bin, the index
    truncated), with the old scanner's angle_increment, range_min, range_max and scan_time, and
    the node's other defaults: bearings -pi to pi, heights that keep any scan plane above the
    ground, and `use_inf`, so that a bin no point falls in reads +inf, along which costmap_2d's
    inf_is_valid (the Husky's) then clears, from the base.
    The old scanner put a point in (nearly) every bin its field of view covers. A sparser one
    (`fewer_beams`, `lms111_to_rplidar_a1`) leaves the bins between its readings empty, clearing
    past and through a pole it missed; a narrower one (`narrower`) the bins beside the robot,
    clearing what it passed; one with a larger range_min (`min_range`) the bins of whatever is
    nearer, its -inf being no point (near_as_far's clearing, by another road). A bin past the
    last (a bearing of exactly pi, which the node would write beyond its array) is left out."""

    def __init__(self, baseline: LaserProfile) -> None:
        self.increment = baseline.angle_increment  # rad
        self.bins = math.ceil(2.0 * math.pi / self.increment)
        self.range_min, self.range_max = baseline.range_min, baseline.range_max  # m
        self.meta = dataclasses.replace(
            baseline.to_laserscan_meta(),
            angle_min=-math.pi,
            angle_max=math.pi,
            angle_increment=self.increment,
        )

    def scan(self, scan: LaserScan, odometry: Odometry) -> LaserScan:
        # projectLaser keeps the readings from range_min to below range_max.
        x, y = scan.points_in_base(within=scan.meta.range_max).T  # (P,), (P,) m
        distance = np.hypot(x, y)
        index = ((np.arctan2(y, x) + math.pi) / self.increment).astype(np.int64)
        inside = (distance >= self.range_min) & (distance <= self.range_max) & (index < self.bins)
        binned = np.full(self.bins, np.inf)
        np.minimum.at(binned, index[inside], distance[inside])
        return LaserScan(scan.stamp, binned, self.meta, Pose3D())


def _slow_costmap(settings: NavigationSettings, baseline: LaserProfile) -> NavigationSettings:
    """costmap_2d's `update_frequency` lowered to 1 Hz, as turtlebot/turtlebot_apps'
    global_costmap_params.yaml runs it and as ros-planning/navigation issue 1196's maintainer
    suggests for a CPU that misses its map-update rate. Costmap2DROS::mapUpdateLoop (costmap_2d
    costmap_2d_ros.cpp, 9ad64419) updates on its own clock, the obstacle layer taking the
    newest observation: a scan waits up to a second to be seen. With the old 270 deg, 50 Hz
    scanner whatever the robot turned toward had long been in the costmap; a narrower one first
    reads what lies beside the robot during the turn (`narrower`), a slower one adds its own
    period to the wait (`slower`, `lms111_to_rplidar_a1`). Both costmaps, as the imitation has
    one grid for both."""
    costmap = dataclasses.replace(settings.costmap, update_frequency=1.0)
    return dataclasses.replace(settings, costmap=costmap)


def _inf_not_valid(settings: NavigationSettings, baseline: LaserProfile) -> NavigationSettings:
    """The laser source without `inf_is_valid`, costmap_2d's default: a team whose old scanner
    published 0.0 for no return (sick_scan_xd) had no use for it, as the drivers of
    uos/sick_tim issue 54 (0.0) and ros-drivers/urg_node PR 8 (NaN) made it useless. With a
    scanner that publishes REP 117's +inf (`lms111_to_rplidar_a1`), laser_geometry's projection
    drops every no-return reading, so no ray clears along it: the global costmap keeps unseen
    cells unknown (navfn's costliest) and a stale mark stands until a reading ends behind it. A
    team whose old scanner published +inf would have seen that, so for it nothing changes."""
    if baseline.driver.no_return == "inf":
        return settings
    costmap = dataclasses.replace(settings.costmap, inf_is_valid=False)
    return dataclasses.replace(settings, costmap=costmap)


def _known_space_only(settings: NavigationSettings, baseline: LaserProfile) -> NavigationSettings:
    """navfn's `allow_unknown` false, as turtlebot/turtlebot_apps PR 122 set it (with the
    obstacle layer's track_unknown_space, which the Husky's global costmap has: "needed for
    disabling global path planning through unknown space"; ros-planning/navigation issue 261):
    navfn_ros.cpp (9ad64419) then makes every cell no ray has crossed an obstacle. A 270 deg
    scanner whose no-return clears had seen every cell a plan around an obstacle needs before
    the plan needed it; a narrower one has not seen what lies beside the robot or behind an
    obstacle (`narrower`), and navfn finds no plan. Set only where the old scanner's no-return
    clears (REP 117's +inf): with a driver that publishes 0.0 (sick_scan_xd) open space stays
    unknown, and a team would have found its robot without a plan on the first day."""
    if baseline.driver.no_return != "inf":
        return settings
    navfn = dataclasses.replace(settings.navfn, allow_unknown=False)
    return dataclasses.replace(settings, navfn=navfn)


MOVE_BASE_MUTANTS = (
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
    Mutant(
        "max_height",
        "the costmap's max_obstacle_height, just above the old scan plane, drops a raised scan",
        "ros-planning/navigation issue 485; turtlebot/turtlebot_apps PR 157; costmap_2d "
        "observation_buffer.cpp bufferCloud, 9ad64419",
        ObstacleHeight,
    ),
    Mutant(
        "slow_costmap",
        "the costmaps updated at 1 Hz, as the old scanner's wide early view allowed",
        "ros-planning/navigation issue 1196; costmap_2d costmap_2d_ros.cpp mapUpdateLoop, 9ad64419",
        lambda baseline: Fault(),
        navigation=_slow_costmap,
    ),
    Mutant(
        "inf_not_valid",
        "the costmap's inf_is_valid left false, of no use with the old scanner's 0.0 no-return",
        "uos/sick_tim issue 54; ros-drivers/urg_node PR 8; costmap_2d obstacle_layer.cpp, 9ad64419",
        lambda baseline: Fault(),
        navigation=_inf_not_valid,
    ),
    Mutant(
        "drop_scans",
        "4 of every 5 scans dropped on their way to move_base, sized for 50 Hz",
        "ros/ros_comm topic_tools drop.cpp, 845f7460; ros-planning/navigation issue 1196",
        DropScans,
    ),
    Mutant(
        "too_near_stops",
        "a safety relay whose min() takes -inf (too near) for the nearest reading",
        "ROBOTIS-GIT/turtlebot3 turtlebot3_obstacle_detection.py, da785b72",
        lambda baseline: TooNearStops(),
    ),
    Mutant(
        "base_frame_scan",
        "the scan re-binned in the base frame at the old increment; an empty bin reads +inf",
        "ros-perception/pointcloud_to_laserscan pointcloud_to_laserscan_node.cpp, d71ed2ea",
        ScanToBaseFrame,
    ),
    Mutant(
        "known_space_only",
        "navfn's allow_unknown false, which a scanner that sees all around never notices",
        "turtlebot/turtlebot_apps PR 122; ros-planning/navigation navfn_ros.cpp, 9ad64419",
        lambda baseline: Fault(),
        navigation=_known_space_only,
    ),
)

MUTANTS = (*MOVE_BASE_MUTANTS, *NAV2_MUTANTS)
