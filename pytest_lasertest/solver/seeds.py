"""Seeds: the points witnesses are built around, and the case split each one chooses.

"Some beam of the detector reads the obstacle, and every beam of every misser scan misses it" is a
disjunction over beams and gaps, scan by scan: far too large to hand Z3 whole (DESIGN.md section
10). A point p on a detector beam picks one disjunct of each. The beam through p reads any
obstacle that holds p; each misser scan misses the obstacle the way it misses p: p lies outside
its field of view, beyond its range, nearer than its minimum range, or between two of its beams.
Each way is a few half-planes the obstacle must keep to, so what is left for Z3 is a conjunction:
a linear program it solves in milliseconds.

Points are ranked by their lead (how far the robot drives, after the anchor, while the misser
still leaves room around the point) and then by that room.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from pytest_lasertest.geometry import FloatArray
from pytest_lasertest.path import contact_times, scan_times, swept_polygons
from pytest_lasertest.placement import Direction, Scene
from pytest_lasertest.sensor import FULL_TURN, LaserProfile
from pytest_lasertest.solver.encoding import HalfPlane
from pytest_lasertest.solver.scans import NEAR_SIDES

SEED_STEP = 0.05  # m between seed points along a beam
RANKING_SCANS = 48  # misser scans a first ranking looks at, evenly spread
FINALISTS = 8  # points whose every misser scan is checked before the final order
DEPTH = 0.02  # m, how deep inside the robot's later way a seed lies
LEAD_STEP = 0.25  # m, leads closer than this count as equal when ranking
SPREAD = 0.25  # m between finalists, so that witnesses kept apart still find seeds
ROOM_CAP = 0.1  # m, room beyond this buys nothing more
# How far the misser's scan plane must stand above the detector's for an obstacle to fit between.
LOW_WINDOW = 0.02  # m

GAP, OUTSIDE, BEYOND, NEAR = range(4)
IntArray = npt.NDArray[np.intp]


@dataclass(frozen=True)
class Seed:
    """A point on a detector beam at the anchor, and how long the misser leaves room around it."""

    point: tuple[float, float]  # m
    until: float  # s, every misser scan up to here leaves `room` around the point
    lead: float  # m of path between the anchor and `until`
    room: float  # m
    tight: tuple[float, ...]  # s, the misser scans that leave the least room


def seeds(scene: Scene, direction: Direction, anchor: float, needed: float) -> list[Seed]:
    """Points with at least `needed` m of room before every misser scan up to the anchor, best
    first: the longest lead, then the most room."""
    points = _candidates(scene, direction, anchor, needed)
    misser = scene.misser(direction)
    # Most points fail at once: the misser's scans at the start and just before the anchor.
    first_and_last = np.array([0.0, scan_times(misser.update_rate, anchor)[-1]])
    points = points[rooms_at(scene, direction, first_and_last, points)[0].min(axis=0) >= needed]
    footprint = scene.robot.footprint_array()
    last = contact_times(scene.path, footprint, points) - scene.robot.braking_distance / (
        scene.path.speed
    )
    last = np.minimum(last, scene.path.duration)
    keep = last >= anchor
    points, last = points[keep], last[keep]
    if not len(points):
        return []
    times = scan_times(misser.update_rate, float(last.max()))
    coarse = times[np.unique(np.linspace(0, len(times) - 1, RANKING_SCANS).round().astype(int))]
    ranked = _rank(scene, direction, anchor, points, last, coarse, needed)
    finals = [_seed(scene, direction, anchor, points[i], last[i], needed) for i in ranked]
    found = [seed for seed in finals if seed is not None]
    return sorted(found, key=_order)


def _order(seed: Seed) -> tuple[float, float, float, float]:
    return (-round(seed.lead / LEAD_STEP), -min(seed.room, ROOM_CAP), *seed.point)


def _candidates(scene: Scene, direction: Direction, anchor: float, needed: float) -> FloatArray:
    """Points on the detector's beams, in range, deep in the robot's later way and clear of it
    until it stands, shape (P, 2)."""
    detector = scene.detector(direction)
    origins, directions = detector.rays(scene.path.poses_at(np.array([anchor])))
    footprint, stands = scene.robot.footprint_array(), scene.standstill(anchor)
    after = swept_polygons(scene.path, footprint, stands, scene.path.duration)
    before = swept_polygons(scene.path, footprint, 0.0, stands)
    corners = np.vstack(after)
    near = max(detector.range_min + needed, 0.0)
    points = _along(origins[0, 0], directions[0], near, detector.range_max - DEPTH, corners)
    deep = np.max([-_outside_by(piece, points) for piece in after], axis=0) >= DEPTH
    clear = np.min([_outside_by(piece, points) for piece in before], axis=0) >= needed
    chosen: FloatArray = points[deep & clear]
    return chosen


def _along(
    origin: FloatArray, directions: FloatArray, near: float, far: float, corners: FloatArray
) -> FloatArray:
    """Points every SEED_STEP along each beam (N, 2) where it crosses the box around `corners`."""
    low, high = corners.min(axis=0), corners.max(axis=0)
    with np.errstate(divide="ignore", invalid="ignore"):
        ends = np.stack([(low - origin) / directions, (high - origin) / directions])
    enter = np.nanmax(np.where(np.isnan(ends[0]), -np.inf, ends.min(axis=0)), axis=1)
    leave = np.nanmin(np.where(np.isnan(ends[0]), np.inf, ends.max(axis=0)), axis=1)
    enter, leave = np.maximum(enter, near), np.minimum(leave, far)
    chunks = []
    for beam in np.flatnonzero(enter <= leave):
        steps = np.arange(enter[beam], leave[beam] + 1e-9, SEED_STEP)
        chunks.append(origin + steps[:, np.newaxis] * directions[beam])
    return np.vstack(chunks) if chunks else np.empty((0, 2))


def _outside_by(polygon: FloatArray, points: FloatArray) -> FloatArray:
    """max over a CCW convex polygon's edges of n . p - offset: how far outside, at least (P,)."""
    edges = np.roll(polygon, -1, axis=0) - polygon
    normals = np.column_stack([edges[:, 1], -edges[:, 0]]) / np.hypot(*edges.T)[:, np.newaxis]
    distances: FloatArray = (points @ normals.T - np.sum(normals * polygon, axis=1)).max(axis=1)
    return distances


def _rank(
    scene: Scene,
    direction: Direction,
    anchor: float,
    points: FloatArray,
    last: FloatArray,
    times: FloatArray,
    needed: float,
) -> IntArray:
    """The FINALISTS most promising points by their lead and room over a few misser scans."""
    rooms, _, _ = rooms_at(scene, direction, times, points)
    counted = times[:, np.newaxis] <= last[np.newaxis, :]
    short = counted & (rooms < needed)
    first = np.where(short.any(axis=0), np.argmax(short, axis=0), len(times))
    until = np.minimum(np.where(first > 0, times[np.maximum(first - 1, 0)], -1.0), last)
    room = np.where(counted & ~short, rooms, np.inf).min(axis=0)
    valid = np.flatnonzero(until >= anchor)
    lead = np.round((until[valid] - anchor) * scene.path.speed / LEAD_STEP)
    order = valid[np.lexsort((np.arange(len(valid)), -np.minimum(room[valid], ROOM_CAP), -lead))]
    return _spread(points, order)


def _spread(points: FloatArray, order: IntArray) -> IntArray:
    """The first FINALISTS points of `order` that lie SPREAD apart from each other."""
    kept: list[int] = []
    for index in order:
        if all(np.max(np.abs(points[index] - points[other])) >= SPREAD for other in kept):
            kept.append(int(index))
            if len(kept) == FINALISTS:
                break
    return np.array(kept, dtype=np.intp)


def _seed(
    scene: Scene,
    direction: Direction,
    anchor: float,
    point: FloatArray,
    last: float,
    needed: float,
) -> Seed | None:
    """A point checked against every misser scan up to its last chance."""
    times = scan_times(scene.misser(direction).update_rate, float(last))
    rooms = rooms_at(scene, direction, times, point[np.newaxis, :])[0][:, 0]
    short = np.flatnonzero(rooms < needed)
    until = float(times[short[0] - 1]) if len(short) and short[0] > 0 else float(last)
    if (len(short) and short[0] == 0) or until < anchor:
        return None
    counted = times <= until
    tightest = np.argsort(rooms[counted], kind="stable")[:6]
    tight = {float(times[0]), until, *(float(t) for t in times[counted][tightest])}
    path = scene.path
    return Seed(
        point=(float(point[0]), float(point[1])),
        until=until,
        lead=path.travelled(until) - path.travelled(anchor),
        room=float(rooms[counted].min()),
        tight=tuple(sorted(t for t in tight if t <= until)),
    )


def rooms_at(
    scene: Scene, direction: Direction, times: FloatArray, points: FloatArray
) -> tuple[FloatArray, IntArray, IntArray]:
    """How the misser's scans at `times` (T,) best miss each point (P, 2): room (T, P) m, the
    way (GAP, OUTSIDE, BEYOND, NEAR) and the gap's first beam, both (T, P).

    Unlimited room when the misser's scan plane is higher than the detector's: an obstacle
    between the two planes is missed by every scan.
    """
    misser = scene.misser(direction)
    shape = (len(times), len(points))
    if hides_below(scene, direction):
        return np.full(shape, np.inf), np.zeros(shape, np.intp), np.zeros(shape, np.intp)
    origin, start = _scanners(misser, scene.path.poses_at(times))
    offsets = points[np.newaxis, :, :] - origin[:, np.newaxis, :]
    distance = np.hypot(offsets[..., 0], offsets[..., 1])
    bearing = (np.arctan2(offsets[..., 1], offsets[..., 0]) - start[:, np.newaxis]) % FULL_TURN
    gap_room, gap = _gap_rooms(misser, distance, bearing)
    rooms = np.stack(
        [
            gap_room,
            _outside_rooms(misser, distance, bearing),
            distance - misser.range_max,
            misser.range_min * math.cos(math.pi / NEAR_SIDES) - distance
            if misser.range_min > 0
            else np.full(shape, -np.inf),
        ]
    )
    way: IntArray = rooms.argmax(axis=0)
    return rooms.max(axis=0), way, gap


def hides_below(scene: Scene, direction: Direction) -> bool:
    """Whether an obstacle fits between the detector's scan plane and the misser's higher one."""
    gap = scene.misser(direction).scan_height - scene.detector(direction).scan_height
    return gap >= LOW_WINDOW


def _scanners(profile: LaserProfile, poses: FloatArray) -> tuple[FloatArray, FloatArray]:
    """The scanner's origin (T, 2) and the world angle its first beam spans from (T,)."""
    start, _ = profile.sector_in_base()
    return profile.origins(poses), poses[:, 2] + start


def _gap_rooms(
    profile: LaserProfile, distance: FloatArray, bearing: FloatArray
) -> tuple[FloatArray, IntArray]:
    """Room between the two beams each point lies between, and the first beam's index."""
    spacing, count = profile.angle_increment, profile.beam_count
    if count < 2 or spacing <= 0.0:
        return np.full(distance.shape, -np.inf), np.zeros(distance.shape, np.intp)
    gap = np.clip(np.floor(bearing / spacing), 0, count - 2).astype(np.intp)
    within = np.minimum(bearing - gap * spacing, (gap + 1) * spacing - bearing)
    room = np.where(bearing <= (count - 1) * spacing, distance * np.sin(within), -np.inf)
    return room, gap


def _outside_rooms(profile: LaserProfile, distance: FloatArray, bearing: FloatArray) -> FloatArray:
    """Room on the far side of the field of view's edges; -inf for a scanner that sees all round."""
    _, extent = profile.sector_in_base()
    if extent >= FULL_TURN:
        return np.full(distance.shape, -np.inf)
    right_of_first = -distance * np.sin(bearing)
    left_of_last = distance * np.sin(bearing - extent)
    both = np.minimum if extent >= math.pi else np.maximum
    rooms: FloatArray = both(right_of_first, left_of_last)
    return rooms


def misses(
    scene: Scene, direction: Direction, times: FloatArray, point: FloatArray
) -> list[tuple[HalfPlane, ...]]:
    """For each misser scan at `times`, the half-planes that make it miss the way it misses
    `point` best; empty when the misser's scan plane is above the detector's."""
    misser = scene.misser(direction)
    if hides_below(scene, direction):
        return [() for _ in times]
    _rooms, ways, gaps = rooms_at(scene, direction, times, point[np.newaxis, :])
    origins, starts = _scanners(misser, scene.path.poses_at(times))
    cases = []
    for origin, start, way, gap in zip(origins, starts, ways[:, 0], gaps[:, 0], strict=True):
        cases.append(_half_planes(misser, origin, float(start), int(way), int(gap), point))
    return cases


def _half_planes(
    profile: LaserProfile, origin: FloatArray, start: float, way: int, gap: int, point: FloatArray
) -> tuple[HalfPlane, ...]:
    if way == GAP:
        spacing = profile.angle_increment
        low, high = start + gap * spacing, start + (gap + 1) * spacing
        return (_left_of(origin, low), _flip(_left_of(origin, high)))
    if way == OUTSIDE:
        _, extent = profile.sector_in_base()
        right_of_first, left_of_last = (
            _flip(_left_of(origin, start)),
            _left_of(origin, start + extent),
        )
        if extent >= math.pi:
            return (right_of_first, left_of_last)
        return (max(right_of_first, left_of_last, key=lambda plane: plane.room(point)),)
    if way == BEYOND:
        axis = (point - origin) / np.hypot(*(point - origin))
        return (
            HalfPlane((float(axis[0]), float(axis[1])), float(axis @ origin) + profile.range_max),
        )
    apothem = profile.range_min * math.cos(math.pi / NEAR_SIDES)
    angles = np.arange(NEAR_SIDES) * FULL_TURN / NEAR_SIDES
    return tuple(
        HalfPlane(
            (-math.cos(a), -math.sin(a)),
            -(math.cos(a) * origin[0] + math.sin(a) * origin[1]) - apothem,
        )
        for a in angles
    )


def _left_of(origin: FloatArray, angle: float) -> HalfPlane:
    """Left of the line through `origin` at `angle`."""
    normal = (-math.sin(angle), math.cos(angle))
    return HalfPlane(normal, normal[0] * float(origin[0]) + normal[1] * float(origin[1]))


def _flip(plane: HalfPlane) -> HalfPlane:
    return HalfPlane((-plane.normal[0], -plane.normal[1]), -plane.offset)
