"""Laser scanner profiles with Gazebo `<ray>` fields, and the LaserScan they publish.

A profile names its fields as Gazebo does (`samples`, `resolution`, `min_angle`, `max_angle`,
`range.min`, `range.max`, `range.resolution`, `update_rate`, `noise`) plus the mount pose relative
to the robot base. Beam k of N = samples x resolution lies at
`min_angle + k (max_angle - min_angle) / (N - 1)`: both ends are sampled; N = 1 is one beam at 0.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, fields

import numpy as np

from pytest_lasertest.model.driver import DEFAULT_DRIVER, Driver
from pytest_lasertest.model.driver import describe as describe_driver
from pytest_lasertest.model.geometry import FULL_TURN, FloatArray, IntArray, Pose3D, wrap_angles
from pytest_lasertest.model.scanner_limits import ProfileError as ProfileError  # re-exported
from pytest_lasertest.model.scanner_limits import (
    check_angles,
    check_beams,
    check_mount,
    check_noise,
    check_ranges,
    check_rate,
)


@dataclass(frozen=True)
class GaussianNoise:
    """Gazebo `<noise type="gaussian">`, applied to in-range readings only."""

    mean: float = 0.0  # m
    stddev: float = 0.0  # m


@dataclass(frozen=True)
class LaserScanMeta:
    """The sensor_msgs/LaserScan header fields a profile publishes, in the laser frame."""

    angle_min: float  # rad
    angle_max: float  # rad
    angle_increment: float  # rad
    time_increment: float  # s
    scan_time: float  # s
    range_min: float  # m
    range_max: float  # m


@dataclass(frozen=True)
class LaserProfile:
    """A 2D laser scanner as Gazebo's `<ray>` describes it, mounted on a robot base."""

    samples: int
    min_angle: float  # rad
    max_angle: float  # rad
    range_min: float  # m
    range_max: float  # m
    update_rate: float  # Hz
    resolution: float = 1.0
    range_resolution: float = 0.0  # m, 0 = readings are not quantised
    noise: GaussianNoise | None = None
    pose: Pose3D = field(default_factory=Pose3D)
    driver: Driver = DEFAULT_DRIVER  # how its LaserScan encodes what it measured

    def __post_init__(self) -> None:
        _check_finite(self)
        check_beams(self.samples, self.resolution)
        check_angles(self.min_angle, self.max_angle)
        check_ranges(self.range_min, self.range_max, self.range_resolution)
        check_rate(self.update_rate)
        if self.noise is not None:
            check_noise(self.noise.mean, self.noise.stddev, self.range_min, self.range_max)
        check_mount(self.pose)

    @property
    def beam_count(self) -> int:
        """N = samples x resolution, the number of readings in one scan."""
        return round(self.samples * self.resolution)

    @property
    def angle_increment(self) -> float:
        """Angle between neighbouring beams (rad); 0 for a single beam."""
        if self.beam_count == 1:
            return 0.0
        return (self.max_angle - self.min_angle) / (self.beam_count - 1)

    @property
    def scan_period(self) -> float:
        """Time between two scans (s)."""
        return 1.0 / self.update_rate

    @property
    def scan_height(self) -> float:
        """Height of the scan plane above the robot base origin (m)."""
        return self.pose.xyz[2]

    def beam_angles(self) -> FloatArray:
        """Beam angles in the laser frame, shape (N,), rad, increasing."""
        if self.beam_count == 1:
            return np.zeros(1)
        return np.linspace(self.min_angle, self.max_angle, self.beam_count)

    def beam_angles_in_base(self) -> FloatArray:
        """Beam angles in the robot base frame, shape (N,), rad in [-pi, pi).

        A scanner mounted upside down mirrors its scan: +theta in the laser frame is -theta in
        the base frame, so the order of the beams is reversed there.
        """
        return _directions_in_base(self.pose, self.beam_angles())

    def rays(self, poses: FloatArray) -> tuple[FloatArray, FloatArray]:
        """World-frame beams of the scans taken at robot poses [x, y, yaw], shape (T, 3).

        Returns origins and unit directions, each shape (T, N, 2), m.
        """
        angles = poses[:, 2:3] + self.beam_angles_in_base()[np.newaxis, :]
        directions = np.stack([np.cos(angles), np.sin(angles)], axis=-1)
        origins = np.broadcast_to(self.origins(poses)[:, np.newaxis, :], directions.shape)
        return origins, directions

    def origins(self, poses: FloatArray) -> FloatArray:
        """Where the scanner is in the world at robot poses [x, y, yaw], shape (T, 3) -> (T, 2)."""
        mount_x, mount_y, _ = self.pose.xyz
        cos, sin = np.cos(poses[:, 2]), np.sin(poses[:, 2])
        origin_x = poses[:, 0] + cos * mount_x - sin * mount_y
        origin_y = poses[:, 1] + sin * mount_x + cos * mount_y
        return np.stack([origin_x, origin_y], axis=-1)

    def beams_near(
        self, poses: FloatArray, point: tuple[float, float], reach: float
    ) -> tuple[IntArray, IntArray]:
        """The beams of the scans at robot poses (T, 3) that, as whole rays, may pass within
        `reach` m of `point`: a scan index and a beam index each, shape (K,).

        Every other beam passes further away: a ray turned by more than asin(reach / d) from the
        direction to a point d away misses a circle of radius `reach` around it.
        """
        angles = self.beam_angles_in_base()
        order = np.argsort(angles, kind="stable")
        ring = np.concatenate([angles[order], angles[order] + FULL_TURN])
        offsets = np.asarray(point) - self.origins(poses)
        distance = np.hypot(offsets[:, 0], offsets[:, 1])
        with np.errstate(divide="ignore"):
            half = np.where(distance > reach, np.arcsin(np.minimum(reach / distance, 1.0)), np.pi)
        low = wrap_angles(np.arctan2(offsets[:, 1], offsets[:, 0]) - poses[:, 2] - half)
        first = np.searchsorted(ring, low, "left")
        counts = np.minimum(np.searchsorted(ring, low + 2.0 * half, "right") - first, len(angles))
        scans = np.repeat(np.arange(len(poses)), counts)
        within = np.arange(counts.sum()) - np.repeat(np.cumsum(counts) - counts, counts)
        beams: IntArray = order[(first[scans] + within) % len(angles)]
        return scans, beams

    def beam_directions(self, poses: FloatArray, scans: IntArray, beams: IntArray) -> FloatArray:
        """World unit vectors of beam `beams[k]` of the scan at `poses[scans[k]]`, shape (K, 2)."""
        angles = poses[scans, 2] + self.beam_angles_in_base()[beams]
        return np.column_stack([np.cos(angles), np.sin(angles)])

    def sector_in_base(self) -> tuple[float, float]:
        """The directions the beams span in the base frame: (start, extent), rad, counter-clockwise.

        A single beam spans no angle; a field of view written as a little over a full turn
        (Gazebo's 6.28319) spans exactly one.
        """
        if self.beam_count == 1:
            return float(self.beam_angles_in_base()[0]), 0.0
        ends = _directions_in_base(self.pose, np.array([self.min_angle, self.max_angle]))
        start = ends[1] if self.pose.is_upside_down() else ends[0]
        return float(start), min(self.max_angle - self.min_angle, FULL_TURN)

    def describe(self) -> str:
        """One line for reports: beams, field of view, range, rate and scan height."""
        return (
            f"{self.beam_count} beams over [{self.min_angle:.3f}, {self.max_angle:.3f}] rad, "
            f"range {self.range_min:.2f}-{self.range_max:.2f} m, {self.update_rate:g} Hz, "
            f"scan plane {self.scan_height:.3f} m"
            + (", upside down" if self.pose.is_upside_down() else "")
            + ("" if self.driver == DEFAULT_DRIVER else f"; driver: {describe_driver(self.driver)}")
        )

    def to_laserscan_meta(self) -> LaserScanMeta:
        """The LaserScan fields this scanner publishes (angles in its own frame, as ROS does)."""
        angles = self.beam_angles()
        return LaserScanMeta(
            angle_min=float(angles[0]),
            angle_max=float(angles[-1]),
            angle_increment=self.angle_increment,
            # Gazebo's ROS laser plugin stamps a whole scan at one instant.
            time_increment=0.0,
            scan_time=self.scan_period,
            range_min=self.range_min,
            range_max=self.range_max,
        )


def same_geometry(first: LaserProfile, second: LaserProfile) -> bool:
    """Whether two scanners cast the same beams from the same place at the same instants.

    Such scanners read any obstacle alike (noise aside), so no placement tells them apart.
    """
    if first.beam_count != second.beam_count:
        return False
    figures = [(p.range_min, p.range_max, p.update_rate, p.pose.xyz) for p in (first, second)]
    pose = np.zeros((1, 3))
    first_rays, second_rays = first.rays(pose), second.rays(pose)
    return figures[0] == figures[1] and all(
        np.allclose(a, b, rtol=0.0, atol=1e-12)
        for a, b in zip(first_rays, second_rays, strict=True)
    )


def same_sensing(first: LaserProfile, second: LaserProfile) -> bool:
    """Whether two scanners read every world alike: the same beams from the same place at the
    same instants, quantised and blurred alike, and published alike by their drivers. A pair of
    them has nothing to test."""
    return (
        same_geometry(first, second)
        and first.range_resolution == second.range_resolution
        and first.noise == second.noise
        and first.driver == second.driver
    )


def _directions_in_base(pose: Pose3D, angles: FloatArray) -> FloatArray:
    """Laser-frame beam angles, shape (N,), turned into base-frame angles, shape (N,), rad."""
    in_laser = np.stack([np.cos(angles), np.sin(angles), np.zeros_like(angles)])
    in_base = pose.rotation() @ in_laser
    return wrap_angles(np.arctan2(in_base[1], in_base[0]))


def _check_finite(profile: LaserProfile) -> None:
    for item in fields(profile):
        value = getattr(profile, item.name)
        if isinstance(value, float) and not math.isfinite(value):
            raise ProfileError(
                _gazebo_name(item.name), f"{value} is not a finite number", "write a real number"
            )
    groups = {"pose": [*profile.pose.xyz, *profile.pose.rpy]}
    if profile.noise is not None:
        groups["noise"] = [profile.noise.mean, profile.noise.stddev]
    for name, numbers in groups.items():
        if not all(math.isfinite(number) for number in numbers):
            raise ProfileError(
                name, "holds a value that is not a finite number", "write real numbers"
            )


def _gazebo_name(attribute: str) -> str:
    """The Gazebo field name of a LaserProfile attribute, as users write it."""
    return attribute.replace("range_", "range.") if attribute.startswith("range_") else attribute
