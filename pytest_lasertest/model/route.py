"""The nominal path: the obstacle-free run from the start pose through the route to the goal.

The robot turns in place toward each waypoint at its nominal turn rate, then drives straight to it
at its nominal speed. Time runs from 0 at the start pose; scanners scan at k / update_rate.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from pytest_lasertest.model.geometry import FloatArray, Point2D, Pose2D, orientation, wrap_angle

# While turning in place the footprint sweeps (part of) a disc; the gate takes the regular polygon
# around that disc with this many sides, so that every swept region is a convex polygon.
TURN_POLYGON_SIDES = 16
# A turn smaller than this is no turn: waypoints straight ahead do not stop the robot.
MIN_TURN = 1e-9  # rad


@dataclass(frozen=True)
class Leg:
    """Driving straight from one waypoint to the next."""

    start: Point2D
    heading: float  # rad
    length: float  # m
    begins: float  # s, when the robot sets off

    def point_at(self, distance: float) -> tuple[float, float]:
        """Where the robot's origin is after `distance` m along this leg."""
        return (
            self.start.x + distance * math.cos(self.heading),
            self.start.y + distance * math.sin(self.heading),
        )


@dataclass(frozen=True)
class Turn:
    """Turning in place at a waypoint."""

    at: Point2D
    from_heading: float  # rad
    angle: float  # rad, counter-clockwise positive
    begins: float  # s


@dataclass(frozen=True)
class NominalPath:
    """Legs and turns in time order, at the robot's nominal speed and turn rate."""

    start: Pose2D
    segments: tuple[Leg | Turn, ...]
    speed: float  # m/s
    turn_rate: float  # rad/s

    @property
    def duration(self) -> float:
        """Time from the start pose to the goal (s)."""
        return self.end_of(self.segments[-1]) if self.segments else 0.0

    def polyline(self) -> list[tuple[float, float]]:
        """The path's corners, from the start to the goal (m)."""
        points = [(self.start.x, self.start.y)]
        points += [leg.point_at(leg.length) for leg in self.legs()]
        return points

    def legs(self) -> list[Leg]:
        """The straight parts, in order."""
        return [segment for segment in self.segments if isinstance(segment, Leg)]

    def poses_at(self, times: FloatArray) -> FloatArray:
        """Robot poses [x, y, yaw] at `times`, shape (T,) s -> (T, 3); held at the goal after."""
        start = np.array([self.start.x, self.start.y, self.start.yaw], dtype=float)
        poses = np.tile(start, (len(times), 1))
        for segment in self.segments:
            inside = times >= segment.begins
            elapsed = np.minimum(
                times[inside] - segment.begins, self.end_of(segment) - segment.begins
            )
            if isinstance(segment, Leg):
                distance = elapsed * self.speed
                poses[inside, 0] = segment.start.x + distance * math.cos(segment.heading)
                poses[inside, 1] = segment.start.y + distance * math.sin(segment.heading)
                poses[inside, 2] = segment.heading
            else:
                turned = np.sign(segment.angle) * elapsed * self.turn_rate
                poses[inside, 0], poses[inside, 1] = segment.at.x, segment.at.y
                poses[inside, 2] = segment.from_heading + turned
        return poses

    def travelled(self, time: float) -> float:
        """How far the robot has driven at `time` (m)."""
        legs = self.legs()
        return sum(min(max(time - leg.begins, 0.0) * self.speed, leg.length) for leg in legs)

    def segment_at(self, time: float) -> Leg | Turn | None:
        """The leg or turn the robot is on at `time`; None after the goal."""
        for segment in self.segments:
            if segment.begins <= time < self.end_of(segment):
                return segment
        return None

    def end_of(self, segment: Leg | Turn) -> float:
        """When the robot finishes this leg or turn (s)."""
        if isinstance(segment, Leg):
            return segment.begins + segment.length / self.speed
        return segment.begins + abs(segment.angle) / self.turn_rate


def nominal_path(
    start: Pose2D, route: tuple[Point2D, ...], speed: float, turn_rate: float
) -> NominalPath:
    """The path that turns toward each waypoint of `route` in turn and drives straight to it."""
    segments: list[Leg | Turn] = []
    here, heading, clock = Point2D(start.x, start.y), start.yaw, 0.0
    for waypoint in route:
        bearing = math.atan2(waypoint.y - here.y, waypoint.x - here.x)
        angle = wrap_angle(bearing - heading)
        if abs(angle) > MIN_TURN:
            segments.append(Turn(here, heading, angle, clock))
            clock += abs(angle) / turn_rate
        length = math.dist((here.x, here.y), (waypoint.x, waypoint.y))
        segments.append(Leg(here, bearing, length, clock))
        clock += length / speed
        here, heading = waypoint, bearing
    return NominalPath(start, tuple(segments), speed, turn_rate)


# A run that cruises within this share of the nominal speed keeps it: its speed varies that much
# along a leg anyway (DWA samples a few speeds), and timing each leg by its middle absorbs it.
SPEED_TOLERANCE = 0.1


def timed_to(path: NominalPath, times: FloatArray, poses: FloatArray) -> NominalPath:
    """The path with the clock of a run along it: times (T,) s and poses (T, 3) [x, y, yaw] of a
    robot driving it. A run that cruised further than SPEED_TOLERANCE from the nominal speed
    (its controller's limits, or a controller of the team's own) gives the path its speed;
    each leg begins when the run's crossing of its middle says it did, at that speed, and each
    turn ends as its leg begins; where the legs and turns lie is unchanged. A leg the run never
    got half way along keeps its time at that speed, as late as the last timed leg.
    """
    crossings = _crossings(path, times, poses)
    cruised = _cruising_speed(path, crossings)
    speed = path.speed
    if cruised is not None and abs(cruised / path.speed - 1.0) > SPEED_TOLERANCE:
        # A run that crawled along a short leg and got no further must not stretch the rest of
        # the path far beyond the run: the solver judges the path scan by scan.
        speed = max(cruised, sum(leg.length for leg in path.legs()) / float(times[-1]))
    path = at_speed(path, speed)
    retimed: list[Leg | Turn] = []
    clock, delay = 0.0, 0.0  # s: the end of the last leg; how late it began
    turn: Turn | None = None
    legs = iter(crossings)
    for segment in path.segments:
        if isinstance(segment, Turn):
            turn = segment
            continue
        turning = abs(turn.angle) / path.turn_rate if turn else 0.0
        middle = next(legs)[1]
        wanted = segment.begins + delay
        if middle is not None:
            wanted = middle - segment.length / 2.0 / path.speed
        begins = max(wanted, clock + turning)
        if turn:
            retimed.append(dataclasses.replace(turn, begins=begins - turning))
        retimed.append(dataclasses.replace(segment, begins=begins))
        clock, delay, turn = begins + segment.length / path.speed, begins - segment.begins, None
    return NominalPath(path.start, tuple(retimed), path.speed, path.turn_rate)


def at_speed(path: NominalPath, speed: float) -> NominalPath:
    """The same legs and turns, the legs driven at `speed` m/s, each part right after the last."""
    if speed == path.speed:
        return path
    segments: list[Leg | Turn] = []
    clock = 0.0  # s
    for segment in path.segments:
        segments.append(dataclasses.replace(segment, begins=clock))
        if isinstance(segment, Leg):
            clock += segment.length / speed
        else:
            clock += abs(segment.angle) / path.turn_rate
    return NominalPath(path.start, tuple(segments), speed, path.turn_rate)


# The run's cruising speed on a leg is timed between these shares of its length, away from where
# it speeds up and slows down; its crossing of the middle times the leg.
_MARKS = (0.25, 0.5, 0.75)
Crossings = tuple[float | None, float | None, float | None]


def _crossings(path: NominalPath, times: FloatArray, poses: FloatArray) -> list[Crossings]:
    """When the run first got a quarter, half and three quarters along each leg (s), counting
    only what it did after it got to the end of the leg before; None where it never did."""
    result: list[Crossings] = []
    finished: float | None = 0.0  # s: when the run got to the end of the last leg, if it did
    for leg in path.legs():
        if finished is None:
            result.append((None, None, None))
            continue
        # Only what the run did after the last leg counts: a route may come back on itself.
        run = times[times >= finished], poses[times >= finished]
        quarter, middle, three = (_crossing_time(leg, share * leg.length, *run) for share in _MARKS)
        result.append((quarter, middle, three))
        finished = _crossing_time(leg, leg.length, *run)
    return result


def _cruising_speed(path: NominalPath, crossings: list[Crossings]) -> float | None:
    """The run's mean speed over the middle halves of the legs it drove through (m/s); None
    when it drove through none."""
    length, duration = 0.0, 0.0  # m, s
    for leg, (quarter, _, three) in zip(path.legs(), crossings, strict=True):
        if quarter is not None and three is not None and three > quarter:
            length, duration = length + leg.length / 2.0, duration + three - quarter
    return length / duration if duration > 0.0 else None


def _crossing_time(leg: Leg, distance: float, times: FloatArray, poses: FloatArray) -> float | None:
    """When the run first got `distance` m along the leg's line (s), between samples by linear
    interpolation; None if it never did."""
    heading = np.array([math.cos(leg.heading), math.sin(leg.heading)])
    along = (poses[:, :2] - [leg.start.x, leg.start.y]) @ heading
    reached = np.flatnonzero(along >= distance)
    if not len(reached):
        return None
    after = int(reached[0])
    if after == 0:
        return float(times[0])
    share = (distance - along[after - 1]) / (along[after] - along[after - 1])
    return float(times[after - 1] + share * (times[after] - times[after - 1]))


def scan_times(rate: float, until: float) -> FloatArray:
    """A scanner's scan instants k / rate from 0 up to and including `until`, shape (K,), s."""
    return np.arange(scan_count(rate, until)) / rate


def scan_count(rate: float, until: float) -> int:
    """How many scans a scanner at `rate` Hz takes from 0 up to and including `until` s."""
    # The small slack keeps a scan due at exactly `until` from rounding down.
    return math.floor(until * rate + 1e-9) + 1


def swept_polygons(
    path: NominalPath, footprint: FloatArray, begin: float, end: float
) -> list[FloatArray]:
    """Convex polygons, each shape (V, 2), whose union holds every footprint of [begin, end] s.

    A straight stretch sweeps the convex hull of its first and last footprints; a turn in place is
    taken to sweep the regular polygon around the disc its footprint turns in. Where a path timed
    to a run waits (the run set off late, or took longer to turn), the robot stands, and its
    footprint there is a piece of its own.
    """
    radius = float(np.max(np.hypot(footprint[:, 0], footprint[:, 1])))
    pieces: list[FloatArray] = []
    clock = 0.0  # s, when the part before ended
    for segment in path.segments:
        if clock < segment.begins and max(begin, clock) <= min(end, segment.begins):
            standing = path.poses_at(np.array([segment.begins]))[0]
            pieces.append(place(footprint, standing))
        clock = path.end_of(segment)
        first, last = max(begin, segment.begins), min(end, clock)
        if first > last or (first == last and segment.begins != first):
            continue
        if isinstance(segment, Turn):
            pieces.append(_turn_polygon(segment.at, radius))
            continue
        ends = path.poses_at(np.array([first, last]))
        pieces.append(_hull(np.vstack([place(footprint, pose) for pose in ends])))
    return pieces


def contact_times(path: NominalPath, footprint: FloatArray, points: FloatArray) -> FloatArray:
    """When the footprint first covers each point, shape (P, 2) -> (P,) s; inf if never.

    As `swept_polygons` has it: a leg covers a point once the footprint's front edge at the
    point's lateral offset reaches it, a turn covers its whole disc from the moment it begins,
    and the footprint where the robot waits covers what it holds from the moment the wait begins.
    """
    times = np.full(len(points), np.inf)
    radius = float(np.max(np.hypot(footprint[:, 0], footprint[:, 1])))
    clock = 0.0  # s, when the part before ended
    for segment in path.segments:
        if clock < segment.begins:
            standing = place(footprint, path.poses_at(np.array([segment.begins]))[0])
            times = np.where(_inside(standing, points), np.minimum(times, clock), times)
        clock = path.end_of(segment)
        if isinstance(segment, Turn):
            inside = _inside(_turn_polygon(segment.at, radius), points)
            times = np.where(inside, np.minimum(times, segment.begins), times)
            continue
        heading = np.array([math.cos(segment.heading), math.sin(segment.heading)])
        offsets = points - [segment.start.x, segment.start.y]
        along, lateral = offsets @ heading, offsets @ [-heading[1], heading[0]]
        back, front = _chord(footprint, lateral)
        reached = np.maximum(along - front, 0.0)
        covered = (reached <= np.minimum(segment.length, along - back)) & (back <= front)
        arrival = segment.begins + reached / path.speed
        times = np.where(covered, np.minimum(times, arrival), times)
    return times


def _chord(polygon: FloatArray, lateral: FloatArray) -> tuple[FloatArray, FloatArray]:
    """Where the line y = lateral, shape (P,), crosses a convex base-frame polygon: x from, to.

    An empty chord comes back as from > to.
    """
    here, there = polygon, np.roll(polygon, -1, axis=0)
    rise = there[:, 1] - here[:, 1]
    with np.errstate(divide="ignore", invalid="ignore"):
        share = (lateral[:, np.newaxis] - here[:, 1]) / rise
    crosses = (rise != 0) & (share >= 0.0) & (share <= 1.0)
    xs = here[:, 0] + share * (there[:, 0] - here[:, 0])
    back = np.where(crosses, xs, np.inf).min(axis=1)
    front = np.where(crosses, xs, -np.inf).max(axis=1)
    return back, front


def _inside(polygon: FloatArray, points: FloatArray) -> npt.NDArray[np.bool_]:
    """Whether each point, shape (P, 2), lies in a counter-clockwise convex polygon (V, 2)."""
    edges = np.roll(polygon, -1, axis=0) - polygon
    relative = points[:, np.newaxis, :] - polygon[np.newaxis, :, :]
    cross = edges[:, 0] * relative[..., 1] - edges[:, 1] * relative[..., 0]
    result: npt.NDArray[np.bool_] = np.all(cross >= 0.0, axis=1)
    return result


def place(footprint: FloatArray, pose: FloatArray) -> FloatArray:
    """A base-frame polygon, shape (V, 2), placed at pose [x, y, yaw] in the world."""
    cos, sin = math.cos(pose[2]), math.sin(pose[2])
    rotation = np.array([[cos, -sin], [sin, cos]])
    placed: FloatArray = footprint @ rotation.T + pose[:2]
    return placed


def _turn_polygon(centre: Point2D, radius: float) -> FloatArray:
    sides = TURN_POLYGON_SIDES
    # The polygon's vertices lie further out than the disc so that its edges touch the circle.
    corner = radius / math.cos(math.pi / sides)
    angles = (np.arange(sides) + 0.5) * 2.0 * math.pi / sides
    return np.column_stack([centre.x + corner * np.cos(angles), centre.y + corner * np.sin(angles)])


def _hull(points: FloatArray) -> FloatArray:
    """Convex hull, counter-clockwise, shape (V, 2) (Andrew's monotone chain)."""
    ordered = sorted({(float(x), float(y)) for x, y in points})
    if len(ordered) < 3:
        return np.array(ordered)
    lower: list[tuple[float, float]] = []
    upper: list[tuple[float, float]] = []
    for chain, sequence in ((lower, ordered), (upper, ordered[::-1])):
        for point in sequence:
            while len(chain) >= 2 and orientation(chain[-2], chain[-1], point) <= 0:
                chain.pop()
            chain.append(point)
    return np.array(lower[:-1] + upper[:-1])
