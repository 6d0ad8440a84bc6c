"""Placements, and their exact verification by ray casting: the judge every witness faces.

A placement discriminates a pair in one direction when, with every margin at least `margin`:
- the detector's scan at the anchor instant has a beam that passes inside the obstacle, in range,
  and the obstacle stands higher than the detector's scan plane;
- every scan the misser takes up to the placement's `until` instant (at or after the anchor) has
  every beam pass clear of it from range_min on (nearer, REP 117 reports -inf, which a costmap
  drops), or the obstacle is lower than the misser's scan plane;
- the robot, braking from the anchor, stands before touching it;
- and it obstructs: it reaches into the footprint swept after the robot would have stopped.

The lead is how far the robot drives between the anchor and `until`; a placement is late when
`until` reaches the robot's last chance to stop, so that the misser reads the obstacle only when it
is too late, or never: it stays discriminating along the whole approach.

A placement without a direction is one both scanners read at the anchor and the robot must act
on (`avoid.py`): it is judged on the same margins, and no scanner conceals it, but it may obstruct
in another way: the candidate reads it nearer than its range_min (REP 117's -inf, which a costmap
drops) at some scan as the robot passes, where the baseline reads it in range.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Literal

import numpy as np

from pytest_lasertest.model.geometry import FloatArray
from pytest_lasertest.model.obstacles import (
    Obstacle,
    polygon_clearance,
    ray_distances,
    segment_clearances,
)
from pytest_lasertest.model.robot import Robot
from pytest_lasertest.model.route import NominalPath, place, scan_times, swept_polygons
from pytest_lasertest.model.sensor import LaserProfile
from pytest_lasertest.model.walls import NO_WALLS, Walls

Direction = Literal["candidate-misses", "baseline-misses"]
DIRECTIONS: tuple[Direction, ...] = ("candidate-misses", "baseline-misses")
Scanner = Literal["baseline", "candidate"]
# Which scanner must read the obstacle and which must miss it, in each direction.
ROLES: dict[Direction, tuple[Scanner, Scanner]] = {
    "candidate-misses": ("baseline", "candidate"),
    "baseline-misses": ("candidate", "baseline"),
}
# Which scanner reads the obstacle in each direction, as reports name it.
DETECTED_BY: dict[Direction, Scanner] = {
    direction: detector for direction, (detector, _) in ROLES.items()
}
BOTH: tuple[Scanner, Scanner] = ("baseline", "candidate")
# PyBullet reports ray hits up to about 1 mm outside exact shapes: keep well clear of every edge.
REQUIRED_MARGIN = 0.005  # m
# Beams further than this from the obstacle get a lower bound on their clearance, not its exact
# value: the verdict needs exact figures near REQUIRED_MARGIN, and culling makes it much faster.
EXACT_WITHIN = 0.1  # m


@dataclass(frozen=True)
class Scene:
    """What placements are judged against: both scanners on the robot, and its nominal path."""

    baseline: LaserProfile
    candidate: LaserProfile
    robot: Robot
    path: NominalPath
    # The world's walls: they hide what stands behind them, and no obstacle may stand in one.
    walls: Walls = field(default_factory=Walls)

    def detector(self, direction: Direction) -> LaserProfile:
        """The scanner that must see the obstacle."""
        return self.baseline if direction == "candidate-misses" else self.candidate

    def misser(self, direction: Direction) -> LaserProfile:
        """The scanner that must not."""
        return self.candidate if direction == "candidate-misses" else self.baseline

    def standstill(self, anchor: float) -> float:
        """When the robot would stand if it started reacting at `anchor` (s)."""
        return anchor + self.robot.braking_distance / self.path.speed

    def arrival(self) -> FloatArray:
        """The robot's footprint at the goal, shape (V, 2), m: an obstacle there would stop any
        robot short of the goal, whatever its scanner."""
        goal = self.path.poses_at(np.array([self.path.duration]))[0]
        return place(self.robot.footprint_array(), goal)


@dataclass(frozen=True)
class Placement:
    """An obstacle, the direction it discriminates, and the detector's scan that first sees it."""

    obstacle: Obstacle
    direction: Direction | None  # None: both scanners read it (see the module)
    anchor: float  # s, a scan instant of the detector on the nominal path
    until: float  # s, no earlier than the anchor: the misser misses every scan up to here

    @property
    def readers(self) -> tuple[Scanner, ...]:
        """The scanners that must read the obstacle at the anchor."""
        if self.direction is None:
            return BOTH
        return (DETECTED_BY[self.direction],)

    @property
    def scanners(self) -> tuple[Scanner, ...]:
        """Both scanners, in the order reports show them: the detector first."""
        return BOTH if self.direction is None else ROLES[self.direction]

    def read_by(self) -> str:
        """`baseline`, `candidate`, or `baseline and candidate`: who reads it at the anchor."""
        return " and ".join(self.readers)


@dataclass(frozen=True)
class Verification:
    """The margins of a placement; each must reach REQUIRED_MARGIN."""

    detection: float  # m, how deep the detector's best beam passes inside, or its height margin
    concealment: float  # m, how far clear the misser's nearest beam stays; inf without a misser
    clearance: float  # m, between the obstacle and the robot until it stands, and at the goal
    obstruction: float  # m, how deep the obstacle reaches into the footprint swept after
    seen_by_misser_at: tuple[float, ...]  # s, misser scans up to `until` that fail to miss
    lead: float  # m of path from the anchor to `until`
    late: bool  # the misser's first scan after `until` comes after the robot's last chance
    # m, placed without a direction: how deep the candidate reads it nearer than its range_min
    # where the baseline reads it in range, along the path; -inf for a direction
    too_near: float = -math.inf
    walls: float = math.inf  # m, how far it stands from the nearest wall; inf without walls

    @property
    def margin(self) -> float:
        """The smallest of the margins (m); obstructing by being read too near counts."""
        obstructs = max(self.obstruction, self.too_near)
        return min(self.detection, self.concealment, self.clearance, obstructs, self.walls)

    def holds(self, required: float = REQUIRED_MARGIN) -> bool:
        """Whether every margin reaches `required`."""
        return self.margin >= required


def verify(scene: Scene, placement: Placement, last: float | None = None) -> Verification:
    """Judge a placement with exact ray casts and swept footprints; `last` is the obstacle's
    `last_chance`, if the caller knows it already."""
    obstacle, direction = placement.obstacle, placement.direction
    anchor_pose = scene.path.poses_at(np.array([placement.anchor]))
    detection = min(
        float(np.max(hit_margins(getattr(scene, reader), anchor_pose, obstacle, scene.walls)))
        for reader in placement.readers
    )
    clearance, obstruction = _in_the_way(scene, obstacle, placement.anchor)
    walls = scene.walls.clearance(obstacle)
    if direction is None:
        too_near, _ = read_too_near(scene, obstacle)
        return Verification(
            detection, math.inf, clearance, obstruction, (), 0.0, False, too_near, walls
        )
    misser = scene.misser(direction)
    times = scan_times(misser.update_rate, max(placement.until, placement.anchor))
    concealments = miss_margins(misser, scene.path.poses_at(times), obstacle, scene.walls)
    last = last_chance(scene, obstacle) if last is None else last
    return Verification(
        detection=detection,
        concealment=float(np.min(concealments)),
        clearance=clearance,
        obstruction=obstruction,
        seen_by_misser_at=tuple(float(t) for t in times[concealments < REQUIRED_MARGIN]),
        lead=scene.path.travelled(placement.until) - scene.path.travelled(placement.anchor),
        late=len(scan_times(misser.update_rate, last)) <= len(times),
        walls=walls,
    )


def _in_the_way(scene: Scene, obstacle: Obstacle, anchor: float) -> tuple[float, float]:
    """How far the robot braking from `anchor` (and at the goal) stays clear of the obstacle, and
    how deep the obstacle reaches into the footprint swept after it would stand (m)."""
    clearance = min(
        stopping_clearance(scene, obstacle, anchor),
        polygon_clearance(scene.arrival(), obstacle),
    )
    stands = scene.standstill(anchor)
    after = swept_polygons(scene.path, scene.robot.footprint_array(), stands, scene.path.duration)
    obstruction = max((-polygon_clearance(piece, obstacle) for piece in after), default=-np.inf)
    return clearance, obstruction


def read_too_near(scene: Scene, obstacle: Obstacle) -> tuple[float, float]:
    """The candidate's scan along the whole path whose beam passes deepest inside the obstacle
    nearer than its range_min, where the baseline's scan from the same pose reads it in range:
    how deep (m) and when (s); (-inf, nan) when the candidate's range_min is no larger than the
    baseline's or no scan comes that near."""
    candidate, baseline = scene.candidate, scene.baseline
    if candidate.range_min <= baseline.range_min:
        return -math.inf, math.nan
    times = scan_times(candidate.update_rate, scene.path.duration)
    offsets = candidate.origins(scene.path.poses_at(times)) - (obstacle.x, obstacle.y)
    times = times[np.hypot(*offsets.T) < candidate.range_min + obstacle.within(0.0)]
    if not len(times):
        return -math.inf, math.nan
    poses = scene.path.poses_at(times)
    depths = np.minimum(
        too_near_margins(candidate, poses, obstacle),
        np.max(hit_margins(baseline, poses, obstacle, scene.walls), axis=1),
    )
    deepest = int(np.argmax(depths))
    return float(depths[deepest]), float(times[deepest])


def stopping_clearance(scene: Scene, obstacle: Obstacle, time: float) -> float:
    """How far the robot, braking from `time`, stays from the obstacle until it stands (m)."""
    footprint = scene.robot.footprint_array()
    before = swept_polygons(scene.path, footprint, 0.0, scene.standstill(time))
    return min(polygon_clearance(piece, obstacle) for piece in before)


def last_chance(scene: Scene, obstacle: Obstacle, tolerance: float = 1e-4) -> float:
    """The latest instant from which braking still stops clear of the obstacle (s).

    The path's duration when the obstacle is never in the way. The clearance only shrinks as the
    braking starts later, so the instant is bracketed to `tolerance` seconds, stepping from the
    clear side. On a leg the clearance falls no faster than the robot drives (exactly that fast
    when the obstacle is straight ahead), linearly or convexly, so the first step, clearance /
    speed, and then secants through two clear instants land on the instant or short of it. A
    step that overshoots, as at a turn, where the robot sweeps a whole disc at once, or that
    finds the clearance flat, is followed by a bisection.
    """
    low, high = 0.0, scene.path.duration
    above, below = (stopping_clearance(scene, obstacle, t) for t in (low, high))
    if below > 0.0 or above <= 0.0:
        return high if below > 0.0 else low
    slope, guided = scene.path.speed, True
    while high - low > tolerance:
        width = high - low
        step = above / slope if guided else width / 2.0
        middle = low + min(max(step, tolerance / 2.0), width - tolerance / 2.0)
        clearance = stopping_clearance(scene, obstacle, middle)
        if clearance <= 0.0:
            high, guided = middle, not guided
        elif clearance < above:
            slope, guided = (above - clearance) / (middle - low), True
            low, above = middle, clearance
        else:  # flat: beside the obstacle, no slope to follow
            low, guided = middle, False
    return low


def hit_margins(
    profile: LaserProfile, poses: FloatArray, obstacle: Obstacle, walls: Walls = NO_WALLS
) -> FloatArray:
    """How surely each beam reads the obstacle in range, shape (T, N), m; negative: it does not.

    A beam reads it when it passes inside the obstacle between range.min and range.max, before
    any wall (REQUIRED_MARGIN short of it, as a cast may meet a face that much early), and
    nothing of the obstacle is nearer than range.min (REP 117 would report -inf); the obstacle
    must also stand above the scan plane.
    """
    origins, directions = profile.rays(poses)
    shape = origins.shape[:2]
    flat_origins, flat_directions = origins.reshape(-1, 2), directions.reshape(-1, 2)
    ends = np.full(len(flat_origins), profile.range_max)
    if walls:
        ends = np.minimum(ends, walls.reach(flat_origins, flat_directions) - REQUIRED_MARGIN)
    starts = np.full(len(flat_origins), profile.range_min)
    inside = -segment_clearances(
        flat_origins, flat_directions, starts, np.maximum(ends, starts), obstacle
    )
    # A wall nearer than range_min: the beam reads -inf, whatever stands behind it.
    margins = np.where(ends < starts, -np.inf, inside).reshape(shape)
    if profile.range_min > 0:
        before = segment_clearances(
            flat_origins, flat_directions, np.zeros(len(starts)), starts, obstacle
        )
        margins = np.minimum(margins, before.reshape(shape))
    above_plane: FloatArray = np.minimum(margins, obstacle.height - profile.scan_height)
    return above_plane


def miss_margins(
    profile: LaserProfile, poses: FloatArray, obstacle: Obstacle, walls: Walls = NO_WALLS
) -> FloatArray:
    """How surely each scan misses the obstacle, shape (T,), m; negative: some beam reads it.

    Only the part of a beam from range_min to range_max can give a reading in range (nearer, REP
    117 reports -inf, which a costmap drops), and none past a wall (taken REQUIRED_MARGIN beyond
    it, as a cast may meet a face that much late), so a beam misses by that part's clearance.
    Only beams that come near the obstacle are cast; a scan whose beams all pass EXACT_WITHIN
    clear gets EXACT_WITHIN, a lower bound.
    """
    scans, beams = profile.beams_near(
        poses, (obstacle.x, obstacle.y), obstacle.within(EXACT_WITHIN)
    )
    origins = profile.origins(poses)[scans]
    directions = profile.beam_directions(poses, scans, beams)
    count = len(scans)
    ends = np.full(count, profile.range_max)
    if walls:
        ends = np.minimum(ends, walls.reach(origins, directions) + REQUIRED_MARGIN)
    starts = np.full(count, profile.range_min)
    clear = segment_clearances(origins, directions, starts, np.maximum(ends, starts), obstacle)
    nearest = np.full(len(poses), EXACT_WITHIN)
    np.minimum.at(nearest, scans, clear)
    lower: FloatArray = np.maximum(nearest, profile.scan_height - obstacle.height)
    return lower


def readings(
    profile: LaserProfile, poses: FloatArray, obstacle: Obstacle, walls: Walls = NO_WALLS
) -> FloatArray:
    """LaserScan ranges of the scans at `poses` that read the obstacle, shape (T, N), m: REP
    117 -inf / +inf outside, and +inf where a wall stands before it."""
    origins, directions = profile.rays(poses)
    flat_origins, flat_directions = origins.reshape(-1, 2), directions.reshape(-1, 2)
    distances = ray_distances(flat_origins, flat_directions, obstacle)
    if walls:
        hidden = walls.reach(flat_origins, flat_directions) < distances
        distances = np.where(hidden, np.inf, distances)
    ranges = distances.reshape(origins.shape[:2])
    if obstacle.height <= profile.scan_height:
        return np.full_like(ranges, np.inf)
    ranges = np.where(ranges > profile.range_max, np.inf, ranges)
    out: FloatArray = np.where(ranges < profile.range_min, -np.inf, ranges)
    return out


def too_near_margins(profile: LaserProfile, poses: FloatArray, obstacle: Obstacle) -> FloatArray:
    """How deep each scan's beams pass inside the obstacle nearer than range_min, where REP 117
    reports -inf, shape (T,), m; negative: no beam of the scan does. Only beams that may come
    near the obstacle are cast; a scan with none gets -inf."""
    reach = obstacle.within(0.0)
    scans, beams = profile.beams_near(poses, (obstacle.x, obstacle.y), reach)
    count = len(scans)
    clear = segment_clearances(
        profile.origins(poses)[scans],
        profile.beam_directions(poses, scans, beams),
        np.zeros(count),
        np.full(count, profile.range_min),
        obstacle,
    )
    deepest = np.full(len(poses), -np.inf)
    np.maximum.at(deepest, scans, -clear)
    above: FloatArray = np.minimum(deepest, obstacle.height - profile.scan_height)
    return above
