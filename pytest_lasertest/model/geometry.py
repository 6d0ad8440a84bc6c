"""Poses in REP 103 frames: x forward, y left, z up, angles counter-clockwise."""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import TypeAlias

import numpy as np
import numpy.typing as npt

FloatArray = npt.NDArray[np.float64]
IntArray = npt.NDArray[np.intp]


@dataclass(frozen=True)
class Point2D:
    """A point in the world plane."""

    x: float  # m
    y: float  # m


@dataclass(frozen=True)
class Pose2D:
    """A robot pose in the world plane."""

    x: float  # m
    y: float  # m
    yaw: float  # rad


@dataclass(frozen=True)
class Pose3D:
    """A mount pose relative to the robot base, as URDF `<origin xyz rpy>`."""

    xyz: tuple[float, float, float] = (0.0, 0.0, 0.0)  # m
    rpy: tuple[float, float, float] = (0.0, 0.0, 0.0)  # rad, fixed-axis roll, pitch, yaw

    def rotation(self) -> FloatArray:
        """The 3x3 rotation matrix Rz(yaw) Ry(pitch) Rx(roll), as URDF composes it."""
        roll, pitch, yaw = self.rpy
        cr, sr = math.cos(roll), math.sin(roll)
        cp, sp = math.cos(pitch), math.sin(pitch)
        cy, sy = math.cos(yaw), math.sin(yaw)
        return np.array(
            [
                [cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
                [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
                [-sp, cp * sr, cp * cr],
            ]
        )

    def tilt(self) -> float:
        """Angle between the mounted frame's z axis and the base's z axis, up or down (rad)."""
        z_component = float(self.rotation()[2, 2])
        return math.acos(min(1.0, abs(z_component)))

    def is_upside_down(self) -> bool:
        """Whether the mounted frame's z axis points down, as a laser hung below its bracket."""
        return float(self.rotation()[2, 2]) < 0.0

    def then(self, child: Pose3D) -> Pose3D:
        """The pose `child`, given in this pose's frame, in the frame this pose is given in: the
        composition a URDF joint chain makes, parent first."""
        rotation = self.rotation()
        xyz = np.asarray(self.xyz) + rotation @ np.asarray(child.xyz)
        return _pose_from(rotation @ child.rotation(), xyz)

    def inverse(self) -> Pose3D:
        """The pose of the parent frame in this one."""
        rotation = self.rotation().T
        return _pose_from(rotation, -(rotation @ np.asarray(self.xyz)))


def _pose_from(rotation: FloatArray, xyz: FloatArray) -> Pose3D:
    """A Pose3D from a rotation matrix Rz(yaw) Ry(pitch) Rx(roll) and a translation."""
    roll = math.atan2(rotation[2, 1], rotation[2, 2])
    pitch = math.atan2(-rotation[2, 0], math.hypot(rotation[0, 0], rotation[1, 0]))
    yaw = math.atan2(rotation[1, 0], rotation[0, 0])
    x, y, z = (float(value) for value in xyz)
    # + 0.0 turns a -0.0 from atan2 into 0.0, which reads better in a printed profile.
    return Pose3D(xyz=(x, y, z), rpy=(roll + 0.0, pitch + 0.0, yaw + 0.0))


def wrap_angle(angles: FloatArray) -> FloatArray:
    """Angles wrapped into [-pi, pi)."""
    wrapped: FloatArray = (angles + math.pi) % (2.0 * math.pi) - math.pi
    return wrapped


@dataclass(frozen=True)
class Box:
    """A box standing on the ground: centre, yaw, side lengths and height."""

    x: float  # m
    y: float  # m
    yaw: float  # rad, of its length axis from the world x axis
    length: float  # m, along its own x axis
    width: float  # m, along its own y axis
    height: float  # m


@dataclass(frozen=True)
class Cylinder:
    """An upright cylinder standing on the ground."""

    x: float  # m
    y: float  # m
    radius: float  # m
    height: float  # m


Obstacle: TypeAlias = Box | Cylinder


def dilated(obstacle: Obstacle, margin: float) -> Obstacle:
    """The obstacle grown by margin on every side (shrunk when margin < 0): a box keeps its
    rectangle shape (half sizes + margin), a cylinder its radius + margin. Raises ValueError if
    the result has no area.

    Only the footprint grows: the height is kept, as the ray casts below are planar.
    """
    if isinstance(obstacle, Box):
        grown_box = replace(
            obstacle, length=obstacle.length + 2.0 * margin, width=obstacle.width + 2.0 * margin
        )
        # `not > 0` also rejects NaN.
        if not (grown_box.length > 0.0 and grown_box.width > 0.0):
            raise ValueError(f"a margin of {margin} m leaves {obstacle} with no area")
        return grown_box
    grown_cylinder = replace(obstacle, radius=obstacle.radius + margin)
    if not grown_cylinder.radius > 0.0:
        raise ValueError(f"a margin of {margin} m leaves {obstacle} with no area")
    return grown_cylinder


def bounding_radius(obstacle: Obstacle) -> float:
    """The radius of the smallest circle around the obstacle's centre that holds its footprint
    (m)."""
    if isinstance(obstacle, Cylinder):
        return obstacle.radius
    return math.hypot(obstacle.length, obstacle.width) / 2.0


def ray_distances(origins: FloatArray, directions: FloatArray, obstacle: Obstacle) -> FloatArray:
    """Distance along each ray to where it first enters the obstacle's footprint.

    origins shape (R, 2) m, directions shape (R, 2) unit vectors -> shape (R,) m; inf where the
    ray misses; 0 where the origin is inside (or on the boundary of) the footprint. Exact: slab
    test in the box's own frame; quadratic for the cylinder. A ray that only grazes the footprint
    (touches an edge or corner, or is tangent to the circle) hits it.
    """
    origins, directions = _checked_rays(origins, directions)
    if isinstance(obstacle, Box):
        return _box_ray_distances(*_in_box_frame(origins, directions, obstacle), obstacle)
    return _cylinder_ray_distances(origins - [obstacle.x, obstacle.y], directions, obstacle)


def segment_clearances(
    origins: FloatArray,
    directions: FloatArray,
    starts: FloatArray,
    ends: FloatArray,
    obstacle: Obstacle,
) -> FloatArray:
    """Signed clearance of each ray segment {o + t d : start <= t <= end} from the footprint.

    origins shape (R, 2) m, directions shape (R, 2) unit vectors, starts and ends shape (R,) m
    with starts <= ends -> shape (R,) m.

    For a cylinder: min over the segment of |p - c| - radius (Euclidean). For a box: min over the
    segment of max(|x'| - length/2, |y'| - width/2), with (x', y') the point in the box's own
    frame. Positive: the segment passes that far clear of the footprint (it misses
    `dilated(obstacle, m)` exactly when m is below the clearance); negative: it passes that deep
    inside (it crosses `dilated(obstacle, -m)` exactly when -m is above the clearance). Exact, in
    closed form.
    """
    origins, directions = _checked_rays(origins, directions)
    starts, ends = _checked_bounds(starts, ends, len(origins))
    if isinstance(obstacle, Box):
        points, vectors = _in_box_frame(origins, directions, obstacle)
        return _box_segment_clearances(points, vectors, starts, ends, obstacle)
    offsets = origins - [obstacle.x, obstacle.y]
    return _cylinder_segment_clearances(offsets, directions, starts, ends, obstacle)


def _checked_rays(origins: FloatArray, directions: FloatArray) -> tuple[FloatArray, FloatArray]:
    """Origins and directions as float arrays, both shape (R, 2), or ValueError."""
    origins = np.asarray(origins, dtype=np.float64)
    directions = np.asarray(directions, dtype=np.float64)
    if origins.ndim != 2 or origins.shape[1] != 2 or directions.shape != origins.shape:
        raise ValueError(
            f"origins and directions must both have shape (R, 2), not {origins.shape} "
            f"and {directions.shape}"
        )
    return origins, directions


def _checked_bounds(starts: FloatArray, ends: FloatArray, count: int) -> tuple[FloatArray, ...]:
    """Segment bounds as float arrays, both shape (count,), or ValueError."""
    starts = np.asarray(starts, dtype=np.float64)
    ends = np.asarray(ends, dtype=np.float64)
    if starts.shape != (count,) or ends.shape != (count,):
        raise ValueError(
            f"starts and ends must both have shape ({count},), not {starts.shape} and {ends.shape}"
        )
    if np.any(starts > ends):
        raise ValueError("every segment must start no later than it ends")
    return starts, ends


def _in_box_frame(
    points: FloatArray, vectors: FloatArray, box: Box
) -> tuple[FloatArray, FloatArray]:
    """World points and vectors, each shape (R, 2), expressed in the box's own frame."""
    cos, sin = math.cos(box.yaw), math.sin(box.yaw)
    # Rows of the world-to-box rotation, the transpose of Rz(yaw); applied to row vectors.
    to_box = np.array([[cos, -sin], [sin, cos]])
    local_points: FloatArray = (points - [box.x, box.y]) @ to_box
    local_vectors: FloatArray = vectors @ to_box
    return local_points, local_vectors


def _slab(positions: FloatArray, steps: FloatArray, half: float) -> tuple[FloatArray, FloatArray]:
    """Ray parameters where each ray, shape (R,) along one axis, enters and leaves |x| <= half.

    Returns two arrays of shape (R,); an empty interval has enter > leave.
    """
    with np.errstate(divide="ignore", invalid="ignore"):
        low = (-half - positions) / steps
        high = (half - positions) / steps
    # A ray parallel to the slab is inside it for ever or never; the divisions above said 0/0.
    parallel = steps == 0.0
    within = np.abs(positions) <= half
    enter = np.where(parallel, np.where(within, -np.inf, np.inf), np.minimum(low, high))
    leave = np.where(parallel, np.where(within, np.inf, -np.inf), np.maximum(low, high))
    return enter, leave


def _box_ray_distances(points: FloatArray, vectors: FloatArray, box: Box) -> FloatArray:
    """Entry distances, shape (R,), of rays given in the box's own frame, each shape (R, 2)."""
    enter_x, leave_x = _slab(points[:, 0], vectors[:, 0], box.length / 2.0)
    enter_y, leave_y = _slab(points[:, 1], vectors[:, 1], box.width / 2.0)
    # Rays start at t = 0, so an origin inside the box enters at once.
    enter = np.maximum(np.maximum(enter_x, enter_y), 0.0)
    leave = np.minimum(leave_x, leave_y)
    distances: FloatArray = np.where(leave >= enter, enter, np.inf)
    return distances


def _cylinder_ray_distances(
    offsets: FloatArray, directions: FloatArray, cylinder: Cylinder
) -> FloatArray:
    """Entry distances, shape (R,), of rays from offsets (R, 2) from the centre along directions.

    Solves |f + t d|^2 = r^2, i.e. a t^2 + 2 b t + c = 0.
    """
    a = np.einsum("ij,ij->i", directions, directions)
    b = np.einsum("ij,ij->i", offsets, directions)
    c = np.einsum("ij,ij->i", offsets, offsets) - cylinder.radius**2
    # b^2 - a c by Lagrange's identity; the cross product loses no digits for distant origins.
    cross = offsets[:, 0] * directions[:, 1] - offsets[:, 1] * directions[:, 0]
    discriminant = a * cylinder.radius**2 - cross**2
    approaching = (b < 0.0) & (discriminant >= 0.0)
    # The near root as c / (-b + sqrt), which stays accurate when the origin is near the circle.
    denominators = -b + np.sqrt(np.maximum(discriminant, 0.0))
    near = np.divide(c, denominators, out=np.full_like(c, np.inf), where=approaching)
    distances: FloatArray = np.where(c <= 0.0, 0.0, near)
    return distances


def _box_segment_clearances(
    points: FloatArray, vectors: FloatArray, starts: FloatArray, ends: FloatArray, box: Box
) -> FloatArray:
    """Least box-metric clearance, shape (R,), of segments given in the box's own frame.

    g(t) = max(|x(t)| - a, |y(t)| - b) is convex and piecewise linear, so its least value on
    [start, end] is at an end or a kink; the candidates, clamped into [start, end], are shape
    (R, 8).
    """
    a, b = box.length / 2.0, box.width / 2.0
    x0, y0 = points[:, :1], points[:, 1:]
    dx, dy = vectors[:, :1], vectors[:, 1:]
    numerators = [-x0, -y0]
    denominators = [dx, dy]
    # Where s1 x(t) - a = s2 y(t) - b, for each pair of signs.
    for s1, s2 in ((1.0, 1.0), (1.0, -1.0), (-1.0, 1.0), (-1.0, -1.0)):
        numerators.append(s2 * y0 - s1 * x0 + a - b)
        denominators.append(s1 * dx - s2 * dy)
    with np.errstate(divide="ignore", invalid="ignore"):
        kinks = np.hstack(numerators) / np.hstack(denominators)
    lower, upper = starts[:, None], ends[:, None]
    candidates = np.hstack([lower, upper, np.where(np.isfinite(kinks), kinks, lower)])
    candidates = np.clip(candidates, lower, upper)
    gaps = np.maximum(np.abs(x0 + candidates * dx) - a, np.abs(y0 + candidates * dy) - b)
    clearances: FloatArray = gaps.min(axis=1)
    return clearances


def _cylinder_segment_clearances(
    offsets: FloatArray,
    directions: FloatArray,
    starts: FloatArray,
    ends: FloatArray,
    cylinder: Cylinder,
) -> FloatArray:
    """Euclidean clearance, shape (R,), of segments from offsets (R, 2) from the centre."""
    a = np.einsum("ij,ij->i", directions, directions)
    b = np.einsum("ij,ij->i", offsets, directions)
    # The foot of the perpendicular from the centre, or any point when the direction is zero.
    feet = np.divide(-b, a, out=np.zeros_like(b), where=a > 0.0)
    nearest = offsets + np.clip(feet, starts, ends)[:, None] * directions
    clearances: FloatArray = np.hypot(nearest[:, 0], nearest[:, 1]) - cylinder.radius
    return clearances


def polygon_clearance(polygon: FloatArray, obstacle: Obstacle) -> float:
    """Signed clearance between a convex polygon (shape (V, 2), counter-clockwise) and an obstacle.

    Positive: the obstacle could grow by that much (a box as a rectangle, a cylinder's radius)
    before touching the polygon; negative: it must shrink by that much to stop overlapping it.
    """
    if isinstance(obstacle, Cylinder):
        return _centre_to_polygon(polygon, np.array([obstacle.x, obstacle.y])) - obstacle.radius
    u = np.array([math.cos(obstacle.yaw), math.sin(obstacle.yaw)])
    v = np.array([-u[1], u[0]])
    axes = np.vstack([_edge_normals(polygon), u, v])
    spread_u, spread_v = np.abs(axes @ u), np.abs(axes @ v)
    reach = spread_u * obstacle.length / 2.0 + spread_v * obstacle.width / 2.0
    centre = axes @ np.array([obstacle.x, obstacle.y])
    projections = polygon @ axes.T
    gaps = np.maximum(
        projections.min(axis=0) - (centre + reach), centre - reach - projections.max(axis=0)
    )
    # Separating axis theorem: the widest gap over all edge normals is how far apart they are.
    return float(np.max(gaps / (spread_u + spread_v)))


def _edge_normals(polygon: FloatArray) -> FloatArray:
    """Outward unit normals of a counter-clockwise polygon's edges, shape (V, 2)."""
    edges = np.roll(polygon, -1, axis=0) - polygon
    normals = np.column_stack([edges[:, 1], -edges[:, 0]])
    unit: FloatArray = normals / np.hypot(normals[:, 0], normals[:, 1])[:, np.newaxis]
    return unit


def _centre_to_polygon(polygon: FloatArray, point: FloatArray) -> float:
    """Signed distance from a point to a convex polygon's boundary: negative inside."""
    edges = np.roll(polygon, -1, axis=0) - polygon
    offsets = np.einsum("ij,ij->i", point - polygon, _edge_normals(polygon))
    if np.all(offsets <= 0):
        return float(np.max(offsets))
    along = np.einsum("ij,ij->i", point - polygon, edges) / np.einsum("ij,ij->i", edges, edges)
    nearest = polygon + np.clip(along, 0.0, 1.0)[:, np.newaxis] * edges
    return float(np.min(np.hypot(*(point - nearest).T)))
