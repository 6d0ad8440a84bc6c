"""laser_filters' filters of one scan at a time, each a frozen value whose `apply` makes the
filtered scan from a scan, as the filter's `update` does.

Every behaviour cites the upstream code it follows: ros-perception/laser_filters at ros2
905f5e9a (ROS 2) and at noetic-devel 75913d51 (ROS 1), where both are given the same where
they agree, and ros-perception/laser_geometry for the projection the geometric filters use.
The scan is ours (`LaserScan`): float64 ranges where the message holds float32, so readings
meet a threshold the same way except within a float32 rounding of it.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from typing import Literal

import numpy as np
import numpy.typing as npt

from pytest_lasertest.model.geometry import FloatArray, IntArray
from pytest_lasertest.nav.protocol import LaserScan

BoolArray = npt.NDArray[np.bool_]
Ros = Literal["ros1", "ros2"]


class ScanRefused(RuntimeError):
    """A filter that cannot filter this scan: its `update` returns false, and the chain node
    publishes nothing, so the stack behind it is left without scans."""


def replaced(scan: LaserScan, ranges: FloatArray) -> LaserScan:
    """The scan with other ranges, all else kept."""
    return dataclasses.replace(scan, ranges=ranges)


def beam_angles(scan: LaserScan) -> FloatArray:
    """Each beam's angle in the laser frame (rad), then the one past the last, summed one
    angle_increment at a time as the angular filters' loops sum them, shape (N + 1,)."""
    steps = np.full(len(scan.ranges) + 1, scan.meta.angle_increment)
    steps[0] = scan.meta.angle_min
    angles: FloatArray = np.cumsum(steps)
    return angles


def projected(scan: LaserScan) -> tuple[IntArray, FloatArray]:
    """laser_geometry's projection of a scan into the robot's base frame: the indices of the
    readings it projects, range_min <= r < range_max (src/laser_geometry.cpp:183-191 at humble
    ba53212e; :414-422 at kinetic-devel 22f3aa94), and their points (M, 3) m. The laser is fixed
    on the base, so its pose over the sweep is one pose."""
    ranges, meta = scan.ranges, scan.meta
    with np.errstate(invalid="ignore"):
        kept = np.flatnonzero((ranges < meta.range_max) & (ranges >= meta.range_min))
    angles = meta.angle_min + kept * meta.angle_increment
    in_laser = np.stack([np.cos(angles), np.sin(angles), np.zeros(len(kept))]) * ranges[kept]
    points: FloatArray = (scan.mount.rotation() @ in_laser).T + np.array(scan.mount.xyz)
    return kept, points


@dataclass(frozen=True)
class RangeFilter:
    """LaserScanRangeFilter: a reading at or below the lower threshold becomes the lower
    replacement value, else one at or above the upper threshold the upper replacement value
    (range_filter.h:86-111 at ros2; :82-110 at noetic-devel). NaN meets neither."""

    lower_threshold: float  # m
    upper_threshold: float  # m
    use_message_range_limits: bool  # the scan's range_min and range_max as the thresholds
    lower_replacement_value: float  # m, may be NaN or infinite
    upper_replacement_value: float  # m, may be NaN or infinite

    def apply(self, scan: LaserScan) -> LaserScan:
        lower, upper = self.lower_threshold, self.upper_threshold
        if self.use_message_range_limits:
            lower, upper = scan.meta.range_min, scan.meta.range_max
        ranges = scan.ranges
        with np.errstate(invalid="ignore"):
            upper_replaced = np.where(ranges >= upper, self.upper_replacement_value, ranges)
            return replaced(
                scan, np.where(ranges <= lower, self.lower_replacement_value, upper_replaced)
            )


@dataclass(frozen=True)
class AngularBoundsFilter:
    """LaserScanAngularBoundsFilter: the scan cut to the beams from the first at or above
    lower_angle to the first whose next beam lies beyond upper_angle. angle_min becomes the
    first kept beam's angle, the stamp moves on a time_increment per beam cut off the start, and
    angle_max becomes the last kept beam's angle, or the angle one past the scan's last beam
    where no beam lies beyond upper_angle (angular_bounds_filter.h:68-123 at ros2; :66-146 at
    noetic-devel, whose clockwise branch no scan here takes)."""

    lower_angle: float  # rad, laser frame
    upper_angle: float  # rad, laser frame

    def apply(self, scan: LaserScan) -> LaserScan:
        angles, count = beam_angles(scan), len(scan.ranges)
        start = int(np.argmax(angles[:count] >= self.lower_angle)) if count else 0
        if count and angles[start] < self.lower_angle:
            start = count  # every beam lies below lower_angle
        beyond = np.flatnonzero(angles[start:count] + scan.meta.angle_increment > self.upper_angle)
        end = start + int(beyond[0]) if len(beyond) else count - 1
        last_angle = angles[end] if len(beyond) else angles[count]
        meta = dataclasses.replace(
            scan.meta, angle_min=float(angles[start]), angle_max=float(last_angle)
        )
        return dataclasses.replace(
            scan,
            stamp=scan.stamp + start * scan.meta.time_increment,
            ranges=scan.ranges[start : end + 1].copy(),
            meta=meta,
        )


@dataclass(frozen=True)
class AngularBoundsFilterInPlace:
    """LaserScanAngularBoundsFilterInPlace: each beam strictly between lower_angle and
    upper_angle reads range_max + 1 m, no reading; the scan keeps its beams
    (angular_bounds_filter_in_place.h:67-88 at ros2; :66-87 at noetic-devel)."""

    lower_angle: float  # rad, laser frame
    upper_angle: float  # rad, laser frame

    def apply(self, scan: LaserScan) -> LaserScan:
        angles = beam_angles(scan)[: len(scan.ranges)]
        inside = (angles > self.lower_angle) & (angles < self.upper_angle)
        return replaced(scan, np.where(inside, scan.meta.range_max + 1.0, scan.ranges))


@dataclass(frozen=True)
class BoxFilter:
    """LaserScanBoxFilter: each projected reading strictly inside the box (outside it, with
    `invert`) becomes NaN (box_filter.h:127-208 at ros2; box_filter.cpp:80-181 at
    noetic-devel). The box is in the robot's base frame (box_frame names it), z up from the
    ground (base_footprint)."""

    min_x: float  # m
    max_x: float  # m
    min_y: float  # m
    max_y: float  # m
    min_z: float  # m
    max_z: float  # m
    invert: bool  # remove the readings outside the box instead

    def apply(self, scan: LaserScan) -> LaserScan:
        beams, points = projected(scan)
        low = np.array([self.min_x, self.min_y, self.min_z])
        high = np.array([self.max_x, self.max_y, self.max_z])
        inside = np.all((points < high) & (points > low), axis=1)
        ranges = scan.ranges.copy()
        ranges[beams[inside != self.invert]] = np.nan
        return replaced(scan, ranges)


@dataclass(frozen=True)
class FootprintFilter:
    """LaserScanFootprintFilter: each projected reading within the square of half-side
    inscribed_radius around base_link's origin, edges included, becomes NaN
    (footprint_filter.h:81-142 at ros2; :75-129 at noetic-devel)."""

    inscribed_radius: float  # m

    def apply(self, scan: LaserScan) -> LaserScan:
        beams, points = projected(scan)
        within = np.all(np.abs(points[:, :2]) <= self.inscribed_radius, axis=1)
        ranges = scan.ranges.copy()
        ranges[beams[within]] = np.nan
        return replaced(scan, ranges)


@dataclass(frozen=True)
class InterpolationFilter:
    """InterpolationFilter: each run of readings at or below range_min or at or above
    range_max becomes the mean of the valid reading before it (range_max - 0.01 m before the
    first) and the one after it; a run that reaches the end takes, for the one after, the one
    after the run before it, as the loop leaves it (interpolation_filter.h:63-110, ros2 and
    noetic-devel alike). NaN counts as valid."""

    def apply(self, scan: LaserScan) -> LaserScan:
        ranges = scan.ranges.copy()
        with np.errstate(invalid="ignore"):
            invalid = (ranges <= scan.meta.range_min) | (ranges >= scan.meta.range_max)
        edges = np.flatnonzero(np.diff(np.concatenate(([0], invalid.astype(np.int8), [0]))))
        previous = following = scan.meta.range_max - 0.01  # m
        for start, stop in zip(edges[::2], edges[1::2], strict=True):
            if start > 0:
                previous = float(scan.ranges[start - 1])
            if stop < len(ranges):
                following = float(scan.ranges[stop])
            ranges[start:stop] = (previous + following) / 2.0
        return replaced(scan, ranges)


@dataclass(frozen=True)
class SpeckleFilter:
    """LaserScanSpeckleFilter: a reading stays where some window of `filter_window`
    consecutive readings holding it is valid, or where it lies beyond max_range; the rest
    become NaN (speckle_filter.h:225-254 at ros2; speckle_filter.cpp:74-123 at noetic-devel).
    Distance (filter_type 0): a window is valid where its first reading is no NaN and every
    other differs from it by at most max_range_difference (speckle_filter.h:61-84); radius
    outlier (1): where at least filter_window of the readings within filter_window beams of the
    first lie within max_range_difference of it (speckle_filter.h:86-154)."""

    ros: Ros
    filter_type: int  # 0 distance, 1 radius outlier (euclidean)
    max_range: float  # m
    max_range_difference: float  # m
    filter_window: int  # readings

    def apply(self, scan: LaserScan) -> LaserScan:
        ranges, window = scan.ranges, self.filter_window
        self._check_size(len(ranges))
        windows = max(len(ranges) - window + 1, 0)
        valid_window = (
            self._distance(ranges, windows)
            if self.filter_type == 0
            else self._radius(ranges, windows, scan.meta.angle_increment)
        )
        with np.errstate(invalid="ignore"):
            valid = ranges > self.max_range
        for offset in range(window):
            valid[offset : offset + windows] |= valid_window
        return replaced(scan, np.where(valid, ranges, np.nan))

    def _check_size(self, count: int) -> None:
        # ROS 1 refuses a scan the window does not fit with room to spare; ROS 2 reads past the
        # end of a shorter one (its unsigned loop bound wraps), which is no behaviour to imitate.
        if self.ros == "ros1" and count <= self.filter_window + 1:
            raise ScanRefused(
                f"ROS 1's LaserScanSpeckleFilter refuses a scan of {count} readings with "
                f"filter_window {self.filter_window} (speckle_filter.cpp:83-87 at noetic-devel "
                "75913d51): the chain publishes no scan"
            )
        if self.ros == "ros2" and count < self.filter_window:
            raise ScanRefused(
                f"ROS 2's LaserScanSpeckleFilter reads past the end of a scan of {count} "
                f"readings with filter_window {self.filter_window} (speckle_filter.h:228 at "
                "ros2 905f5e9a)"
            )

    def _distance(self, ranges: FloatArray, windows: int) -> BoolArray:
        first = ranges[:windows]
        valid: BoolArray = ~np.isnan(first)
        with np.errstate(invalid="ignore"):
            for offset in range(1, self.filter_window):
                # The windows end by the last reading: none reaches past it.
                neighbour = ranges[offset : offset + windows]
                apart = np.abs(neighbour - first) > self.max_range_difference
                valid &= ~(np.isnan(neighbour) | apart)
        return valid

    def _radius(self, ranges: FloatArray, windows: int, increment: float) -> BoolArray:
        first, window = ranges[:windows], self.filter_window
        neighbours = np.zeros(windows, dtype=np.intp)
        with np.errstate(invalid="ignore"):
            for offset in range(-window, window + 1):
                index = np.arange(windows) + offset
                inside = (offset != 0) & (index >= 0) & (index < len(ranges))
                other = np.where(inside, ranges[np.clip(index, 0, len(ranges) - 1)], np.nan)
                squared = first**2 + other**2 - 2.0 * first * other * math.cos(offset * increment)
                neighbours += np.sqrt(squared) <= self.max_range_difference
        valid: BoolArray = neighbours >= window
        return valid


@dataclass(frozen=True)
class ShadowDetector:
    """ScanShadowDetector: whether the line from one reading to its neighbour's is seen at an
    angle below min_angle or above max_angle (scan_shadow_detector.h:49-77 at ros2;
    scan_shadow_detector.cpp:45-80 at noetic-devel)."""

    min_angle: float  # rad
    max_angle: float  # rad

    def is_shadow(
        self, first: FloatArray, second: FloatArray, sine: float, cosine: float
    ) -> BoolArray:
        """Whether each reading of `first` is a shadow against `second`, the readings
        |y| beams away, given that angle's sine and cosine."""
        min_tan, max_tan = abs(math.tan(self.min_angle)), -abs(math.tan(self.max_angle))
        with np.errstate(invalid="ignore", divide="ignore"):
            across = np.abs(second * sine) / (first - second * cosine)
            shadow: BoolArray = np.where(across > 0, across < min_tan, across > max_tan)
        return shadow

    def is_shadow_at(self, first: FloatArray, second: FloatArray, angle: float) -> BoolArray:
        """`is_shadow` for readings `angle` rad apart."""
        return self.is_shadow(first, second, math.sin(angle), math.cos(angle))


@dataclass(frozen=True)
class ShadowsFilter:
    """ScanShadowsFilter: a reading that is a shadow against any reading within `window` beams
    of it (`ShadowDetector`) deletes, as NaN, each of the readings within `neighbors` beams of
    it that lies farther than it, and, with `remove_shadow_start_point` (ROS 1 only), itself
    (scan_shadows_filter.h:138-176 at ros2; scan_shadows_filter.cpp:129-172 at noetic-devel)."""

    detector: ShadowDetector
    window: int  # beams
    neighbors: int  # beams
    remove_shadow_start_point: bool

    def apply(self, scan: LaserScan) -> LaserScan:
        ranges, count = scan.ranges, len(scan.ranges)
        shadow = np.zeros(count, dtype=bool)
        for offset in (y for y in range(-self.window, self.window + 1) if y != 0):
            here, there = _shifted(count, offset)
            angle = offset * scan.meta.angle_increment
            shadow[here] |= self.detector.is_shadow_at(ranges[here], ranges[there], angle)
        if not shadow.any():
            return scan
        deleted = shadow & self.remove_shadow_start_point
        with np.errstate(invalid="ignore"):
            for offset in range(-self.neighbors, self.neighbors + 1):
                here, there = _shifted(count, offset)
                deleted[there] |= shadow[here] & (ranges[here] < ranges[there])
        return replaced(scan, np.where(deleted, np.nan, ranges))


def _shifted(count: int, offset: int) -> tuple[slice, slice]:
    """The readings i, and i + offset, of a scan of `count`, where both lie in the scan."""
    if offset >= 0:
        return slice(0, max(count - offset, 0)), slice(offset, count)
    return slice(-offset, count), slice(0, max(count + offset, 0))
