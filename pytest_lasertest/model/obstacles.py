"""Obstacles standing on the ground, boxes and upright cylinders, and exact planar casts
against their footprints: where a ray enters one, how far a segment or a convex polygon stays
clear of one. Positions in the world frame (REP 103), m; angles counter-clockwise, rad.

Each shape answers for itself (its sides, corners, description, how it moves and grows), so that
the code that places, perturbs, draws or reports an obstacle need not ask which shape it is.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields, replace
from typing import ClassVar, TypeAlias

import numpy as np
import numpy.typing as npt

from pytest_lasertest.model.cast_kernels import (
    box_ray_distances,
    box_segment_clearances,
    centre_to_polygon,
    checked_bounds,
    checked_rays,
    cylinder_ray_distances,
    cylinder_segment_clearances,
    edge_normals,
    in_box_frame,
)
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
        points, vectors = in_box_frame(origins, directions, (self.x, self.y), self.yaw)
        return box_ray_distances(points, vectors, (self.length / 2.0, self.width / 2.0))

    def _segment_clearances(
        self, origins: FloatArray, directions: FloatArray, starts: FloatArray, ends: FloatArray
    ) -> FloatArray:
        points, vectors = in_box_frame(origins, directions, (self.x, self.y), self.yaw)
        half_sides = (self.length / 2.0, self.width / 2.0)
        return box_segment_clearances(points, vectors, starts, ends, half_sides)

    def _polygon_clearance(self, polygon: FloatArray) -> float:
        u = np.array([math.cos(self.yaw), math.sin(self.yaw)])
        v = np.array([-u[1], u[0]])
        axes = np.vstack([edge_normals(polygon), u, v])
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
        return cylinder_ray_distances(origins - [self.x, self.y], directions, self.radius)

    def _segment_clearances(
        self, origins: FloatArray, directions: FloatArray, starts: FloatArray, ends: FloatArray
    ) -> FloatArray:
        offsets = origins - [self.x, self.y]
        return cylinder_segment_clearances(offsets, directions, starts, ends, self.radius)

    def _polygon_clearance(self, polygon: FloatArray) -> float:
        return centre_to_polygon(polygon, np.array([self.x, self.y])) - self.radius


Obstacle: TypeAlias = Box | Cylinder

# The decimals of every number of an obstacle as a drive places it and a pinned replay writes it
# (m, rad): a micrometre, so that the replay file reads 3.6, not 3.5999999999999996, and drives
# the very obstacle the failure drove. Not 4 (0.1 mm), though a placement's ray-cast margins are
# at least 5 mm: no margin bounds how far an obstacle may move before a drive changes (a beam
# grazing its edge, a costmap cell's boundary). A micrometre is far below what PyBullet's ray
# tests resolve (about 1 mm, DESIGN.md section 10).
PLACED_DECIMALS = 6
_SIZES = frozenset({"length", "width", "radius", "height"})


def placed(obstacle: Obstacle) -> Obstacle:
    """`obstacle` as drives place it: each number rounded to PLACED_DECIMALS (-0.0 as 0.0), but
    a size that would round to zero, which would be no obstacle, kept in full."""
    values: dict[str, float] = {}
    for field in fields(obstacle):
        # float(): solver output may hold numpy floats.
        value = float(getattr(obstacle, field.name))
        rounded = round(value, PLACED_DECIMALS) + 0.0
        values[field.name] = value if field.name in _SIZES and rounded <= 0.0 else rounded
    return type(obstacle)(**values)


def _where(obstacle: Obstacle) -> str:
    return f"at ({obstacle.x:.3f}, {obstacle.y:.3f}) m, {obstacle.height:.3f} m high"


def ray_distances(origins: FloatArray, directions: FloatArray, obstacle: Obstacle) -> FloatArray:
    """Distance along each ray to where it first enters the obstacle's footprint.

    origins shape (R, 2) m, directions shape (R, 2) unit vectors -> shape (R,) m; inf where the
    ray misses; 0 where the origin is inside (or on the boundary of) the footprint. Exact: slab
    test in the box's own frame; quadratic for the cylinder. A ray that only grazes the footprint
    (touches an edge or corner, or is tangent to the circle) hits it.
    """
    return obstacle._ray_distances(*checked_rays(origins, directions))


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
    origins, directions = checked_rays(origins, directions)
    starts, ends = checked_bounds(starts, ends, len(origins))
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
