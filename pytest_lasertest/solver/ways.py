"""How a misser scan misses a point: the room each way of missing leaves, and the half-planes
that keep an obstacle missed the same way.

A scan misses an obstacle when the obstacle lies outside its field of view, beyond its range,
nearer than its minimum range, or between two of its beams (`scans.miss_ways` gives the whole
disjunction). For one point, the way that leaves the most room is the disjunct a seed picks; its
half-planes are what a witness search hands Z3.
"""

from __future__ import annotations

import math

import numpy as np

from pytest_lasertest.model.geometry import FULL_TURN, FloatArray
from pytest_lasertest.model.sensor import LaserProfile
from pytest_lasertest.model.verify import Direction, Scene
from pytest_lasertest.solver.encoding import HalfPlane
from pytest_lasertest.solver.scans import NEAR_SIDES

# How far the misser's scan plane must stand above the detector's for an obstacle to fit between.
LOW_WINDOW = 0.02  # m

GAP, OUTSIDE, BEYOND, NEAR = range(4)


def rooms_at(
    scene: Scene, direction: Direction, times: FloatArray, points: FloatArray
) -> FloatArray:
    """How much room (T, P) m the misser's scans at `times` (T,) leave around each point (P, 2),
    missing it whichever way leaves the most.

    Unlimited room when the misser's scan plane is higher than the detector's: an obstacle
    between the two planes is missed by every scan.
    """
    if hides_below(scene, direction):
        return np.full((len(times), len(points)), np.inf)
    misser = scene.misser(direction)
    origin, start = _scanners(misser, scene.path.poses_at(times))
    ways = iter(_way_rooms(misser, *_polar(origin, start, points)).values())
    rooms = next(ways)
    for other in ways:
        np.maximum(rooms, other, out=rooms)
    return rooms


def hides_below(scene: Scene, direction: Direction) -> bool:
    """Whether an obstacle fits between the detector's scan plane and the misser's higher one."""
    gap = scene.misser(direction).scan_height - scene.detector(direction).scan_height
    return gap >= LOW_WINDOW


def _scanners(profile: LaserProfile, poses: FloatArray) -> tuple[FloatArray, FloatArray]:
    """The scanner's origin (T, 2) and the world angle its first beam spans from (T,)."""
    start, _ = profile.sector_in_base()
    return profile.origins(poses), poses[:, 2] + start


def _polar(
    origin: FloatArray, start: FloatArray, points: FloatArray
) -> tuple[FloatArray, FloatArray]:
    """Each point's (P, 2) distance from the scanner at each origin (T, 2), and its bearing from
    the first beam (world angle `start`, (T,)), counter-clockwise in [0, 2 pi), both (T, P)."""
    offsets = points[np.newaxis, :, :] - origin[:, np.newaxis, :]
    distance = np.hypot(offsets[..., 0], offsets[..., 1])
    bearing = (np.arctan2(offsets[..., 1], offsets[..., 0]) - start[:, np.newaxis]) % FULL_TURN
    return distance, bearing


def _way_rooms(
    profile: LaserProfile, distance: FloatArray, bearing: FloatArray
) -> dict[int, FloatArray]:
    """The room each way of missing leaves, for the ways this scanner has, each (T, P) m."""
    rooms = {GAP: _gap_rooms(profile, distance, bearing)}
    _, extent = profile.sector_in_base()
    if extent < FULL_TURN:
        rooms[OUTSIDE] = _outside_rooms(extent, distance, bearing)
    rooms[BEYOND] = distance - profile.range_max
    if profile.range_min > 0:
        rooms[NEAR] = profile.range_min * math.cos(math.pi / NEAR_SIDES) - distance
    return rooms


def _gap_rooms(profile: LaserProfile, distance: FloatArray, bearing: FloatArray) -> FloatArray:
    """Room between the two beams each point lies between; -inf outside the field of view."""
    spacing, count = profile.angle_increment, profile.beam_count
    if count < 2 or spacing <= 0.0:
        return np.full(distance.shape, -np.inf)
    past = np.remainder(bearing, spacing)
    room = distance * np.sin(np.minimum(past, spacing - past))
    room[bearing > (count - 1) * spacing] = -np.inf
    return room


def _gap_index(profile: LaserProfile, bearing: float) -> int:
    """The first beam of the gap a bearing from the first beam lies in."""
    gap = math.floor(bearing / profile.angle_increment)
    return min(max(gap, 0), profile.beam_count - 2)


def _outside_rooms(extent: float, distance: FloatArray, bearing: FloatArray) -> FloatArray:
    """Room on the far side of the field of view's edges, for a sector `extent` rad wide."""
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
    poses = scene.path.poses_at(times)
    origins, starts = _scanners(misser, poses)
    distance, bearing = _polar(origins, starts, point[np.newaxis, :])
    rooms = _way_rooms(misser, distance, bearing)
    ways = np.array(list(rooms))[np.argmax(np.stack(list(rooms.values())), axis=0)[:, 0]]
    cases = []
    for origin, start, way, angle in zip(origins, starts, ways, bearing[:, 0], strict=True):
        gap = _gap_index(misser, float(angle)) if way == GAP else 0
        cases.append(_half_planes(misser, origin, float(start), int(way), gap, point))
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
