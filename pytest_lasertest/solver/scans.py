"""What one scan sees of the obstacle, as linear constraints: the per-beam slab and gap forms.

`detected`: some beam of the scan passes inside the obstacle, in range (a disjunction over the
beams that can reach the region where the obstacle must lie). `missed`: the obstacle is lower
than the scan plane, or lies wholly outside the field of view, or beyond range along one of a
fan of tangent directions, or inside one gap between neighbouring beams (the gap form: evenly
spaced beams make "between beam j and j+1" two half-planes). Each is sound: a model of it
passes the exact ray cast, with the margin M.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from pytest_lasertest.geometry import FloatArray
from pytest_lasertest.sensor import FULL_TURN, LaserProfile
from pytest_lasertest.solver.encoding import ObstacleShape, all_of, any_of, linear, number

# Beyond range is "outside a circle", which is not linear; tangent half-planes stand in for it,
# spaced so that none of them gives away more than this much of the range.
RANGE_SLACK = 0.001  # m
SAMPLE_STEP = 0.02  # m, along beams when ranking them

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
) -> str:
    """Some beam of the scan at robot pose [x, y, yaw] reads the obstacle with margin M.

    `beams` (indices) limits the disjunction to those beams; by default every beam that can
    reach the region takes part.
    """
    origins, directions = profile.rays(pose[np.newaxis, :])
    origins, directions = origins[0], directions[0]
    if beams is None:
        beams = np.flatnonzero(
            _reaches_region(origins, directions, profile.range_min, profile.range_max, region)
        )
    options = []
    for origin, direction in zip(origins[beams], directions[beams], strict=True):
        parts = [shape.crossed_by(origin, direction, profile.range_min, profile.range_max)]
        if profile.range_min > 0:
            parts.append(shape.at_least(direction, float(origin @ direction) + profile.range_min))
        options.append(all_of(parts))
    above = f"(>= {linear(H=1.0, M=-1.0)} {number(profile.scan_height)})"
    return all_of([above, any_of(options)])


def promising_beams(
    detector: LaserProfile,
    misser: LaserProfile,
    poses: FloatArray,
    region: Region,
    min_size: float,
    limit: int,
) -> IndexArray:
    """The detector's beams likeliest to see what the misser cannot, best first, shape (<= limit,).

    Poses [x, y, yaw], shape (2, 3): the detector's at the anchor, the misser's last before it.
    A heuristic that only orders the search: points every SAMPLE_STEP along each beam inside the
    region count when the misser's nearest beam would pass more than min_size / 2 from them, or
    they lie outside its field of view or range.
    """
    origins, directions = detector.rays(poses[:1])
    origin, steps = origins[0, 0], np.arange(detector.range_min, detector.range_max, SAMPLE_STEP)
    points = origin + steps[np.newaxis, :, np.newaxis] * directions[0][:, np.newaxis, :]
    low, high = np.array(region.low), np.array(region.high)
    inside = np.all((points >= low) & (points <= high), axis=-1)
    hidden = inside & ~_covers(misser, poses[1], points, min_size)
    if detector.scan_height < misser.scan_height:
        hidden = inside
    score = hidden.sum(axis=1)
    order = np.lexsort((np.arange(len(score)), -score))
    best: IndexArray = order[score[order] > 0][:limit]
    return best


def _covers(
    profile: LaserProfile, pose: FloatArray, points: FloatArray, min_size: float
) -> BoolArray:
    """Whether the scan at `pose` surely crosses a min_size obstacle at each point (..., 2)."""
    origins, _ = profile.rays(pose[np.newaxis, :])
    offset = points - origins[0, 0]
    distance = np.hypot(offset[..., 0], offset[..., 1])
    start, extent = profile.sector_in_base()
    bearing = (np.arctan2(offset[..., 1], offset[..., 0]) - pose[2] - start) % FULL_TURN
    spacing = profile.angle_increment
    nearest = np.clip(np.round(bearing / spacing), 0, profile.beam_count - 1) if spacing else 0.0
    lateral = distance * np.abs(np.sin(bearing - nearest * spacing))
    in_view = (
        (bearing <= extent) & (distance >= profile.range_min) & (distance <= profile.range_max)
    )
    result: BoolArray = in_view & (lateral < min_size / 2.0)
    return result


def missed(
    shape: ObstacleShape, profile: LaserProfile, pose: FloatArray, region: Region, min_size: float
) -> str:
    """Every beam of the scan at robot pose [x, y, yaw] passes clear of the obstacle by M."""
    origins, _ = profile.rays(pose[np.newaxis, :])
    origin = origins[0, 0]
    start, extent = profile.sector_in_base()
    start += float(pose[2])
    below = f"(<= {linear(H=1.0, M=1.0)} {number(profile.scan_height)})"
    return any_of(
        [
            below,
            *_outside(shape, origin, start, extent),
            *_beyond(shape, origin, start, extent, profile.range_max, region),
            *_gaps(shape, origin, profile, start, region, min_size),
        ]
    )


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
) -> list[str]:
    count, spacing = profile.beam_count, profile.angle_increment
    if count < 2:
        return []
    furthest = float(np.hypot(*(region.corners() - origin).T).max())
    # Nothing min_size wide fits between two beams nearer than where their gap is that wide.
    if 2.0 * furthest * math.sin(spacing / 2.0) < min_size:
        return []
    options = []
    for index in range(count - 1):
        low, high = start + index * spacing, start + (index + 1) * spacing
        left_of_low = shape.at_least(_normal(low), float(origin @ _normal(low)))
        right_of_high = shape.at_most(_normal(high), float(origin @ _normal(high)))
        options.append(all_of([left_of_low, right_of_high]))
    return options


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
