"""Obstacles standing on the ground, boxes and upright cylinders, and exact planar casts
against their footprints: where a ray enters one, how far a segment or a convex polygon stays
clear of one. Positions in the world frame (REP 103), m; angles counter-clockwise, rad.

Each shape answers for itself (its sides, corners, description, how it moves and grows), so that
the code that places, perturbs, draws or reports an obstacle need not ask which shape it is.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import ClassVar, TypeAlias

import numpy as np
import numpy.typing as npt

from pytest_lasertest.model.geometry import FloatArray


@dataclass(frozen=True)
class Box:
    """A box standing on the ground: centre, yaw, side lengths and height."""

    has_yaw: ClassVar[bool] = True  # turning it changes what it covers

    x: float  # m
    y: float  # m
    yaw: float  # rad, of its length axis from the world x axis
    length: float  # m, along its own x axis
    width: float  # m, along its own y axis
    height: float  # m

    @property
    def sides(self) -> tuple[float, float]:
        """Its shorter and its longer side (m)."""
        return min(self.length, self.width), max(self.length, self.width)

    @property
    def bounding_radius(self) -> float:
        """The radius of the smallest circle around its centre that holds its footprint (m)."""
        return math.hypot(self.length, self.width) / 2.0

    def corners(self) -> tuple[tuple[float, float], ...]:
        """The footprint's four corners, m, counter-clockwise from the front right one."""
        cos, sin = math.cos(self.yaw), math.sin(self.yaw)
        half_length, half_width = self.length / 2.0, self.width / 2.0
        return tuple(
            (self.x + cos * u - sin * v, self.y + sin * u + cos * v)
            for u, v in (
                (half_length, -half_width),
                (half_length, half_width),
                (-half_length, half_width),
                (-half_length, -half_width),
            )
        )

    def describe(self) -> str:
        """`box 0.051 x 0.051 m, yaw 0.000 rad, at (4.524, -0.312) m, 0.327 m high`."""
        sides = f"{self.length:.3f} x {self.width:.3f} m"
        return f"box {sides}, yaw {self.yaw:.3f} rad, {_where(self)}"

    def perturbed(self, x: float, y: float, yaw: float, size: float, height: float) -> Box:
        """Moved by (x, y) m, turned by yaw rad, each side widened by size m, raised by height m."""
        return replace(
            self,
            x=self.x + x,
            y=self.y + y,
            yaw=self.yaw + yaw,
            length=self.length + size,
            width=self.width + size,
            height=self.height + height,
        )

    def grown(self, margin: float) -> Box:
        """Grown by margin on every side (shrunk when margin < 0), still a rectangle (half sides
        + margin); the height is kept, as the casts here are planar. ValueError if no area is
        left."""
        grown = replace(self, length=self.length + 2.0 * margin, width=self.width + 2.0 * margin)
        # `not > 0` also rejects NaN.
        if not (grown.length > 0.0 and grown.width > 0.0):
            raise ValueError(f"a margin of {margin} m leaves {self} with no area")
        return grown

    def within(self, clearance: float) -> float:
        """How near a line must pass its centre to come within `clearance` of it, in the box's
        own clearance metric, max(|x'| - a, |y'| - b) (m): that metric is at least the Euclidean
        distance to its corners' circle divided by sqrt(2)."""
        return self.bounding_radius + math.sqrt(2.0) * clearance

    def nearest_point(self, x: float, y: float) -> tuple[float, float]:
        """The point of its footprint nearest (x, y), m."""
        dx, dy = x - self.x, y - self.y
        cos, sin = np.cos(self.yaw), np.sin(self.yaw)
        along = np.clip(cos * dx + sin * dy, -self.length / 2, self.length / 2)
        across = np.clip(-sin * dx + cos * dy, -self.width / 2, self.width / 2)
        return float(self.x + cos * along - sin * across), float(
            self.y + sin * along + cos * across
        )

    def _ray_distances(self, origins: FloatArray, directions: FloatArray) -> FloatArray:
        return _box_ray_distances(*_in_box_frame(origins, directions, self), self)

    def _segment_clearances(
        self, origins: FloatArray, directions: FloatArray, starts: FloatArray, ends: FloatArray
    ) -> FloatArray:
        points, vectors = _in_box_frame(origins, directions, self)
        return _box_segment_clearances(points, vectors, starts, ends, self)

    def _polygon_clearance(self, polygon: FloatArray) -> float:
        u = np.array([math.cos(self.yaw), math.sin(self.yaw)])
        v = np.array([-u[1], u[0]])
        axes = np.vstack([_edge_normals(polygon), u, v])
        spread_u, spread_v = np.abs(axes @ u), np.abs(axes @ v)
        reach = spread_u * self.length / 2.0 + spread_v * self.width / 2.0
        centre = axes @ np.array([self.x, self.y])
        projections = polygon @ axes.T
        gaps = np.maximum(
            projections.min(axis=0) - (centre + reach), centre - reach - projections.max(axis=0)
        )
        # Separating axis theorem: the widest gap over all edge normals is how far apart they are.
        return float(np.max(gaps / (spread_u + spread_v)))


@dataclass(frozen=True)
class Cylinder:
    """An upright cylinder standing on the ground."""

    has_yaw: ClassVar[bool] = False  # it looks the same at every yaw

    x: float  # m
    y: float  # m
    radius: float  # m
    height: float  # m

    @property
    def yaw(self) -> float:
        """0 rad: a cylinder is round."""
        return 0.0

    @property
    def sides(self) -> tuple[float, float]:
        """Its diameter, twice (m): its footprint is as wide every way."""
        return 2.0 * self.radius, 2.0 * self.radius

    @property
    def bounding_radius(self) -> float:
        """Its radius (m)."""
        return self.radius

    def describe(self) -> str:
        """`cylinder of radius 0.025 m at (4.524, -0.312) m, 0.327 m high`."""
        return f"cylinder of radius {self.radius:.3f} m {_where(self)}"

    def perturbed(self, x: float, y: float, yaw: float, size: float, height: float) -> Cylinder:
        """Moved by (x, y) m, its diameter widened by size m and raised by height m; yaw turns
        nothing."""
        del yaw  # a cylinder looks the same at every yaw
        return replace(
            self,
            x=self.x + x,
            y=self.y + y,
            radius=self.radius + size / 2.0,
            height=self.height + height,
        )

    def grown(self, margin: float) -> Cylinder:
        """Its radius grown by margin (shrunk when margin < 0); ValueError if no area is left."""
        grown = replace(self, radius=self.radius + margin)
        if not grown.radius > 0.0:
            raise ValueError(f"a margin of {margin} m leaves {self} with no area")
        return grown

    def within(self, clearance: float) -> float:
        """How near a line must pass its centre to come within `clearance` of it (m)."""
        return self.radius + clearance

    def nearest_point(self, x: float, y: float) -> tuple[float, float]:
        """The point of its footprint nearest (x, y), m."""
        dx, dy = x - self.x, y - self.y
        distance = max(float(np.hypot(dx, dy)), 1e-12)
        scale = min(1.0, self.radius / distance)
        return self.x + dx * scale, self.y + dy * scale

    def _ray_distances(self, origins: FloatArray, directions: FloatArray) -> FloatArray:
        return _cylinder_ray_distances(origins - [self.x, self.y], directions, self)

    def _segment_clearances(
        self, origins: FloatArray, directions: FloatArray, starts: FloatArray, ends: FloatArray
    ) -> FloatArray:
        offsets = origins - [self.x, self.y]
        return _cylinder_segment_clearances(offsets, directions, starts, ends, self)

    def _polygon_clearance(self, polygon: FloatArray) -> float:
        return _centre_to_polygon(polygon, np.array([self.x, self.y])) - self.radius


Obstacle: TypeAlias = Box | Cylinder


def _where(obstacle: Obstacle) -> str:
    return f"at ({obstacle.x:.3f}, {obstacle.y:.3f}) m, {obstacle.height:.3f} m high"


def ray_distances(origins: FloatArray, directions: FloatArray, obstacle: Obstacle) -> FloatArray:
    """Distance along each ray to where it first enters the obstacle's footprint.

    origins shape (R, 2) m, directions shape (R, 2) unit vectors -> shape (R,) m; inf where the
    ray misses; 0 where the origin is inside (or on the boundary of) the footprint. Exact: slab
    test in the box's own frame; quadratic for the cylinder. A ray that only grazes the footprint
    (touches an edge or corner, or is tangent to the circle) hits it.
    """
    return obstacle._ray_distances(*_checked_rays(origins, directions))


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
    `obstacle.grown(m)` exactly when m is below the clearance); negative: it passes that deep
    inside (it crosses `obstacle.grown(-m)` exactly when -m is above the clearance). Exact, in
    closed form.
    """
    origins, directions = _checked_rays(origins, directions)
    starts, ends = _checked_bounds(starts, ends, len(origins))
    return obstacle._segment_clearances(origins, directions, starts, ends)


def polygon_clearance(polygon: FloatArray, obstacle: Obstacle) -> float:
    """Signed clearance between a convex polygon (shape (V, 2), counter-clockwise) and an obstacle.

    Positive: the obstacle could grow by that much (a box as a rectangle, a cylinder's radius)
    before touching the polygon; negative: it must shrink by that much to stop overlapping it.
    """
    return obstacle._polygon_clearance(polygon)


def box_holds(box: Box, points: FloatArray) -> npt.NDArray[np.bool_]:
    """Which points, shape (P, 2) m, lie in the box's footprint (its edges included), (P,)."""
    cos, sin = math.cos(box.yaw), math.sin(box.yaw)
    offsets = np.asarray(points, dtype=np.float64) - (box.x, box.y)
    along, across = offsets @ (cos, sin), offsets @ (-sin, cos)
    held: npt.NDArray[np.bool_] = (np.abs(along) <= box.length / 2.0) & (
        np.abs(across) <= box.width / 2.0
    )
    return held


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
    # A segment (nearly) parallel to a side or a diagonal has no kink there, or one so far
    # off that the division overflows: either is not finite, and its candidate is the start.
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
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
