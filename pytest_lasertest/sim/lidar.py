"""The simulated laser: the rays of one scan, and the LaserScan ranges they give (REP 117).

Two ways to cast them: in PyBullet (`PhysicsWorld.cast`, what the scene really holds) or flat,
against the obstacles as upright prisms (every obstacle here is one, standing on the ground),
casting only the beams that can reach each one. Tests hold the flat cast equal to PyBullet's beam
for beam, and to `geometry.ray_distances`.
"""

from __future__ import annotations

import bisect
import math

import numpy as np

from pytest_lasertest.geometry import (
    Box,
    Cylinder,
    FloatArray,
    IntArray,
    Obstacle,
    bounding_radius,
)
from pytest_lasertest.sensor import FULL_TURN, LaserProfile


def scan_rays(profile: LaserProfile, pose: FloatArray) -> tuple[FloatArray, FloatArray]:
    """The scan's rays from the scanner at robot pose [x, y, yaw] out to range_max, in the scan
    plane: starts and ends, each shape (N, 3), m."""
    origins, directions = profile.rays(pose[np.newaxis, :])
    height = np.full((profile.beam_count, 1), profile.scan_height)
    starts = np.hstack([origins[0], height])
    ends = np.hstack([origins[0] + profile.range_max * directions[0], height])
    return starts, ends


def ranges_from_fractions(profile: LaserProfile, fractions: FloatArray) -> FloatArray:
    """LaserScan ranges (N,) from where each ray of `scan_rays` first met something, as a fraction
    of range_max (1.0: nothing): +inf for no return, -inf nearer than range_min (REP 117)."""
    distances = np.where(fractions < 1.0, fractions * profile.range_max, np.inf)
    return _rep117(profile, distances)


class FlatLidar:
    """The scanner cast flat against a fixed set of obstacles, one scan at a time.

    Only the obstacles that reach above the scan plane are kept, and of each only the beams that
    can touch its bounding circle are cast: every other beam is turned by more than
    asin(reach / d) from the direction to a centre d away, so it misses that circle and all
    inside it. The ranges equal those of casting every beam (a test holds them so).
    """

    def __init__(self, profile: LaserProfile, obstacles: tuple[Obstacle, ...]) -> None:
        self.profile = profile
        self.obstacles = tuple(o for o in obstacles if o.height > profile.scan_height)
        self._reach = [bounding_radius(obstacle) for obstacle in self.obstacles]
        angles = profile.beam_angles_in_base()
        self._angles = angles
        # The beams by angle, twice round, so that a window across -pi is one slice.
        order = np.argsort(angles, kind="stable")
        self._order = np.tile(order, 2)
        self._ring = [*angles[order].tolist(), *(angles[order] + FULL_TURN).tolist()]
        self._mount = profile.pose.xyz[:2]
        self._nothing = np.full(profile.beam_count, np.inf)

    def ranges(self, pose: FloatArray) -> FloatArray:
        """LaserScan ranges (N,) of the scan at robot pose [x, y, yaw], in beam order (REP 117)."""
        x, y, yaw = (float(value) for value in pose)
        cos, sin = math.cos(yaw), math.sin(yaw)
        mount_x, mount_y = self._mount
        origin = (x + cos * mount_x - sin * mount_y, y + sin * mount_x + cos * mount_y)
        ranges = self._nothing.copy()
        for obstacle, reach in zip(self.obstacles, self._reach, strict=True):
            distance = math.hypot(obstacle.x - origin[0], obstacle.y - origin[1])
            if distance - reach > self.profile.range_max:
                continue
            beams = self._beams_towards(origin, yaw, obstacle, reach, distance)
            if len(beams):
                hits = fan_distances(origin, yaw + self._angles[beams], obstacle)
                ranges[beams] = np.minimum(ranges[beams], self._in_range(hits, distance, reach))
        return ranges

    def _beams_towards(
        self,
        origin: tuple[float, float],
        yaw: float,
        obstacle: Obstacle,
        reach: float,
        distance: float,
    ) -> IntArray:
        """The beams that may touch the circle of radius `reach` around the obstacle's centre,
        `distance` m from the scanner."""
        half = math.asin(reach / distance) if distance > reach else math.pi
        bearing = math.atan2(obstacle.y - origin[1], obstacle.x - origin[0])
        low = (bearing - yaw - half + math.pi) % FULL_TURN - math.pi
        first = bisect.bisect_left(self._ring, low)
        last = bisect.bisect_right(self._ring, low + 2.0 * half)
        beams: IntArray = self._order[first : min(last, first + self.profile.beam_count)]
        return beams

    def _in_range(self, distances: FloatArray, centre: float, reach: float) -> FloatArray:
        """Distances (K,) m to an obstacle whose centre is `centre` m away as LaserScan ranges:
        +inf beyond range_max, -inf short of range_min; an obstacle wholly between the two is
        read as it is."""
        profile = self.profile
        if centre + reach > profile.range_max:
            distances = np.where(distances > profile.range_max, np.inf, distances)
        if centre - reach < profile.range_min:
            distances = np.where(distances < profile.range_min, -np.inf, distances)
        return distances


def fan_distances(
    origin: tuple[float, float], angles: FloatArray, obstacle: Obstacle
) -> FloatArray:
    """Distance along each ray from one origin (m) at world angles (K,) rad to where it first
    enters the obstacle's footprint, shape (K,) m: inf where it misses, 0 from inside.

    `geometry.ray_distances` for rays that share their origin, which leaves one scalar offset
    and a few operations on (K,) arrays: the simulated laser casts it at every scan.
    """
    if isinstance(obstacle, Cylinder):
        return _fan_to_cylinder(obstacle.x - origin[0], obstacle.y - origin[1], angles, obstacle)
    cos, sin = math.cos(obstacle.yaw), math.sin(obstacle.yaw)
    dx, dy = origin[0] - obstacle.x, origin[1] - obstacle.y
    # The origin and the rays in the box's own frame.
    local = (cos * dx + sin * dy, cos * dy - sin * dx)
    return _fan_to_box(local, angles - obstacle.yaw, obstacle)


def _fan_to_cylinder(dx: float, dy: float, angles: FloatArray, cylinder: Cylinder) -> FloatArray:
    """Rays at `angles` from an origin (dx, dy) m short of the centre: each enters at
    b - sqrt(r^2 - c^2), with b how far along it the centre lies and c how far across."""
    cos, sin = np.cos(angles), np.sin(angles)
    along = dx * cos + dy * sin
    across = dx * sin - dy * cos
    room = cylinder.radius**2 - across * across
    near = along - np.sqrt(np.maximum(room, 0.0))
    if dx * dx + dy * dy <= cylinder.radius**2:
        return np.zeros_like(angles)
    distances: FloatArray = np.where((room >= 0.0) & (along > 0.0), near, np.inf)
    return distances


def _fan_to_box(origin: tuple[float, float], angles: FloatArray, box: Box) -> FloatArray:
    """Slab test of rays at `angles` (K,) from `origin`, both in the box's own frame."""
    enter_x, leave_x = _fan_slab(origin[0], np.cos(angles), box.length / 2.0)
    enter_y, leave_y = _fan_slab(origin[1], np.sin(angles), box.width / 2.0)
    enter = np.maximum(np.maximum(enter_x, enter_y), 0.0)
    distances: FloatArray = np.where(np.minimum(leave_x, leave_y) >= enter, enter, np.inf)
    return distances


def _fan_slab(position: float, steps: FloatArray, half: float) -> tuple[FloatArray, FloatArray]:
    """Where rays from `position` with `steps` (K,) along one axis enter and leave |x| <= half.

    A ray parallel to the slab is given a step of 1e-300: its interval is then (-huge, +huge)
    from inside the slab and empty or out of range from outside, as it should be.
    """
    if not steps.all():
        steps = np.where(steps == 0.0, 1e-300, steps)
    inverse = 1.0 / steps
    low, high = (-half - position) * inverse, (half - position) * inverse
    return np.minimum(low, high), np.maximum(low, high)


def noisy(profile: LaserProfile, ranges: FloatArray, rng: np.random.Generator) -> FloatArray:
    """The ranges as the scanner reports them: Gaussian noise on in-range readings only, clamped
    to [range_min, range_max], then quantised to range.resolution when it is set."""
    in_range = np.flatnonzero(np.isfinite(ranges))
    if not len(in_range):
        return ranges
    readings = ranges[in_range]
    if profile.noise is not None and profile.noise.stddev > 0.0:
        noise = rng.normal(profile.noise.mean, profile.noise.stddev, len(in_range))
        readings = np.clip(readings + noise, profile.range_min, profile.range_max)
    if profile.range_resolution > 0.0:
        readings = np.round(readings / profile.range_resolution) * profile.range_resolution
    reported = ranges.copy()
    reported[in_range] = readings
    return reported


def _rep117(profile: LaserProfile, distances: FloatArray) -> FloatArray:
    ranges: FloatArray = np.where(distances < profile.range_min, -np.inf, distances)
    return ranges
