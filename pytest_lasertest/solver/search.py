"""The search for witnesses: anchors on the nominal path, one Z3 query each, refined by ray casts.

For one direction of a pair, the detector's scan instants along the nominal path are anchors. At
each, a query asks for an obstacle the detector's scan reads while the misser's scans miss it,
clear of the robot until it could stand, and in its way after. The exact ray cast judges each
model; a misser scan that still sees the obstacle becomes one more constraint (refinement), so
the model converges on a placement that every misser scan up to the anchor misses.
"""

from __future__ import annotations

import math
from collections.abc import Iterator, Sequence
from dataclasses import dataclass, field

import numpy as np

from pytest_lasertest.geometry import Box, Cylinder, FloatArray, Obstacle
from pytest_lasertest.path import Leg, scan_times, swept_polygons
from pytest_lasertest.placement import (
    REQUIRED_MARGIN,
    Direction,
    Placement,
    Scene,
    Verification,
    verify,
)
from pytest_lasertest.solver.backend import RLIMIT, Solution, solve
from pytest_lasertest.solver.encoding import VARIABLES, ObstacleShape, all_of, any_of, number
from pytest_lasertest.solver.scans import Region, detected, missed, promising_beams
from pytest_lasertest.solver.user import formula_text
from pytest_lasertest.spec.constraints import Constraint

# The solver aims a little above the required margin so that rounding to floats cannot undo it.
TARGET_MARGIN = REQUIRED_MARGIN + 1e-4  # m
MAX_MARGIN = 0.02  # m, beyond this a larger margin buys nothing
MAX_REFINEMENTS = 12
MIN_HEIGHT = 0.05  # m
BEAM_LIMIT = 12


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
    """One anchor and obstacle shape of one direction."""

    scene: Scene
    direction: Direction
    anchor: float  # s
    shape: ObstacleShape
    settings: SearchSettings
    apart_from: tuple[Obstacle, ...] = ()
    # How many of the detector's most promising beams the query offers Z3; None: every beam, so
    # that an unsat answer proves that no placement discriminates at this anchor.
    beam_limit: int | None = BEAM_LIMIT

    def run(self) -> Found | Solution:
        """A verified witness, or Z3's unsat / unknown answer."""
        misser = self.scene.misser(self.direction)
        times = scan_times(misser.update_rate, self.anchor)
        refined = sorted({float(times[0]), float(times[-1])})
        region = self.region()
        # Only the misser's scans change between refinements; the rest is built once.
        scene_blocks, user_blocks = self.scene_blocks(region), self.user_blocks()
        # A proof over every beam only decides; searches maximise the margin, then prefer the
        # thinnest obstacle, the hardest to see.
        goals = ("M", "-S") if self.beam_limit is not None else ()
        for _ in range(MAX_REFINEMENTS):
            blocks = {**scene_blocks, **self.misser_blocks(refined, region), **user_blocks}
            solution = solve(VARIABLES, blocks, goals, self.settings.rlimit)
            if solution.verdict != "sat":
                return solution
            placement = Placement(self.obstacle(solution), self.direction, self.anchor)
            verification = verify(self.scene, placement)
            if verification.holds():
                return Found(placement, verification)
            refined = self._refine(refined, verification, placement)
        return Solution("unknown", {}, reason=f"{MAX_REFINEMENTS} refinements did not converge")

    def region(self) -> Region:
        """A box holding every obstacle that reaches into the path after the robot could stop."""
        reach = self.settings.max_size * (math.sqrt(0.5) if self.shape.shape == "box" else 0.5)
        pieces = self._swept_after()
        if not pieces:
            return Region((0.0, 0.0), (0.0, 0.0))
        points = np.vstack(pieces)
        low, high = points.min(axis=0) - reach, points.max(axis=0) + reach
        return Region((float(low[0]), float(low[1])), (float(high[0]), float(high[1])))

    def scene_blocks(self, region: Region) -> dict[str, str]:
        """Size bounds, the robot's path, and the detector's scan at the anchor."""
        scene, shape = self.scene, self.shape
        stands = scene.standstill(self.anchor)
        before = swept_polygons(scene.path, scene.robot.footprint_array(), 0.0, stands)
        return {
            "bounds": self._bounds(),
            "robot": all_of([shape.clear_of_polygon(piece) for piece in before]),
            "path": any_of([shape.inside_polygon(piece) for piece in self._swept_after()]),
            "detector": self._detector(region),
        }

    def user_blocks(self) -> dict[str, str]:
        """The user's constraints, and distance from the witnesses found before."""
        blocks = {}
        for index, constraint in enumerate(self.settings.constraints):
            blocks[f"constraint {index}"] = formula_text(constraint.formula, self.shape.yaw)
        for index, other in enumerate(self.apart_from):
            blocks[f"apart {index}"] = self._apart(other)
        return blocks

    def misser_blocks(self, misser_times: Sequence[float], region: Region) -> dict[str, str]:
        """One formula per misser scan that must miss the obstacle."""
        misser = self.scene.misser(self.direction)
        poses = self.scene.path.poses_at(np.array(misser_times))
        return {
            f"misser@{time:.3f}": missed(self.shape, misser, pose, region, self.settings.min_size)
            for time, pose in zip(misser_times, poses, strict=True)
        }

    def obstacle(self, solution: Solution) -> Obstacle:
        """The obstacle of a model."""
        x, y = solution.values["X"], solution.values["Y"]
        size, height = solution.values["S"], solution.values["H"]
        if self.shape.shape == "cylinder":
            return Cylinder(x, y, size / 2.0, height)
        return Box(x, y, self.shape.yaw, size, size, height)

    def _bounds(self) -> str:
        settings = self.settings
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

    def _swept_after(self) -> list[FloatArray]:
        path = self.scene.path
        stands = self.scene.standstill(self.anchor)
        return swept_polygons(path, self.scene.robot.footprint_array(), stands, path.duration)

    def _detector(self, region: Region) -> str:
        scene = self.scene
        detector, misser = scene.detector(self.direction), scene.misser(self.direction)
        last_miss = scan_times(misser.update_rate, self.anchor)[-1]
        poses = scene.path.poses_at(np.array([self.anchor, last_miss]))
        beams = None
        if self.beam_limit is not None:
            beams = promising_beams(
                detector, misser, poses, region, self.settings.min_size, self.beam_limit
            )
        return detected(self.shape, detector, poses[0], region, beams)

    def _apart(self, other: Obstacle) -> str:
        gap = self.settings.diversity
        return any_of(
            [
                f"(>= X {number(other.x + gap)})",
                f"(<= X {number(other.x - gap)})",
                f"(>= Y {number(other.y + gap)})",
                f"(<= Y {number(other.y - gap)})",
            ]
        )

    def _refine(
        self, refined: list[float], verification: Verification, placement: Placement
    ) -> list[float]:
        promised = min(verification.detection, verification.clearance, verification.obstruction)
        late = [t for t in verification.seen_by_misser_at if t not in refined]
        if promised < REQUIRED_MARGIN or not late:
            raise WitnessRejected(
                f"the solver placed {placement.obstacle} for {placement.direction} at "
                f"t = {placement.anchor} s, but the ray cast finds margins {verification}"
            )
        picks = {late[0], late[len(late) // 2], late[-1]}
        return sorted({*refined, *picks})


def anchor_times(scene: Scene, direction: Direction, spacing: float) -> list[float]:
    """Detector scan instants on legs, with room to brake on the leg, `spacing` m apart."""
    path = scene.path
    times = scan_times(scene.detector(direction).update_rate, path.duration)
    anchors: list[float] = []
    for time in times:
        segment = path.segment_at(float(time))
        if not isinstance(segment, Leg) or scene.standstill(float(time)) > path.end_of(segment):
            continue
        if anchors and (time - anchors[-1]) * path.speed < spacing - 1e-9:
            continue
        anchors.append(float(time))
    return anchors


def shapes_for(index: int, heading: float) -> Iterator[ObstacleShape]:
    """The shapes a witness search tries, varied by witness index: boxes turned in eighths."""
    box = ObstacleShape("box", (heading + (index // 2) * math.pi / 8.0) % (math.pi / 2.0))
    cylinder = ObstacleShape("cylinder")
    yield from (box, cylinder) if index % 2 == 0 else (cylinder, box)
