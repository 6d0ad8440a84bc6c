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

from dataclasses import dataclass

import numpy as np

from pytest_lasertest.model.geometry import FloatArray, IntArray
from pytest_lasertest.model.route import NominalPath, contact_times, scan_times, swept_polygons
from pytest_lasertest.model.verify import Direction, Scene
from pytest_lasertest.solver.ways import rooms_at

SEED_STEP = 0.05  # m between seed points along a beam
RANKING_SCANS = 48  # misser scans a first ranking looks at, evenly spread
SCANS_AT_ONCE = 16  # of those, how many are judged together before dropped points are let go
FINALISTS = 8  # points whose every misser scan is checked before the final order
DEPTH = 0.02  # m, how deep inside the robot's later way a seed lies
LEAD_STEP = 0.25  # m, leads closer than this count as equal when ranking
SPREAD = 0.25  # m between finalists, so that witnesses kept apart still find seeds
ROOM_CAP = 0.1  # m, room beyond this buys nothing more


@dataclass(frozen=True)
class Seed:
    """A point on a detector beam at the anchor, and how long the misser leaves room around it."""

    point: tuple[float, float]  # m
    until: float  # s, every misser scan up to here leaves `room` around the point
    lead: float  # m of path between the anchor and `until`
    room: float  # m
    tight: tuple[float, ...]  # s, the misser scans that leave the least room


@dataclass(frozen=True)
class Candidates:
    """Points on the detector's beams at one anchor, deep in the robot's later way, each with the
    room it leaves: a shape that needs no more can be built around it."""

    anchor: float  # s
    points: FloatArray  # (P, 2) m
    room: FloatArray  # (P,) m, to range_min, to the robot until it stands, to the misser's beams
    last: FloatArray  # (P,) s, the robot's last chance to stop short of the point
    times: FloatArray  # (T,) s, RANKING_SCANS misser scans spread up to the latest last chance
    rooms: FloatArray  # (T, P) m, the room those scans leave, for a first ranking


def candidates(scene: Scene, direction: Direction, anchor: float, needed: float) -> Candidates:
    """Points every SEED_STEP along the detector's beams at the anchor, in range and deep in the
    robot's later way, that leave `needed` m of room (the least any shape needs) before
    range_min, before the robot until it stands, and before the misser's scans at the start and
    just before the anchor (most points fail there at once)."""
    detector, misser = scene.detector(direction), scene.misser(direction)
    origins, directions = detector.rays(scene.path.poses_at(np.array([anchor])))
    origin, footprint = origins[0, 0], scene.robot.footprint_array()
    after = swept_polygons(scene.path, footprint, scene.standstill(anchor), scene.path.duration)
    # A beam reads nothing past the first wall it meets.
    far = np.minimum(detector.range_max, scene.walls.reach(origins[0], directions[0])) - DEPTH
    points = _along(origin, directions[0], detector.range_min, far, np.vstack(after))
    points = points[np.max([-_outside_by(piece, points) for piece in after], axis=0) >= DEPTH]
    room = np.minimum(
        np.hypot(*(points - origin).T) - detector.range_min,
        _room_up_to_anchor(scene, direction, anchor, points),
    )
    room = np.minimum(room, scene.walls.distances(points))
    braking = scene.robot.braking_distance / scene.path.speed
    last = np.minimum(contact_times(scene.path, footprint, points) - braking, scene.path.duration)
    keep = (room >= needed) & (last >= anchor)
    points, last = points[keep], last[keep]
    times = scan_times(misser.update_rate, float(last.max(initial=anchor)))
    coarse = times[np.unique(np.linspace(0, len(times) - 1, RANKING_SCANS).round().astype(int))]
    rooms = _rooms_while_kept(scene, direction, coarse, points, last, needed)
    return Candidates(anchor, points, room[keep], last, coarse, rooms)


def _room_up_to_anchor(
    scene: Scene, direction: Direction, anchor: float, points: FloatArray
) -> FloatArray:
    """Room (P,) m, to the robot until it stands, to the robot at the goal, and to the misser's
    scans at the start and just before the anchor."""
    footprint = scene.robot.footprint_array()
    before = swept_polygons(scene.path, footprint, 0.0, scene.standstill(anchor))
    first_and_last = np.array([0.0, scan_times(scene.misser(direction).update_rate, anchor)[-1]])
    room: FloatArray = np.minimum(
        np.min([_outside_by(piece, points) for piece in [*before, scene.arrival()]], axis=0),
        rooms_at(scene, direction, first_and_last, points).min(axis=0),
    )
    return room


def _rooms_while_kept(
    scene: Scene,
    direction: Direction,
    times: FloatArray,
    points: FloatArray,
    last: FloatArray,
    needed: float,
) -> FloatArray:
    """The room (T, P) the misser's scans at `times` leave each point, up to the first that
    leaves less than `needed` or comes after the point's last chance; -inf after it, since
    later scans cannot change a point's lead. Most points drop out within a few scans."""
    rooms = np.full((len(times), len(points)), -np.inf)
    kept = np.arange(len(points))
    for start in range(0, len(times), SCANS_AT_ONCE):
        chunk = slice(start, start + SCANS_AT_ONCE)
        some = rooms_at(scene, direction, times[chunk], points[kept])
        rooms[chunk, kept] = some
        short = (some < needed) & (times[chunk, np.newaxis] <= last[kept])
        kept = kept[~short.any(axis=0) & (last[kept] > times[chunk][-1])]
        if not len(kept):
            break
    return rooms


def seeds(scene: Scene, direction: Direction, near: Candidates, needed: float) -> list[Seed]:
    """Seeds with at least `needed` m of room before every misser scan up to their last chance,
    best first: the longest lead, then the most room."""
    keep = near.room >= needed
    points, last, anchor = near.points[keep], near.last[keep], near.anchor
    if not len(points):
        return []
    leads = Leads.of(anchor, near.times, near.rooms[:, keep], last, needed)
    finalists = _rank(leads, points, scene.path.speed)
    if not len(finalists):
        return []
    times = scan_times(scene.misser(direction).update_rate, float(last[finalists].max()))
    rooms = rooms_at(scene, direction, times, points[finalists])
    exact = Leads.of(anchor, times, rooms, last[finalists], needed)
    found = [exact.seed(scene.path, index, points[i]) for index, i in enumerate(finalists)]
    return sorted((seed for seed in found if seed is not None), key=_order)


def _order(seed: Seed) -> tuple[float, float, float, float]:
    return (-round(seed.lead / LEAD_STEP), -min(seed.room, ROOM_CAP), *seed.point)


def _along(
    origin: FloatArray, directions: FloatArray, near: float, far: FloatArray, corners: FloatArray
) -> FloatArray:
    """Points every SEED_STEP along each beam (N, 2), from `near` to its `far` (N,) m, where it
    crosses the box around `corners`."""
    low, high = corners.min(axis=0), corners.max(axis=0)
    with np.errstate(divide="ignore", invalid="ignore"):
        ends = np.stack([(low - origin) / directions, (high - origin) / directions])
    enter = np.nanmax(np.where(np.isnan(ends[0]), -np.inf, ends.min(axis=0)), axis=1)
    leave = np.nanmin(np.where(np.isnan(ends[0]), np.inf, ends.max(axis=0)), axis=1)
    enter, leave = np.maximum(enter, near), np.minimum(leave, far)
    beams = np.flatnonzero(enter <= leave)
    # As many points as np.arange(enter, leave + 1e-9, SEED_STEP) gives, for all beams at once.
    counts = np.ceil((leave[beams] + 1e-9 - enter[beams]) / SEED_STEP).astype(np.intp)
    each = np.repeat(beams, counts)
    steps = np.arange(counts.sum()) - np.repeat(np.cumsum(counts) - counts, counts)
    along = enter[each] + steps * SEED_STEP
    points: FloatArray = origin + along[:, np.newaxis] * directions[each]
    return points


def _outside_by(polygon: FloatArray, points: FloatArray) -> FloatArray:
    """max over a CCW convex polygon's edges of n . p - offset: how far outside, at least (P,)."""
    edges = np.roll(polygon, -1, axis=0) - polygon
    normals = np.column_stack([edges[:, 1], -edges[:, 0]]) / np.hypot(*edges.T)[:, np.newaxis]
    distances: FloatArray = (points @ normals.T - np.sum(normals * polygon, axis=1)).max(axis=1)
    return distances


@dataclass(frozen=True)
class Leads:
    """How long the misser leaves room around each of P points, judged at its scans `times`."""

    anchor: float  # s
    times: FloatArray  # (T,) s
    rooms: FloatArray  # (T, P) m
    until: FloatArray  # (P,) s, every counted scan up to here leaves the room needed; -1: none
    room: FloatArray  # (P,) m, the least room those scans leave

    @classmethod
    def of(
        cls, anchor: float, times: FloatArray, rooms: FloatArray, last: FloatArray, needed: float
    ) -> Leads:
        """From the rooms (T, P) the scans at `times` leave; scans after a point's last chance
        (`last`, (P,) s) do not count."""
        counted = times[:, np.newaxis] <= last[np.newaxis, :]
        short = counted & (rooms < needed)
        first = np.where(short.any(axis=0), np.argmax(short, axis=0), len(times))
        until = np.where(first < len(times), times[np.maximum(first - 1, 0)], last)
        until = np.where(first > 0, until, -1.0)
        room = np.where(times[:, np.newaxis] <= until, rooms, np.inf).min(axis=0)
        return cls(anchor, times, rooms, until, room)

    def valid(self) -> IntArray:
        """The points whose room lasts until the anchor at least."""
        return np.flatnonzero(self.until >= self.anchor)

    def seed(self, path: NominalPath, index: int, point: FloatArray) -> Seed | None:
        """Point `index` as a seed, if its room lasts until the anchor."""
        until = float(self.until[index])
        if until < self.anchor:
            return None
        counted = self.times <= until
        tightest = self.times[counted][np.argsort(self.rooms[counted, index], kind="stable")[:6]]
        tight = {float(self.times[0]), until, *(float(t) for t in tightest)}
        return Seed(
            point=(float(point[0]), float(point[1])),
            until=until,
            lead=path.travelled(until) - path.travelled(self.anchor),
            room=float(self.room[index]),
            tight=tuple(sorted(t for t in tight if t <= until)),
        )


def _rank(leads: Leads, points: FloatArray, speed: float) -> IntArray:
    """The FINALISTS most promising points by their lead and room, SPREAD apart."""
    valid = leads.valid()
    lead = np.round((leads.until[valid] - leads.anchor) * speed / LEAD_STEP)
    room = np.minimum(leads.room[valid], ROOM_CAP)
    return _spread(points, valid[np.lexsort((np.arange(len(valid)), -room, -lead))])


def _spread(points: FloatArray, order: IntArray) -> IntArray:
    """The first FINALISTS points of `order` that lie SPREAD apart from each other."""
    kept: list[int] = []
    left = order
    while len(left) and len(kept) < FINALISTS:
        kept.append(int(left[0]))
        apart = np.max(np.abs(points[left] - points[left[0]]), axis=1) >= SPREAD
        left = left[apart]
    return np.array(kept, dtype=np.intp)
