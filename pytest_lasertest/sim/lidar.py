"""The simulated laser: the rays of one scan, and the LaserScan ranges they give (REP 117).

Two ways to cast them: in PyBullet (`PhysicsWorld.cast`, what the scene really holds) or flat,
against the obstacles as upright prisms (every obstacle here is one, standing on the ground),
casting only the beams that can reach each one. Tests hold the flat cast equal to PyBullet's beam
for beam, and to `obstacles.ray_distances`.
"""

from __future__ import annotations

import bisect
import itertools
import math
from typing import NamedTuple

import numpy as np

from pytest_lasertest.model.geometry import FULL_TURN, FloatArray, IntArray, wrap_angle
from pytest_lasertest.model.obstacles import Box, Cylinder, Obstacle
from pytest_lasertest.model.sensor import LaserProfile

# The distance (m) every beam reads from inside an obstacle.
_INSIDE = np.zeros(1)
_INSIDE.setflags(write=False)


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
    can touch it are cast: those between the bearings of a cylinder's two tangents, and those
    between the bearings of the two ends of each face of a box that faces the scanner. A beam in
    such a window meets the face (or the circle) first, at a distance one cosine gives. The
    ranges equal those of casting every beam with `obstacles.ray_distances` (a test holds them
    so).
    """

    def __init__(self, profile: LaserProfile, obstacles: tuple[Obstacle, ...]) -> None:
        self.profile = profile
        self.obstacles = tuple(o for o in obstacles if o.height > profile.scan_height)
        self._reach = [obstacle.bounding_radius for obstacle in self.obstacles]
        self._faces = [_faces(o) if isinstance(o, Box) else () for o in self.obstacles]
        self._count = profile.beam_count
        self._mount = profile.pose.xyz[:2]
        angles = profile.beam_angles_in_base()
        order = np.argsort(angles, kind="stable")
        # The beams by angle, twice round, so that a window across -pi is one slice.
        self._ring = np.concatenate([angles[order], angles[order] + FULL_TURN])
        self._bisectable = self._ring.tolist()
        # Beams in angle order, or (a scanner mounted upside down) in the reverse order, need no
        # shuffle back into beam order.
        self._reversed = bool(np.all(order == np.arange(len(order))[::-1]))
        in_order = self._reversed or bool(np.all(order == np.arange(len(order))))
        self._order: IntArray | None = None if in_order else order
        self._nothing = np.full(len(self._ring), np.inf)

    def ranges(self, pose: FloatArray) -> FloatArray:
        """LaserScan ranges (N,) of the scan at robot pose [x, y, yaw], in beam order (REP 117)."""
        x, y, yaw = pose.tolist()
        mount_x, mount_y = self._mount
        cos, sin = math.cos(yaw), math.sin(yaw)
        origin = (x + cos * mount_x - sin * mount_y, y + sin * mount_x + cos * mount_y)
        # Ranges by beam angle, twice round, as the windows are sliced.
        ring = self._nothing.copy()
        for obstacle, reach, faces in zip(self.obstacles, self._reach, self._faces, strict=True):
            centre = math.hypot(obstacle.x - origin[0], obstacle.y - origin[1])
            if centre - reach > self.profile.range_max:
                continue
            if isinstance(obstacle, Cylinder):
                self._cast_cylinder(ring, origin, yaw, obstacle, centre)
            else:
                self._cast_box(ring, origin, yaw, faces, (centre, reach))
        by_angle: FloatArray = np.minimum(ring[: self._count], ring[self._count :])
        if self._order is None:
            return by_angle[::-1] if self._reversed else by_angle
        ranges = np.empty(self._count)
        ranges[self._order] = by_angle
        return ranges

    def _cast_cylinder(
        self,
        ring: FloatArray,
        origin: tuple[float, float],
        yaw: float,
        cylinder: Cylinder,
        centre: float,
    ) -> None:
        """Read the cylinder, its centre `centre` m away: a beam turned by theta from the bearing
        of the centre enters at centre cos(theta) - sqrt(r^2 - centre^2 sin^2(theta))."""
        circle = (centre, cylinder.radius)
        if centre <= cylinder.radius:
            self._mark(ring, slice(None), _INSIDE, circle)
            return
        bearing = math.atan2(cylinder.y - origin[1], cylinder.x - origin[0])
        half = math.asin(cylinder.radius / centre)
        window = self._window(bearing - half - yaw, 2.0 * half)
        along = centre * np.cos(self._ring[window] + (yaw - bearing))
        # Within the window the discriminant is >= 0 up to rounding, which would make it a NaN.
        across = np.sqrt(np.maximum(along * along + (cylinder.radius**2 - centre**2), 0.0))
        self._mark(ring, window, along - across, circle)

    def _cast_box(
        self,
        ring: FloatArray,
        origin: tuple[float, float],
        yaw: float,
        faces: tuple[_Face, ...],
        circle: tuple[float, float],
    ) -> None:
        """Read each face of the box that faces the scanner: a beam turned by theta from the
        face's inward normal meets it at (its distance) / cos(theta). `circle` is the distance
        to the box's centre and its bounding radius (m)."""
        inside = True
        for face in faces:
            distance = face.normal[0] * origin[0] + face.normal[1] * origin[1] - face.offset
            if distance <= 0.0:
                continue
            inside = False
            # The ends run counter-clockwise round the box, so clockwise as the scanner sees
            # them: the face spans less than half a turn from the bearing of its last end.
            first = math.atan2(face.ends[3] - origin[1], face.ends[2] - origin[0])
            last = math.atan2(face.ends[1] - origin[1], face.ends[0] - origin[0])
            window = self._window(first - yaw, (last - first) % FULL_TURN)
            turned = self._ring[window] + (yaw - face.inward)
            self._mark(ring, window, distance / np.cos(turned), circle)
        if inside:
            self._mark(ring, slice(None), _INSIDE, circle)

    def _window(self, low: float, width: float) -> slice:
        """The beams (on the ring) whose angles in the base frame lie in [low, low + width]."""
        low = wrap_angle(low)
        first = bisect.bisect_left(self._bisectable, low)
        last = bisect.bisect_right(self._bisectable, low + width)
        return slice(first, min(last, first + self._count))

    def _mark(
        self, ring: FloatArray, window: slice, distances: FloatArray, circle: tuple[float, float]
    ) -> None:
        """Keep the nearer of each beam's range and its distance (m) to an obstacle, read as
        LaserScan ranges: +inf beyond range_max, -inf short of range_min. `circle`, the
        obstacle's centre distance and bounding radius (m), says whether either can happen."""
        profile = self.profile
        centre, reach = circle
        if centre + reach > profile.range_max:
            distances = np.where(distances > profile.range_max, np.inf, distances)
        if centre - reach < profile.range_min:
            distances = np.where(distances < profile.range_min, -np.inf, distances)
        beams = ring[window]
        np.minimum(beams, distances, out=beams)


class _Face(NamedTuple):
    """One side of a box's footprint: the line normal . p = offset, with the normal pointing out
    of the box, and its ends in counter-clockwise order round the box."""

    normal: tuple[float, float]
    offset: float  # m
    inward: float  # rad, the direction of -normal
    ends: tuple[float, float, float, float]  # m, x0 y0 x1 y1


def _faces(box: Box) -> tuple[_Face, ...]:
    """The four faces of the box's footprint."""
    corners = box.corners()
    faces = []
    for index, (start, end) in enumerate(itertools.pairwise([*corners, corners[0]])):
        outward = box.yaw + index * math.pi / 2.0
        normal = (math.cos(outward), math.sin(outward))
        offset = normal[0] * start[0] + normal[1] * start[1]
        faces.append(_Face(normal, offset, outward + math.pi, (*start, *end)))
    return tuple(faces)


def noisy(profile: LaserProfile, ranges: FloatArray, rng: np.random.Generator) -> FloatArray:
    """The ranges as the scanner reports them: Gaussian noise on in-range readings only, clamped
    to [range_min, range_max], then quantised to range.resolution when it is set."""
    in_range = np.isfinite(ranges).nonzero()[0]
    if not len(in_range):
        return ranges
    readings = ranges[in_range]
    if profile.noise is not None and profile.noise.stddev > 0.0:
        readings += rng.normal(profile.noise.mean, profile.noise.stddev, len(in_range))
        np.maximum(readings, profile.range_min, out=readings)
        np.minimum(readings, profile.range_max, out=readings)
    if profile.range_resolution > 0.0:
        readings /= profile.range_resolution
        np.rint(readings, out=readings)
        readings *= profile.range_resolution
    reported = ranges.copy()
    reported[in_range] = readings
    return reported


def _rep117(profile: LaserProfile, distances: FloatArray) -> FloatArray:
    ranges: FloatArray = np.where(distances < profile.range_min, -np.inf, distances)
    return ranges
