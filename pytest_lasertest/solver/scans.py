"""What one scan sees of the obstacle, as linear constraints: the per-beam slab and gap forms.

These are the whole disjunctions, which proofs need; searches split them by a seed point
(`seeds.py`). `detected`: some beam of the scan passes inside the obstacle, in range (a
disjunction over the beams that can reach the region where the obstacle must lie). `miss_ways`:
the obstacle is lower than the scan plane, or lies wholly outside the field of view, or beyond
range along one of a fan of tangent directions, or inside the minimum-range circle, or inside one
gap between neighbouring beams (the gap form: evenly spaced beams make "between beam j and j+1"
two half-planes). Each is sound: a model of it passes the exact ray cast, with the margin M.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from pytest_lasertest.model.geometry import FULL_TURN, FloatArray
from pytest_lasertest.model.sensor import LaserProfile
from pytest_lasertest.model.verify import REQUIRED_MARGIN
from pytest_lasertest.model.walls import NO_WALLS, Walls
from pytest_lasertest.solver.encoding import ObstacleShape, all_of, any_of, linear, number

# Beyond range is "outside a circle", which is not linear; tangent half-planes stand in for it,
# spaced so that none of them gives away more than this much of the range.
RANGE_SLACK = 0.001  # m
NEAR_SIDES = 16  # sides of the polygons standing in for range circles

BoolArray = npt.NDArray[np.bool_]
IndexArray = npt.NDArray[np.intp]


@dataclass(frozen=True)
class Region:
    """An axis-aligned box that holds every obstacle the query can place (m)."""

    low: tuple[float, float]
    high: tuple[float, float]

    def corners(self) -> FloatArray:
        """Shape (4, 2)."""
        (x0, y0), (x1, y1) = self.low, self.high
        return np.array([[x0, y0], [x1, y0], [x1, y1], [x0, y1]])


def detected(
    shape: ObstacleShape,
    profile: LaserProfile,
    pose: FloatArray,
    region: Region,
    beams: IndexArray | None = None,
    walls: Walls = NO_WALLS,
) -> str:
    """Some beam of the scan at robot pose [x, y, yaw] reads the obstacle with margin M, before
    it meets a wall (REQUIRED_MARGIN short of it, as the verifier has it).

    `beams` (indices) limits the disjunction to those beams; by default every beam that can
    reach the region takes part.
    """
    if beams is None:
        beams = reaching_beams(profile, pose, region)
    origins, directions = profile.rays(pose[np.newaxis, :])
    origins, directions = origins[0][beams], directions[0][beams]
    ends = np.full(len(beams), profile.range_max)
    if walls:
        ends = np.minimum(ends, walls.reach(origins, directions) - REQUIRED_MARGIN)
    options = []
    for origin, direction, end in zip(origins, directions, ends.tolist(), strict=True):
        if end <= profile.range_min:
            continue  # a wall nearer than range_min: this beam reads nothing behind it
        parts = [shape.crossed_by(origin, direction, profile.range_min, end)]
        if profile.range_min > 0:
            parts.append(shape.at_least(direction, float(origin @ direction) + profile.range_min))
        options.append(all_of(parts))
    above = f"(>= {linear(H=1.0, M=-1.0)} {number(profile.scan_height)})"
    return all_of([above, any_of(options)])


@dataclass(frozen=True)
class Reading:
    """Where a detector reads an obstacle: a part of it within `radius` m of `centre` [x, y]
    (m), its origin and its range_max, and all of it beyond `inner` m (its range_min)."""

    centre: tuple[float, float]
    radius: float  # m
    inner: float = 0.0  # m


def reaching_beams(profile: LaserProfile, pose: FloatArray, region: Region) -> IndexArray:
    """The beams of the scan at robot pose [x, y, yaw] that can read an obstacle in `region`,
    by index: those `detected` asks about by default."""
    origins, directions = profile.rays(pose[np.newaxis, :])
    inside = _reaches_region(
        origins[0], directions[0], profile.range_min, profile.range_max, region
    )
    beams: IndexArray = np.flatnonzero(inside)
    return beams


def miss_ways(
    shape: ObstacleShape,
    profile: LaserProfile,
    pose: FloatArray,
    region: Region,
    min_size: float,
    read_within: Reading | None = None,
) -> dict[str, list[str]]:
    """The ways every beam of the scan at robot pose [x, y, yaw] passes clear of the obstacle by
    M, each a list of alternatives; a way that cannot happen in the region (or, if given, with a
    part of the obstacle in `read_within`) has none."""
    origins, _ = profile.rays(pose[np.newaxis, :])
    origin = origins[0, 0]
    start, extent = profile.sector_in_base()
    start += float(pose[2])
    ways = {
        "below": [f"(<= {linear(H=1.0, M=1.0)} {number(profile.scan_height)})"],
        "outside": _outside(shape, origin, start, extent),
        "beyond": _beyond(shape, origin, start, extent, profile.range_max, region),
        "near": _near(shape, origin, profile.range_min),
        "between": _gaps(shape, origin, profile, start, region, min_size, read_within),
    }
    if read_within is not None:
        apart = math.dist(origin, read_within.centre)  # m between the two scanners
        # Both ways grow the obstacle by M and the reading needs it M deep, so even where the
        # two bounds meet no obstacle is both.
        # Wholly beyond range_max from this scanner, yet a part within the reader's range.
        if apart + read_within.radius <= profile.range_max:
            ways["beyond"] = []
        # Wholly within range_min of this scanner, yet wholly beyond the reader's range_min.
        if apart + profile.range_min <= read_within.inner:
            ways["near"] = []
    return ways


def reaches(shape: ObstacleShape, profile: LaserProfile, pose: FloatArray) -> str:
    """A point (QX, QY) of the obstacle shrunk by M lies in the scan's sector, within its range,
    and the obstacle stands above the scan plane.

    Every reading implies this, so a proof may use it in place of the disjunction over beams: a
    relaxation, convex but for sectors wider than half a turn, whose edges it leaves out.
    """
    origins, _ = profile.rays(pose[np.newaxis, :])
    origin = origins[0, 0]
    parts = [f"(>= {linear(H=1.0, M=-1.0)} {number(profile.scan_height)})"]
    for axis in shape.axes() or list(_fan(4, math.pi)):
        parts += [
            f"(<= {linear(QX=axis[0], QY=axis[1], X=-axis[0], Y=-axis[1], S=-0.5, M=1.0)} 0.0)",
            f"(>= {linear(QX=axis[0], QY=axis[1], X=-axis[0], Y=-axis[1], S=0.5, M=-1.0)} 0.0)",
        ]
    for axis in _fan(NEAR_SIDES, FULL_TURN):
        reach = float(origin @ axis) + profile.range_max
        parts.append(f"(<= {linear(QX=axis[0], QY=axis[1])} {number(reach)})")
    start, extent = profile.sector_in_base()
    if extent < math.pi:
        first, last = _normal(start + float(pose[2])), _normal(start + extent + float(pose[2]))
        parts.append(f"(>= {linear(QX=first[0], QY=first[1])} {number(float(origin @ first))})")
        parts.append(f"(<= {linear(QX=last[0], QY=last[1])} {number(float(origin @ last))})")
    return all_of(parts)


def _fan(count: int, turn: float) -> list[FloatArray]:
    angles = np.arange(count) * turn / count
    return [np.array([math.cos(angle), math.sin(angle)]) for angle in angles]


def _near(shape: ObstacleShape, origin: FloatArray, range_min: float) -> list[str]:
    """Inside the polygon inscribed in the minimum-range circle: every beam meets it too near."""
    if range_min <= 0:
        return []
    apothem = range_min * math.cos(math.pi / NEAR_SIDES)
    return [
        all_of(
            [
                shape.at_most(axis, float(origin @ axis) + apothem)
                for axis in _fan(NEAR_SIDES, FULL_TURN)
            ]
        )
    ]


def _outside(shape: ObstacleShape, origin: FloatArray, start: float, extent: float) -> list[str]:
    if extent >= FULL_TURN:
        return []
    first, last = _normal(start), _normal(start + extent)
    right_of_first = shape.at_most(first, float(origin @ first))
    left_of_last = shape.at_least(last, float(origin @ last))
    if extent < math.pi:
        return [right_of_first, left_of_last]
    return [all_of([right_of_first, left_of_last])]


def _beyond(
    shape: ObstacleShape,
    origin: FloatArray,
    start: float,
    extent: float,
    reach: float,
    region: Region,
) -> list[str]:
    step = 2.0 * math.acos(reach / (reach + RANGE_SLACK))
    count = max(2, math.ceil(min(extent, FULL_TURN) / step) + 1)
    angles = np.linspace(start, start + min(extent, FULL_TURN), count)
    axes = np.column_stack([np.cos(angles), np.sin(angles)])
    furthest = ((region.corners() - origin) @ axes.T).max(axis=0)
    return [
        shape.at_least(axis, float(origin @ axis) + reach)
        for axis, far in zip(axes, furthest, strict=True)
        if far >= reach
    ]


def _gaps(
    shape: ObstacleShape,
    origin: FloatArray,
    profile: LaserProfile,
    start: float,
    region: Region,
    min_size: float,
    read_within: Reading | None,
) -> list[str]:
    """One option per gap between neighbouring beams that can hold an obstacle min_size wide
    where the region (and `read_within`) lets it be (`_reachable_gaps`)."""
    spacing = profile.angle_increment
    options = []
    for low in _reachable_gaps(origin, profile, start, region, min_size, read_within).tolist():
        high = low + spacing
        left_of_low = shape.at_least(_normal(low), float(origin @ _normal(low)))
        right_of_high = shape.at_most(_normal(high), float(origin @ _normal(high)))
        options.append(all_of([left_of_low, right_of_high]))
    return options


def gap_regions(
    profile: LaserProfile,
    pose: FloatArray,
    region: Region,
    min_size: float,
    read_within: Reading | None = None,
) -> list[Region]:
    """For each option of miss_ways' "between", in order, a box holding every obstacle that
    option admits: the part of its gap's wedge beyond where min_size fits, within `region`."""
    origins, _ = profile.rays(pose[np.newaxis, :])
    origin = origins[0, 0]
    start = profile.sector_in_base()[0] + float(pose[2])
    lows = _reachable_gaps(origin, profile, start, region, min_size, read_within)
    nearest = max(_nearest_in_gap(profile.angle_increment, min_size), 0.0)
    furthest = float(np.hypot(*(region.corners() - origin).T).max())
    return [
        _sector_box(origin, low, low + profile.angle_increment, nearest, furthest, region)
        for low in lows.tolist()
    ]


def near_region(profile: LaserProfile, pose: FloatArray, region: Region) -> Region:
    """A box holding every obstacle miss_ways' "near" admits: within range_min of the scanner
    at robot pose [x, y, yaw], within `region`."""
    origins, _ = profile.rays(pose[np.newaxis, :])
    origin = origins[0, 0]
    low = np.maximum(origin - profile.range_min, region.low)
    high = np.minimum(origin + profile.range_min, region.high)
    return Region((float(low[0]), float(low[1])), (float(high[0]), float(high[1])))


def _reachable_gaps(
    origin: FloatArray,
    profile: LaserProfile,
    start: float,
    region: Region,
    min_size: float,
    read_within: Reading | None,
) -> FloatArray:
    """The angles (rad) at which the gaps begin that can hold an obstacle min_size wide in the
    region, and with a part of it in `read_within` if given. Shape (G,).

    The gaps an obstacle cannot reach are left out: a proof with hundreds of options ran out of
    its rlimit where none could hold anything.
    """
    count, spacing = profile.beam_count, profile.angle_increment
    if count < 2:
        return np.zeros(0)
    furthest = float(np.hypot(*(region.corners() - origin).T).max())
    # Nothing min_size wide fits between two beams nearer than where their gap is that wide.
    if 2.0 * furthest * math.sin(spacing / 2.0) < min_size:
        return np.zeros(0)
    lows = start + np.arange(count - 1) * spacing  # (G,) rad
    middles = lows + spacing / 2.0
    bisectors = np.column_stack([np.cos(middles), np.sin(middles)])  # (G, 2)
    reach = ((region.corners() - origin) @ bisectors.T).max(axis=0)  # (G,) m
    if read_within is not None:
        centre = np.array(read_within.centre) - origin
        reach = np.minimum(reach, bisectors @ centre + read_within.radius)
    kept: FloatArray = lows[reach >= _nearest_in_gap(spacing, min_size)]
    return kept


def _nearest_in_gap(spacing: float, min_size: float) -> float:
    """How far out along the bisector of two rays `spacing` rad apart the nearest point of an
    obstacle at least min_size wide (a square of any yaw, or a disc) between them lies, at
    least (m): its width across the bisector, at least min_size, must fit within the wedge at
    the far end of its extent along it, at most sqrt(2) min_size further out."""
    return min_size / (2.0 * math.tan(spacing / 2.0)) - math.sqrt(2.0) * min_size


def _sector_box(
    origin: FloatArray, low: float, high: float, near: float, far: float, region: Region
) -> Region:
    """The box around the part of the wedge from `low` to `high` (rad) between `near` and
    `far` m from `origin`, cut to `region`."""
    angles = [low, high] + [k * math.pi / 2.0 for k in range(-8, 9) if low < k * math.pi / 2 < high]
    rays = np.array([[math.cos(a), math.sin(a)] for a in angles])  # (A, 2)
    points = np.vstack([origin + near * rays, origin + far * rays])
    low_corner = np.maximum(points.min(axis=0), region.low)
    high_corner = np.minimum(points.max(axis=0), region.high)
    return Region(
        (float(low_corner[0]), float(low_corner[1])), (float(high_corner[0]), float(high_corner[1]))
    )


def _normal(angle: float) -> FloatArray:
    """The unit normal to the left of a ray at `angle`."""
    return np.array([-math.sin(angle), math.cos(angle)])


def _reaches_region(
    origins: FloatArray, directions: FloatArray, start: float, end: float, region: Region
) -> BoolArray:
    """Which beam segments, shapes (N, 2), cross the region's box: slab test, shape (N,) bool."""
    low, high = np.array(region.low), np.array(region.high)
    with np.errstate(divide="ignore", invalid="ignore"):
        near = (low - origins) / directions
        far = (high - origins) / directions
    entry = np.nanmax(np.where(np.isnan(near), -np.inf, np.minimum(near, far)), axis=1)
    leave = np.nanmin(np.where(np.isnan(far), np.inf, np.maximum(near, far)), axis=1)
    inside_slab = (directions != 0) | ((origins >= low) & (origins <= high))
    ok = inside_slab.all(axis=1)
    result: BoolArray = ok & (np.maximum(entry, start) <= np.minimum(leave, end))
    return result
