"""The kernels of `obstacles.py`'s exact casts, vectorised over rays: slab tests and quadratics
for where a ray enters a box or a circle, closed-form clearances of ray segments, and convex
polygon distances. Shapes in docstrings; positions in m. `obstacles.py` is their interface:
it checks the arrays and hands each shape's figures in.
"""

from __future__ import annotations

import math

import numpy as np

from pytest_lasertest.model.geometry import FloatArray


def checked_rays(origins: FloatArray, directions: FloatArray) -> tuple[FloatArray, FloatArray]:
    """Origins and directions as float arrays, both shape (R, 2), or ValueError."""
    origins = np.asarray(origins, dtype=np.float64)
    directions = np.asarray(directions, dtype=np.float64)
    if origins.ndim != 2 or origins.shape[1] != 2 or directions.shape != origins.shape:
        raise ValueError(
            f"origins and directions must both have shape (R, 2), not {origins.shape} "
            f"and {directions.shape}"
        )
    return origins, directions


def checked_bounds(starts: FloatArray, ends: FloatArray, count: int) -> tuple[FloatArray, ...]:
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


def in_box_frame(
    points: FloatArray, vectors: FloatArray, centre: tuple[float, float], yaw: float
) -> tuple[FloatArray, FloatArray]:
    """World points and vectors, each shape (R, 2), expressed in the frame of a box centred at
    `centre` (m) turned by `yaw` (rad)."""
    cos, sin = math.cos(yaw), math.sin(yaw)
    # Rows of the world-to-box rotation, the transpose of Rz(yaw); applied to row vectors.
    to_box = np.array([[cos, -sin], [sin, cos]])
    local_points: FloatArray = (points - centre) @ to_box
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


def box_ray_distances(
    points: FloatArray, vectors: FloatArray, half_sides: tuple[float, float]
) -> FloatArray:
    """Entry distances, shape (R,), of rays given in the box's own frame, each shape (R, 2),
    into a box `half_sides` (m) long and wide either side of its centre."""
    enter_x, leave_x = _slab(points[:, 0], vectors[:, 0], half_sides[0])
    enter_y, leave_y = _slab(points[:, 1], vectors[:, 1], half_sides[1])
    # Rays start at t = 0, so an origin inside the box enters at once.
    enter = np.maximum(np.maximum(enter_x, enter_y), 0.0)
    leave = np.minimum(leave_x, leave_y)
    distances: FloatArray = np.where(leave >= enter, enter, np.inf)
    return distances


def cylinder_ray_distances(
    offsets: FloatArray, directions: FloatArray, radius: float
) -> FloatArray:
    """Entry distances, shape (R,), of rays from offsets (R, 2) from the centre along directions.

    Solves |f + t d|^2 = r^2, i.e. a t^2 + 2 b t + c = 0.
    """
    a = np.einsum("ij,ij->i", directions, directions)
    b = np.einsum("ij,ij->i", offsets, directions)
    c = np.einsum("ij,ij->i", offsets, offsets) - radius**2
    # b^2 - a c by Lagrange's identity; the cross product loses no digits for distant origins.
    cross = offsets[:, 0] * directions[:, 1] - offsets[:, 1] * directions[:, 0]
    discriminant = a * radius**2 - cross**2
    approaching = (b < 0.0) & (discriminant >= 0.0)
    # The near root as c / (-b + sqrt), which stays accurate when the origin is near the circle.
    denominators = -b + np.sqrt(np.maximum(discriminant, 0.0))
    near = np.divide(c, denominators, out=np.full_like(c, np.inf), where=approaching)
    distances: FloatArray = np.where(c <= 0.0, 0.0, near)
    return distances


def box_segment_clearances(
    points: FloatArray,
    vectors: FloatArray,
    starts: FloatArray,
    ends: FloatArray,
    half_sides: tuple[float, float],
) -> FloatArray:
    """Least box-metric clearance, shape (R,), of segments given in the box's own frame.

    g(t) = max(|x(t)| - a, |y(t)| - b) is convex and piecewise linear, so its least value on
    [start, end] is at an end or a kink; the candidates, clamped into [start, end], are shape
    (R, 8).
    """
    a, b = half_sides
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


def cylinder_segment_clearances(
    offsets: FloatArray,
    directions: FloatArray,
    starts: FloatArray,
    ends: FloatArray,
    radius: float,
) -> FloatArray:
    """Euclidean clearance, shape (R,), of segments from offsets (R, 2) from the centre."""
    a = np.einsum("ij,ij->i", directions, directions)
    b = np.einsum("ij,ij->i", offsets, directions)
    # The foot of the perpendicular from the centre, or any point when the direction is zero.
    feet = np.divide(-b, a, out=np.zeros_like(b), where=a > 0.0)
    nearest = offsets + np.clip(feet, starts, ends)[:, None] * directions
    clearances: FloatArray = np.hypot(nearest[:, 0], nearest[:, 1]) - radius
    return clearances


def edge_normals(polygon: FloatArray) -> FloatArray:
    """Outward unit normals of a counter-clockwise polygon's edges, shape (V, 2)."""
    edges = np.roll(polygon, -1, axis=0) - polygon
    normals = np.column_stack([edges[:, 1], -edges[:, 0]])
    unit: FloatArray = normals / np.hypot(normals[:, 0], normals[:, 1])[:, np.newaxis]
    return unit


def centre_to_polygon(polygon: FloatArray, point: FloatArray) -> float:
    """Signed distance from a point to a convex polygon's boundary: negative inside."""
    edges = np.roll(polygon, -1, axis=0) - polygon
    offsets = np.einsum("ij,ij->i", point - polygon, edge_normals(polygon))
    if np.all(offsets <= 0):
        return float(np.max(offsets))
    along = np.einsum("ij,ij->i", point - polygon, edges) / np.einsum("ij,ij->i", edges, edges)
    nearest = polygon + np.clip(along, 0.0, 1.0)[:, np.newaxis] * edges
    return float(np.min(np.hypot(*(point - nearest).T)))
