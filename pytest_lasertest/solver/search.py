"""The search for witnesses: anchors on the nominal path, seeds at each, one Z3 query per seed.

For one direction of a pair, some of the detector's scan instants along the nominal path are
anchors. At each, a seed point (`seeds.py`) fixes how the detector reads the obstacle and how each
misser scan misses it, so a query is a linear program: an obstacle holding the seed, clear of the
robot until it could stand, kept by the seed's half-planes from every misser scan up to the seed's
`until`, with the largest margin and then the smallest size. The exact ray cast judges each model;
a misser scan that still sees the obstacle joins the program (refinement), so the model converges
on a placement every misser scan up to `until` misses.
"""

from __future__ import annotations

import math
from collections.abc import Iterator, Sequence
from dataclasses import dataclass, field

import numpy as np

from pytest_lasertest.model.geometry import FloatArray
from pytest_lasertest.model.obstacles import Box, Cylinder, Obstacle
from pytest_lasertest.model.route import Leg, scan_times, swept_polygons
from pytest_lasertest.model.verify import (
    REQUIRED_MARGIN,
    Direction,
    Placement,
    Scene,
    Verification,
    last_chance,
    verify,
)
from pytest_lasertest.pairsfile.constraints import Constraint
from pytest_lasertest.solver.backend import RLIMIT, Solution, Workspace
from pytest_lasertest.solver.encoding import (
    VARIABLES,
    HalfPlane,
    ObstacleShape,
    all_of,
    linear,
    number,
)
from pytest_lasertest.solver.seeds import Seed
from pytest_lasertest.solver.user import formula_text
from pytest_lasertest.solver.ways import hides_below, misses

# The solver aims a little above the required margin so that rounding to floats cannot undo it.
TARGET_MARGIN = REQUIRED_MARGIN + 1e-4  # m
MAX_MARGIN = 0.02  # m, beyond this a larger margin buys nothing
MAX_REFINEMENTS = 12
MIN_HEIGHT = 0.05  # m


class WitnessRejected(AssertionError):
    """The solver's model failed a check the encoding promised: a bug in the gate, never noise."""


@dataclass(frozen=True)
class SearchSettings:
    """How hard and how widely to look for witnesses."""

    witnesses: int = 3  # per direction
    min_size: float = 0.05  # m
    max_size: float = 1.0  # m
    max_height: float = 2.0  # m
    anchor_spacing: float = 0.5  # m of path between anchors
    diversity: float = 0.5  # m, how far apart two witnesses' centres are
    rlimit: int = RLIMIT
    constraints: tuple[Constraint, ...] = field(default=())


@dataclass(frozen=True)
class Found:
    """A verified witness of one query."""

    placement: Placement
    verification: Verification


@dataclass(frozen=True)
class Query:
    """One seed of one anchor, and one obstacle shape: a linear program, refined by ray casts."""

    scene: Scene
    direction: Direction
    anchor: float  # s
    seed: Seed
    shape: ObstacleShape
    settings: SearchSettings
    apart_from: tuple[Obstacle, ...] = ()

    def run(self, workspace: Workspace | None = None) -> Found | Solution:
        """A verified witness, or Z3's unsat / unknown answer; asked in `workspace` if given."""
        workspace = Workspace() if workspace is None else workspace
        times = list(self.seed.tight)
        fixed = {**self.scene_blocks(), **self.user_blocks()}
        for _ in range(MAX_REFINEMENTS):
            blocks = {**fixed, **self.misser_blocks(times)}
            solution = workspace.solve(
                VARIABLES, blocks, ("M", "-S"), self.settings.rlimit, explained=False
            )
            if solution.verdict != "sat":
                return solution
            obstacle = obstacle_of(self.shape, solution)
            last = last_chance(self.scene, obstacle)
            until = max(min(self.seed.until, last), self.anchor)
            placement = Placement(obstacle, self.direction, self.anchor, until)
            verification = verify(self.scene, placement, last)
            if verification.holds():
                return Found(placement, verification)
            times = self._refine(times, verification, placement)
        return Solution("unknown", {}, reason=f"{MAX_REFINEMENTS} refinements did not converge")

    def scene_blocks(self) -> dict[str, str]:
        """Size bounds, the detector's reading through the seed, the robot's room to stop, and
        the goal left free."""
        scene, shape, point = self.scene, self.shape, np.array(self.seed.point)
        stands = scene.standstill(self.anchor)
        before = swept_polygons(scene.path, scene.robot.footprint_array(), 0.0, stands)
        return {
            "bounds": bounds(self.settings),
            "detector": all_of([shape.holds(point), *self._reading()]),
            "robot": all_of([shape.beyond(_separating(piece, point, shape)) for piece in before]),
            "goal": shape.beyond(_separating(scene.arrival(), point, shape)),
            "walls": all_of(
                [
                    shape.beyond(_separating(np.array(wall.corners()), point, shape))
                    for wall in scene.walls.near(*self.seed.point, needed_reach(self.settings))
                ]
            ),
        }

    def user_blocks(self) -> dict[str, str]:
        """The user's constraints, and distance from the witnesses found before."""
        blocks = constraint_blocks(self.settings, self.shape)
        for index, other in enumerate(self.apart_from):
            blocks[f"apart {index}"] = self._apart(other)
        return blocks

    def misser_blocks(self, times: Sequence[float]) -> dict[str, str]:
        """One formula per misser scan that must miss the obstacle: the seed's way of missing."""
        scene, direction = self.scene, self.direction
        misser = scene.misser(direction)
        if hides_below(scene, direction):
            return {"misser": f"(<= {linear(H=1.0, M=1.0)} {number(misser.scan_height)})"}
        cases = misses(scene, direction, np.array(times), np.array(self.seed.point))
        return {
            f"misser@{time:.3f}": all_of([self.shape.beyond(plane) for plane in case])
            for time, case in zip(times, cases, strict=True)
        }

    def _reading(self) -> list[str]:
        """Above the detector's scan plane, and wholly beyond its minimum range along the beam."""
        detector = self.scene.detector(self.direction)
        above = f"(>= {linear(H=1.0, M=-1.0)} {number(detector.scan_height)})"
        if detector.range_min <= 0:
            return [above]
        origins, _ = detector.rays(self.scene.path.poses_at(np.array([self.anchor])))
        origin = origins[0, 0]
        axis = (np.array(self.seed.point) - origin) / math.dist(self.seed.point, origin)
        return [above, self.shape.at_least(axis, float(origin @ axis) + detector.range_min)]

    def _apart(self, other: Obstacle) -> str:
        """At least `diversity` m from another witness along x or y, on the seed's side."""
        gap, (x, y) = self.settings.diversity, self.seed.point
        options = [
            (x - (other.x + gap), f"(>= X {number(other.x + gap)})"),
            ((other.x - gap) - x, f"(<= X {number(other.x - gap)})"),
            (y - (other.y + gap), f"(>= Y {number(other.y + gap)})"),
            ((other.y - gap) - y, f"(<= Y {number(other.y - gap)})"),
        ]
        return max(options)[1]

    def _refine(
        self, times: list[float], verification: Verification, placement: Placement
    ) -> list[float]:
        promised = min(verification.detection, verification.clearance, verification.obstruction)
        late = [t for t in verification.seen_by_misser_at if t not in times]
        if promised < REQUIRED_MARGIN or not late:
            raise WitnessRejected(
                f"the solver placed {placement.obstacle} for {placement.direction} at "
                f"t = {placement.anchor} s, but the ray cast finds margins {verification}"
            )
        picks = {late[0], late[len(late) // 2], late[-1]}
        return sorted({*times, *picks})


def obstacle_of(shape: ObstacleShape, solution: Solution) -> Obstacle:
    """The obstacle of a model."""
    x, y = solution.values["X"], solution.values["Y"]
    size, height = solution.values["S"], solution.values["H"]
    if shape.shape == "cylinder":
        return Cylinder(x, y, size / 2.0, height)
    return Box(x, y, shape.yaw, size, size, height)


def constraint_blocks(settings: SearchSettings, shape: ObstacleShape) -> dict[str, str]:
    """The user's constraints, one labelled block each."""
    return {
        f"constraint {index}": formula_text(constraint.formula, shape.yaw)
        for index, constraint in enumerate(settings.constraints)
    }


def bounds(settings: SearchSettings) -> str:
    """The obstacle's size and height, and the margin the solver aims for."""
    return all_of(
        [
            f"(>= S {number(settings.min_size)})",
            f"(<= S {number(settings.max_size)})",
            f"(>= H {number(MIN_HEIGHT)})",
            f"(<= H {number(settings.max_height)})",
            f"(>= M {number(TARGET_MARGIN)})",
            f"(<= M {number(MAX_MARGIN)})",
            # Shrunk by M, the obstacle must still be an obstacle.
            f"(>= (- (* 0.5 S) M) {number(REQUIRED_MARGIN)})",
        ]
    )


def needed_reach(settings: SearchSettings) -> float:
    """How far from its seed any part of an obstacle the settings allow can reach (m): the
    obstacle holds the seed."""
    return math.sqrt(2.0) * settings.max_size + MAX_MARGIN


def needed_room(shape: ObstacleShape, settings: SearchSettings) -> float:
    """The room around a seed the smallest obstacle of this shape needs, margin included (m)."""
    spread = 1.0 if shape.shape == "cylinder" else math.sqrt(2.0)
    return spread * (settings.min_size / 2.0 + TARGET_MARGIN)


def _separating(piece: FloatArray, point: FloatArray, shape: ObstacleShape) -> HalfPlane:
    """Of the axes that can separate the obstacle from a convex piece, the one with most room."""
    options = []
    edges = np.roll(piece, -1, axis=0) - piece
    for edge, corner in zip(edges, piece, strict=True):
        length = float(np.hypot(*edge))
        if length > 0.0:
            normal = np.array([edge[1], -edge[0]]) / length
            options.append(HalfPlane((float(normal[0]), float(normal[1])), float(normal @ corner)))
    for axis in shape.axes():
        projection = piece @ axis
        options.append(HalfPlane((float(axis[0]), float(axis[1])), float(projection.max())))
        options.append(HalfPlane((float(-axis[0]), float(-axis[1])), float(-projection.min())))
    return max(options, key=lambda plane: plane.room(point) / shape.spread(np.array(plane.normal)))


# A direction without a witness is searched at every anchor: a route of kilometres at 0.5 m
# spacing would take an hour; spread this many along it, it takes seconds.
MAX_ANCHORS = 100


def anchor_times(scene: Scene, direction: Direction, spacing: float) -> list[float]:
    """Detector scan instants on legs, with room to brake on the leg, `spacing` m apart, or
    further apart on a route so long that it would hold more than MAX_ANCHORS.

    Each is moved to the detector's last scan before the misser's next one, where the misser's
    picture is stalest: a slower misser shows its difference there.
    """
    path, detector = scene.path, scene.detector(direction)
    spacing = max(spacing, sum(leg.length for leg in path.legs()) / MAX_ANCHORS)
    rate, misser_rate = detector.update_rate, scene.misser(direction).update_rate
    anchors: list[float] = []
    for time in scan_times(rate, path.duration):
        if anchors and (time - anchors[-1]) * path.speed < spacing - 1e-9:
            continue
        following = (math.floor(time * misser_rate + 1e-9) + 1) / misser_rate
        stalest = max(float(time), (math.ceil(following * rate - 1e-9) - 1) / rate)
        for anchor in dict.fromkeys((stalest, float(time))):
            segment = path.segment_at(anchor)
            if isinstance(segment, Leg) and scene.standstill(anchor) <= path.end_of(segment):
                anchors.append(anchor)
                break
    return anchors


def shapes_for(index: int, heading: float) -> Iterator[ObstacleShape]:
    """The shapes a witness search tries, varied by witness index: boxes turned in eighths."""
    box = ObstacleShape("box", (heading + (index // 2) * math.pi / 8.0) % (math.pi / 2.0))
    cylinder = ObstacleShape("cylinder")
    yield from (box, cylinder) if index % 2 == 0 else (cylinder, box)
