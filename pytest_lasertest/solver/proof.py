"""Proofs that no placement discriminates at an anchor, one way of missing at a time, in words.

A misser scan misses an obstacle only in a few ways (`scans.miss_ways`). No placement exists
exactly when each way, joined to the rest of the question, is unsatisfiable, so a proof is one
query per way and shape, and its explanation says for each way what rules it out: the unsat core
in words. A cheap relaxation of the detector's reading is tried first; only a way it cannot rule
out meets the disjunction over the beams that can reach it. A way of many options (the gaps
between hundreds of beams) is asked a few dozen options at a time, and only about the gaps an
obstacle of the smallest size can reach. The misser's last scan before the anchor is asked
first; an earlier scan, from where the robot was then, that reads a model joins the question.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np

from pytest_lasertest.model.geometry import FloatArray
from pytest_lasertest.model.obstacles import Box
from pytest_lasertest.model.plan import Status, Witness
from pytest_lasertest.model.route import scan_times, swept_polygons
from pytest_lasertest.model.verify import (
    REQUIRED_MARGIN,
    Direction,
    Placement,
    Scene,
    Verification,
    verify,
)
from pytest_lasertest.solver.backend import Solution, Workspace
from pytest_lasertest.solver.encoding import VARIABLES, ObstacleShape, all_of, any_of
from pytest_lasertest.solver.proof_words import earlier_label, sentence, why
from pytest_lasertest.solver.scans import (
    IndexArray,
    Reading,
    Region,
    detected,
    gap_regions,
    miss_ways,
    near_region,
    reaches,
    reaching_beams,
)
from pytest_lasertest.solver.search import (
    MAX_REFINEMENTS,
    SearchSettings,
    bounds,
    constraint_blocks,
    obstacle_of,
)

PROOF_VARIABLES = (*VARIABLES, "QX", "QY")
# Beams of the detector asked about at once, when one option against all of them is too hard.
BEAM_CHUNK = 32
# Ways of missing that a scanner's own figures rule out, not worth a word.
IMPOSSIBLE = ("outside", "near")


@dataclass(frozen=True)
class Proof:
    """Z3's verdict on one anchor: unsat with the reasons, unknown, or a witness it found."""

    verdict: Status
    explanation: str
    witness: Witness | None = None


@dataclass(frozen=True)
class Question:
    """Everything but the misser's scan, for one anchor and obstacle shape."""

    scene: Scene
    direction: Direction
    anchor: float  # s
    shape: ObstacleShape
    settings: SearchSettings

    def blocks(
        self, relaxed: bool, within: Region | None = None, beams: IndexArray | None = None
    ) -> dict[str, str]:
        """Labelled SMT-LIB blocks: bounds, the robot's room to stop, its way, the reading (by
        `beams`, or by those that reach `within`, a box the misser's options keep the obstacle
        in, or the question's whole region)."""
        detector, pose = self.scene.detector(self.direction), self.pose()
        reading = reaches(self.shape, detector, pose) if relaxed else None
        return {
            **self._robot_blocks,
            "detector": reading
            or detected(self.shape, detector, pose, within or self.region, beams, self.scene.walls),
            **constraint_blocks(self.settings, self.shape),
        }

    @functools.cached_property
    def _robot_blocks(self) -> dict[str, str]:
        """The blocks every query of the question shares; a proof asks dozens of queries."""
        scene, shape = self.scene, self.shape
        footprint, stands = scene.robot.footprint_array(), scene.standstill(self.anchor)
        before = swept_polygons(scene.path, footprint, 0.0, stands)
        after = swept_polygons(scene.path, footprint, stands, scene.path.duration)
        return {
            "bounds": bounds(self.settings),
            "robot": all_of([shape.clear_of_polygon(piece) for piece in before]),
            # The verifier's clearance holds the goal free too (the robot must be able to
            # arrive); without it a model at the goal failed the ray cast.
            "goal": shape.clear_of_polygon(scene.arrival()),
            "path": any_of([shape.inside_polygon(piece) for piece in after]),
            "walls": all_of(
                [shape.clear_of_polygon(np.array(wall.corners())) for wall in self._walls]
            ),
        }

    @property
    def _walls(self) -> tuple[Box, ...]:
        """The walls an obstacle in the region may touch."""
        region = self.region
        centre = (np.array(region.low) + region.high) / 2.0
        reach = float(np.hypot(*(np.array(region.high) - region.low))) / 2.0
        return self.scene.walls.near(float(centre[0]), float(centre[1]), reach)

    def pose(self) -> FloatArray:
        """The robot at the anchor, [x, y, yaw]."""
        poses: FloatArray = self.scene.path.poses_at(np.array([self.anchor]))[0]
        return poses

    @functools.cached_property
    def reading(self) -> Reading:
        """Where the detector at the anchor can read an obstacle: from its origin, out to its
        range_max, beyond its range_min."""
        detector = self.scene.detector(self.direction)
        origins, _ = detector.rays(self.pose()[np.newaxis, :])
        centre = (float(origins[0, 0, 0]), float(origins[0, 0, 1]))
        return Reading(centre, detector.range_max, detector.range_min)

    def missed_at(self, time: float, within: Region | None) -> str:
        """The misser's scan at `time` misses the obstacle, in any of its ways that can hold an
        obstacle in `within` (or the question's region)."""
        misser = self.scene.misser(self.direction)
        pose = self.scene.path.poses_at(np.array([time]))[0]
        ways = miss_ways(
            self.shape, misser, pose, within or self.region, self.settings.min_size, self.reading
        )
        if misser.scan_height <= self.scene.detector(self.direction).scan_height:
            ways["below"] = []  # as in `prove`: nothing stands above one plane, below a lower one
        return any_of([option for options in ways.values() for option in options])

    @functools.cached_property
    def region(self) -> Region:
        """A box holding every obstacle that reaches into the robot's way after it could stop."""
        scene = self.scene
        footprint, stands = scene.robot.footprint_array(), scene.standstill(self.anchor)
        points = np.vstack(swept_polygons(scene.path, footprint, stands, scene.path.duration))
        reach = self.settings.max_size * (math.sqrt(0.5) if self.shape.shape == "box" else 0.5)
        low, high = points.min(axis=0) - reach, points.max(axis=0) + reach
        return Region((float(low[0]), float(low[1])), (float(high[0]), float(high[1])))


def prove(
    scene: Scene,
    direction: Direction,
    anchor: float,
    settings: SearchSettings,
    shapes: tuple[ObstacleShape, ...],
) -> Proof:
    """Whether any placement of these shapes discriminates at the anchor, with the reasons."""
    misser = scene.misser(direction)
    # Only the misser's last scan is asked at first; an earlier one that reads a model joins
    # the question then (`_confirmed`).
    last_scan = scan_times(misser.update_rate, anchor)[-1:]
    pose = scene.path.poses_at(last_scan)[0]
    detector = scene.detector(direction)
    # Each way's reasons, for every shape: a shape may need more of the question than another.
    cores: dict[str, set[str]] = {}
    workspace = Workspace()
    for shape in shapes:
        question = Question(scene, direction, anchor, shape, settings)
        region, read = question.region, question.reading
        ways = miss_ways(shape, misser, pose, region, settings.min_size, read)
        # Where each option keeps the obstacle, for the ways that keep it in a small part of
        # the region: the detector's disjunction then holds only the beams that reach it.
        boxes = {
            "between": gap_regions(misser, pose, region, settings.min_size, read),
            "near": [near_region(misser, pose, region)] * len(ways["near"]),
        }
        if misser.scan_height <= detector.scan_height:
            ways["below"] = []  # nothing stands above one plane and below a lower one
        for way, options in ways.items():
            if not options and way in IMPOSSIBLE:
                continue
            outcome = _rule_out(question, way, options, workspace, boxes.get(way))
            if isinstance(outcome, Witness):
                return Proof("sat", "", outcome)
            if outcome.verdict == "unknown":
                return Proof(
                    "unknown",
                    f"Z3 could not decide at t = {anchor:.2f} s within its rlimit "
                    f"({settings.rlimit:,} per query; {outcome.reason})",
                )
            cores.setdefault(way, set()).update(outcome.core)
    reasons = {way: why(scene, direction, settings, way, core) for way, core in cores.items()}
    return Proof("unsat", sentence(scene, direction, anchor, settings.min_size, reasons))


def _rule_out(
    question: Question,
    way: str,
    options: list[str],
    workspace: Workspace,
    boxes: list[Region] | None = None,
    chunk: int = 32,
) -> Solution | Witness:
    """Whether any of a way's options admits a placement, asked `chunk` options at a time: one
    disjunction over hundreds of gaps ran out of its rlimit where a few dozen at a time are
    refuted in milliseconds each. `boxes`, if given, hold each option's obstacles. An unsat
    answer's core gathers every chunk's labels."""
    if not options:
        return Solution("unsat", {}, ("misser",))
    core: set[str] = set()
    for first in range(0, len(options), chunk):
        part = slice(first, first + chunk)
        outcome = _rule_out_chunk(
            question, way, options[part], workspace, None if boxes is None else boxes[part]
        )
        if isinstance(outcome, Witness) or outcome.verdict != "unsat":
            return outcome
        core.update(outcome.core)
    return Solution("unsat", {}, tuple(sorted(core)))


def _rule_out_chunk(
    question: Question,
    way: str,
    options: list[str],
    workspace: Workspace,
    boxes: list[Region] | None,
) -> Solution | Witness:
    """The relaxed question first, then the whole one, its detector's beams only those that
    reach the chunk's boxes; a chunk Z3 cannot decide is halved until a single option is left
    undecided."""
    within = None if boxes is None else _around(boxes)
    solution = Solution("unknown", {})
    for relaxed in (True, False):
        blocks = {**question.blocks(relaxed, within), "misser": any_of(options)}
        variables = PROOF_VARIABLES if relaxed else VARIABLES
        solution = workspace.solve(variables, blocks, (), question.settings.rlimit)
        if solution.verdict == "unknown" and len(options) > 1:
            return _rule_out(question, way, options, workspace, boxes, len(options) // 2)
        if solution.verdict == "unknown" and not relaxed:
            return _rule_out_by_beams(question, way, options, workspace, within)
        if solution.verdict != "sat":
            return solution
    return _confirmed(question, way, blocks, solution, workspace, within)


def _rule_out_by_beams(
    question: Question, way: str, options: list[str], workspace: Workspace, within: Region | None
) -> Solution | Witness:
    """One option Z3 cannot decide against every beam of the detector at once, asked against
    BEAM_CHUNK beams at a time."""
    detector = question.scene.detector(question.direction)
    beams = reaching_beams(detector, question.pose(), within or question.region)
    core = {"detector", "misser"}  # no beam reaches: the reading and the way rule it out
    for first in range(0, len(beams), BEAM_CHUNK):
        blocks = {
            **question.blocks(False, within, beams[first : first + BEAM_CHUNK]),
            "misser": any_of(options),
        }
        solution = workspace.solve(VARIABLES, blocks, (), question.settings.rlimit)
        if solution.verdict == "sat":
            return _confirmed(question, way, blocks, solution, workspace, within)
        if solution.verdict == "unknown":
            return solution
        core.update(solution.core)
    return Solution("unsat", {}, tuple(sorted(core)))


def _confirmed(
    question: Question,
    way: str,
    blocks: dict[str, str],
    solution: Solution,
    workspace: Workspace,
    within: Region | None,
) -> Solution | Witness:
    """The model's placement as a witness once the ray cast confirms it, or the answer of the
    question refined until it does.

    The question asks only the misser's last scan before the anchor, but a witness must be
    missed by every scan up to the anchor, taken as the robot moved: where the obstacle fits a
    gap only just, a scan a few millimetres back reads it. Such scans join the question, each
    with every way it misses (the whole disjunction, so an unsat answer still proves), and it
    is asked again, as a search refines its query.
    """
    blocks = dict(blocks)
    for _ in range(MAX_REFINEMENTS):
        placement = Placement(
            obstacle_of(question.shape, solution),
            question.direction,
            question.anchor,
            question.anchor,
        )
        verification = verify(question.scene, placement)
        if verification.holds():
            x, y, yaw = (float(value) for value in question.pose())
            return Witness(0, placement, verification, (x, y, yaw))
        earlier = _earlier_scans(question, verification, blocks)
        if not earlier:
            return Solution("unknown", {}, reason=f"a model of the {way} case failed the ray cast")
        for time in earlier:
            blocks[earlier_label(time)] = question.missed_at(time, within)
        solution = workspace.solve(VARIABLES, blocks, (), question.settings.rlimit)
        if solution.verdict != "sat":
            return solution
    return Solution("unknown", {}, reason=f"{MAX_REFINEMENTS} refinements did not converge")


def _earlier_scans(
    question: Question, verification: Verification, blocks: dict[str, str]
) -> list[float]:
    """A few of the misser's scans (s) that read the model and are not yet asked, when only
    the misser fails the model; none when it fails anything else, which the question promised
    and a refinement cannot mend."""
    promised = min(
        verification.detection,
        verification.clearance,
        verification.obstruction,
        verification.walls,
    )
    times = np.array(verification.seen_by_misser_at)
    if promised < REQUIRED_MARGIN or not len(times):
        return []
    # Scans from one pose ask the same (the robot stood still between them): the first will do.
    _, first = np.unique(question.scene.path.poses_at(times), axis=0, return_index=True)
    seen = [float(time) for time in times[np.sort(first)] if earlier_label(time) not in blocks]
    return sorted({seen[0], seen[len(seen) // 2], seen[-1]}) if seen else []


def _around(boxes: list[Region]) -> Region:
    """The smallest box holding every one of `boxes`."""
    return Region(
        (min(box.low[0] for box in boxes), min(box.low[1] for box in boxes)),
        (max(box.high[0] for box in boxes), max(box.high[1] for box in boxes)),
    )
